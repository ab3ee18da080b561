// The colour of one alloy at many compositions, fast: the chain of material_color.h (n, k on
// the colorimeter's grid -> Fresnel reflectance R = (Rs + Rp) / 2, eq. 2-4 -> XYZ, eq. 5)
// with everything that does not depend on the composition x done once.
//
// Exact evaluation. The wavelengths are the colorimeter's 5 nm grid held inside the model's
// range (EvaluationGrid), the weights its normalised P(l) xbar(l) etc. The model is bound
// to that grid once (AlloyModel::Bind), so a composition costs what the method needs to
// evaluate eps there (for the interpolating methods, one knot interval and two cubic
// Hermite sums per wavelength), then eq. 13-14 and eq. 2-4 on arrays in SIMD lanes
// (AVX2 where the processor has it), with no allocation. The result equals
// MaterialXYZ(IndexOnGrid(...)) to rounding (1e-12 relative, tested).
//
// Table. For long sweeps, XYZ is tabulated against x at uniform nodes between breakpoints
// (the ends of the sweep and the training compositions inside it, where the paper and
// eps-linear models have kinks) and read by 4-point Lagrange (cubic) interpolation. The
// table is refined until the largest error, measured against the exact XYZ at the midpoint
// of every table interval, is at most the tolerance (default 1e-7 in X, Y and Z, each of
// which lies in [0, ~1.1]); if that needs more than the caller's budget of nodes (the
// number of compositions it will read, at most kSweepMaxTableNodes), no table is built and
// every composition is evaluated exactly: building never costs more than a few times the
// exact evaluations it would save, whatever the model.
#ifndef ALLOYCOLOR_COLOR_SWEEP_H_
#define ALLOYCOLOR_COLOR_SWEEP_H_

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::color {

inline constexpr double kSweepTableTolerance = 1e-7;
inline constexpr int kSweepMaxTableNodes = 1 << 20;
// Sweeps of this many compositions or more at one angle read XYZ from the table (unless
// exact evaluation is asked for): `alloycolor sweep` and Python's colours alike.
inline constexpr std::size_t kSweepTableMinCompositions = 1000;

class ColorSweep {
 public:
  // Keeps references to the colorimeter and the model, which must outlive it. Throws Error
  // when the model does not cover the visible (as EvaluationGrid) or the angle lies outside
  // 0-90 degrees.
  ColorSweep(const Colorimeter& colorimeter, const AlloyModel& model, double angle_deg);

  // XYZ at x_atomic, evaluated exactly (the caller checks the composition's range).
  XYZ ExactXYZ(double x_atomic) const;

  // Tabulates XYZ over [x_from, x_to] (either order). Returns false, and keeps no table,
  // when the tolerance cannot be met within max_nodes nodes (at most kSweepMaxTableNodes;
  // the evaluations spent trying stay under 2 max_nodes + 256), when the range is empty,
  // or when the model gives a non-finite colour somewhere.
  bool BuildTable(double x_from, double x_to, double tolerance = kSweepTableTolerance,
                  int max_nodes = kSweepMaxTableNodes);
  // The table for a sweep of `count` compositions over [x_from, x_to], when the sweep is
  // long enough to read one (kSweepTableMinCompositions), not `exact` and not at one
  // composition: BuildTable with at most `count` nodes (never more evaluations than the
  // sweep's own). Returns whether there is a table.
  bool BuildTableFor(std::size_t count, double x_from, double x_to, bool exact);
  bool has_table() const { return !segments_.empty(); }
  // The largest |dX|, |dY|, |dZ| measured at the interval midpoints while building.
  double table_error() const { return table_error_; }
  int table_nodes() const { return table_nodes_; }

  // XYZ from the table for x inside its range (held at its ends outside), else exact.
  XYZ XYZAt(double x_atomic) const;

 private:
  struct Segment {
    double x_lo, x_hi, step;
    std::vector<std::array<double, 3>> xyz;  // at x_lo + i * step, i = 0..intervals
  };
  XYZ TableXYZ(double x_atomic) const;
  static XYZ Interpolate(const Segment& segment, double x_atomic);
  bool BuildSegment(double x_lo, double x_hi, int intervals, double tolerance, Segment* segment,
                    double* error) const;

  const Colorimeter& colorimeter_;
  const AlloyModel& model_;
  std::unique_ptr<BoundModel> bound_;
  double cos_psi_ = 1.0;
  bool normal_ = true;
  std::vector<double> grid_nm_;  // colorimeter grid held inside the model's range
  // Scratch on grid_nm_ for ExactXYZ, sized once: eps1, eps2.
  mutable std::vector<double> eps1_, eps2_;
  std::vector<Segment> segments_;
  double table_error_ = 0.0;
  int table_nodes_ = 0;
};

}  // namespace alloycolor::color

#endif  // ALLOYCOLOR_COLOR_SWEEP_H_
