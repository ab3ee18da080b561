# The alloy in Blender: a material whose colour at every angle of incidence comes from the
# reflection table `alloycolor export --format blender-table` writes (the explorer page's
# table: D65, CIE 1931 2-degree observer, polished surface), with the composition as a
# property in at%, wt% or karat.
#
# The table is an image (columns: composition x, rows: mu = cos theta, linear sRGB, 16 bit)
# looked up in a node group: mu = |Normal . Incoming|, u and v at Blender's texel centres
# ((i + 1/2) / width), Linear interpolation, Extension EXTEND, colour space Non-Color,
# feeding a perfect-mirror Glossy BSDF (Cycles and Eevee). The approximate mode is the
# Principled BSDF with Metallic 1: Base Color = F0 (the table at mu = 1) and, from Blender
# 4.0, Specular Tint = the F82 tint (Principled's metallic Fresnel is then F82-tint).
#
# The composition sets a Value node from a property update (no drivers: they would need
# scripts to run automatically). See docs/blender.md.

bl_info = {
    "name": "alloycolor material",
    "author": "alloycolor",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > Alloy material (alloycolor table); Properties > Material",
    "description": "Binary alloy materials whose colour follows composition and angle, "
                   "from alloycolor's reflection table",
    "category": "Import-Export",
}

import json
import os
import shutil
import subprocess
import tempfile

import bpy
from bpy.props import (BoolProperty, EnumProperty, FloatProperty, PointerProperty,
                       StringProperty)
from bpy_extras.io_utils import ImportHelper

GROUP_PREFIX = "alloycolor lookup "
X_NODE = "alloycolor x"
TINT_NODE = "alloycolor F82 tint"
GLOSSY_NODE = "alloycolor mirror"
PRINCIPLED_NODE = "alloycolor approximate"
OUTPUT_NODE = "alloycolor output"
GROUP_NODE = "alloycolor table"

# Blender 4.0 renamed Principled BSDF inputs and made Specular Tint a colour (the F82
# tint of metals); group sockets moved to node_tree.interface.
BLENDER_4 = bpy.app.version >= (4, 0, 0)


# ---- compositions -------------------------------------------------------------------------

from .compositions import KARAT_RANGE, PERCENT_RANGE, atomic_fraction, weight_fraction
from .compositions import karat_from_x, x_from_karat as _x_from_karat


def karat_of(x, settings):
    return karat_from_x(x, settings.molar_masses, settings.gold_element)


def x_of_karat(k, settings):
    return _x_from_karat(k, settings.molar_masses, settings.gold_element)


def table_settings(material):
    return material.alloycolor


def interpolate_samples(samples, settings, x):
    """Linear interpolation of per-column samples (F0, tint) at atomic fraction x."""
    n = len(samples)
    span = settings.x_max - settings.x_min
    t = 0.0 if span <= 0 else (x - settings.x_min) / span * (n - 1)
    t = min(max(t, 0.0), n - 1.0)
    i = min(int(t), n - 2)
    f = t - i
    return [samples[i][c] + f * (samples[i + 1][c] - samples[i][c]) for c in range(3)]


# ---- the material -------------------------------------------------------------------------

def _new_socket(group, name, in_out, kind):
    if BLENDER_4:
        return group.interface.new_socket(name, in_out=in_out, socket_type=kind)
    sockets = group.inputs if in_out == "INPUT" else group.outputs
    return sockets.new(kind, name)


def _math(nodes, op, location, a=None, b=None, c=None):
    node = nodes.new("ShaderNodeMath")
    node.operation = op
    node.location = location
    for i, v in enumerate((a, b, c)):
        if v is not None:
            node.inputs[i].default_value = v
    return node


