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
// Between nodes the curves' values are linear in wavelength. Why eps: across composition
// it varies most gently of the quantities tried (n, k; 1 / (1 - eps); ln gamma and ln wp^2
// of the Drude inversion, which carries interband absorption and spans orders of
// magnitude), and PCHIP never overshoots between knots: eps2 >= 0 at the knots (a bound of
// the fit) holds at every composition between them, and |eps| never exceeds the knots'
// largest. The curves may instead run through ln eps = ln|eps| + i arg eps (SmoothSpace):
// eps then varies geometrically between knots, as it must where the samples' |eps| differ
// by orders of magnitude or one of them is not metallic (a metal's eps sits near the
// negative real axis, arg eps near pi; a dielectric's near 0); arg eps in [0, pi] at the
// knots keeps eps2 >= 0 between them, and |eps| stays between the knots' too. The Drude
// parameters tau(x) and m*(x) are read out by inverting eps (eq. 11, 12), as for
// every model: the inversion maps a smooth eps(x) to smooth tau(x), m*(x).
#ifndef ALLOYCOLOR_MODEL_SMOOTH_MODEL_H_
#define ALLOYCOLOR_MODEL_SMOOTH_MODEL_H_

#include <array>
#include <complex>
#include <vector>

#include "alloycolor/model/alloy_model.h"

namespace alloycolor {

// Knots of a smooth model: at most this many.
inline constexpr int kSmoothMaxKnots = 32;

// What the curves across composition describe: eps itself (the two parts eps1, eps2) or
// its logarithm (ln|eps| and arg eps in radians).
enum class SmoothSpace { kEps, kLogEps };
const char* SmoothSpaceName(SmoothSpace space);  // "eps", "log_eps"

// The two parts of eps in `space`: eps2 taken as at least 0 and |eps| as at least 1e-12
// for the logarithm, whose argument then lies in [0, pi].
std::array<double, 2> PartsFromEps(SmoothSpace space, std::complex<double> eps);
// eps from the two parts: for the logarithm the argument held to [0, pi] (passive) and
// |eps| to at most kMaxOpticalConstant^2, as the readers hold n and k.
std::complex<double> EpsFromParts(SmoothSpace space, double part1, double part2);

class SmoothModel : public AlloyModel {
 public:
  // part1[j], part2[j]: the values at the knots at node j, in `space` (eps1 and eps2, or
  // ln|eps| and arg eps). smoothing: the roughness weight the fit used (recorded in the
  // file).
  SmoothModel(const Dataset& dataset, std::vector<double> grid_nm, std::vector<double> knots_x,
              SmoothSpace space, std::vector<std::vector<double>> part1,
              std::vector<std::vector<double>> part2, double smoothing);
  SmoothModel(const nlohmann::json& doc, const std::string& source);
  // `model` as a smooth model, or null when it is of another method.
  static const SmoothModel* From(const AlloyModel* model);

  std::string method() const override { return "smooth"; }
  std::vector<std::complex<double>> Permittivity(
      double x_atomic, const std::vector<double>& lambda_nm) const override;
  // Knot values and slopes interpolated to the grid once: a composition then costs one
  // bracket search and, per wavelength, two cubic Hermite sums (and, in the logarithm, an
  // exponential and a sine and cosine).
  std::unique_ptr<BoundModel> Bind(const std::vector<double>& lambda_nm) const override;

  std::vector<double> native_grid_nm() const override { return grid_nm_; }
  std::vector<double> FittedCoefficients() const override;

  const std::vector<double>& grid_nm() const { return grid_nm_; }
  const std::vector<double>& knots_x() const { return knots_x_; }
  SmoothSpace space() const { return space_; }
  const std::vector<std::vector<double>>& part1() const { return part1_; }
  const std::vector<std::vector<double>>& part2() const { return part2_; }
  double smoothing() const { return smoothing_; }
  // Adds fit diagnostics to warnings().
  void AddWarnings(const std::vector<std::string>& warnings);

 protected:
  nlohmann::json ParametersJson() const override;

 private:
  void Validate(const std::string& source);

  std::vector<double> grid_nm_;
  std::vector<double> knots_x_;
  SmoothSpace space_ = SmoothSpace::kEps;
  std::vector<std::vector<double>> part1_, part2_;    // [node][knot], in space_
  std::vector<std::vector<double>> slope1_, slope2_;  // PCHIP slopes, [node][knot]
  double smoothing_ = 0;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_SMOOTH_MODEL_H_
