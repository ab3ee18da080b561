#!/usr/bin/env python3
"""The add-on's zip against what Blender checks when it installs one, without Blender:

    addon_zip_check.py ZIP VERSION

- Blender 3.4 to 4.1 (Edit > Preferences > Add-ons > Install): one top-level folder, a
  module with __init__.py, whose bl_info Blender reads without running it (ast, literal
  values only), at VERSION and asking for no Blender newer than 3.4.
- Blender 4.2+ extensions (Install from Disk): blender_manifest.toml in that one folder, by
  the rules of Blender's manifest validation (scripts/addons_core/bl_pkg/cli/blender_ext.py):
  the required fields and their types, id the folder's name, semantic versions, the tagline
  and each permission at most 64 characters, ending in a letter, digit or closing bracket,
  licences as SPDX identifiers, permissions from the known five.
Prints one line per problem and exits 1 if there was one."""
import ast
import re
import sys
import tomllib
import zipfile

REQUIRED = {"schema_version": str, "id": str, "name": str, "tagline": str, "version": str,
            "type": str, "maintainer": str, "license": list, "blender_version_min": str}
PERMISSIONS = {"files", "network", "clipboard", "camera", "microphone"}
SEMVER = re.compile(r"^(0|[1-9]\d*)\.(0|[1-9]\d*)\.(0|[1-9]\d*)$")


def terse(what, text):
    if not text or len(text) > 64:
        return ["%s: %d characters, 1 to 64 expected" % (what, len(text))]
    if not (text[-1].isalnum() or text[-1] in ")]}"):
        return ["%s: ends with %r; Blender wants a letter, digit or bracket" % (what, text[-1])]
    return []


def bl_info_problems(source, version):
    tree = ast.parse(source)
    for node in tree.body:
        if isinstance(node, ast.Assign) and [t.id for t in node.targets
                                             if isinstance(t, ast.Name)] == ["bl_info"]:
            info = ast.literal_eval(node.value)
            break
    else:
        return ["__init__.py: no bl_info"]
    problems = []
    if tuple(info.get("version", ())) != tuple(int(p) for p in version.split(".")):
        problems.append("bl_info version %s, the project's is %s" % (info.get("version"), version))
    if tuple(info.get("blender", (99,))) > (3, 4, 0):
        problems.append("bl_info asks for Blender %s, above 3.4" % (info.get("blender"),))
    return problems


def manifest_problems(manifest, folder, version):
    problems = ["manifest: %s missing or not a %s" % (key, kind.__name__)
                for key, kind in REQUIRED.items() if not isinstance(manifest.get(key), kind)]
    if problems:
        return problems
    if manifest["id"] != folder or not manifest["id"].isidentifier():
        problems.append("manifest: id %r, the folder is %r" % (manifest["id"], folder))
    for key in ("schema_version", "version", "blender_version_min"):
        if not SEMVER.match(manifest[key]):
            problems.append("manifest: %s %r is not x.y.z" % (key, manifest[key]))
    if manifest["version"] != version:
        problems.append("manifest: version %s, the project's is %s" % (manifest["version"], version))
    if manifest["type"] != "add-on":
        problems.append("manifest: type %r, not add-on" % manifest["type"])
    problems += terse("manifest: tagline", manifest["tagline"])
    if not manifest["license"] or not all(isinstance(x, str) and x.startswith("SPDX:")
                                          for x in manifest["license"]):
        problems.append("manifest: license %r: SPDX:<identifier> expected" % manifest["license"])
    for key, text in manifest.get("permissions", {}).items():
        if key not in PERMISSIONS:
            problems.append("manifest: unknown permission %r" % key)
        problems += terse("manifest: permission %s" % key, text)
    return problems


def main():
    path, version = sys.argv[1:3]
    with zipfile.ZipFile(path) as z:
        names = [n for n in z.namelist() if not n.endswith("/")]
        folders = {n.split("/")[0] for n in z.namelist()}
        if len(folders) != 1 or any("/" not in n for n in names):
            problems = ["%s: one top-level folder expected, found %s" % (path, sorted(folders))]
        else:
            folder = folders.pop()
            missing = [f for f in ("__init__.py", "blender_manifest.toml")
                       if folder + "/" + f not in names]
            problems = ["%s: no %s/%s" % (path, folder, f) for f in missing]
            if not missing:
                problems = bl_info_problems(z.read(folder + "/__init__.py").decode(), version)
                manifest = tomllib.loads(z.read(folder + "/blender_manifest.toml").decode())
                problems += manifest_problems(manifest, folder, version)
    for p in problems:
        print("FAILED: " + p)
    if not problems:
        print("%s: a Blender 3.4+ add-on and a 4.2+ extension at version %s (%d files)"
              % (path, version, len(names)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
