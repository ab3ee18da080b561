#include "alloycolor/export/material_files.h"

#include <algorithm>
#include <cstdio>

#include "alloycolor/core/json.h"
#include "alloycolor/core/markup.h"
#include "text.h"

namespace alloycolor::exports {
namespace {

using text::OneLine;
using text::XmlComment;

nlohmann::json Array(const color::RGB& c) { return nlohmann::json::array({c.r, c.g, c.b}); }

nlohmann::json ErrorJson(const AngularError& e) {
  return {{"max_delta_e00", e.max_delta_e00}, {"at_angle_deg", e.at_angle_deg}};
}

// Six significant digits, separated by `separator`.
std::string Triple(const color::RGB& c, const char* separator) {
  char buf[120];
  std::snprintf(buf, sizeof buf, "%.6g%s%.6g%s%.6g", c.r, separator, c.g, separator, c.b);
  return buf;
}

std::string DeltaText(const AngularError& e) {
  char buf[80];
  std::snprintf(buf, sizeof buf, "%.3g (at %g deg)", e.max_delta_e00, e.at_angle_deg);
  return buf;
}

// A name made of letters, digits and '_', not starting with a digit (MaterialX names,
// Python identifiers).
std::string Identifier(const std::string& name) {
  std::string id;
  for (char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    id += keep ? c : '_';
  }
  if (id.empty() || (id[0] >= '0' && id[0] <= '9')) id = "m_" + id;
  return id;
}

// A Python string literal.
std::string PythonString(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '\\' || c == '"') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string FitLine(const RendererMaterials& m) {
  return "RGB eta, k fitted per channel to the spectral Fresnel colour over 0-85 deg (" +
         m.rgb_conductor.fit + "); largest CIEDE2000 against the spectral colour " +
         DeltaText(m.rgb_conductor.error);
}

}  // namespace

nlohmann::json RendererMaterialsJson(const RendererMaterials& m, const std::string& material) {
  nlohmann::json r;
  r["material"] = material;
  r["colour_space"] = kColorSpaceNote;
  r["angles_deg"] = {m.angle_deg.front(), m.angle_deg.back(), kAngleStepDeg};
  r["rgb_conductor"] = {{"eta", Array(m.rgb_conductor.eta)},
                        {"k", Array(m.rgb_conductor.k)},
                        {"fit", m.rgb_conductor.fit},
                        {"error", ErrorJson(m.rgb_conductor.error)}};
  r["f82_tint"] = {{"f0", Array(m.f82.f0)},
                   {"f82", Array(m.f82.f82)},
                   {"tint", Array(m.f82.tint)},
                   {"fit",
                    "F0 and F82 are the spectral Fresnel colour at 0 and 82 deg; tint = F82 / "
                    "Schlick(F0, cos 82 deg); error of OpenPBR's F82-tint curve (mu_bar = 1/7)"},
                   {"error", ErrorJson(m.f82.error)}};
  r["schlick_f0"] = {{"f0", Array(m.f82.f0)},
                     {"fit", "Schlick's curve from F0 alone (glTF metal)"},
                     {"error", ErrorJson(m.f82.schlick_error)}};
  nlohmann::json clamped_r = nlohmann::json::array(), clamped_g = nlohmann::json::array();
  for (int c = 0; c < 3; ++c) {
    clamped_r.push_back(m.gulbrandsen.r_clamped[c]);
    clamped_g.push_back(m.gulbrandsen.g_clamped[c]);
  }
  r["gulbrandsen"] = {
      {"r", Array(m.gulbrandsen.r)},
      {"g", Array(m.gulbrandsen.g)},
      {"r_clamped", clamped_r},
      {"g_clamped", clamped_g},
      {"fit",
       "r = F0 (held in [0, 0.99]); g solved so that Gulbrandsen's conductor has the "
       "spectral colour at 82 deg"},
      {"error", ErrorJson(m.gulbrandsen.error)}};
  return r;
}

std::string MitsubaRgbConductorXml(const RendererMaterials& m, const std::string& material,
                                   const std::string& id, const std::vector<std::string>& header) {
  std::string out = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
  out += XmlComment("Mitsuba 3 RGB variants, smooth conductor: " + material);
  out += XmlComment(std::string("eta, k in ") + kColorSpaceNote);
  out += XmlComment(FitLine(m));
  for (const std::string& line : header) out += XmlComment(line);
  out += "<bsdf type=\"conductor\" id=\"" + EscapeXml(id) + "\" version=\"3.0.0\">\n";
  out += "    <rgb name=\"eta\" value=\"" + Triple(m.rgb_conductor.eta, ", ") + "\"/>\n";
  out += "    <rgb name=\"k\" value=\"" + Triple(m.rgb_conductor.k, ", ") + "\"/>\n";
  out += "</bsdf>\n";
  return out;
}

// The script picks the best node the running Blender has, by feature, not by a version
// number: the Metallic BSDF with the physical-conductor Fresnel (Blender 4.2 on); else the
// Principled BSDF with Metallic 1, Base Color = F0 and, from Blender 4.0 (whose metallic
// Fresnel is F82-tint), Specular Tint = the F82 tint; else (Blender 2.80 to 3.6) the
// Principled BSDF with Base Color = F0, Schlick's Fresnel. Older than 2.80 it stops with
// one line naming the version it needs. Each branch's largest CIEDE2000 is in its comment.
std::string BlenderMetallicScript(const RendererMaterials& m, const std::string& material,
                                  const std::string& name, const std::vector<std::string>& header) {
  std::string out;
  const auto comment = [&out](const std::string& line) { out += "# " + OneLine(line) + "\n"; };
  comment("Blender 2.80 or later: a material for " + material +
          " with the best conductor node the running Blender has");
  comment(std::string("values in ") + kColorSpaceNote);
  comment("Blender 4.2 on: Metallic BSDF, physical conductor; " + FitLine(m));
  comment(
      "Blender 4.0-4.1: Principled BSDF, Metallic 1, Base Color = F0, Specular Tint = F82 tint "
      "(F82-tint Fresnel), largest CIEDE2000 " +
      DeltaText(m.f82.error));
  comment(
      "Blender 2.80-3.6: Principled BSDF, Metallic 1, Base Color = F0 (Schlick's Fresnel), "
      "largest CIEDE2000 " +
      DeltaText(m.f82.schlick_error));
  for (const std::string& line : header) comment(line);
  const std::string f0 = "(" + Triple(m.f82.f0, ", ") + ", 1.0)";
  out += "import bpy\n\n";
  out += "if bpy.app.version < (2, 80, 0):\n";
  out +=
      "    raise RuntimeError(\"this material script needs Blender 2.80 or later (Principled "
      "BSDF); this is Blender %d.%d\" % bpy.app.version[:2])\n\n";
  out += "material = bpy.data.materials.new(" + PythonString(name) + ")\n";
  out += "material.use_nodes = True\n";
  out += "nodes = material.node_tree.nodes\n";
  out += "for node in [n for n in nodes if n.type != \"OUTPUT_MATERIAL\"]:\n";
  out += "    nodes.remove(node)\n";
  out += "if hasattr(bpy.types, \"ShaderNodeBsdfMetallic\"):\n";
  out += "    metal = nodes.new(\"ShaderNodeBsdfMetallic\")\n";
  out += "    metal.fresnel_type = \"PHYSICAL_CONDUCTOR\"\n";
  out += "    metal.inputs[\"IOR\"].default_value = (" + Triple(m.rgb_conductor.eta, ", ") + ")\n";
  out += "    metal.inputs[\"Extinction\"].default_value = (" + Triple(m.rgb_conductor.k, ", ") +
         ")\n";
  out += "    metal.inputs[\"Roughness\"].default_value = 0.0\n";
  out += "    # metal.fresnel_type = \"F82\"\n";
  out += "    # metal.inputs[\"Base Color\"].default_value = " + f0 + "\n";
  out +=
      "    # metal.inputs[\"Edge Tint\"].default_value = (" + Triple(m.f82.tint, ", ") + ", 1.0)\n";
  out += "else:\n";
  out += "    metal = nodes.new(\"ShaderNodeBsdfPrincipled\")\n";
  out += "    metal.inputs[\"Base Color\"].default_value = " + f0 + "\n";
  out += "    metal.inputs[\"Metallic\"].default_value = 1.0\n";
  out += "    metal.inputs[\"Roughness\"].default_value = 0.0\n";
  out += "    if bpy.app.version >= (4, 0, 0):\n";
  out += "        metal.inputs[\"Specular Tint\"].default_value = (" + Triple(m.f82.tint, ", ") +
         ", 1.0)\n";
  out += "output = nodes.get(\"Material Output\") or nodes.new(\"ShaderNodeOutputMaterial\")\n";
  out += "material.node_tree.links.new(metal.outputs[\"BSDF\"], output.inputs[\"Surface\"])\n";
  return out;
}

std::string MaterialXDocument(const RendererMaterials& m, const std::string& material,
                              const std::string& name, double roughness,
                              const std::vector<std::string>& header) {
  const std::string id = Identifier(name);
  char rough[64];
  std::snprintf(rough, sizeof rough, "%.6g, %.6g", roughness, roughness);
  std::string out = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
  out += "<materialx version=\"1.38\" colorspace=\"lin_rec709\">\n";
  out += "  " + XmlComment("conductor for " + material);
  out += "  " + XmlComment(std::string("colours in ") + kColorSpaceNote);
  out += "  " + XmlComment(FitLine(m));
  out +=
      "  " + XmlComment("artistic_ior alternative: reflectivity " + Triple(m.gulbrandsen.r, ", ") +
                        ", edge_color " + Triple(m.gulbrandsen.g, ", ") + "; largest CIEDE2000 " +
                        DeltaText(m.gulbrandsen.error));
  for (const std::string& line : header) out += "  " + XmlComment(line);
  out += "  <conductor_bsdf name=\"" + id + "_bsdf\" type=\"BSDF\">\n";
  out += "    <input name=\"weight\" type=\"float\" value=\"1\" />\n";
  out += "    <input name=\"ior\" type=\"color3\" value=\"" + Triple(m.rgb_conductor.eta, ", ") +
         "\" />\n";
  out += "    <input name=\"extinction\" type=\"color3\" value=\"" +
         Triple(m.rgb_conductor.k, ", ") + "\" />\n";
  out += std::string("    <input name=\"roughness\" type=\"vector2\" value=\"") + rough + "\" />\n";
  out += "  </conductor_bsdf>\n";
  out += "  <surface name=\"" + id + "_surface\" type=\"surfaceshader\">\n";
  out += "    <input name=\"bsdf\" type=\"BSDF\" nodename=\"" + id + "_bsdf\" />\n";
  out += "  </surface>\n";
  out += "  <surfacematerial name=\"" + id + "\" type=\"material\">\n";
  out += "    <input name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"" + id +
         "_surface\" />\n";
  out += "  </surfacematerial>\n";
  out += "</materialx>\n";
  return out;
}

std::string GltfMaterial(const RendererMaterials& m, const std::string& material,
                         const std::string& name, double roughness, const std::string& generator) {
  const color::RGB f0 = m.f82.f0;
  const color::RGB base{std::clamp(f0.r, 0.0, 1.0), std::clamp(f0.g, 0.0, 1.0),
                        std::clamp(f0.b, 0.0, 1.0)};
  nlohmann::json extras = {
      {"material", material},
      {"colour_space", kColorSpaceNote},
      {"fit",
       "baseColorFactor = F0, the spectral Fresnel colour at normal incidence; glTF "
       "renders Schlick's curve from it"},
      {"f0_unclamped", Array(f0)},
      {"max_delta_e00_0_85_deg", m.f82.schlick_error.max_delta_e00}};
  if (base.r != f0.r || base.g != f0.g || base.b != f0.b) {
    extras["note"] = "F0 lies outside [0, 1] in a channel: baseColorFactor is clamped";
  }
  nlohmann::json doc = {
      {"asset", {{"version", "2.0"}, {"generator", generator}}},
      {"materials", nlohmann::json::array({{{"name", name},
                                            {"pbrMetallicRoughness",
                                             {{"baseColorFactor", {base.r, base.g, base.b, 1.0}},
                                              {"metallicFactor", 1.0},
                                              {"roughnessFactor", roughness}}},
                                            {"extras", extras}}})}};
  return JsonText(doc, 2) + "\n";
}

}  // namespace alloycolor::exports
