// The "smooth" model: at every node of a wavelength grid, eps1 and eps2 are smooth curves
// of composition, fitted jointly to all samples with Ceres (fit/smooth_fit.h); this class
// only evaluates them.
//
// Each curve is the monotone piecewise cubic (PCHIP, interpolation.h) through values at
// knots x_1 < ... < x_K in composition (the training compositions, or quantiles of them
// when there are many); the fit chooses the knot values under a roughness penalty, so the
// curve is an interpolation of sparse data and a regression through noisy or dense data.
// The fit's second form, a Gaussian process across composition, is stored the same way:
// its mean at evenly spaced knots.
// Between nodes eps is linear in wavelength. Why eps: across composition it varies most
// gently of the quantities tried (n, k; 1 / (1 - eps); ln gamma and ln wp^2 of the Drude
// inversion, which carries interband absorption and spans orders of magnitude), and PCHIP
// never overshoots between knots: eps2 >= 0 at the knots (a bound of the fit) holds at
// every composition between them, and |eps| never exceeds the knots' largest. The Drude
// parameters tau(x) and m*(x) are read out by inverting eps (eq. 11, 12), as for
// every model: the inversion maps a smooth eps(x) to smooth tau(x), m*(x).
#ifndef ALLOYCOLOR_MODEL_SMOOTH_MODEL_H_
#define ALLOYCOLOR_MODEL_SMOOTH_MODEL_H_

#include <complex>
#include <vector>

#include "alloycolor/model/alloy_model.h"

namespace alloycolor {

// Knots of a smooth model: at most this many.
inline constexpr int kSmoothMaxKnots = 32;

class SmoothModel : public AlloyModel {
 public:
  // eps1[j], eps2[j]: the values at the knots at node j. smoothing: the roughness weight
  // the fit used (recorded in the file).
  SmoothModel(const Dataset& dataset, std::vector<double> grid_nm, std::vector<double> knots_x,
              std::vector<std::vector<double>> eps1, std::vector<std::vector<double>> eps2,
              double smoothing);
  SmoothModel(const nlohmann::json& doc, const std::string& source);

  std::string method() const override { return "smooth"; }
  std::vector<std::complex<double>> Permittivity(
      double x_atomic, const std::vector<double>& lambda_nm) const override;
  // Knot values and slopes interpolated to the grid once: a composition then costs one
  // bracket search and, per wavelength, two cubic Hermite sums.
  std::unique_ptr<BoundModel> Bind(const std::vector<double>& lambda_nm) const override;

  std::vector<double> native_grid_nm() const override { return grid_nm_; }
  std::vector<double> FittedCoefficients() const override;

  const std::vector<double>& grid_nm() const { return grid_nm_; }
  const std::vector<double>& knots_x() const { return knots_x_; }
  const std::vector<std::vector<double>>& eps1() const { return eps1_; }
  const std::vector<std::vector<double>>& eps2() const { return eps2_; }
  double smoothing() const { return smoothing_; }
  // Adds fit diagnostics to warnings().
  void AddWarnings(const std::vector<std::string>& warnings);

 protected:
  nlohmann::json ParametersJson() const override;

 private:
  void Validate(const std::string& source);

  std::vector<double> grid_nm_;
  std::vector<double> knots_x_;
  std::vector<std::vector<double>> eps1_, eps2_;      // [node][knot]
  std::vector<std::vector<double>> slope1_, slope2_;  // PCHIP slopes, [node][knot]
  double smoothing_ = 0;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_SMOOTH_MODEL_H_
