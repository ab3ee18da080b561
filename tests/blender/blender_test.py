#!/usr/bin/env python3
"""The Blender add-on proven in Blender: Cycles renders of a sphere with the add-on's
material against the program's own colours (`alloycolor color --json`, srgb8).

    blender_test.py --program ALLOYCOLOR --zip alloycolor_material.zip [--blender BLENDER]
                    [--version X.Y.Z]

BLENDER: default the blender on PATH, else /usr/bin/blender.

Fits eps-linear models of the bundled Au-Ag and Cu-Zn data, exports their tables, renders
(orthographic camera, sphere of radius 1, uniform white world of strength 1, Standard view
transform, 8-bit sRGB PNG) and checks, each within 3 of 8 bits per channel:
  - the centre pixel (normal incidence) of 18k Au-Ag, pure Cu and Cu70Zn30;
  - a pixel near the rim at theta = asin(r) (r: its centre's distance from the axis);
  - the render after the composition property moved by 10 at%, at its new composition,
    and that the move changes the colour by more than 3 (so drift would be seen);
  - the approximate mode (Principled BSDF, Base Color = F0) at the centre of Cu70Zn30;
  - the material panel, polled and drawn for each material, shows its system and its
    composition in at%;
  - with --version, the installed add-on's bl_info version is X.Y.Z.
Exits 77 (skipped) when Blender is absent."""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

TOLERANCE = 3
SIZE = 97  # odd: a pixel at the centre
ORTHO_SCALE = 2.2
SAMPLES = 4
HERE = os.path.dirname(os.path.abspath(__file__))


