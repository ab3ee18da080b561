# Run inside Blender with a display (scripts/blender_pictures.sh runs it under Xvfb): the
# add-on's panel in the material properties, as a screenshot.
#   blender --python blender_panel.py -- OUT.png TABLE.json
# The largest area is turned into the properties editor so that every panel fits; the
# screenshot waits for the window to draw (timers), then Blender quits.
import os
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
out, table = args[0], args[1]
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "blender"))
import alloycolor_material  # noqa: E402

alloycolor_material.register()
cube = bpy.data.objects["Cube"]
bpy.context.view_layer.objects.active = cube
material = alloycolor_material.import_table(table)
cube.data.materials.clear()
cube.data.materials.append(material)
material.alloycolor.unit = "KARAT"
material.alloycolor.karat = 18.0


def largest_area():
    window = bpy.context.window_manager.windows[0]
    areas = [a for a in window.screen.areas if a.type in ("VIEW_3D", "PROPERTIES")]
    return window, max(areas, key=lambda a: a.width * a.height)


def make_properties():
    largest_area()[1].type = "PROPERTIES"
    bpy.app.timers.register(show_material, first_interval=0.5)


def show_material():
    largest_area()[1].spaces.active.context = "MATERIAL"
    bpy.app.timers.register(shoot, first_interval=1.5)


def shoot():
    window, area = largest_area()
    with bpy.context.temp_override(window=window, area=area):
        bpy.ops.screen.screenshot_area(filepath=out)
    bpy.ops.wm.quit_blender()


bpy.app.timers.register(make_properties, first_interval=1.0)
