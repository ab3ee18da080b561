// alloycolor export: n and k of a metal (measured, --nk) or of an alloy at one composition
// as the spectrum files and material definitions pbrt-v4 and Mitsuba 3 read for conductors,
// and as RGB conductors, F0 / F82 tint, Gulbrandsen's r / g, MaterialX and glTF materials.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/io.h"
#include "alloycolor/export/material_files.h"
#include "alloycolor/export/renderer_materials.h"
#include "alloycolor/export/spectral_export.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct ExportOptions {
  MaterialSource material;
  std::string format = "spd";
  std::string out;
  std::string scene_dir;
  double roughness = 0.0;
  bool json = false;
  bool quiet = false;
};

const std::vector<std::string> kFormats = {"spd",       "rgb-conductor", "f82", "gulbrandsen",
                                           "materialx", "gltf",          "all"};

std::string Triple(const color::RGB& c) {
  char buf[120];
  std::snprintf(buf, sizeof buf, "(%.4g, %.4g, %.4g)", c.r, c.g, c.b);
  return buf;
}

std::string Loss(const exports::AngularError& e) {
  char buf[120];
  std::snprintf(buf, sizeof buf,
                "largest CIEDE2000 against the spectral colour over 0-85 deg: %.3f (at %g deg)",
                e.max_delta_e00, e.at_angle_deg);
  return buf;
}

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

void Run(const ExportOptions& o) {
  bool known = false;
  for (const std::string& f : kFormats) known = known || f == o.format;
  if (!known) {
    throw Error("--format: unknown format '" + o.format +
                "' (spd, rgb-conductor, f82, gulbrandsen, materialx, gltf, all)");
  }
  if (o.out.empty()) throw Error("--out: give a file name prefix");
  if (!(o.roughness >= 0.0 && o.roughness <= 1.0)) {
    throw Error("--roughness: give a number in [0, 1]");
  }
  CheckOutputFolder(o.out, "--out");
  if (!o.scene_dir.empty() && !std::filesystem::is_directory(o.scene_dir)) {
    throw Error("--scene-dir: no folder " + o.scene_dir);
  }
  const color::Colorimeter d65 = LoadColorimeter("D65", 2);
  exports::ConductorSpectra spectra;
  std::vector<std::complex<double>> index;  // on d65's grid: the spectral truth
  std::string id;
  if (o.material.measured()) {
    const NkSpectrum nk = o.material.LoadMeasured(o.quiet);
    spectra = exports::MeasuredSpectra(nk, "measured n, k from " + o.material.nk_file);
    index = color::IndexOnGrid(d65, nk);
    std::string stem = o.material.nk_file.substr(o.material.nk_file.find_last_of('/') + 1);
    id = Identifier(stem.substr(0, stem.find_last_of('.')));
  } else {
    const auto model = o.material.LoadModel(o.quiet);
    const double x = o.material.Compositions(*model, true)[0];
    const AlloySystem& system = model->system();
    const std::string material =
        system.Name() + " at x = " + Format("%.6g", x) + " (atomic fraction of " + system.a.symbol +
        "; " + Format("%.4g", 100.0 * WeightFromAtomicFraction(x, system)) + " wt% " +
        system.a.symbol + "), " + model->method() + " model " +
        (o.material.source.model_path.empty() ? "built from data " + o.material.source.data_dir
                                     : "from " + o.material.source.model_path);
    spectra = exports::ModelSpectra(*model, x, material);
    index = color::IndexOnGrid(d65, *model, x);
    id = Identifier(system.Name() + "_x" + Format("%.6g", x));
  }
  const std::vector<std::string> header = {std::string("written by alloycolor ") +
                                           ALLOYCOLOR_VERSION};
  const bool all = o.format == "all";
  // Everything is formatted before the first file is written.
  std::vector<std::pair<std::string, std::string>> files;
  if (all || o.format == "spd") {
    const std::string eta_file = o.out + ".eta.spd";
    const std::string k_file = o.out + ".k.spd";
    const std::string eta_name = exports::SpectrumFileReference(eta_file, o.scene_dir);
    const std::string k_name = exports::SpectrumFileReference(k_file, o.scene_dir);
    const std::string names_note =
        o.scene_dir.empty()
            ? "spectrum file names are relative to this file's folder (the files sit side by "
              "side): load this file, or a scene in this folder"
            : "spectrum file names are relative to the scene folder " + o.scene_dir +
                  " (--scene-dir): load a scene file from that folder";
    files.emplace_back(eta_file, exports::SpdText(spectra, true, header));
    files.emplace_back(k_file, exports::SpdText(spectra, false, header));
    files.emplace_back(o.out + ".pbrt",
                       exports::PbrtMaterialText(spectra, eta_name, k_name, names_note, header));
    files.emplace_back(o.out + ".xml",
                       exports::MitsubaBsdfXml(spectra, id, eta_name, k_name, names_note, header));
  }
  const exports::RendererMaterials m = exports::FitRendererMaterials(d65, index, spectra.material);
  const nlohmann::json summary = exports::RendererMaterialsJson(m, spectra.material);
  const std::string generator = std::string("alloycolor ") + ALLOYCOLOR_VERSION;
  if (all || o.format == "rgb-conductor") {
    files.emplace_back(o.out + ".rgb.xml",
                       exports::MitsubaRgbConductorXml(m, spectra.material, id, header));
    files.emplace_back(o.out + ".blender.py",
                       exports::BlenderMetallicScript(m, spectra.material, id, header));
  }
  if (all || o.format == "f82") {
    nlohmann::json f82 = {
        {"material", spectra.material},
        {"colour_space", exports::kColorSpaceNote},
        {"f82_tint", summary["f82_tint"]},
        {"openpbr",
         {{"base_metalness", 1.0},
          {"base_color", summary["f82_tint"]["f0"]},
          {"specular_color", summary["f82_tint"]["tint"]}}},
        {"blender_metallic_f82",
         {{"Base Color", summary["f82_tint"]["f0"]}, {"Edge Tint", summary["f82_tint"]["tint"]}}},
        {"generator", generator}};
    files.emplace_back(o.out + ".f82.json", JsonText(f82, 2) + "\n");
  }
  if (all || o.format == "gulbrandsen") {
    const nlohmann::json& g = summary["gulbrandsen"];
    nlohmann::json out = {
        {"material", spectra.material},
        {"colour_space", exports::kColorSpaceNote},
        {"gulbrandsen", g},
        {"standard_surface",
         {{"metalness", 1.0}, {"base_color", g["r"]}, {"specular_color", g["g"]}}},
        {"materialx_artistic_ior", {{"reflectivity", g["r"]}, {"edge_color", g["g"]}}},
        {"generator", generator}};
    files.emplace_back(o.out + ".gulbrandsen.json", JsonText(out, 2) + "\n");
  }
  if (all || o.format == "materialx") {
    files.emplace_back(o.out + ".mtlx",
                       exports::MaterialXDocument(m, spectra.material, id, o.roughness, header));
  }
  if (all || o.format == "gltf") {
    files.emplace_back(o.out + ".gltf",
                       exports::GltfMaterial(m, spectra.material, id, o.roughness, generator));
  }
  if (!o.quiet) {
    for (const std::string& note : spectra.notes) Warn(note);
  }
  std::vector<OutputFile> outputs;
  for (const auto& [path, text] : files) outputs.push_back({path, text});
  WriteOutputs(outputs, o.quiet);
  if (!o.quiet && o.format != "spd") {
    const auto& c = m.rgb_conductor;
    std::cerr << "alloycolor: colours in " << exports::kColorSpaceNote << "\n";
    std::cerr << "alloycolor: rgb-conductor eta " << Triple(c.eta) << " k " << Triple(c.k) << "; "
              << Loss(c.error) << "\n";
    std::cerr << "alloycolor: f82 F0 " << Triple(m.f82.f0) << " F82 " << Triple(m.f82.f82)
              << " tint " << Triple(m.f82.tint) << "; " << Loss(m.f82.error) << "\n";
    std::cerr << "alloycolor: gulbrandsen r " << Triple(m.gulbrandsen.r) << " g "
              << Triple(m.gulbrandsen.g) << "; " << Loss(m.gulbrandsen.error) << "\n";
    std::cerr << "alloycolor: gltf (Schlick from F0) " << Loss(m.f82.schlick_error) << "\n";
  }
  if (o.json) {
    nlohmann::json out = summary;
    out["format"] = o.format;
    nlohmann::json written = nlohmann::json::array();
    for (const auto& file : files) written.push_back(file.first);
    out["files"] = written;
    PrintOutput(JsonText(out, 2) + "\n");
  }
}

}  // namespace

