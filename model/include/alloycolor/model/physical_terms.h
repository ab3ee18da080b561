// The terms of the physical model (physical_model.h has the formulas and their sources),
// each as a function of its parameters at one photon energy w (eV), templated on the
// scalar: the fit differentiates them with ceres::Jet or takes their gradients below, the
// model evaluates them on double, the wavelength kernel (physical_kernel.h) on a scalar of
// its own that the compiler turns into SIMD lanes. Complex arithmetic on explicit real and
// imaginary parts (std::complex<Jet> is not supported).
//
// Gradients. Each term's derivatives with respect to its parameters (layout order), by
// hand, for the fit's Jacobian (tests/physical_kernel_test.cc checks them against
// ceres::Jet and finite differences). Every term is holomorphic in c = w + i G, so
// d/dG = i d/dc. Rioux et al.'s first term, A B / c^2 with
//   B = K - t1 - t2 - (r / 2) lg,  t1 = s1 atan(r / s1),  t2 = s2 atanh(r / s2),
//   lg = ln(1 - c^2 / E0^2),  K = 2 sqrt(Eg) atanh(r / sqrt(Eg)),  r^2 = Eg - E0,
// has derivatives that need no function beyond those of its value (s1^2 + r^2 = c - E0,
// s2^2 - r^2 = c + E0 make the rational parts cancel):
//   dB/dc  = -(t1 / (c - Eg) + t2 / (c + Eg)) / 2,
//   dB/dE0 = lg / (4 r),
//   dB/dEg = K / (2 Eg) + (t1 / (c - Eg) - t2 / (c + Eg)) / 2 - lg / (4 r).
#ifndef ALLOYCOLOR_MODEL_PHYSICAL_TERMS_H_
#define ALLOYCOLOR_MODEL_PHYSICAL_TERMS_H_

#include <cmath>

#include "alloycolor/core/complex.h"
#include "alloycolor/model/optics.h"

