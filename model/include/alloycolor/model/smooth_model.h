// The "smooth" model: Drude parameters as smooth functions of composition, fitted jointly
// to all samples with Ceres (fit/smooth_fit.h); this class only evaluates them.
//
// At each node lambda_j of a wavelength grid, with u = 2 (x - x_lo) / (x_hi - x_lo) - 1
// (x_lo, x_hi the training range) and Legendre polynomials P_0..P_D,
//   ln gamma(x) = sum_d a_jd P_d(u),   ln wp^2(x) = sum_d b_jd P_d(u),
//   eps(x, w_j) = 1 - wp^2 / (w_j (w_j + i gamma))                (eq. 7)
// so tau = hbar / gamma and m*/m_e = kPlasmaEv2M3 N_e(x) / wp^2 are positive and smooth
// in x; the fit also penalises the curvature of a, b across the grid. Between nodes the
// coefficients are interpolated linearly in wavelength. Each node carries the covariance
// of its 2(D+1) coefficients (ceres::Covariance scaled by the residual variance).
#ifndef ALLOYCOLOR_MODEL_SMOOTH_MODEL_H_
#define ALLOYCOLOR_MODEL_SMOOTH_MODEL_H_

#include <cmath>
#include <complex>
#include <vector>

#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/optics.h"

namespace alloycolor {

inline constexpr int kSmoothMaxDegree = 8;

// The argument of the Legendre polynomials for composition x over the training range
// [x_lo, x_hi]: u = 2 (x - x_lo) / (x_hi - x_lo) - 1, so u runs over [-1, 1].
inline double CompositionArgument(double x, double x_lo, double x_hi) {
  return 2.0 * (x - x_lo) / (x_hi - x_lo) - 1.0;
}

// P_0..P_degree at u (Bonnet's recursion).
inline void LegendreBasis(double u, int degree, double* p) {
  p[0] = 1.0;
  if (degree >= 1) p[1] = u;
  for (int d = 2; d <= degree; ++d) {
    p[d] = ((2.0 * d - 1.0) * u * p[d - 1] - (d - 1.0) * p[d - 2]) / d;
  }
}

// eps at photon energy omega_ev from the coefficients of one node: coeffs[0..nb) are the
// a (ln gamma), coeffs[nb..2nb) the b (ln wp^2); basis holds P_d(u) at the composition.
template <typename T>
Complex<T> SmoothNodePermittivity(const T* coeffs, const double* basis, int nb,
                                  double omega_ev) {
  using std::exp;
  T ln_gamma(0.0), ln_wp2(0.0);
  for (int d = 0; d < nb; ++d) {
    ln_gamma += coeffs[d] * basis[d];
    ln_wp2 += coeffs[nb + d] * basis[d];
  }
  return DrudePermittivity(T(omega_ev), exp(ln_wp2), exp(ln_gamma));
}

class SmoothModel : public AlloyModel {
 public:
  // coeffs[j] holds 2 (degree + 1) values for node j; covariance[j] (row-major, may be
  // empty) their covariance.
  SmoothModel(const Dataset& dataset, std::vector<double> grid_nm, int degree,
              std::vector<std::vector<double>> coeffs,
              std::vector<std::vector<double>> covariance);
  SmoothModel(const nlohmann::json& doc, const std::string& source);

  std::string method() const override { return "smooth"; }
  std::vector<std::complex<double>> Permittivity(
      double x_atomic, const std::vector<double>& lambda_nm) const override;
  // Coefficients interpolated to the grid once: a composition then costs the Legendre
  // basis and, per wavelength, two dot products and two exp.
  std::unique_ptr<BoundModel> Bind(const std::vector<double>& lambda_nm) const override;
  bool HasUncertainty() const override { return !covariance_.empty(); }
  std::vector<std::vector<std::complex<double>>> PermittivityDraws(
      double x_atomic, const std::vector<double>& lambda_nm, int count = kUncertaintyDraws,
      std::uint32_t seed = kUncertaintySeed) const override;

  std::vector<double> native_grid_nm() const override { return grid_nm_; }
  std::vector<double> FittedCoefficients() const override;

  int degree() const { return degree_; }
  int basis_size() const { return degree_ + 1; }
  const std::vector<double>& grid_nm() const { return grid_nm_; }
  const std::vector<std::vector<double>>& coeffs() const { return coeffs_; }
  const std::vector<std::vector<double>>& covariance() const { return covariance_; }
  // u of eq. above for composition x.
  double BasisArgument(double x_atomic) const;
  // Adds fit diagnostics (samples left out at some wavelengths) to warnings().
  void AddWarnings(const std::vector<std::string>& warnings);

 protected:
  nlohmann::json ParametersJson() const override;

 private:
  void Validate(const std::string& source) const;
  std::vector<std::complex<double>> Evaluate(
      double x_atomic, const std::vector<double>& lambda_nm,
      const std::vector<std::vector<double>>& coeffs) const;

  std::vector<double> grid_nm_;
  int degree_ = 2;
  std::vector<std::vector<double>> coeffs_;
  std::vector<std::vector<double>> covariance_;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_SMOOTH_MODEL_H_
