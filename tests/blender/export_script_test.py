#!/usr/bin/env python3
"""The Blender script `alloycolor export --format rgb-conductor` writes (PREFIX.blender.py),
run in the real Blender (`blender --background`), whatever its version: it makes its
material without error, with the node that Blender has (the Metallic BSDF from 4.2, else
the Principled BSDF with Metallic 1), and a Cycles render of a sphere of it shows at its
centre (normal incidence) the program's own colour (`alloycolor color --json`, srgb8)
within 3 of 8 bits per channel, for 18k Au-Ag and Cu70Zn30.

    export_script_test.py --program ALLOYCOLOR [--blender BLENDER]

Exits 77 (skipped) when Blender is absent."""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

TOLERANCE = 3
SIZE = 33  # odd: a pixel at the centre

# Run inside Blender: the exported script, then a sphere of its material under a uniform
# white world, orthographic, Standard view transform, 8-bit sRGB; writes the node feeding
# the output, its inputs and the centre pixel.
RENDER = r'''
import json, sys, bpy
script, png, out = sys.argv[sys.argv.index("--") + 1:]
names_before = set(bpy.data.materials.keys())
exec(compile(open(script).read(), script, "exec"), {"__name__": "__main__"})
material = bpy.data.materials[(set(bpy.data.materials.keys()) - names_before).pop()]
tree = material.node_tree
output = [n for n in tree.nodes if n.type == "OUTPUT_MATERIAL"][0]
shader = output.inputs["Surface"].links[0].from_node
scene = bpy.context.scene
for obj in list(scene.objects):
    bpy.data.objects.remove(obj, do_unlink=True)
bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=1.0)
sphere = bpy.context.active_object
bpy.ops.object.shade_smooth()
sphere.data.materials.append(material)
camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
camera.data.type = "ORTHO"
camera.data.ortho_scale = 2.2
camera.location = (0.0, 0.0, 10.0)
scene.collection.objects.link(camera)
scene.camera = camera
world = bpy.data.worlds.new("white")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (1, 1, 1, 1)
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
scene.world = world
render = scene.render
render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 4
scene.cycles.use_denoising = False
scene.cycles.pixel_filter_type = "BOX"
scene.cycles.filter_width = 0.01
render.resolution_x = render.resolution_y = %d
render.resolution_percentage = 100
render.dither_intensity = 0.0
render.image_settings.file_format = "PNG"
render.image_settings.color_mode = "RGB"
render.image_settings.color_depth = "8"
scene.display_settings.display_device = "sRGB"
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
render.filepath = png
bpy.ops.render.render(write_still=True)
image = bpy.data.images.load(png)
centre = (image.size[0] // 2) * image.size[0] + image.size[0] // 2
pixel = [round(255 * image.pixels[4 * centre + c]) for c in range(3)]
inputs = {i.name: list(i.default_value) if hasattr(i.default_value, "__len__")
          else i.default_value for i in shader.inputs if hasattr(i, "default_value")}
json.dump({"blender": bpy.app.version_string, "node": shader.bl_idname, "inputs": inputs,
           "centre": pixel}, open(out, "w"))
''' % SIZE


def run(args, **kw):
    done = subprocess.run(args, capture_output=True, text=True, **kw)
    if done.returncode != 0:
        sys.exit("failed: %s\n%s%s" % (" ".join(args), done.stdout, done.stderr))
    return done.stdout


def check(o, tmp):
    failures = []
    render = os.path.join(tmp, "render.py")
    with open(render, "w") as f:
        f.write(RENDER)
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