def build_lookup_group(name, image, doc):
    """The node group: x in, table colour at this shading point's mu and F0 (mu = 1) out."""
    group = bpy.data.node_groups.new(name, "ShaderNodeTree")
    _new_socket(group, "x", "INPUT", "NodeSocketFloat")
    _new_socket(group, "Color", "OUTPUT", "NodeSocketColor")
    _new_socket(group, "F0", "OUTPUT", "NodeSocketColor")
    nodes, links = group.nodes, group.links
    gin = nodes.new("NodeGroupInput")
    gin.location = (-900, 0)
    gout = nodes.new("NodeGroupOutput")
    gout.location = (400, 0)
    width, height = doc["columns"], doc["rows"]
    x_min, x_max = doc["x_range"]
    span = (x_max - x_min) or 1.0
    # u = (1/2 + (x - x_min) / span (width - 1)) / width
    scale_u = (width - 1) / (width * span)
    u = _math(nodes, "MULTIPLY_ADD", (-650, 150), None, scale_u, 0.5 / width - x_min * scale_u)
    links.new(gin.outputs["x"], u.inputs[0])
    # mu = |Normal . Incoming|, v = (1/2 + mu (height - 1)) / height
    geometry = nodes.new("ShaderNodeNewGeometry")
    geometry.location = (-900, -200)
    dot = nodes.new("ShaderNodeVectorMath")
    dot.operation = "DOT_PRODUCT"
    dot.location = (-700, -200)
    links.new(geometry.outputs["Normal"], dot.inputs[0])
    links.new(geometry.outputs["Incoming"], dot.inputs[1])
    mu = _math(nodes, "ABSOLUTE", (-500, -200))
    links.new(dot.outputs["Value"], mu.inputs[0])
    mu1 = _math(nodes, "MINIMUM", (-350, -200), None, 1.0)
    links.new(mu.outputs[0], mu1.inputs[0])
    v = _math(nodes, "MULTIPLY_ADD", (-200, -200), None, (height - 1) / height, 0.5 / height)
    links.new(mu1.outputs[0], v.inputs[0])
    lookups = []
    for i, (label, v_socket, y) in enumerate((("angle", v.outputs[0], 0), ("F0", None, -350))):
        combine = nodes.new("ShaderNodeCombineXYZ")
        combine.location = (-50, y)
        links.new(u.outputs[0], combine.inputs["X"])
        if v_socket is not None:
            links.new(v_socket, combine.inputs["Y"])
        else:
            combine.inputs["Y"].default_value = (height - 0.5) / height  # mu = 1
        texture = nodes.new("ShaderNodeTexImage")
        texture.name = texture.label = "table " + label
        texture.image = image
        texture.interpolation = "Linear"
        texture.extension = "EXTEND"
        texture.location = (150, y)
        links.new(combine.outputs["Vector"], texture.inputs["Vector"])
        lookups.append(texture)
    links.new(lookups[0].outputs["Color"], gout.inputs["Color"])
    links.new(lookups[1].outputs["Color"], gout.inputs["F0"])
    return group


def load_table_image(path, doc):
    image = bpy.data.images.load(os.path.join(os.path.dirname(path), doc["image"]),
                                 check_existing=False)
    image.colorspace_settings.name = "Non-Color"
    image.alpha_mode = "NONE"
    image.pack()  # the .blend keeps the table; the files may go
    return image


def build_material(path, doc):
    """A new material from a table's JSON document (path: the .alloy-table.json)."""
    image = load_table_image(path, doc)
    name = doc["system"] + " (alloycolor)"
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    nodes, links = tree.nodes, tree.links
    group = build_lookup_group(GROUP_PREFIX + doc["system"], image, doc)
    x_node = nodes.new("ShaderNodeValue")
    x_node.name = X_NODE
    x_node.label = "x (atomic fraction of %s)" % doc["elements"][0]
    x_node.location = (-600, 0)
    group_node = nodes.new("ShaderNodeGroup")
    group_node.name = GROUP_NODE
    group_node.node_tree = group
    group_node.location = (-400, 0)
    links.new(x_node.outputs[0], group_node.inputs["x"])
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.name = GLOSSY_NODE
    glossy.location = (-100, 150)
    glossy.distribution = "GGX"
    glossy.inputs["Roughness"].default_value = 0.0
    links.new(group_node.outputs["Color"], glossy.inputs["Color"])
    principled = nodes.new("ShaderNodeBsdfPrincipled")
    principled.name = PRINCIPLED_NODE
    principled.location = (-100, -200)
    principled.inputs["Metallic"].default_value = 1.0
    principled.inputs["Roughness"].default_value = 0.0
    links.new(group_node.outputs["F0"], principled.inputs["Base Color"])
    if BLENDER_4:
        tint = nodes.new("ShaderNodeRGB")
        tint.name = TINT_NODE
        tint.label = "F82 tint"
        tint.location = (-400, -300)
        links.new(tint.outputs[0], principled.inputs["Specular Tint"])
    output = nodes.new("ShaderNodeOutputMaterial")
    output.name = OUTPUT_NODE
    output.location = (250, 0)

    s = material.alloycolor
    s.is_alloy = True
    s.system = doc["system"]
    s.element_a, s.element_b = doc["elements"]
    s.molar_masses = doc["molar_masses_g_mol"]
    s.x_min, s.x_max = doc["x_range"]
    s.karat_applies = bool(doc.get("karat", False))
    s.gold_element = int(doc.get("gold_element", -1))
    s.samples = json.dumps({"f0": doc["f0"], "f82_tint": doc["f82_tint"]})
    s.lookup_error = "largest 8-bit sRGB difference %d, CIEDE2000 %.3f" % (
        doc["lookup_error"]["max_srgb8_difference"], doc["lookup_error"]["max_delta_e00"])
    s.table_file = path
    set_mode(material)
    set_composition(material, 0.5 * (s.x_min + s.x_max))
    return material


