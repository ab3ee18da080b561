// alloycolor export: n and k of a metal (measured, --nk) or of an alloy at one composition
// as the spectrum files and material definitions pbrt-v4 and Mitsuba 3 read for conductors,
// and as RGB conductors, F0 / F82 tint, Gulbrandsen's r / g, MaterialX and glTF materials.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/text.h"
#include "alloycolor/export/export_files.h"
#include "alloycolor/export/material_files.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct ExportOptions {
  MaterialSource material;
  std::string out;
  exports::ExportSettings settings;
  bool json = false;
  bool quiet = false;
};

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

void Run(const ExportOptions& o) {
  exports::CheckExportFormat(o.settings.format, "--format");
  if (o.out.empty()) throw Error("--out: give a file name prefix");
  if (o.out.back() == '/' || std::filesystem::is_directory(o.out)) {
    std::string folder = o.out;
    while (folder.size() > 1 && folder.back() == '/') folder.pop_back();
    throw Error("--out " + Quote(o.out, 100) +
                " names a folder: --out is a file name prefix, e.g. " +
                (folder == "/" ? "" : folder) + "/au18k");
  }
  exports::CheckExportRoughness(o.settings.roughness, "--roughness");
  CheckOutputFolder(o.out, "--out");
  exports::CheckExportSceneDir(o.settings.scene_dir, "--scene-dir");
  const color::Colorimeter d65 = LoadColorimeter("D65", 2);
  exports::ExportMaterial material;
  std::unique_ptr<const AlloyModel> model;  // outlives the material, which points to it
  if (o.material.measured()) {
    material = exports::MeasuredExportMaterial(d65, o.material.LoadMeasured(o.quiet));
  } else {
    // A format over the whole range needs no --x (and ignores one).
    const bool whole_range = exports::ExportFormatCoversRange(o.settings.format);
    model = o.material.LoadModel(o.quiet, !whole_range);
    const ModelSource& source = o.material.source;
    const double x = whole_range ? model->x_min() : o.material.Compositions(*model, true)[0];
    material = exports::AlloyExportMaterial(d65, *model, x,
                                            source.model_path.empty()
                                                ? "built from data " + source.data_dir
                                                : "from " + source.model_path);
  }
  // Everything is formatted before the first file is written.
  const exports::ExportFiles e = exports::BuildExport(d65, material, o.out, o.settings);
  if (!o.quiet) {
    for (const std::string& note : material.spectra.notes) Warn(note);
  }
  WriteOutputs(e.files, o.quiet);
  if (!o.quiet && exports::ExportFormatCoversRange(o.settings.format)) {
    const nlohmann::json& error = e.summary["lookup_error"];
    std::cerr << "alloycolor: table " << e.summary["columns"] << " x " << e.summary["rows"]
              << " (composition x mu); bilinear lookup against direct evaluation at "
              << error["check_points"] << " points between texels: largest CIEDE2000 "
              << error["max_delta_e00"].get<double>() << ", largest 8-bit sRGB difference "
              << error["max_srgb8_difference"] << "\n";
  } else if (!o.quiet && o.settings.format != "spd") {
    const exports::RendererMaterials& m = e.materials;
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
  if (o.json) PrintOutput(JsonText(e.summary, 2) + "\n");
}

}  // namespace

void RegisterExport(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export", "Materials for renderers (pbrt, Mitsuba, Blender, OpenPBR, MaterialX, glTF)");
  cmd->footer(
      "Materials for renderers from measured n, k (--nk FILE) or an alloy at one composition "
      "--x (--model or --data). --format spd: PREFIX.eta.spd and PREFIX.k.spd (wavelength_nm "
      "value per line, 360-830 nm, end values held where the data stop short, as comment lines "
      "say), PREFIX.pbrt (pbrt-v4 conductor) and PREFIX.xml (Mitsuba 3 conductor), naming the "
      ".spd files relative to their own folder (or --scene-dir). The other formats reduce the "
      "spectral colour to linear sRGB (Rec. 709, D65; truth under D65, 2-degree observer): "
      "rgb-conductor (PREFIX.rgb.xml for Mitsuba 3 RGB variants, PREFIX.blender.py for "
      "Blender's Metallic BSDF), f82 (PREFIX.f82.json: F0, F82 and the OpenPBR F82 tint), "
      "gulbrandsen (PREFIX.gulbrandsen.json: r, g for Standard Surface and artistic_ior), "
      "materialx (PREFIX.mtlx, conductor_bsdf), gltf (PREFIX.gltf), all (every file above); "
      "blender-table (an alloy's whole range, --x not needed: PREFIX.alloy-table.png and "
      "PREFIX.alloy-table.json for the Blender add-on, docs/blender.md). Each "
      "approximation's largest CIEDE2000 difference from the spectral colour over 0-85 "
      "degrees is printed on stderr (and with --json on stdout).");
  o->material.AddOptions(cmd, "Composition of the system's first element: 0.75, 75at%, 75wt%, 18k");
  cmd->add_option("--format", o->settings.format,
                  "spd, rgb-conductor, f82, gulbrandsen, materialx, gltf, all or blender-table")
      ->capture_default_str();
  cmd->add_option("--out", o->out,
                  "Output prefix: PREFIX.eta.spd, PREFIX.k.spd, PREFIX.pbrt, PREFIX.xml (spd), "
                  "PREFIX.rgb.xml, PREFIX.blender.py, PREFIX.f82.json, PREFIX.gulbrandsen.json, "
                  "PREFIX.mtlx, PREFIX.gltf, PREFIX.alloy-table.png and .json")
      ->required();
  cmd->add_option("--scene-dir", o->settings.scene_dir,
                  "spd: write the .spd names relative to this folder, where the scene file that "
                  "includes the material lives (pbrt-v4 and Mitsuba 3 resolve names against the "
                  "main scene file's folder); default: the names alone, beside the material "
                  "files");
  cmd->add_option("--roughness", o->settings.roughness,
                  "materialx, gltf: the material's roughness in [0, 1] (0: polished)")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Every fitted number and error as JSON on stdout");
  cmd->add_flag("--quiet", o->quiet, "No warnings, values or progress on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
