#!/usr/bin/env python3
"""The Blender script `alloycolor export --format rgb-conductor` writes (PREFIX.blender.py),
run in the real Blender (`blender --background`), whatever its version: it makes its
material without error, with the node that Blender has (the Metallic BSDF from 4.2, else
the Principled BSDF with Metallic 1), and a Cycles render of a sphere of it shows at its
centre (normal incidence) the program's own colour (`alloycolor color --json`, srgb8)
within 3 of 8 bits per channel, for 18k Au-Ag and Cu70Zn30. The Blender side is
render_export_script.py (its scene: sphere_scene.py, shared with render_spheres.py).

    export_script_test.py --program ALLOYCOLOR [--blender BLENDER]

Exits 77 (skipped) when Blender is absent."""
import argparse
import json
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from blender_test import TOLERANCE, run  # noqa: E402  (beside this file)


def check(o, tmp):
    failures = []
    render = os.path.join(HERE, "render_export_script.py")
    env = dict(os.environ, BLENDER_USER_SCRIPTS=os.path.join(tmp, "scripts"),
               BLENDER_USER_CONFIG=os.path.join(tmp, "config"))
    for system, x in (("Au-Ag", "18k"), ("Cu-Zn", "0.7")):
        model = os.path.join(tmp, system + ".json")
        prefix = os.path.join(tmp, system)
        run([o.program, "fit", "--data", system, "--method", "eps-linear", "--out", model,
             "--quiet"])
        run([o.program, "export", "--model", model, "--x", x, "--format", "all", "--out", prefix,
             "--quiet"])
        out = os.path.join(tmp, system + ".out.json")
        run([o.blender, "--background", "--factory-startup", "--python-exit-code", "1",
             "--python", render, "--", prefix + ".blender.py", prefix + ".png", out], env=env)
        with open(out) as f:
            got = json.load(f)
        with open(prefix + ".f82.json") as f:
            f82 = json.load(f)
        want = json.loads(run([o.program, "color", "--model", model, "--x", x, "--json"]))["srgb8"]
        if isinstance(want[0], list):
            want = want[0]
        what = "%s %s in Blender %s (%s)" % (system, x, got["blender"], got["node"])
        print("%s: centre %s, the program's %s" % (what, got["centre"], want))
        if any(abs(a - b) > TOLERANCE for a, b in zip(got["centre"], want)):
            failures.append("%s: centre %s, not %s" % (what, got["centre"], want))
        if got["node"] == "ShaderNodeBsdfPrincipled":
            base = got["inputs"]["Base Color"][:3]
            f0 = f82_value(f82, "f0")
            if any(abs(a - b) > 1e-5 for a, b in zip(base, f0)) or got["inputs"]["Metallic"] != 1:
                failures.append("%s: Base Color %s, Metallic %s; F0 is %s" % (
                    what, base, got["inputs"]["Metallic"], f0))
        elif got["node"] != "ShaderNodeBsdfMetallic":
            failures.append("%s: the output is fed by %s" % (what, got["node"]))
    for failure in failures:
        print("FAIL " + failure)
    return 1 if failures else 0


def f82_value(doc, key):
    """The F0 (or tint) of an .f82.json, wherever the document keeps it."""
    if isinstance(doc, dict):
        if key in doc and isinstance(doc[key], list) and len(doc[key]) == 3:
            return doc[key]
        for value in doc.values():
            found = f82_value(value, key)
            if found is not None:
                return found
    return None


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--program", required=True)
    parser.add_argument("--blender", default=shutil.which("blender") or "/usr/bin/blender")
    o = parser.parse_args()
    if not os.path.exists(o.blender):
        print("Blender is absent (%s; Debian package blender): skipped" % o.blender)
        return 77
    tmp = tempfile.mkdtemp(prefix="alloycolor-blender-export-")
    try:
        return check(o, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
