// Complex index and permittivity of an absorbing medium, templated on the scalar so that
// the readers (double) and the fits (ceres::Jet) share one implementation. Equations
// from Kuboshima & Furukawa as corrected in MISSION.md:
//   eps1 = n^2 - k^2,  eps2 = 2 n k                         (eq. 9, 10)
//   n^2 = (|eps| + eps1) / 2,  k^2 = (|eps| - eps1) / 2      (eq. 13, 14), n, k >= 0
#ifndef ALLOYCOLOR_CORE_PERMITTIVITY_H_
#define ALLOYCOLOR_CORE_PERMITTIVITY_H_

#include <cmath>

#include "alloycolor/core/complex.h"

namespace alloycolor {

// eq. 9, 10: eps = N^2.
template <typename T>
Complex<T> PermittivityFromIndex(const Complex<T>& nk) {
  return nk * nk;
}

// eq. 13, 14: the root of eps with n, k >= 0 (for eps2 >= 0), computed without
// cancellation: the larger of n, k from its formula, the other from eps2 = 2 n k.
template <typename T>
Complex<T> IndexFromPermittivity(const Complex<T>& eps) {
  using std::sqrt;
  const T mod = sqrt(eps.re * eps.re + eps.im * eps.im);
  if (mod == T(0)) return {T(0), T(0)};
  if (eps.re >= T(0)) {
    const T n = sqrt((mod + eps.re) * T(0.5));
    return {n, eps.im / (T(2) * n)};
  }
  const T k = sqrt((mod - eps.re) * T(0.5));
  return {eps.im / (T(2) * k), k};
}

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_PERMITTIVITY_H_
