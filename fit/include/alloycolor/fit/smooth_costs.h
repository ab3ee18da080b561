// Cost functors of the smooth fit (smooth_fit.h), templated so Ceres differentiates the
// same physics (model/smooth_model.h, model/optics.h) that the model evaluates.
#ifndef ALLOYCOLOR_FIT_SMOOTH_COSTS_H_
#define ALLOYCOLOR_FIT_SMOOTH_COSTS_H_

#include <ceres/ceres.h>

#include <algorithm>
#include <complex>

#include "alloycolor/model/smooth_model.h"

namespace alloycolor::fit {

// Relative misfit of the model's eps at one sample and node (see smooth_fit.h).
template <int kNb>
struct EpsResidual {
  EpsResidual(const double* basis, double omega_ev, std::complex<double> eps)
      : omega_ev(omega_ev), eps1(eps.real()), eps2(eps.imag()), inv_abs(1.0 / std::abs(eps)) {
    std::copy(basis, basis + kNb, this->basis);
  }
  template <typename T>
  bool operator()(const T* const coeffs, T* residual) const {
    const Complex<T> e = SmoothNodePermittivity(coeffs, basis, kNb, omega_ev);
    residual[0] = (e.re - T(eps1)) * T(inv_abs);
    residual[1] = (e.im - T(eps2)) * T(inv_abs);
    return true;
  }
  static ceres::CostFunction* Create(const double* basis, double omega_ev,
                                     std::complex<double> eps) {
    return new ceres::AutoDiffCostFunction<EpsResidual, 2, 2 * kNb>(
        new EpsResidual(basis, omega_ev, eps));
  }
  double basis[kNb];
  const double omega_ev, eps1, eps2, inv_abs;
};

// Second difference of every coefficient across three neighbouring nodes.
template <int kNb>
struct CurvatureResidual {
  explicit CurvatureResidual(double weight) : weight(weight) {}
  template <typename T>
  bool operator()(const T* const a, const T* const b, const T* const c, T* residual) const {
    for (int d = 0; d < 2 * kNb; ++d) residual[d] = T(weight) * (a[d] - T(2) * b[d] + c[d]);
    return true;
  }
  static ceres::CostFunction* Create(double weight) {
    return new ceres::AutoDiffCostFunction<CurvatureResidual, 2 * kNb, 2 * kNb, 2 * kNb,
                                           2 * kNb>(new CurvatureResidual(weight));
  }
  const double weight;
};

// Pulls the composition-dependent coefficients (d >= 1) weakly toward zero.
template <int kNb>
struct RidgeResidual {
  explicit RidgeResidual(double weight) : weight(weight) {}
  template <typename T>
  bool operator()(const T* const c, T* residual) const {
    for (int d = 1; d < kNb; ++d) {
      residual[2 * (d - 1)] = T(weight) * c[d];
      residual[2 * (d - 1) + 1] = T(weight) * c[kNb + d];
    }
    return true;
  }
  static ceres::CostFunction* Create(double weight) {
    return new ceres::AutoDiffCostFunction<RidgeResidual, 2 * (kNb - 1), 2 * kNb>(
        new RidgeResidual(weight));
  }
  const double weight;
};

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_SMOOTH_COSTS_H_