def run(args, **kw):
    done = subprocess.run(args, capture_output=True, text=True, **kw)
    if done.returncode != 0:
        sys.exit("failed: %s\n%s%s" % (" ".join(args), done.stdout, done.stderr))
    return done.stdout


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--program", required=True)
    parser.add_argument("--zip", required=True)
    parser.add_argument("--blender", default=shutil.which("blender") or "/usr/bin/blender")
    parser.add_argument("--version", help="the add-on's version expected (x.y.z)")
    o = parser.parse_args()
    if not os.path.exists(o.blender):
        print("Blender is absent (%s; Debian package blender): skipped" % o.blender)
        return 77
    if not os.path.exists(o.zip):
        sys.exit("no add-on zip %s: build the target blender_addon" % o.zip)
    tmp = tempfile.mkdtemp(prefix="alloycolor-blender-")
    try:
        return check(o, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def colour(o, model, x, angle):
    doc = json.loads(run([o.program, "color", "--model", model, "--x", str(x), "--angle",
                          "%.6f" % angle, "--json"]))
    return doc["srgb8"], doc["x"]


def panel_failures(what, system, result):
    """The panel as drawn for a material: its first line names the system, and it shows the
    composition in at% (the unit the materials keep)."""
    drawn = result["panel"]
    at_percent = 100.0 * result["x_atomic"]
    if not drawn or not str(drawn[0]).startswith(system + ","):
        return ["%s: the panel drew %r" % (what, drawn)]
    if not any(isinstance(v, float) and abs(v - at_percent) < 1e-3 for v in drawn):
        return ["%s: the panel shows %r, not %.4f at%%" % (what, drawn, at_percent)]
    return []


def check(o, tmp):
    start = time.time()
    tables = {}
    for system in ("Au-Ag", "Cu-Zn"):
        model = os.path.join(tmp, system + ".model.json")
        run([o.program, "fit", "--data", system, "--method", "eps-linear", "--out", model,
             "--quiet"])
        run([o.program, "export", "--model", model, "--format", "blender-table", "--out",
             os.path.join(tmp, system), "--quiet"])
        tables[system] = (model, os.path.join(tmp, system + ".alloy-table.json"))

    centre = (SIZE - 1) // 2
    # Pixels on the centre row whose centres lie at r = 0.86 R and 0.97 R or so: theta
    # near 60 and 75 degrees.
    rims = []
    for fraction in (0.86, 0.97):
        column = centre + round(fraction * SIZE / ORTHO_SCALE)
        r = (column - centre) * ORTHO_SCALE / SIZE
        rims.append((column, math.degrees(math.asin(r))))
    pixels = [[centre, centre]] + [[column, centre] for column, _ in rims]

    cases = []  # (what, system, property, value, x for `color`, mode)
    cases.append(("18k Au-Ag", "Au-Ag", "karat", 18.0, "18k", "TABLE"))
    cases.append(("Cu (x = 1 of Cu-Zn)", "Cu-Zn", "at_percent", 100.0, "1", "TABLE"))
    cases.append(("Cu70Zn30", "Cu-Zn", "at_percent", 70.0, "0.7", "TABLE"))
    # 10 at% more gold than 18k (x of 18k from the program itself).
    x18 = colour(o, tables["Au-Ag"][0], "18k", 0.0)[1]
    cases.append(("18k Au-Ag + 10 at%", "Au-Ag", "at_percent", 100.0 * x18 + 10.0,
                  "%.10f" % (x18 + 0.1), "TABLE"))
    cases.append(("Cu70Zn30 approximate", "Cu-Zn", "wt_percent", 69.4, "69.4wt%",
                  "APPROXIMATE"))
    jobs = {"zip": os.path.abspath(o.zip), "size": SIZE, "ortho_scale": ORTHO_SCALE,
            "samples": SAMPLES, "renders": []}
    for i, (_, system, prop, value, _, mode) in enumerate(cases):
        jobs["renders"].append({"table": tables[system][1], "property": prop, "value": value,
                                "mode": mode, "png": os.path.join(tmp, "render%d.png" % i),
                                "pixels": pixels if mode == "TABLE" else pixels[:1]})
    jobs_path = os.path.join(tmp, "jobs.json")
    out_path = os.path.join(tmp, "out.json")
    with open(jobs_path, "w") as f:
        json.dump(jobs, f)
    env = dict(os.environ, BLENDER_USER_SCRIPTS=os.path.join(tmp, "scripts"),
               BLENDER_USER_CONFIG=os.path.join(tmp, "config"))
    blender_start = time.time()
    run([o.blender, "--background", "--factory-startup", "--python-exit-code", "1",
         "--python", os.path.join(HERE, "render_spheres.py"), "--", jobs_path, out_path],
        env=env)
    blender_seconds = time.time() - blender_start
    with open(out_path) as f:
        out = json.load(f)

    failures = []
    rendered = {}
    for (what, system, prop, value, x_text, mode), result in zip(cases, out["results"]):
        model = tables[system][0]
        centre_want, x = colour(o, model, x_text, 0.0)
        checks = [("centre", centre_want, result["pixels"][0])]
        for (_, angle), got in zip(rims, result["pixels"][1:]):
            checks.append(("rim at %.2f deg" % angle, colour(o, model, x_text, angle)[0], got))
        rendered[what] = result["pixels"][0]
        failures += panel_failures(what, system, result)
        print("%-22s panel: %s" % (what, " | ".join(str(v) for v in result["panel"])))
        if abs(result["x_atomic"] - x) > 1e-6:
            failures.append("%s: the material is at x = %.6f, the program's is %.6f"
                            % (what, result["x_atomic"], x))
        for where, want, got in checks:
            diff = max(abs(a - b) for a, b in zip(want, got))
            print("%-22s %-16s Blender %-16s alloycolor %-16s largest difference %d"
                  % (what, where, got, want, diff))
            if diff > TOLERANCE:
                failures.append("%s, %s: Blender %s, alloycolor %s" % (what, where, got, want))
        print("%-22s render %.2f s" % (what, result["seconds"]))
    moved = max(abs(a - b) for a, b in zip(rendered["18k Au-Ag"], rendered["18k Au-Ag + 10 at%"]))
    print("10 at%% more gold changes the centre pixel by %d" % moved)
    if moved <= TOLERANCE:
        failures.append("10 at%% more gold changes the colour by only %d" % moved)
    if o.version and out["addon_version"] != [int(p) for p in o.version.split(".")]:
        failures.append("the installed add-on is version %s, not %s"
                        % (out["addon_version"], o.version))
    print("Blender %s: %.1f s in Blender, %.1f s in all" % (out["blender"], blender_seconds,
                                                            time.time() - start))
    for f in failures:
        print("FAILED: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
