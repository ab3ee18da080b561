#include "alloycolor/color/sweep.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>

#include "alloycolor/color/material_color.h"
#include "alloycolor/color/reflectance_arrays.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/units.h"

namespace alloycolor::color {
namespace {

bool Finite(const XYZ& xyz) {
  return std::isfinite(xyz.X) && std::isfinite(xyz.Y) && std::isfinite(xyz.Z);
}

// Weights of 4-point Lagrange interpolation at t on nodes 0, 1, 2, 3.
void LagrangeWeights(double t, double w[4]) {
  const double t0 = t, t1 = t - 1.0, t2 = t - 2.0, t3 = t - 3.0;
  w[0] = -t1 * t2 * t3 / 6.0;
  w[1] = t0 * t2 * t3 / 2.0;
  w[2] = -t0 * t1 * t3 / 2.0;
  w[3] = t0 * t1 * t2 / 6.0;
}

}  // namespace

ColorSweep::ColorSweep(const Colorimeter& colorimeter, const AlloyModel& model, double angle_deg)
    : colorimeter_(colorimeter), model_(model) {
  if (!(angle_deg >= 0.0 && angle_deg <= 90.0)) {
    std::ostringstream msg;
    msg << "angle of incidence " << angle_deg << " degrees lies outside 0-90";
    throw Error(msg.str());
  }
  // As ReflectanceSpectrum: cos psi0, never negative.
  cos_psi_ = std::max(std::cos(angle_deg * kPi / 180.0), 0.0);
  normal_ = angle_deg == 0.0;
  grid_nm_ = EvaluationGrid(colorimeter, model.lambda_min_nm(), model.lambda_max_nm(),
                            "the " + model.method() + " model");
  bound_ = model.Bind(grid_nm_);
  eps1_.resize(grid_nm_.size());
  eps2_.resize(grid_nm_.size());
}

XYZ ColorSweep::ExactXYZ(double x_atomic) const {
  bound_->Permittivity(x_atomic, eps1_.data(), eps2_.data());
  double sums[3];
  ReflectanceSums(grid_nm_.size(), eps1_.data(), eps2_.data(), cos_psi_, normal_,
                  colorimeter_.wx().data(), colorimeter_.wy().data(), colorimeter_.wz().data(),
                  sums);
  return {sums[0], sums[1], sums[2]};
}

bool ColorSweep::BuildSegment(double x_lo, double x_hi, int intervals, double tolerance,
                              Segment* segment, double* error) const {
  segment->x_lo = x_lo;
  segment->x_hi = x_hi;
  segment->step = (x_hi - x_lo) / intervals;
  segment->xyz.resize(intervals + 1);
  for (int i = 0; i <= intervals; ++i) {
    const double x = i == intervals ? x_hi : x_lo + i * segment->step;
    const XYZ xyz = ExactXYZ(x);
    if (!Finite(xyz)) return false;
    segment->xyz[i] = {xyz.X, xyz.Y, xyz.Z};
  }
  // The error at the midpoint of every interval, against the exact value.
  double worst = 0.0;
  for (int i = 0; i < intervals; ++i) {
    const double x = x_lo + (i + 0.5) * segment->step;
    const XYZ exact = ExactXYZ(x);
    if (!Finite(exact)) return false;
    const XYZ table = Interpolate(*segment, x);
    worst = std::max({worst, std::abs(exact.X - table.X), std::abs(exact.Y - table.Y),
                      std::abs(exact.Z - table.Z)});
    *error = worst;
    if (worst > tolerance) return false;
  }
  *error = worst;
  return true;
}

bool ColorSweep::BuildTableFor(std::size_t count, double x_from, double x_to, bool exact) {
  if (exact || count < kSweepTableMinCompositions || x_from == x_to) return false;
  return BuildTable(x_from, x_to, kSweepTableTolerance,
                    static_cast<int>(std::min<std::size_t>(count, kSweepMaxTableNodes)));
}

bool ColorSweep::BuildTable(double x_from, double x_to, double tolerance, int max_nodes) {
  max_nodes = std::min(max_nodes, kSweepMaxTableNodes);
  segments_.clear();
  table_error_ = 0.0;
  table_nodes_ = 0;
  const double lo = std::min(x_from, x_to), hi = std::max(x_from, x_to);
  if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi)) return false;
  // Breakpoints: the ends and the training compositions strictly inside.
  std::vector<double> breaks = {lo};
  for (const TrainingSample& s : model_.training_samples()) {
    if (s.x_atomic > lo + 1e-12 && s.x_atomic < hi - 1e-12) breaks.push_back(s.x_atomic);
  }
  breaks.push_back(hi);
  std::sort(breaks.begin(), breaks.end());
  std::vector<Segment> segments;
  double worst = 0.0;
  int nodes = 0;
  for (size_t b = 0; b + 1 < breaks.size(); ++b) {
    const double a = breaks[b], z = breaks[b + 1];
    if (!(z > a)) continue;
    // Start near 256 intervals per unit of x; double until the midpoints agree.
    int intervals = std::max(8, static_cast<int>(std::ceil(256.0 * (z - a))));
    Segment segment;
    double error = 0.0;
    // Each attempt costs two evaluations per interval: past max_nodes the table would cost
    // more than the evaluations it saves (a model whose colour swings wildly), so none.
    if (nodes + intervals + 1 > max_nodes) return false;
    while (!BuildSegment(a, z, intervals, tolerance, &segment, &error)) {
      if (!(error > tolerance) || nodes + 2 * intervals + 1 > max_nodes) return false;
      intervals *= 2;
    }
    worst = std::max(worst, error);
    nodes += intervals + 1;
    segments.push_back(std::move(segment));
  }
  if (segments.empty()) return false;
  segments_ = std::move(segments);
  table_error_ = worst;
  table_nodes_ = nodes;
  return true;
}

XYZ ColorSweep::Interpolate(const Segment& seg, double x) {
  const int intervals = static_cast<int>(seg.xyz.size()) - 1;  // >= 3 (BuildTable uses >= 8)
  const double u = std::clamp((x - seg.x_lo) / seg.step, 0.0, static_cast<double>(intervals));
  const int cell = std::min(static_cast<int>(u), intervals - 1);
  // Nodes cell-1 .. cell+2, shifted to stay inside the segment.
  const int first = std::clamp(cell - 1, 0, intervals - 3);
  double w[4];
  LagrangeWeights(u - first, w);
  const std::array<double, 3>* p = &seg.xyz[first];
  return {w[0] * p[0][0] + w[1] * p[1][0] + w[2] * p[2][0] + w[3] * p[3][0],
          w[0] * p[0][1] + w[1] * p[1][1] + w[2] * p[2][1] + w[3] * p[3][1],
          w[0] * p[0][2] + w[1] * p[1][2] + w[2] * p[2][2] + w[3] * p[3][2]};
}

XYZ ColorSweep::TableXYZ(double x) const {
  // The segment holding x (held at the ends).
  size_t s = 0;
  while (s + 1 < segments_.size() && x > segments_[s].x_hi) ++s;
  return Interpolate(segments_[s], x);
}

XYZ ColorSweep::XYZAt(double x_atomic) const {
  return segments_.empty() ? ExactXYZ(x_atomic) : TableXYZ(x_atomic);
}

}  // namespace alloycolor::color
