# Run inside Blender (blender --background --factory-startup --python THIS -- JOBS OUT):
# installs the add-on from its zip, imports alloy tables as materials, renders a smooth
# UV sphere of each under a uniform white world with Cycles and writes the 8-bit sRGB
# values of the asked pixels, what the material panel draws and the installed add-on's
# version to OUT (JSON). JOBS (JSON):
#   {"zip": path, "size": N, "ortho_scale": s, "samples": n,
#    "renders": [{"table": .alloy-table.json, "property": "at_percent" | "wt_percent" |
#                 "karat", "value": v, "mode": "TABLE" | "APPROXIMATE", "png": path,
#                 "pixels": [[column, row], ...]}]}
# Rows count from the bottom (Blender's pixel order).
import json
import os
import sys
import time
import types

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
with open(args[0]) as f:
    jobs = json.load(f)

bpy.ops.preferences.addon_install(filepath=jobs["zip"], overwrite=True)
bpy.ops.preferences.addon_enable(module="alloycolor_material")
import addon_utils  # noqa: E402
import alloycolor_material  # noqa: E402  (installed just above)


class DrawnLayout:
    """Stands in for a panel's layout in the background (no window): records labels' text
    and properties' values; rows, columns and the rest lay out into itself."""

    def __init__(self):
        self.drawn = []

    def label(self, text="", **_):
        self.drawn.append(text)

    def prop(self, data, name, **_):
        self.drawn.append(getattr(data, name))

    def __getattr__(self, _name):
        return lambda *args, **kwargs: self


def panel_draws(material):
    """The add-on's material panel, polled and drawn for this material: what it shows."""
    panel = bpy.types.MATERIAL_PT_alloycolor
    context = types.SimpleNamespace(material=material)
    if not panel.poll(context):
        return []
    layout = DrawnLayout()
    panel.draw(types.SimpleNamespace(layout=layout), context)
    return layout.drawn

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sphere_scene import sphere_scene  # noqa: E402  (beside this file)

scene, sphere = sphere_scene(jobs["size"], jobs["ortho_scale"], jobs["samples"])
render = scene.render

results = []
materials = {}
for job in jobs["renders"]:
    material = materials.get(job["table"])
    if material is None:
        material = alloycolor_material.import_table(job["table"])
        materials[job["table"]] = material
    setattr(material.alloycolor, job["property"], job["value"])
    material.alloycolor.mode = job["mode"]
    sphere.data.materials.clear()
    sphere.data.materials.append(material)
    render.filepath = job["png"]
    start = time.time()
    bpy.ops.render.render(write_still=True)
    seconds = time.time() - start
    image = bpy.data.images.load(job["png"], check_existing=False)
    width = image.size[0]
    pixels = image.pixels[:]
    values = []
    for column, row in job["pixels"]:
        i = (row * width + column) * 4
        values.append([round(255 * pixels[i + c]) for c in range(3)])
    bpy.data.images.remove(image)
    results.append({"x_atomic": material.alloycolor.x_atomic, "pixels": values,
                    "seconds": seconds, "panel": panel_draws(material)})

with open(args[1], "w") as f:
    json.dump({"blender": bpy.app.version_string, "results": results,
               "addon_version": addon_utils.module_bl_info(alloycolor_material)["version"]},
              f, indent=1)