def set_mode(material):
    s = material.alloycolor
    nodes, links = material.node_tree.nodes, material.node_tree.links
    shader = nodes[GLOSSY_NODE if s.mode == "TABLE" else PRINCIPLED_NODE]
    links.new(shader.outputs["BSDF"], nodes[OUTPUT_NODE].inputs["Surface"])


def set_composition(material, x):
    """Sets the material to atomic fraction x of the first element (held in range); the
    composition properties follow."""
    s = material.alloycolor
    x = min(max(x, s.x_min), s.x_max)
    s.x_atomic = x
    _syncing[0] = True
    try:
        s.at_percent = 100.0 * x
        s.wt_percent = 100.0 * weight_fraction(x, s.molar_masses)
        if s.karat_applies:
            s.karat = karat_of(x, s)
    finally:
        _syncing[0] = False
    nodes = material.node_tree.nodes
    nodes[X_NODE].outputs[0].default_value = x
    if TINT_NODE in nodes and s.samples:
        tint = interpolate_samples(json.loads(s.samples)["f82_tint"], s, x)
        nodes[TINT_NODE].outputs[0].default_value = [min(max(c, 0.0), 1.0) for c in tint] + [1.0]


def import_table(path, context=None):
    """Imports a .alloy-table.json as a new material (assigned to the active object when
    there is one); returns the material."""
    with open(path, encoding="utf-8") as f:
        doc = json.load(f)
    if not str(doc.get("format", "")).startswith("alloycolor blender-table"):
        raise ValueError("%s: not an alloycolor blender-table file" % path)
    material = build_material(os.path.abspath(path), doc)
    obj = context.active_object if context is not None else None
    if obj is not None and obj.type == "MESH":
        if obj.data.materials:
            obj.data.materials[0] = material
        else:
            obj.data.materials.append(material)
    return material


def program_path(context):
    prefs = context.preferences.addons.get(__name__)
    given = prefs.preferences.program if prefs is not None else ""
    return given or shutil.which("alloycolor") or ""


def import_model(path, program, context=None):
    """Runs `alloycolor export --format blender-table` on a model file into a temporary
    folder, then imports the table (the image is packed into the .blend)."""
    if not program:
        raise ValueError("the alloycolor program was not found: set its path in the "
                         "add-on's preferences")
    folder = tempfile.mkdtemp(prefix="alloycolor-")
    try:
        prefix = os.path.join(folder, "alloy")
        run = subprocess.run([program, "export", "--model", path, "--format", "blender-table",
                              "--out", prefix, "--quiet"], capture_output=True, text=True)
        if run.returncode != 0:
            raise ValueError((run.stderr.strip() or "alloycolor failed").splitlines()[-1])
        return import_table(prefix + ".alloy-table.json", context)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


# ---- properties and their updates ---------------------------------------------------------

_syncing = [False]


def _on_at(self, context):
    if not _syncing[0]:
        set_composition(self.id_data, self.at_percent / 100.0)


def _on_wt(self, context):
    if not _syncing[0]:
        set_composition(self.id_data, atomic_fraction(self.wt_percent / 100.0, self.molar_masses))


def _on_karat(self, context):
    if not _syncing[0] and self.karat_applies:
        set_composition(self.id_data, x_of_karat(self.karat, self))


def _on_mode(self, context):
    set_mode(self.id_data)


# Blender keeps no reference to a dynamic enum's strings: these lists stay alive here.
_UNITS = [("AT", "at%", "Atomic percent of the first element"),
          ("WT", "wt%", "Weight percent of the first element (from the molar masses)")]
_UNITS_GOLD = _UNITS + [("KARAT", "karat", "Karat: 24 x the weight fraction of gold")]


def _units(self, context):
    return _UNITS_GOLD if self.karat_applies else _UNITS


