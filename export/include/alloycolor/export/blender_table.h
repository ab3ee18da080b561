// The reflection colour of an alloy against composition and angle, baked into an image
// that a Blender material looks up (the add-on in blender/alloycolor_material).
//
// The colour is the explorer page's: render::BuildCompositionTable (D65, 2-degree
// observer, roughness 0), the XYZ of sum_l w(l) R(l, mu) with R = (Rs + Rp) / 2 of eq. 2-4
// and w the colorimeter's weights of eq. 5, converted to linear sRGB (IEC 61966-2-1). The
// image resamples that table, with its own interpolation (InterpolateCompositionTable), at
//   column i: x_i = x_min + i (x_max - x_min) / (columns - 1),  i = 0..columns-1,
//   row m:    mu_m = m / (rows - 1),                             m = 0..rows-1,
// row 0 at the bottom (Blender's v grows upward; the PNG's first row is mu = 1). Blender
// samples texel i at u = (i + 1/2) / columns and interpolates bilinearly (Linear,
// Extension EXTEND), so the material reads
//   u = (1/2 + (x - x_min) / (x_max - x_min) (columns - 1)) / columns,
//   v = (1/2 + mu (rows - 1)) / rows.
// Samples are linear sRGB clamped to [0, 1] (an 8-bit sRGB render clips them there too)
// and stored as 16-bit integers, with no colour chunks: the image is data (Non-Color).
//
// Accuracy. That lookup, on the quantised samples, is compared with direct spectral
// evaluation (render::DirectReflection) at every midpoint between columns crossed with
// every row and every midpoint between rows, and at every column crossed with every
// midpoint between rows: the largest CIEDE2000 (Lab with the D65 white, both colours
// clamped to the sRGB gamut) and the largest difference of 8-bit sRGB values are measured
// figures, not bounds.
//
// For Principled BSDF's metallic mode, F0 (mu = 1) and the F82 tint
// (renderer_materials.h: tint = F82 / Schlick(F0, cos 82 deg)) at every column.
#ifndef ALLOYCOLOR_EXPORT_BLENDER_TABLE_H_
#define ALLOYCOLOR_EXPORT_BLENDER_TABLE_H_

#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/output.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::exports {

// 256 columns x 128 rows keep the lookup within 1 of 8-bit sRGB for the bundled systems
// (the figure is measured for each table and written with it).
inline constexpr int kBlenderTableColumns = 256;
inline constexpr int kBlenderTableRows = 128;

struct BlenderTableOptions {
  int columns = kBlenderTableColumns;  // at least 2
  int rows = kBlenderTableRows;        // at least 2
  int threads = 0;                     // 0: one per hardware thread
};

struct BlenderTable {
  AlloySystem system;
  double x_min = 0.0, x_max = 1.0;
  int columns = 0, rows = 0;
  // Linear sRGB in [0, 1], rgb[(m * columns + i) * 3 + c], row m = 0 at mu = 0.
  std::vector<double> rgb;
  std::vector<color::RGB> f0, f82_tint;  // per column
  double max_de00 = 0.0;
  int max_srgb8_difference = 0;
  int check_points = 0;
};

// `d65` must be a D65, 2-degree colorimeter. Throws Error for bad options or a model that
// does not cover the visible.
BlenderTable BuildBlenderTable(const color::Colorimeter& d65, const AlloyModel& model,
                               const BlenderTableOptions& options);

// PREFIX.alloy-table.png (16-bit RGB(A), linear) and PREFIX.alloy-table.json (what the
// add-on reads: system, elements and molar masses, x range, sizes, the image's file name,
// whether karats apply, F0 and tint, the measured error); `material` describes the model.
std::vector<OutputFile> BlenderTableFiles(const BlenderTable& table, const std::string& prefix,
                                          const std::string& material,
                                          const std::string& generator);

}  // namespace alloycolor::exports

#endif  // ALLOYCOLOR_EXPORT_BLENDER_TABLE_H_
