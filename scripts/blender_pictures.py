# Run inside Blender by scripts/blender_pictures.sh: three rings with the add-on's
# material (table mode) under a studio-like gradient world, rendered with Cycles.
#   blender --background --factory-startup --python blender_pictures.py -- OUT.png \
#       TABLE.json PROPERTY VALUE [TABLE.json PROPERTY VALUE ...]
import math
import os
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
out, rings = args[0], [args[i:i + 3] for i in range(1, len(args), 3)]
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "blender"))
import alloycolor_material  # noqa: E402

alloycolor_material.register()
scene = bpy.context.scene
for obj in list(scene.objects):
    bpy.data.objects.remove(obj, do_unlink=True)

for i, (table, prop, value) in enumerate(rings):
    bpy.ops.mesh.primitive_torus_add(major_radius=1.0, minor_radius=0.28, major_segments=128,
                                     minor_segments=48,
                                     location=(2.6 * (i - (len(rings) - 1) / 2), 0.0, 0.0),
                                     rotation=(math.radians(62), 0.0, 0.0))
    bpy.ops.object.shade_smooth()
    material = alloycolor_material.import_table(table)
    setattr(material.alloycolor, prop, float(value))
    bpy.context.active_object.data.materials.append(material)

camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
camera.data.type = "ORTHO"
camera.data.ortho_scale = 2.7 * len(rings)
camera.location = (0.0, -10.0, 0.0)
camera.rotation_euler = (math.radians(90), 0.0, 0.0)
scene.collection.objects.link(camera)
scene.camera = camera

# A studio: bright above, dark below, a soft band at the horizon.
world = bpy.data.worlds.new("studio")
world.use_nodes = True
nodes, links = world.node_tree.nodes, world.node_tree.links
coords = nodes.new("ShaderNodeTexCoord")
separate = nodes.new("ShaderNodeSeparateXYZ")
ramp = nodes.new("ShaderNodeValToRGB")
links.new(coords.outputs["Generated"], separate.inputs[0])
links.new(separate.outputs["Z"], ramp.inputs["Fac"])
elements = ramp.color_ramp.elements
elements[0].position, elements[0].color = 0.45, (0.02, 0.02, 0.025, 1.0)
elements[1].position, elements[1].color = 0.75, (1.0, 1.0, 1.0, 1.0)
band = elements.new(0.52)
band.color = (0.35, 0.35, 0.36, 1.0)
links.new(ramp.outputs["Color"], nodes["Background"].inputs["Color"])
nodes["Background"].inputs["Strength"].default_value = 1.0
scene.world = world

render = scene.render
render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 32
scene.cycles.use_denoising = False
render.resolution_x, render.resolution_y = 200 * len(rings), 190
render.resolution_percentage = 100
render.film_transparent = True
render.image_settings.file_format = "PNG"
render.image_settings.color_mode = "RGBA"
render.image_settings.color_depth = "8"
render.image_settings.compression = 100
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
render.filepath = out
bpy.ops.render.render(write_still=True)
