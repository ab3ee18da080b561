# Run inside Blender (blender --background --factory-startup --python THIS -- SCRIPT PNG OUT):
# runs SCRIPT (the PREFIX.blender.py `alloycolor export` writes), renders a sphere of the
# material it made (sphere_scene.py) and writes to OUT (JSON) the Blender version, the node
# that feeds the material's output, that node's input values and the centre pixel (normal
# incidence) as 8-bit sRGB.
import json
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sphere_scene import sphere_scene  # noqa: E402  (beside this file)

SIZE = 33  # odd: a pixel at the centre

script, png, out = sys.argv[sys.argv.index("--") + 1:]
before = set(bpy.data.materials.keys())
with open(script) as f:
    exec(compile(f.read(), script, "exec"), {"__name__": "__main__"})
material = bpy.data.materials[(set(bpy.data.materials.keys()) - before).pop()]
output = [n for n in material.node_tree.nodes if n.type == "OUTPUT_MATERIAL"][0]
shader = output.inputs["Surface"].links[0].from_node

scene, sphere = sphere_scene(SIZE, 2.2, 4, segments=64, ring_count=32)
sphere.data.materials.append(material)
scene.render.filepath = png
bpy.ops.render.render(write_still=True)
image = bpy.data.images.load(png)
centre = (image.size[1] // 2) * image.size[0] + image.size[0] // 2
pixel = [round(255 * image.pixels[4 * centre + c]) for c in range(3)]
inputs = {}
for socket in shader.inputs:
    if hasattr(socket, "default_value"):
        value = socket.default_value
        inputs[socket.name] = list(value) if hasattr(value, "__len__") else value
with open(out, "w") as f:
    json.dump({"blender": bpy.app.version_string, "node": shader.bl_idname, "inputs": inputs,
               "centre": pixel}, f)
