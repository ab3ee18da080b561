// Cost functors of the smooth fit (smooth_fit.h), templated so Ceres differentiates the
// same interpolation (model/interpolation.h) that the model evaluates.
#ifndef ALLOYCOLOR_FIT_SMOOTH_COSTS_H_
#define ALLOYCOLOR_FIT_SMOOTH_COSTS_H_

#include <ceres/ceres.h>

#include <complex>
#include <vector>

#include "alloycolor/model/interpolation.h"
#include "alloycolor/model/smooth_model.h"

namespace alloycolor::fit {

// Stride of the dynamic cost functions: derivatives computed this many at a time.
inline constexpr int kSmoothStride = 8;

// Misfit of the model at one sample and node: parameter blocks are the node's two parts at
// the knots (eps1 and eps2, or ln|eps| and arg eps: SmoothSpace); residuals (part -
// part_i) * weight, for both parts. The weight 1 / |eps_i| makes the eps misfit relative;
// in the logarithm the misfit is relative already (weight 1).
struct SmoothDataResidual {
  SmoothDataResidual(const std::vector<double>& knots, double x, std::complex<double> parts,
                     double weight)
      : knots(knots), x(x), part1(parts.real()), part2(parts.imag()), weight(weight) {}
  template <typename T>
  bool operator()(T const* const* blocks, T* residual) const {
    const size_t k = knots.size();
    T slopes[kSmoothMaxKnots];
    PchipSlopes(knots.data(), blocks[0], k, slopes);
    residual[0] = (HermiteAt(knots.data(), blocks[0], slopes, k, x) - T(part1)) * T(weight);
    PchipSlopes(knots.data(), blocks[1], k, slopes);
    residual[1] = (HermiteAt(knots.data(), blocks[1], slopes, k, x) - T(part2)) * T(weight);
    return true;
  }
  static ceres::CostFunction* Create(const std::vector<double>& knots, double x,
                                     std::complex<double> parts, double weight) {
    auto* cost = new ceres::DynamicAutoDiffCostFunction<SmoothDataResidual, kSmoothStride>(
        new SmoothDataResidual(knots, x, parts, weight));
    cost->AddParameterBlock(static_cast<int>(knots.size()));
    cost->AddParameterBlock(static_cast<int>(knots.size()));
    cost->SetNumResiduals(2);
    return cost;
  }
  const std::vector<double> knots;
  const double x, part1, part2, weight;
};

// Roughness of one node's curves: sqrt(weight) times the second divided difference at
// each inner knot, times sqrt of its share (h0 + h1) / 2 of the composition axis, so the
// sum of squares approximates weight * integral of (d^2 eps / du^2)^2 du over u = x scaled
// to [0, 1] on the training range. Linear in the knot values.
struct SmoothRoughnessResidual {
  SmoothRoughnessResidual(const std::vector<double>& knots_u, double weight)
      : knots_u(knots_u), weight(weight) {}
  template <typename T>
  bool operator()(T const* const* blocks, T* residual) const {
    const size_t k = knots_u.size();
    for (int part = 0; part < 2; ++part) {
      const T* y = blocks[part];
      for (size_t c = 1; c + 1 < k; ++c) {
        const double h0 = knots_u[c] - knots_u[c - 1], h1 = knots_u[c + 1] - knots_u[c];
        const double scale = weight * 2.0 / (h0 + h1) * std::sqrt(0.5 * (h0 + h1));
        residual[part * (k - 2) + c - 1] =
            T(scale) * ((y[c + 1] - y[c]) / T(h1) - (y[c] - y[c - 1]) / T(h0));
      }
    }
    return true;
  }
  static ceres::CostFunction* Create(const std::vector<double>& knots_u, double weight) {
    auto* cost = new ceres::DynamicAutoDiffCostFunction<SmoothRoughnessResidual, kSmoothStride>(
        new SmoothRoughnessResidual(knots_u, weight));
    cost->AddParameterBlock(static_cast<int>(knots_u.size()));
    cost->AddParameterBlock(static_cast<int>(knots_u.size()));
    cost->SetNumResiduals(2 * (static_cast<int>(knots_u.size()) - 2));
    return cost;
  }
  const std::vector<double> knots_u;
  const double weight;
};

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_SMOOTH_COSTS_H_