namespace alloycolor {

enum class TermKind { kDrude, kLorentz, kCriticalPoint, kRiouxGap, kRiouxEdge };

// The physics is inlined wherever it is used: the wavelength kernel's loops become SIMD
// lanes only when every call in them is inlined.
#if defined(__GNUC__)
#define ALLOYCOLOR_PHYSICS_INLINE inline __attribute__((always_inline))
#else
#define ALLOYCOLOR_PHYSICS_INLINE inline
#endif

// Complex arithmetic the terms need (principal branches). A scalar type may bring its own
// overloads, found by argument-dependent lookup, as the wavelength kernel does.
namespace complex_ops {

template <typename T>
ALLOYCOLOR_PHYSICS_INLINE Complex<T> Divide(const Complex<T>& a, const Complex<T>& b) {
  const T inverse = T(1.0) / (b.re * b.re + b.im * b.im);
  return {(a.re * b.re + a.im * b.im) * inverse, (a.im * b.re - a.re * b.im) * inverse};
}
template <typename T>
ALLOYCOLOR_PHYSICS_INLINE Complex<T> Log(const Complex<T>& z) {
  using std::atan2;
  using std::log;
  return {T(0.5) * log(z.re * z.re + z.im * z.im), atan2(z.im, z.re)};
}
// ln(a / b) (principal branch) where the arguments of a and b differ by less than pi, as
// they do in the terms below: one logarithm.
template <typename T>
ALLOYCOLOR_PHYSICS_INLINE Complex<T> LogRatio(const Complex<T>& a, const Complex<T>& b) {
  return Log(Divide(a, b));
}
template <typename T>
ALLOYCOLOR_PHYSICS_INLINE Complex<T> Scaled(const Complex<T>& z, const T& s) {
  return {z.re * s, z.im * s};
}
// i z.
template <typename T>
ALLOYCOLOR_PHYSICS_INLINE Complex<T> TimesI(const Complex<T>& z) {
  return {-z.im, z.re};
}

}  // namespace complex_ops

// Lorentz (A, E0, G): A E0^2 / (E0^2 - w^2 - i w G).
template <typename T, typename W>
ALLOYCOLOR_PHYSICS_INLINE Complex<T> LorentzTerm(const T* v, const W& omega_ev) {
  using complex_ops::Divide;
  const T w(omega_ev);
  const T e2 = v[1] * v[1];
  return Divide(Complex<T>{v[0] * e2, T(0.0)}, Complex<T>{e2 - w * w, -w * v[2]});
}

// Critical point (A, E0, G, phi): A E0 [e^{i phi} / (E0 - w - i G) + e^{-i phi} /
// (E0 + w + i G)].
template <typename T, typename W>
ALLOYCOLOR_PHYSICS_INLINE Complex<T> CriticalPointTerm(const T* v, const W& omega_ev) {
  using complex_ops::Divide;
  using std::cos;
  using std::sin;
  const T w(omega_ev);
  const T c = cos(v[3]), s = sin(v[3]);
  const Complex<T> a = Divide(Complex<T>{c, s}, Complex<T>{v[1] - w, -v[2]});
  const Complex<T> b = Divide(Complex<T>{c, -s}, Complex<T>{v[1] + w, v[2]});
  const T scale = v[0] * v[1];
  return {scale * (a.re + b.re), scale * (a.im + b.im)};
}

// ln(1 - c^2 / E0^2), c = w + i G: both terms of Rioux et al. have it.
template <typename T>
ALLOYCOLOR_PHYSICS_INLINE Complex<T> RiouxEdgeLog(const Complex<T>& c2, const T& e0) {
  using complex_ops::Log;
  const T inverse = T(1.0) / (e0 * e0);
  return Log(Complex<T>{T(1.0) - c2.re * inverse, -c2.im * inverse});
}

// Rioux et al.'s first term, the part that does not depend on w:
// K = 2 sqrt(Eg) atanh(r / sqrt(Eg)).
template <typename T>
ALLOYCOLOR_PHYSICS_INLINE T RiouxGapConstant(const T* v) {
  using std::log;
  using std::sqrt;
  const T y = sqrt(v[2] - v[1]) / sqrt(v[2]);
  return sqrt(v[2]) * log((T(1.0) + y) / (T(1.0) - y));
}

// Rioux et al.'s first term (A, E0, Eg, G) at w, in parts (the header above), with the
// arctangents as logarithms of one ratio each:
//   s1 atan(r / s1) = (i s1 / 2) ln((s1 - i r) / (s1 + i r)),
//   s2 atanh(r / s2) = (s2 / 2) ln((s2 + r) / (s2 - r)),
// principal branches as the closed form's (the ratios never cross the negative real axis
// for G > 0).
template <typename T>
struct RiouxGapParts {
  Complex<T> c2, t1, t2, lg, bracket;  // bracket: B
  T r;
};
template <typename T, typename W>
ALLOYCOLOR_PHYSICS_INLINE RiouxGapParts<T> RiouxGapAt(const T* v, const T& constant,
                                                      const W& omega_ev) {
  using complex_ops::LogRatio;
  using std::sqrt;
  const T w(omega_ev);
  const T e0 = v[1], eg = v[2], g = v[3];
  RiouxGapParts<T> p;
  p.r = sqrt(eg - e0);
  const Complex<T> c{w, g};
  p.c2 = c * c;
  const Complex<T> s1 = Sqrt(Complex<T>{w - eg, g});
  const Complex<T> s2 = Sqrt(Complex<T>{w + eg, g});
  const Complex<T> l1 = LogRatio(Complex<T>{s1.re, s1.im - p.r}, Complex<T>{s1.re, s1.im + p.r});
  const Complex<T> l2 = LogRatio(Complex<T>{s2.re + p.r, s2.im}, Complex<T>{s2.re - p.r, s2.im});
  // t1 = (i s1 / 2) l1, t2 = (s2 / 2) l2.
  p.t1 = {T(-0.5) * (s1.re * l1.im + s1.im * l1.re), T(0.5) * (s1.re * l1.re - s1.im * l1.im)};
  p.t2 = T(0.5) * (s2 * l2);
  p.lg = RiouxEdgeLog(p.c2, e0);
  p.bracket = {-p.t1.re - p.t2.re + constant - T(0.5) * p.r * p.lg.re,
               -p.t1.im - p.t2.im - T(0.5) * p.r * p.lg.im};
  return p;
}
template <typename T, typename W>
ALLOYCOLOR_PHYSICS_INLINE Complex<T> RiouxGapTerm(const T* v, const T& constant,
                                                  const W& omega_ev) {
  using complex_ops::Divide;
  const RiouxGapParts<T> p = RiouxGapAt(v, constant, omega_ev);
  const Complex<T> q = Divide(p.bracket, p.c2);
  return {v[0] * q.re, v[0] * q.im};
}

// Rioux et al.'s second term (A, E0, G): -A ln(1 - c^2 / E0^2) / (2 c^2).
template <typename T, typename W>
ALLOYCOLOR_PHYSICS_INLINE Complex<T> RiouxEdgeTerm(const T* v, const W& omega_ev) {
  using complex_ops::Divide;
  const T w(omega_ev);
  const Complex<T> c{w, v[2]};
  const Complex<T> c2 = c * c;
  const Complex<T> q = Divide(RiouxEdgeLog(c2, v[1]), c2);
  return {T(-0.5) * v[0] * q.re, T(-0.5) * v[0] * q.im};
}

// One interband term at photon energy w; v points at the term's parameters.
template <typename T, typename W>
Complex<T> InterbandPermittivity(TermKind kind, const T* v, const W& omega_ev) {
  switch (kind) {
    case TermKind::kLorentz:  // A, E0, G
      return LorentzTerm(v, omega_ev);
    case TermKind::kCriticalPoint:  // A, E0, G, phi
      return CriticalPointTerm(v, omega_ev);
    case TermKind::kRiouxGap:  // A, E0, Eg, G
      return RiouxGapTerm(v, RiouxGapConstant(v), omega_ev);
    case TermKind::kRiouxEdge:  // A, E0, G
      return RiouxEdgeTerm(v, omega_ev);
    case TermKind::kDrude:
      break;
  }
  return {T(0.0), T(0.0)};
}

// ---- gradients -------------------------------------------------------------------------

// A term's eps and its derivatives with respect to its parameters (layout order).
template <typename T>
struct TermGradient {
  Complex<T> value;
  Complex<T> d[4];
};

// Drude (eps_inf, wp, gamma): eps_inf - wp^2 q, q = 1 / (w (w + i gamma)).
template <typename T, typename W>
ALLOYCOLOR_PHYSICS_INLINE TermGradient<T> DrudeGradient(const T* v, const W& omega_ev) {
  using complex_ops::Divide;
  using complex_ops::Scaled;
  using complex_ops::TimesI;
  const T w(omega_ev);
  const Complex<T> wg{w, v[2]};
  const Complex<T> q = Divide(Complex<T>{T(1.0), T(0.0)}, Complex<T>{w * w, w * v[2]});
  const T wp2 = v[1] * v[1];
  TermGradient<T> g;
  g.value = {v[0] - wp2 * q.re, -wp2 * q.im};
  g.d[0] = {T(1.0), T(0.0)};
  g.d[1] = Scaled(q, T(-2.0) * v[1]);
  g.d[2] = TimesI(Scaled(Divide(q, wg), wp2));
  return g;
}

// Lorentz: with D = E0^2 - w^2 - i w G, d/dA = E0^2 / D, d/dE0 = -2 A E0 w (w + i G) / D^2,
// d/dG = i w A E0^2 / D^2.
template <typename T, typename W>
ALLOYCOLOR_PHYSICS_INLINE TermGradient<T> LorentzGradient(const T* v, const W& omega_ev) {
  using complex_ops::Divide;
  using complex_ops::Scaled;
  using complex_ops::TimesI;
  const T w(omega_ev);
  const T e2 = v[1] * v[1];
  const Complex<T> inv_d = Divide(Complex<T>{T(1.0), T(0.0)}, Complex<T>{e2 - w * w, -w * v[2]});
  const Complex<T> inv_d2 = inv_d * inv_d;
  TermGradient<T> g;
  g.d[0] = Scaled(inv_d, e2);
  g.value = Scaled(g.d[0], v[0]);
  g.d[1] = Scaled(Complex<T>{w, v[2]} * inv_d2, T(-2.0) * v[0] * v[1] * w);
  g.d[2] = TimesI(Scaled(inv_d2, w * v[0] * e2));
  return g;
}

// Critical point: with P = e^{i phi} a, a = 1 / (E0 - w - i G), M = e^{-i phi} b,
// b = 1 / (E0 + w + i G): d/dA = E0 (P + M), d/dE0 = A (P + M) - A E0 (P a + M b),
// d/dG = i A E0 (P a - M b), d/dphi = i A E0 (P - M).
template <typename T, typename W>
ALLOYCOLOR_PHYSICS_INLINE TermGradient<T> CriticalPointGradient(const T* v, const W& omega_ev) {
  using complex_ops::Divide;
  using complex_ops::Scaled;
  using complex_ops::TimesI;
  using std::cos;
  using std::sin;
  const T w(omega_ev);
  const T c = cos(v[3]), s = sin(v[3]);
  const Complex<T> a = Divide(Complex<T>{T(1.0), T(0.0)}, Complex<T>{v[1] - w, -v[2]});
  const Complex<T> b = Divide(Complex<T>{T(1.0), T(0.0)}, Complex<T>{v[1] + w, v[2]});
  const Complex<T> p = Complex<T>{c, s} * a, m = Complex<T>{c, -s} * b;
  const Complex<T> sum = p + m;
  const Complex<T> pa = p * a, mb = m * b;
  const T scale = v[0] * v[1];
  TermGradient<T> g;
  g.value = Scaled(sum, scale);
  g.d[0] = Scaled(sum, v[1]);
  g.d[1] = Scaled(sum, v[0]) - Scaled(pa + mb, scale);
  g.d[2] = TimesI(Scaled(pa - mb, scale));
  g.d[3] = TimesI(Scaled(p - m, scale));
  return g;
}

// Rioux et al.'s first term, A B / c^2 (the header's derivatives of B).
template <typename T, typename W>
ALLOYCOLOR_PHYSICS_INLINE TermGradient<T> RiouxGapGradient(const T* v, const T& constant,
                                                           const W& omega_ev) {
  using complex_ops::Divide;
  using complex_ops::Scaled;
  using complex_ops::TimesI;
  const T w(omega_ev);
  const T eg = v[2], g_width = v[3];
  const RiouxGapParts<T> p = RiouxGapAt(v, constant, omega_ev);
  const Complex<T> inv_c2 = Divide(Complex<T>{T(1.0), T(0.0)}, p.c2);
  const Complex<T> u1 = Divide(p.t1, Complex<T>{w - eg, g_width});  // t1 / (c - Eg)
  const Complex<T> u2 = Divide(p.t2, Complex<T>{w + eg, g_width});  // t2 / (c + Eg)
  const Complex<T> lg4r = Scaled(p.lg, T(0.25) / p.r);
  // dB/dc - 2 B / c: the derivative of B / c^2 times c^2.
  const Complex<T> dc =
      Scaled(u1 + u2, T(-0.5)) - Scaled(Divide(p.bracket, Complex<T>{w, g_width}), T(2.0));
  const Complex<T> a_c2 = Scaled(inv_c2, v[0]);
  TermGradient<T> g;
  g.d[0] = p.bracket * inv_c2;
  g.value = Scaled(g.d[0], v[0]);
  g.d[1] = a_c2 * lg4r;
  g.d[2] = a_c2 * (Complex<T>{constant / (T(2.0) * eg), T(0.0)} + Scaled(u1 - u2, T(0.5)) - lg4r);
  g.d[3] = TimesI(a_c2 * dc);
  return g;
}

// Rioux et al.'s second term: d/dA = -lg / (2 c^2),
// d/dc = -A (c / (c^2 - E0^2) - lg / c) / c^2, d/dE0 = A / (E0 (c^2 - E0^2)).
template <typename T, typename W>
ALLOYCOLOR_PHYSICS_INLINE TermGradient<T> RiouxEdgeGradient(const T* v, const W& omega_ev) {
  using complex_ops::Divide;
  using complex_ops::Scaled;
  using complex_ops::TimesI;
  const T w(omega_ev);
  const Complex<T> c{w, v[2]};
  const Complex<T> c2 = c * c;
  const Complex<T> lg = RiouxEdgeLog(c2, v[1]);
  const Complex<T> inv_c2 = Divide(Complex<T>{T(1.0), T(0.0)}, c2);
  const Complex<T> inv_gap =
      Divide(Complex<T>{T(1.0), T(0.0)}, Complex<T>{c2.re - v[1] * v[1], c2.im});
  TermGradient<T> g;
  g.d[0] = Scaled(lg * inv_c2, T(-0.5));
  g.value = Scaled(g.d[0], v[0]);
  g.d[1] = Scaled(inv_gap, v[0] / v[1]);
  g.d[2] = TimesI(Scaled((c * inv_gap - Divide(lg, c)) * inv_c2, -v[0]));
  return g;
}

// Any term's gradient at w (the Drude term's too); v points at the term's parameters.
template <typename T, typename W>
TermGradient<T> TermGradientAt(TermKind kind, const T* v, const W& omega_ev) {
  switch (kind) {
    case TermKind::kDrude:
      return DrudeGradient(v, omega_ev);
    case TermKind::kLorentz:
      return LorentzGradient(v, omega_ev);
    case TermKind::kCriticalPoint:
      return CriticalPointGradient(v, omega_ev);
    case TermKind::kRiouxGap:
      return RiouxGapGradient(v, RiouxGapConstant(v), omega_ev);
    case TermKind::kRiouxEdge:
      return RiouxEdgeGradient(v, omega_ev);
  }
  return {};
}

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_PHYSICAL_TERMS_H_
