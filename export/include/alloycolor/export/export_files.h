// Every file `alloycolor export` writes, built here once for every face (the program, the
// Python package), from a material and an output prefix:
//  - spd: PREFIX.eta.spd, PREFIX.k.spd, PREFIX.pbrt, PREFIX.xml (spectral_export.h);
//  - rgb-conductor: PREFIX.rgb.xml (Mitsuba 3 RGB), PREFIX.blender.py (material_files.h);
//  - f82: PREFIX.f82.json: F0, F82 and the tint (renderer_materials.h) with the settings
//    that carry them, OpenPBR (base_metalness 1, base_color = F0, specular_color = tint)
//    and Blender's Metallic BSDF in F82 mode (Base Color, Edge Tint);
//  - gulbrandsen: PREFIX.gulbrandsen.json: r and g with Standard Surface (metalness 1,
//    base_color = r, specular_color = g) and MaterialX artistic_ior (reflectivity = r,
//    edge_color = g);
//  - materialx: PREFIX.mtlx; gltf: PREFIX.gltf; all: every file above, in that order;
//  - blender-table: the alloy over its whole composition range, not at one composition
//    (an alloy only, not in "all"): PREFIX.alloy-table.png and PREFIX.alloy-table.json,
//    the Blender add-on's table (blender_table.h).
// Nothing is written here: the face writes the files as a set (core/output.h).
#ifndef ALLOYCOLOR_EXPORT_EXPORT_FILES_H_
#define ALLOYCOLOR_EXPORT_EXPORT_FILES_H_

#include <complex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/output.h"
#include "alloycolor/core/spectrum.h"
#include "alloycolor/export/renderer_materials.h"
#include "alloycolor/export/spectral_export.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::exports {

// "spd", "rgb-conductor", "f82", "gulbrandsen", "materialx", "gltf", "all", "blender-table".
const std::vector<std::string>& ExportFormats();
// Whether a format describes the model over its whole range (the composition is ignored).
bool ExportFormatCoversRange(const std::string& format);

// What is exported: n and k for the spectral files, n + ik on the D65 colorimeter's grid
// (the truth the RGB reductions are fitted to), and the identifier material files give it.
struct ExportMaterial {
  ConductorSpectra spectra;
  std::vector<std::complex<double>> index;
  std::string id;
  // An alloy's model (not owned: it must outlive the material) and its description
  // without the composition; null and empty for a measured metal.
  const AlloyModel* model = nullptr;
  std::string model_description;
};

// How export files describe an alloy at x_atomic: "Au-Ag at x = 0.75 (atomic fraction of
// Au; 84.56 wt% Au), paper model " + origin, origin saying where the model came from
// ("from m.json", "built from data Au-Ag").
std::string AlloyDescription(const AlloyModel& model, double x_atomic, const std::string& origin);

// An alloy at x_atomic, described as above. `d65` must be a D65, 2-degree colorimeter.
ExportMaterial AlloyExportMaterial(const color::Colorimeter& d65, const AlloyModel& model,
                                   double x_atomic, const std::string& origin);
// A measured metal; nk.source (its file) names it.
ExportMaterial MeasuredExportMaterial(const color::Colorimeter& d65, const NkSpectrum& nk);

struct ExportSettings {
  std::string format = "spd";  // one of ExportFormats()
  std::string scene_dir;       // spd: name the .spd files relative to it (empty: side by side)
  double roughness = 0.0;      // materialx, gltf: in [0, 1]
};

// Each check throws Error saying what is wrong, after `name`: the name the face gives the
// setting ("--format", "format").
void CheckExportFormat(const std::string& format, const std::string& name);
void CheckExportSceneDir(const std::string& scene_dir, const std::string& name);
void CheckExportRoughness(double roughness, const std::string& name);

struct ExportFiles {
  std::vector<OutputFile> files;  // in the order above
  RendererMaterials materials;    // empty for blender-table
  // `alloycolor export --json`: RendererMaterialsJson with "format" and "files" (the paths);
  // for blender-table the table's sizes and "lookup_error" instead of the materials.
  nlohmann::json summary;
};

// The files for `prefix` (a path without the suffixes). Throws Error for a bad setting
// (named "format", "scene_dir" or "roughness") or a material the files cannot hold
// (blender-table of a measured metal).
ExportFiles BuildExport(const color::Colorimeter& d65, const ExportMaterial& material,
                        const std::string& prefix, const ExportSettings& settings);

}  // namespace alloycolor::exports

#endif  // ALLOYCOLOR_EXPORT_EXPORT_FILES_H_