void RegisterExport(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Materials for renderers from measured n, k (--nk FILE) or an alloy at one composition "
      "--x (--model or --data). --format spd: PREFIX.eta.spd and PREFIX.k.spd (wavelength_nm "
      "value per line, 360-830 nm, end values held where the data stop short, as comment lines "
      "say), PREFIX.pbrt (pbrt-v4 conductor) and PREFIX.xml (Mitsuba 3 conductor), naming the "
      ".spd files relative to their own folder (or --scene-dir). The other formats reduce the "
      "spectral colour to linear sRGB (Rec. 709, D65; truth under D65, 2-degree observer): "
      "rgb-conductor (PREFIX.rgb.xml for Mitsuba 3 RGB variants, PREFIX.blender.py for "
      "Blender's Metallic BSDF), f82 (PREFIX.f82.json: F0, F82 and the OpenPBR F82 tint), "
      "gulbrandsen (PREFIX.gulbrandsen.json: r, g for Standard Surface and artistic_ior), "
      "materialx (PREFIX.mtlx, conductor_bsdf), gltf (PREFIX.gltf), all (every file). Each "
      "approximation's largest CIEDE2000 difference from the spectral colour over 0-85 "
      "degrees is printed on stderr (and with --json on stdout).");
  o->material.AddOptions(cmd, "Composition of the system's first element: 0.75, 75at%, 75wt%, 18k");
  cmd->add_option("--format", o->format,
                  "spd, rgb-conductor, f82, gulbrandsen, materialx, gltf or all")
      ->capture_default_str();
  cmd->add_option("--out", o->out,
                  "Output prefix: PREFIX.eta.spd, PREFIX.k.spd, PREFIX.pbrt, PREFIX.xml (spd), "
                  "PREFIX.rgb.xml, PREFIX.blender.py, PREFIX.f82.json, PREFIX.gulbrandsen.json, "
                  "PREFIX.mtlx, PREFIX.gltf")
      ->required();
  cmd->add_option("--scene-dir", o->scene_dir,
                  "spd: write the .spd names relative to this folder, where the scene file that "
                  "includes the material lives (pbrt-v4 and Mitsuba 3 resolve names against the "
                  "main scene file's folder); default: the names alone, beside the material "
                  "files");
  cmd->add_option("--roughness", o->roughness,
                  "materialx, gltf: the material's roughness in [0, 1] (0: polished)")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Every fitted number and error as JSON on stdout");
  cmd->add_flag("--quiet", o->quiet, "No warnings, values or progress on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
