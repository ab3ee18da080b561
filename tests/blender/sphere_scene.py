# The scene the Blender tests render, run inside Blender (render_spheres.py,
# render_export_script.py): a smooth UV sphere of radius 1 at the origin (poles off the view
# axis) seen by an orthographic camera down -z, under a uniform white world of strength 1;
# Cycles on the CPU, every sample at its pixel's centre, no denoising nor glossy blur;
# Standard view transform, 8-bit sRGB PNG.
import bpy


def sphere_scene(size, ortho_scale, samples, segments=256, ring_count=128):
    """Empties the scene and sets it up; returns (scene, sphere)."""
    scene = bpy.context.scene
    for obj in list(scene.objects):
        bpy.data.objects.remove(obj, do_unlink=True)

    bpy.ops.mesh.primitive_uv_sphere_add(segments=segments, ring_count=ring_count, radius=1.0)
    sphere = bpy.context.active_object
    bpy.ops.object.shade_smooth()
    sphere.rotation_euler = (1.5707963267948966, 0.0, 0.0)  # the poles off the view axis

    camera_data = bpy.data.cameras.new("camera")
    camera_data.type = "ORTHO"
    camera_data.ortho_scale = ortho_scale
    camera = bpy.data.objects.new("camera", camera_data)
    camera.location = (0.0, 0.0, 10.0)  # a camera looks down its -z axis: at the sphere
    scene.collection.objects.link(camera)
    scene.camera = camera

    world = bpy.data.worlds.new("white")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    background.inputs["Strength"].default_value = 1.0
    scene.world = world

    render = scene.render
    render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.blur_glossy = 0.0
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 0.01  # every sample at the pixel's centre
    render.threads_mode = "FIXED"
    render.threads = 2
    render.resolution_x = render.resolution_y = size
    render.resolution_percentage = 100
    render.film_transparent = False
    render.dither_intensity = 0.0
    render.image_settings.file_format = "PNG"
    render.image_settings.color_mode = "RGB"
    render.image_settings.color_depth = "8"
    scene.display_settings.display_device = "sRGB"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.sequencer_colorspace_settings.name = "sRGB"
    return scene, sphere
