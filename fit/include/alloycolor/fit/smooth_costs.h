// Cost functors of the smooth fit (smooth_fit.h), templated so Ceres differentiates the
// same interpolation (model/interpolation.h) that the model evaluates.
#ifndef ALLOYCOLOR_FIT_SMOOTH_COSTS_H_
#define ALLOYCOLOR_FIT_SMOOTH_COSTS_H_

#include <ceres/ceres.h>

#include <algorithm>
#include <complex>
#include <vector>

#include "alloycolor/model/interpolation.h"
#include "alloycolor/model/smooth_model.h"

namespace alloycolor::fit {

// Stride of the dynamic cost functions: derivatives computed this many at a time.
inline constexpr int kSmoothStride = 8;

// Misfit of the model at one sample and node in one of the node's two parts (eps1 or eps2,
// or ln|eps| or arg eps: SmoothSpace), the parameter block that part's values at the knots:
// residual (part - part_i) * weight. The weight 1 / |eps_i| makes the eps misfit relative;
// in the logarithm the misfit is relative already (weight 1).
//
// The curve at x depends on the knots of x's interval and their neighbours alone (PCHIP's
// slope at a knot depends on the knots beside it; at an end, on the two next to it): the
// same interpolation as the model's, on that window of at most four knots, differentiated
// with a Jet of four, the other knots' derivatives zero.
class SmoothDataResidual : public ceres::CostFunction {
 public:
  SmoothDataResidual(const std::vector<double>& knots, double x, double part, double weight)
      : x_(x), part_(part), weight_(weight), k_(knots.size()) {
    size_t hi = std::upper_bound(knots.begin(), knots.end(), x) - knots.begin();
    hi = std::clamp<size_t>(hi, 1, k_ - 1);
    const size_t lo = hi - 1;
    first_ = lo > 0 ? lo - 1 : 0;
    size_t last = std::min(k_, hi + 2);
    if (first_ == 0) last = std::min(k_, std::max<size_t>(last, 3));
    if (last == k_) first_ = std::min(first_, k_ >= 3 ? k_ - 3 : 0);
    window_ = last - first_;
    for (size_t w = 0; w < window_; ++w) window_x_[w] = knots[first_ + w];
    set_num_residuals(1);
    mutable_parameter_block_sizes()->push_back(static_cast<int>(k_));
  }

  bool Evaluate(double const* const* blocks, double* residuals, double** jacobians) const override {
    const double* y = blocks[0] + first_;
    if (jacobians == nullptr || jacobians[0] == nullptr) {
      double slopes[4];
      PchipSlopes(window_x_, y, window_, slopes);
      residuals[0] = (HermiteAt(window_x_, y, slopes, window_, x_) - part_) * weight_;
      return true;
    }
    using Jet = ceres::Jet<double, 4>;
    Jet yj[4], slopes[4];
    for (size_t w = 0; w < window_; ++w) yj[w] = Jet(y[w], static_cast<int>(w));
    PchipSlopes(window_x_, yj, window_, slopes);
    const Jet r = (HermiteAt(window_x_, yj, slopes, window_, x_) - Jet(part_)) * Jet(weight_);
    residuals[0] = r.a;
    std::fill(jacobians[0], jacobians[0] + k_, 0.0);
    for (size_t w = 0; w < window_; ++w) jacobians[0][first_ + w] = r.v[w];
    return true;
  }

 private:
  double x_, part_, weight_;
  size_t k_, first_ = 0, window_ = 0;
  double window_x_[4];
};

// Roughness of one part of one node's curve: sqrt(weight) times the second divided
// difference at each inner knot, times sqrt of its share (h0 + h1) / 2 of the composition
// axis, so the sum of squares approximates weight * integral of (d^2 eps / du^2)^2 du over
// u = x scaled to [0, 1] on the training range. Linear in the knot values.
struct SmoothRoughnessResidual {
  SmoothRoughnessResidual(const std::vector<double>& knots_u, double weight)
      : knots_u(knots_u), weight(weight) {}
  template <typename T>
  bool operator()(T const* const* blocks, T* residual) const {
    const size_t k = knots_u.size();
    const T* y = blocks[0];
    for (size_t c = 1; c + 1 < k; ++c) {
      const double h0 = knots_u[c] - knots_u[c - 1], h1 = knots_u[c + 1] - knots_u[c];
      const double scale = weight * 2.0 / (h0 + h1) * std::sqrt(0.5 * (h0 + h1));
      residual[c - 1] = T(scale) * ((y[c + 1] - y[c]) / T(h1) - (y[c] - y[c - 1]) / T(h0));
    }
    return true;
  }
  static ceres::CostFunction* Create(const std::vector<double>& knots_u, double weight) {
    auto* cost = new ceres::DynamicAutoDiffCostFunction<SmoothRoughnessResidual, kSmoothStride>(
        new SmoothRoughnessResidual(knots_u, weight));
    cost->AddParameterBlock(static_cast<int>(knots_u.size()));
    cost->SetNumResiduals(static_cast<int>(knots_u.size()) - 2);
    return cost;
  }
  const std::vector<double> knots_u;
  const double weight;
};

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_SMOOTH_COSTS_H_