class AlloycolorMaterialSettings(bpy.types.PropertyGroup):
    is_alloy: BoolProperty(default=False)
    system: StringProperty()
    element_a: StringProperty()
    element_b: StringProperty()
    molar_masses: bpy.props.FloatVectorProperty(size=2, default=(1.0, 1.0))
    x_min: FloatProperty(default=0.0)
    x_max: FloatProperty(default=1.0)
    karat_applies: BoolProperty(default=False)
    gold_element: bpy.props.IntProperty(default=-1)
    samples: StringProperty()
    x_atomic: FloatProperty(name="x", description="Atomic fraction of the first element")
    lookup_error: StringProperty()
    table_file: StringProperty(subtype="FILE_PATH")
    unit: EnumProperty(name="Unit", items=_units)
    at_percent: FloatProperty(name="Composition", description="Atomic percent of the first "
                              "element", min=PERCENT_RANGE[0], max=PERCENT_RANGE[1], precision=2,
                              update=_on_at)
    wt_percent: FloatProperty(name="Composition", description="Weight percent of the first "
                              "element", min=PERCENT_RANGE[0], max=PERCENT_RANGE[1], precision=2,
                              update=_on_wt)
    karat: FloatProperty(name="Karat", description="24 x the weight fraction of gold",
                         min=KARAT_RANGE[0], max=KARAT_RANGE[1], precision=2,
                         update=_on_karat)
    mode: EnumProperty(name="Mode", items=[
        ("TABLE", "Table", "Exact colour at every angle: the table on a mirror Glossy BSDF"),
        ("APPROXIMATE", "Approximate", "Principled BSDF, Metallic 1, Base Color = F0 (and the "
         "F82 tint from Blender 4.0)")], default="TABLE", update=_on_mode)


class AlloycolorPreferences(bpy.types.AddonPreferences):
    bl_idname = __name__
    program: StringProperty(name="alloycolor program", subtype="FILE_PATH",
                            description="The alloycolor program (empty: found on PATH)")

    def draw(self, context):
        self.layout.prop(self, "program")


class IMPORT_OT_alloycolor_table(bpy.types.Operator, ImportHelper):
    """Import an alloy material from an alloycolor table (.alloy-table.json)"""
    bl_idname = "import_scene.alloycolor_table"
    bl_label = "Alloy material (alloycolor table)"
    bl_options = {"REGISTER", "UNDO"}
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})
    from_model: BoolProperty(name="From a model file", default=False,
                             description="The file is a model (.model.json): run alloycolor "
                             "export --format blender-table on it first")

    def execute(self, context):
        try:
            if self.from_model:
                material = import_model(self.filepath, program_path(context), context)
            else:
                material = import_table(self.filepath, context)
        except (OSError, ValueError, KeyError) as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, "alloycolor: material " + material.name)
        return {"FINISHED"}


class MATERIAL_PT_alloycolor(bpy.types.Panel):
    bl_label = "Alloy (alloycolor)"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"

    @classmethod
    def poll(cls, context):
        material = context.material
        return material is not None and material.alloycolor.is_alloy

    def draw(self, context):
        s = context.material.alloycolor
        layout = self.layout
        layout.label(text="%s, %s from %.4g to %.4g at%%" % (
            s.system, s.element_a, 100 * s.x_min, 100 * s.x_max))
        layout.row().prop(s, "unit", expand=True)
        prop = {"AT": "at_percent", "WT": "wt_percent", "KARAT": "karat"}[s.unit]
        layout.prop(s, prop, text="%s (%s)" % (s.element_a if s.unit != "KARAT" else "Au",
                                               {"AT": "at%", "WT": "wt%", "KARAT": "karat"}[s.unit]))
        layout.row().prop(s, "mode", expand=True)
        layout.label(text="Table lookup: " + s.lookup_error)


def _menu(self, context):
    self.layout.operator(IMPORT_OT_alloycolor_table.bl_idname,
                         text="Alloy material (alloycolor table)")


_classes = (AlloycolorMaterialSettings, AlloycolorPreferences, IMPORT_OT_alloycolor_table,
            MATERIAL_PT_alloycolor)


def register():
    for cls in _classes:
        bpy.utils.register_class(cls)
    bpy.types.Material.alloycolor = PointerProperty(type=AlloycolorMaterialSettings)
    bpy.types.TOPBAR_MT_file_import.append(_menu)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(_menu)
    del bpy.types.Material.alloycolor
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
