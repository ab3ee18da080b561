// Tables for a page that shades an alloy itself (the `explore` page): the reflection colour
// of the alloy against composition x and the cosine mu of the angle of incidence, under
// several illuminants and roughnesses, with the uncertainty of the colour and the n, k and
// reflectance spectra, all computed by the library's own chain so that the page only
// interpolates.
//
// Colour. At every composition node x_i and illuminant, the rows are the renderer's own
// ReflectionTable (shading.h) read at its nodes mu_m = m / (mu_nodes - 1): for a smooth
// surface sum_l w(l) R(l, mu) with R = (Rs + Rp) / 2 of eq. 2-4 and w the colorimeter's
// weights of eq. 5, for a rough one the GGX directional albedo A_XYZ(mu). Between nodes the
// page interpolates
//   - linearly in mu (as ReflectionTable::At does), and
//   - in x by 4-point Lagrange (cubic) interpolation on uniform nodes between breakpoints:
//     the ends of the model's range and the training compositions inside it (where the
//     paper and eps-linear models have kinks), the scheme of ColorSweep (sweep.h).
// Because the albedo of a rough surface is a fixed linear average of the smooth table,
// interpolating the rough rows in x errs by at most what the smooth rows err.
//
// Density. The number of mu nodes is doubled until linear interpolation in mu at the
// breakpoints, and the nodes of each segment until cubic interpolation at its interval
// midpoints, agree with direct spectral evaluation (DirectReflection) to `tolerance_de00`
// (CIEDE2000) for every illuminant. The errors are then measured on the final table at
// every node and midpoint in x crossed with every node and midpoint in mu, as CIEDE2000
// and as the largest difference of 8-bit sRGB (IEC 61966-2-1) values: these are the
// figures the page states, not bounds (the largest error between check points may be a
// little larger).
//
// Uncertainty: color::DeltaE00Sigma at every node for each illuminant at the angles
// `sigma_angles_deg`, interpolated linearly by the page (in x and angle).
// Spectra: n, k and the normal-incidence reflectance (eq. 2-4 at 0 degrees) at every node
// on the colorimeter's wavelengths held inside the model's range (EvaluationGrid).
#ifndef ALLOYCOLOR_RENDER_COMPOSITION_TABLE_H_
#define ALLOYCOLOR_RENDER_COMPOSITION_TABLE_H_

#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/render/shading.h"

namespace alloycolor::render {

struct CompositionTableOptions {
  std::vector<double> roughness = {0.0};  // GGX alpha of each table; the first must be 0
  double tolerance_de00 = 0.02;           // largest CIEDE2000 while refining (see above)
  // Refinement stops at these limits (the page stays a few MB); the table then says so
  // (tolerance_met) and its measured error is larger.
  int min_mu_intervals = 64;
  int max_mu_intervals = 256;
  // A rough surface's albedo varies slowly with mu; its tables are coarser (and each
  // costs a lobe integral per node).
  int rough_mu_intervals = 32;
  int min_intervals_per_unit_x = 16;   // starting density of each segment (at least 3)
  int max_intervals_per_unit_x = 128;  // the limit (at least 3 per segment)
  std::vector<double> sigma_angles_deg = {0, 15, 30, 45, 60, 75, 90};
  int threads = 0;     // 0: one per hardware thread
  CancelCheck cancel;  // called before each block of nodes (core/progress.h)
};

struct CompositionSegment {
  double x_lo, x_hi;
  int intervals;   // uniform nodes x_lo + i (x_hi - x_lo) / intervals, i = 0..intervals
  int first_node;  // index of x_lo in CompositionTable::x_nodes
};

struct IlluminantTable {
  std::string illuminant;
  color::XYZ white;
  // xyz[r][(node * nodes_r + m) * 3 + c]: X, Y, Z at x_nodes[node], mu_m, roughness[r],
  // with nodes_r = CompositionTable::MuNodes(r).
  std::vector<std::vector<double>> xyz;
  // sigma_de00[node * sigma_angles + a]; empty for a model without uncertainty.
  std::vector<double> sigma_de00;
};

struct CompositionTable {
  std::vector<CompositionSegment> segments;
  std::vector<double> x_nodes;  // segment by segment; a breakpoint appears in both segments
  int mu_nodes = 0;             // smooth surface (roughness 0)
  int rough_mu_nodes = 0;       // the other roughnesses
  int MuNodes(int roughness_index) const {
    return roughness_index == 0 ? mu_nodes : rough_mu_nodes;
  }
  std::vector<double> roughness;
  std::vector<IlluminantTable> illuminants;
  std::vector<double> sigma_angles_deg;
  // Spectra at every node: n, k, R at normal incidence, [node * lambda + l].
  std::vector<double> lambda_nm;
  std::vector<double> n, k, r_normal;
  // Measured errors of the smooth-surface colour (see above), over all illuminants.
  double max_de00 = 0.0;
  int max_srgb8_difference = 0;
  int check_points = 0;
  bool tolerance_met = true;  // false when refinement stopped at a limit
};

// Throws Error when the model does not cover the visible for a colorimeter or for bad
// options.
CompositionTable BuildCompositionTable(const AlloyModel& model,
                                       const std::vector<color::Colorimeter>& colorimeters,
                                       const CompositionTableOptions& options);

// The page's interpolation, in C++ (for the error figures and for tests): XYZ of
// illuminant table `illuminant`, roughness table `roughness` at x_atomic (held inside the
// table's range) and mu (clamped to [0, 1]).
color::XYZ InterpolateCompositionTable(const CompositionTable& table, int illuminant, int roughness,
                                       double x_atomic, double mu);

// The radiance factor E(w) of an environment (shading.h) at the centres of a
// width x height latitude-longitude grid: texel (i, j), row j from the top, lies at
// theta = (j + 1/2) pi / height from +y and phi = (i + 1/2) 2 pi / width measured around
// +y from +x toward +z. With roughness > 0 it is the GGX-prefiltered environment
// (PrefilteredEnvironment). Row-major, top row first.
std::vector<float> LatLongRadiance(Lighting lighting, double roughness_alpha, int width, int height,
                                   int threads);

}  // namespace alloycolor::render

#endif  // ALLOYCOLOR_RENDER_COMPOSITION_TABLE_H_
