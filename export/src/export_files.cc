#include "alloycolor/export/export_files.h"

#include <cstdio>
#include <filesystem>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/json.h"
#include "alloycolor/export/blender_table.h"
#include "alloycolor/export/material_files.h"

namespace alloycolor::exports {
namespace {

std::string Format(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

// A Mitsuba object id from a description: letters, digits, '-', '_' and '.'.
std::string Identifier(const std::string& text) {
  std::string id = "alloycolor_";
  for (char c : text) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '-' || c == '.';
    id += keep ? c : '_';
  }
  return id;
}

// PREFIX.eta.spd, PREFIX.k.spd, PREFIX.pbrt, PREFIX.xml.
void AddSpectralFiles(const ExportMaterial& material, const std::string& prefix,
                      const std::string& scene_dir, const std::vector<std::string>& header,
                      std::vector<OutputFile>* files) {
  const ConductorSpectra& spectra = material.spectra;
  const std::string eta_file = prefix + ".eta.spd";
  const std::string k_file = prefix + ".k.spd";
  const std::string eta_name = SpectrumFileReference(eta_file, scene_dir);
  const std::string k_name = SpectrumFileReference(k_file, scene_dir);
  const std::string names_note =
      scene_dir.empty()
          ? "spectrum file names are relative to this file's folder (the files sit side by "
            "side): load this file, or a scene in this folder"
          : "spectrum file names are relative to the scene folder " + scene_dir +
                " (--scene-dir): load a scene file from that folder";
  files->push_back({eta_file, SpdText(spectra, true, header)});
  files->push_back({k_file, SpdText(spectra, false, header)});
  files->push_back(
      {prefix + ".pbrt", PbrtMaterialText(spectra, eta_name, k_name, names_note, header)});
  files->push_back({prefix + ".xml",
                    MitsubaBsdfXml(spectra, material.id, eta_name, k_name, names_note, header)});
}

nlohmann::json F82Document(const std::string& material, const nlohmann::json& summary,
                           const std::string& generator) {
  const nlohmann::json& f82 = summary["f82_tint"];
  return {{"material", material},
          {"colour_space", kColorSpaceNote},
          {"f82_tint", f82},
          {"openpbr",
           {{"base_metalness", 1.0}, {"base_color", f82["f0"]}, {"specular_color", f82["tint"]}}},
          {"blender_metallic_f82", {{"Base Color", f82["f0"]}, {"Edge Tint", f82["tint"]}}},
          {"generator", generator}};
}

nlohmann::json GulbrandsenDocument(const std::string& material, const nlohmann::json& summary,
                                   const std::string& generator) {
  const nlohmann::json& g = summary["gulbrandsen"];
  return {{"material", material},
          {"colour_space", kColorSpaceNote},
          {"gulbrandsen", g},
          {"standard_surface",
           {{"metalness", 1.0}, {"base_color", g["r"]}, {"specular_color", g["g"]}}},
          {"materialx_artistic_ior", {{"reflectivity", g["r"]}, {"edge_color", g["g"]}}},
          {"generator", generator}};
}

}  // namespace

const std::vector<std::string>& ExportFormats() {
  static const std::vector<std::string> formats = {
      "spd", "rgb-conductor", "f82", "gulbrandsen", "materialx", "gltf", "all", "blender-table"};
  return formats;
}

bool ExportFormatCoversRange(const std::string& format) { return format == "blender-table"; }

std::string AlloyDescription(const AlloyModel& model, double x_atomic, const std::string& origin) {
  const AlloySystem& system = model.system();
  return system.Name() + " at x = " + Format("%.6g", x_atomic) + " (atomic fraction of " +
         system.a.symbol + "; " +
         Format("%.4g", 100.0 * WeightFromAtomicFraction(x_atomic, system)) + " wt% " +
         system.a.symbol + "), " + model.method() + " model " + origin;
}

ExportMaterial AlloyExportMaterial(const color::Colorimeter& d65, const AlloyModel& model,
                                   double x_atomic, const std::string& origin) {
  return {ModelSpectra(model, x_atomic, AlloyDescription(model, x_atomic, origin)),
          color::IndexOnGrid(d65, model, x_atomic),
          Identifier(model.system().Name() + "_x" + Format("%.6g", x_atomic)), &model,
          model.system().Name() + ", " + model.method() + " model " + origin};
}

ExportMaterial MeasuredExportMaterial(const color::Colorimeter& d65, const NkSpectrum& nk) {
  const std::string stem = nk.source.substr(nk.source.find_last_of('/') + 1);
  return {MeasuredSpectra(nk, "measured n, k from " + nk.source), color::IndexOnGrid(d65, nk),
          Identifier(stem.substr(0, stem.find_last_of('.')))};
}

void CheckExportFormat(const std::string& format, const std::string& name) {
  std::string names;
  for (const std::string& f : ExportFormats()) {
    if (f == format) return;
    names += (names.empty() ? "" : ", ") + f;
  }
  throw Error(name + ": unknown format '" + format + "' (" + names + ")");
}

void CheckExportSceneDir(const std::string& scene_dir, const std::string& name) {
  if (!scene_dir.empty() && !std::filesystem::is_directory(scene_dir)) {
    throw Error(name + ": no folder " + scene_dir);
  }
}

void CheckExportRoughness(double roughness, const std::string& name) {
  if (!(roughness >= 0.0 && roughness <= 1.0)) {
    throw Error(name + ": " + Format("%g", roughness) + " is not a number in [0, 1]");
  }
}

ExportFiles BuildExport(const color::Colorimeter& d65, const ExportMaterial& material,
                        const std::string& prefix, const ExportSettings& settings) {
  CheckExportFormat(settings.format, "format");
  CheckExportSceneDir(settings.scene_dir, "scene_dir");
  CheckExportRoughness(settings.roughness, "roughness");
  if (prefix.empty()) throw Error("export: give a file name prefix");
  const std::string generator = std::string("alloycolor ") + ALLOYCOLOR_VERSION;
  const std::vector<std::string> header = {"written by " + generator};
  const std::string& name = material.spectra.material;
  const auto wanted = [&settings](const char* format) {
    return settings.format == "all" || settings.format == format;
  };
  ExportFiles out;
  if (settings.format == "blender-table") {
    if (material.model == nullptr) {
      throw Error("format blender-table: needs an alloy's model, not measured n, k (" + name + ")");
    }
    const BlenderTable table = BuildBlenderTable(d65, *material.model, {});
    out.files = BlenderTableFiles(table, prefix, material.model_description, generator);
    out.summary = {{"material", material.model_description},
                   {"x_range", {table.x_min, table.x_max}},
                   {"columns", table.columns},
                   {"rows", table.rows},
                   {"lookup_error",
                    {{"max_delta_e00", table.max_de00},
                     {"max_srgb8_difference", table.max_srgb8_difference},
                     {"check_points", table.check_points}}}};
  }
  if (wanted("spd")) AddSpectralFiles(material, prefix, settings.scene_dir, header, &out.files);
  if (settings.format != "blender-table") {
    out.materials = FitRendererMaterials(d65, material.index, name);
    out.summary = RendererMaterialsJson(out.materials, name);
  }
  const RendererMaterials& m = out.materials;
  if (wanted("rgb-conductor")) {
    out.files.push_back(
        {prefix + ".rgb.xml", MitsubaRgbConductorXml(m, name, material.id, header)});
    out.files.push_back(
        {prefix + ".blender.py", BlenderMetallicScript(m, name, material.id, header)});
  }
  if (wanted("f82")) {
    out.files.push_back(
        {prefix + ".f82.json", JsonText(F82Document(name, out.summary, generator), 2) + "\n"});
  }
  if (wanted("gulbrandsen")) {
    out.files.push_back({prefix + ".gulbrandsen.json",
                         JsonText(GulbrandsenDocument(name, out.summary, generator), 2) + "\n"});
  }
  if (wanted("materialx")) {
    out.files.push_back(
        {prefix + ".mtlx", MaterialXDocument(m, name, material.id, settings.roughness, header)});
  }
  if (wanted("gltf")) {
    out.files.push_back(
        {prefix + ".gltf", GltfMaterial(m, name, material.id, settings.roughness, generator)});
  }
  out.summary["format"] = settings.format;
  out.summary["files"] = nlohmann::json::array();
  for (const OutputFile& file : out.files) out.summary["files"].push_back(file.path);
  return out;
}

}  // namespace alloycolor::exports
