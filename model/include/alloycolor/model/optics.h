// Optics of a conductor, written once and templated on the scalar so that the fit (with
// ceres::Jet) and the renderer (with double) run the same physics. Complex numbers are
// carried as explicit real and imaginary parts (std::complex<ceres::Jet> is not supported).
//
// Equations from Kuboshima & Furukawa, "colour expression of solids considering the
// composition of the material", as corrected in MISSION.md:
//   N = n + i k                                             (eq. 1)
//   eps1 = n^2 - k^2,  eps2 = 2 n k                         (eq. 9, 10)
//   n^2 = (|eps| + eps1) / 2,  k^2 = (|eps| - eps1) / 2      (eq. 13, 14), n, k >= 0
//   Fresnel at incidence angle psi0, with S = sqrt(N^2 - sin^2 psi0):
//     Rs = |cos psi0 - S|^2 / |cos psi0 + S|^2
//     Rp = |N^2 cos psi0 - S|^2 / |N^2 cos psi0 + S|^2,   R = (Rs + Rp) / 2   (eq. 2-4)
//   Drude: eps(w) = eps_inf - wp^2 / (w (w + i gamma)),  gamma = 1/tau       (eq. 7)
//     eps1 = eps_inf - wp^2 / (w^2 + gamma^2),  eps2 = wp^2 gamma / (w (w^2 + gamma^2))
//   Pointwise inversion (eq. 11, 12, with the omega the paper drops), eps_inf = 1:
//     w tau = (1 - eps1) / eps2,  wp^2 = (1 - eps1) (w^2 + gamma^2)
//     defined only where eps1 < 1 and eps2 > 0.
// Units: photon energies w, gamma, wp in eV (hbar w); see units.h.
#ifndef ALLOYCOLOR_MODEL_OPTICS_H_
#define ALLOYCOLOR_MODEL_OPTICS_H_

#include <cmath>

#include "alloycolor/core/complex.h"
#include "alloycolor/core/permittivity.h"  // eq. 9, 10, 13, 14
#include "alloycolor/core/units.h"

namespace alloycolor {

template <typename T>
struct Reflectance {
  T s;  // Rs
  T p;  // Rp
  T Average() const { return (s + p) * T(0.5); }
};

// eq. 2-4 for a conductor of index nk in vacuum (or air), light at angle psi0 given by
// cos_psi0 in [0, 1].
template <typename T>
Reflectance<T> FresnelReflectance(const Complex<T>& nk, const T& cos_psi0) {
  const Complex<T> n2 = nk * nk;
  const T sin2 = T(1) - cos_psi0 * cos_psi0;
  const Complex<T> s = Sqrt(Complex<T>{n2.re - sin2, n2.im});
  const Complex<T> c{cos_psi0, T(0)};
  // Two 0/0 limits: N = 1 at grazing incidence (no interface: R = 0), and N = 0 at
  // normal incidence, where Rp tends to Rs = 1.
  const T rs_den = Norm2(c + s);
  const T rs = rs_den == T(0) ? T(0) : Norm2(c - s) / rs_den;
  const Complex<T> n2c = cos_psi0 * n2;
  const T rp_den = Norm2(n2c + s);
  const T rp = rp_den == T(0) ? rs : Norm2(n2c - s) / rp_den;
  return {rs, rp};
}

// Normal incidence: R = ((n-1)^2 + k^2) / ((n+1)^2 + k^2).
template <typename T>
T NormalReflectance(const Complex<T>& nk) {
  const T a = nk.re - T(1);
  const T b = nk.re + T(1);
  const T k2 = nk.im * nk.im;
  return (a * a + k2) / (b * b + k2);
}

// eq. 7 with a background eps_inf: eps = eps_inf - wp2 / (w (w + i gamma)).
template <typename T>
Complex<T> DrudePermittivity(const T& omega_ev, const T& wp2_ev2, const T& gamma_ev,
                             const T& eps_inf = T(1)) {
  const T d = omega_ev * omega_ev + gamma_ev * gamma_ev;
  return {eps_inf - wp2_ev2 / d, wp2_ev2 * gamma_ev / (omega_ev * d)};
}

// Drude parameters that reproduce one permittivity exactly at one photon energy.
struct DrudePoint {
  double gamma_ev;  // hbar / tau
  double wp2_ev2;   // (hbar omega_p)^2
};

// True where eq. 11, 12 are defined: eps1 < 1 and eps2 > 0 (finite).
inline bool DrudeInvertible(double eps1, double eps2) {
  return std::isfinite(eps1) && std::isfinite(eps2) && eps1 < 1.0 && eps2 > 0.0;
}

// eq. 11, 12 with omega: the caller checks DrudeInvertible first.
inline DrudePoint InvertDrude(double omega_ev, double eps1, double eps2) {
  const double gamma = omega_ev * eps2 / (1.0 - eps1);
  return {gamma, (1.0 - eps1) * (omega_ev * omega_ev + gamma * gamma)};
}

// m*/m_e from the free-electron density and the plasma energy: (hbar wp)^2 =
// kPlasmaEv2M3 N_e / (m*/m_e) (eq. 7's wp^2 = N_e e^2 / (eps0 m*)).
inline double EffectiveMassRatio(double n_e_m3, double wp2_ev2) {
  return kPlasmaEv2M3 * n_e_m3 / wp2_ev2;
}

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_OPTICS_H_
