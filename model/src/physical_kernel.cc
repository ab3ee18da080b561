#include "alloycolor/model/physical_kernel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "alloycolor/core/simd.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/optics.h"

// The kernel's loops are built for x86-64-v4 (AVX-512) as well where the compiler clones
// (core/simd.h, and as there not under ThreadSanitizer): its many divisions and
// polynomial steps gain from the wider registers.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__linux__) && \
    !defined(__SANITIZE_THREAD__)
#define ALLOYCOLOR_KERNEL_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define ALLOYCOLOR_KERNEL_CLONES
#endif

// On the lambdas that hold a term, so that the loop inlines them.
#if defined(__GNUC__)
#define ALLOYCOLOR_LANE_INLINE __attribute__((always_inline))
#else
#define ALLOYCOLOR_LANE_INLINE
#endif

namespace alloycolor::kernel {
namespace {

constexpr double kNaN = __builtin_nan("");

ALLOYCOLOR_PHYSICS_INLINE std::uint64_t BitsOf(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
ALLOYCOLOR_PHYSICS_INLINE double DoubleOf(std::uint64_t b) {
  double x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}

// ln x: x = 2^k m with m in [sqrt(1/2), sqrt(2)), ln m = 2 atanh(s), s = (m - 1) / (m + 1),
// |s| <= 0.1716, 2 atanh(s) = 2 s + 2 s z Q(z), z = s^2, Q fitted to the series
// sum_{j>=1} z^(j-1) / (2 j + 1) (least squares reweighted towards the minimax, relative
// error 8e-16 over z in [0, 0.0295]); ln 2 in two parts (Cody and Waite). NaN unless x is
// a positive normal number.
ALLOYCOLOR_PHYSICS_INLINE double Ln(double x) {
  const std::uint64_t bits = BitsOf(x);
  // The exponent field as a double (2^52 + field - 2^52), unbiased.
  const double field = DoubleOf((bits >> 52) | 0x4330000000000000ull) - 4503599627370496.0;
  const double mantissa = DoubleOf((bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);
  const bool high = mantissa > 1.4142135623730951;
  const double m = high ? 0.5 * mantissa : mantissa;
  const double k = (high ? field + 1.0 : field) - 1023.0;
  const double s = (m - 1.0) / (m + 1.0);
  const double z = s * s;
  double q = 0.07302297856779695;
  q = q * z + 0.07666418065966413;
  q = q * z + 0.09091424510920676;
  q = q * z + 0.11111105910923404;
  q = q * z + 0.14285714310165906;
  q = q * z + 0.19999999999959436;
  q = q * z + 0.3333333333333333;
  const double ln_m = 2.0 * s + 2.0 * s * z * q;
  const double result = k * 0.6931471803691238 + (ln_m + k * 1.9082149292705877e-10);
  const bool normal = (x >= 2.2250738585072014e-308) & (x <= 1.7976931348623157e308);
  return normal ? result : kNaN;
}

// atan2(y, x): t = min(|x|, |y|) / max(|x|, |y|) in [0, 1], and above tan(pi/8)
// atan t = pi/4 + atan((t - 1) / (t + 1)), so that the argument u lies in
// [-tan(pi/8), tan(pi/8)] (one division either way); atan u = u + u z P(z), z = u^2, P
// fitted to sum_{j>=1} (-1)^j z^(j-1) / (2 j + 1) as Q above (relative error 1.2e-15
// over z in [0, 0.1716]); then the octant. NaN unless x and y are finite.
ALLOYCOLOR_PHYSICS_INLINE double Atan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const bool steep = ay > ax;
  const double big = steep ? ay : ax, small = steep ? ax : ay;
  const bool reduce = small > 0.41421356237309503 * big;
  const double num = reduce ? small - big : small;
  const double den = reduce ? small + big : big;
  const double u = den == 0.0 ? 0.0 : num / den;
  const double z = u * u;
  double p = -0.01818595656732212;
  p = p * z + 0.03832634018101479;
  p = p * z + -0.05050058616163249;
  p = p * z + 0.058504319706126795;
  p = p * z + -0.06663486164325856;
  p = p * z + 0.07692098071476236;
  p = p * z + -0.09090900223123417;
  p = p * z + 0.11111110884829609;
  p = p * z + -0.14285714282605888;
  p = p * z + 0.19999999999981652;
  p = p * z + -0.333333333333333;
  double a = u + u * z * p;
  a = reduce ? a + 0.78539816339744831 : a;
  a = steep ? 1.5707963267948966 - a : a;
  a = (BitsOf(x) >> 63) != 0 ? 3.1415926535897931 - a : a;
  a = (BitsOf(y) >> 63) != 0 ? -a : a;
  const bool finite = (x - x) + (y - y) == 0.0;
  return finite ? a : kNaN;
}

// ln(a / b) for positive normal a and b, with one division: a = 2^i ma, b = 2^j mb with
// mantissas in [1, 2), one of them doubled so that ma / mb lies in [sqrt(1/2), sqrt(2)),
// then ln(ma / mb) = 2 atanh(s), s = (ma - mb) / (ma + mb), as in Ln. NaN unless both are
// positive normal numbers.
ALLOYCOLOR_PHYSICS_INLINE double LnRatio(double a, double b) {
  const std::uint64_t ba = BitsOf(a), bb = BitsOf(b);
  const double ea = DoubleOf((ba >> 52) | 0x4330000000000000ull);
  const double eb = DoubleOf((bb >> 52) | 0x4330000000000000ull);
  double ma = DoubleOf((ba & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);
  double mb = DoubleOf((bb & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);
  double k = ea - eb;
  const bool high = ma > 1.4142135623730951 * mb, low = mb > 1.4142135623730951 * ma;
  mb = high ? 2.0 * mb : mb;
  ma = low ? 2.0 * ma : ma;
  k = high ? k + 1.0 : low ? k - 1.0 : k;
  const double s = (ma - mb) / (ma + mb);
  const double z = s * s;
  double q = 0.07302297856779695;
  q = q * z + 0.07666418065966413;
  q = q * z + 0.09091424510920676;
  q = q * z + 0.11111105910923404;
  q = q * z + 0.14285714310165906;
  q = q * z + 0.19999999999959436;
  q = q * z + 0.3333333333333333;
  const double result =
      k * 0.6931471803691238 + (2.0 * s + 2.0 * s * z * q + k * 1.9082149292705877e-10);
  const bool normal = (a >= 2.2250738585072014e-308) & (a <= 1.7976931348623157e308) &
                      (b >= 2.2250738585072014e-308) & (b <= 1.7976931348623157e308);
  return normal ? result : kNaN;
}

// The scalar the terms run on here: a double whose ln and atan2 are the above (found by
// argument-dependent lookup from the templated physics), and whose complex square root,
// logarithm, logarithm of a ratio and division avoid branches and second divisions.
struct Lane {
  double v;
  Lane() = default;
  ALLOYCOLOR_PHYSICS_INLINE Lane(double x) : v(x) {}  // NOLINT: a scalar converts
};
ALLOYCOLOR_PHYSICS_INLINE Lane operator+(Lane a, Lane b) { return a.v + b.v; }
ALLOYCOLOR_PHYSICS_INLINE Lane operator-(Lane a, Lane b) { return a.v - b.v; }
ALLOYCOLOR_PHYSICS_INLINE Lane operator*(Lane a, Lane b) { return a.v * b.v; }
ALLOYCOLOR_PHYSICS_INLINE Lane operator/(Lane a, Lane b) { return a.v / b.v; }
ALLOYCOLOR_PHYSICS_INLINE Lane operator-(Lane a) { return -a.v; }
ALLOYCOLOR_PHYSICS_INLINE Lane log(Lane x) { return Ln(x.v); }
ALLOYCOLOR_PHYSICS_INLINE Lane atan2(Lane y, Lane x) { return Atan2(y.v, x.v); }
ALLOYCOLOR_PHYSICS_INLINE Lane sqrt(Lane x) { return std::sqrt(x.v); }
// Of a loop-invariant phase only (hoisted out of the loops).
ALLOYCOLOR_PHYSICS_INLINE Lane cos(Lane x) { return std::cos(x.v); }
ALLOYCOLOR_PHYSICS_INLINE Lane sin(Lane x) { return std::sin(x.v); }

using LaneComplex = Complex<Lane>;

// complex.h's Sqrt with selects in place of branches.
ALLOYCOLOR_PHYSICS_INLINE LaneComplex Sqrt(const LaneComplex& z) {
  const double re = z.re.v, im = z.im.v;
  const double r = std::sqrt(re * re + im * im);
  const double t = std::sqrt((r + std::abs(re)) * 0.5);
  const double other = t == 0.0 ? 0.0 : im / (2.0 * t);
  if (re >= 0.0) return {t, other};
  return {std::abs(other), im < 0.0 ? -t : t};
}
ALLOYCOLOR_PHYSICS_INLINE LaneComplex Divide(const LaneComplex& a, const LaneComplex& b) {
  const double inverse = 1.0 / (b.re.v * b.re.v + b.im.v * b.im.v);
  return {(a.re.v * b.re.v + a.im.v * b.im.v) * inverse,
          (a.im.v * b.re.v - a.re.v * b.im.v) * inverse};
}
ALLOYCOLOR_PHYSICS_INLINE LaneComplex Log(const LaneComplex& z) {
  return {0.5 * Ln(z.re.v * z.re.v + z.im.v * z.im.v), Atan2(z.im.v, z.re.v)};
}
// ln(a / b): ln |a|^2 / |b|^2 in one division and the argument of a conj(b), none.
ALLOYCOLOR_PHYSICS_INLINE LaneComplex LogRatio(const LaneComplex& a, const LaneComplex& b) {
  const double ar = a.re.v, ai = a.im.v, br = b.re.v, bi = b.im.v;
  return {0.5 * LnRatio(ar * ar + ai * ai, br * br + bi * bi),
          Atan2(ai * br - ar * bi, ar * br + ai * bi)};
}

// eps1[i] (+)= term at omega[i], eps2 likewise: `Add` false sets, true adds.
template <bool kAdd, typename Term>
ALLOYCOLOR_PHYSICS_INLINE void TermLoop(std::size_t m, const double* __restrict omega,
                                        double* __restrict eps1, double* __restrict eps2,
                                        Term term) {
  for (std::size_t i = 0; i < m; ++i) {
    const LaneComplex e = term(Lane(omega[i]));
    eps1[i] = kAdd ? eps1[i] + e.re.v : e.re.v;
    eps2[i] = kAdd ? eps2[i] + e.im.v : e.im.v;
  }
}

// The Drude term (eps_inf, wp, gamma) sets eps; each interband term adds its own.
ALLOYCOLOR_KERNEL_CLONES
void SetDrude(std::size_t m, const double* omega, const double* v, double* eps1, double* eps2) {
  const Lane eps_inf(v[0]), wp2(v[1] * v[1]), gamma(v[2]);
  TermLoop<false>(m, omega, eps1, eps2, [&](Lane w) ALLOYCOLOR_LANE_INLINE {
    return DrudePermittivity(w, wp2, gamma, eps_inf);
  });
}

ALLOYCOLOR_KERNEL_CLONES
void AddLorentz(std::size_t m, const double* omega, const double* v, double* eps1, double* eps2) {
  const Lane p[3] = {v[0], v[1], v[2]};
  TermLoop<true>(m, omega, eps1, eps2,
                 [&](Lane w) ALLOYCOLOR_LANE_INLINE { return LorentzTerm(p, w); });
}

ALLOYCOLOR_KERNEL_CLONES
void AddCriticalPoint(std::size_t m, const double* omega, const double* v, double* eps1,
                      double* eps2) {
  const Lane p[4] = {v[0], v[1], v[2], v[3]};
  TermLoop<true>(m, omega, eps1, eps2,
                 [&](Lane w) ALLOYCOLOR_LANE_INLINE { return CriticalPointTerm(p, w); });
}

ALLOYCOLOR_KERNEL_CLONES
void AddRiouxGap(std::size_t m, const double* omega, const double* v, double* eps1, double* eps2) {
  const Lane p[4] = {v[0], v[1], v[2], v[3]};
  const Lane constant = RiouxGapConstant(v);  // with the C library's logarithm, once
  TermLoop<true>(m, omega, eps1, eps2,
                 [&](Lane w) ALLOYCOLOR_LANE_INLINE { return RiouxGapTerm(p, constant, w); });
}

ALLOYCOLOR_KERNEL_CLONES
void AddRiouxEdge(std::size_t m, const double* omega, const double* v, double* eps1, double* eps2) {
  const Lane p[3] = {v[0], v[1], v[2]};
  TermLoop<true>(m, omega, eps1, eps2,
                 [&](Lane w) ALLOYCOLOR_LANE_INLINE { return RiouxEdgeTerm(p, w); });
}

// The gradient loops: eps1, eps2 set (Drude) or added to, and each of the term's n
// parameters' derivative into its rows d1[j][i], d2[j][i].
struct GradientRows {
  double* d1[4];
  double* d2[4];
};

template <bool kAdd, int kParams, typename Term>
ALLOYCOLOR_PHYSICS_INLINE void GradientLoop(std::size_t m, const double* __restrict omega,
                                            double* __restrict eps1, double* __restrict eps2,
                                            double* __restrict a1, double* __restrict a2,
                                            double* __restrict b1, double* __restrict b2,
                                            double* __restrict c1, double* __restrict c2,
                                            double* __restrict d1, double* __restrict d2,
                                            Term term) {
  for (std::size_t i = 0; i < m; ++i) {
    const TermGradient<Lane> g = term(Lane(omega[i]));
    eps1[i] = kAdd ? eps1[i] + g.value.re.v : g.value.re.v;
    eps2[i] = kAdd ? eps2[i] + g.value.im.v : g.value.im.v;
    a1[i] = g.d[0].re.v;
    a2[i] = g.d[0].im.v;
    b1[i] = g.d[1].re.v;
    b2[i] = g.d[1].im.v;
    c1[i] = g.d[2].re.v;
    c2[i] = g.d[2].im.v;
    if (kParams == 4) {
      d1[i] = g.d[3].re.v;
      d2[i] = g.d[3].im.v;
    }
  }
}
template <bool kAdd, int kParams, typename Term>
ALLOYCOLOR_PHYSICS_INLINE void GradientLoop(std::size_t m, const double* omega, double* eps1,
                                            double* eps2, const GradientRows& rows, Term term) {
  GradientLoop<kAdd, kParams>(m, omega, eps1, eps2, rows.d1[0], rows.d2[0], rows.d1[1], rows.d2[1],
                              rows.d1[2], rows.d2[2], rows.d1[kParams - 1], rows.d2[kParams - 1],
                              term);
}

ALLOYCOLOR_KERNEL_CLONES
void DrudeWithGradient(std::size_t m, const double* omega, const double* v, double* eps1,
                       double* eps2, const GradientRows& rows) {
  const Lane p[3] = {v[0], v[1], v[2]};
  GradientLoop<false, 3>(m, omega, eps1, eps2, rows,
                         [&](Lane w) ALLOYCOLOR_LANE_INLINE { return DrudeGradient(p, w); });
}

ALLOYCOLOR_KERNEL_CLONES
void LorentzWithGradient(std::size_t m, const double* omega, const double* v, double* eps1,
                         double* eps2, const GradientRows& rows) {
  const Lane p[3] = {v[0], v[1], v[2]};
  GradientLoop<true, 3>(m, omega, eps1, eps2, rows,
                        [&](Lane w) ALLOYCOLOR_LANE_INLINE { return LorentzGradient(p, w); });
}

ALLOYCOLOR_KERNEL_CLONES
void CriticalPointWithGradient(std::size_t m, const double* omega, const double* v, double* eps1,
                               double* eps2, const GradientRows& rows) {
  const Lane p[4] = {v[0], v[1], v[2], v[3]};
  GradientLoop<true, 4>(m, omega, eps1, eps2, rows,
                        [&](Lane w) ALLOYCOLOR_LANE_INLINE { return CriticalPointGradient(p, w); });
}

ALLOYCOLOR_KERNEL_CLONES
void RiouxGapWithGradient(std::size_t m, const double* omega, const double* v, double* eps1,
                          double* eps2, const GradientRows& rows) {
  const Lane p[4] = {v[0], v[1], v[2], v[3]};
  const Lane constant = RiouxGapConstant(v);
  GradientLoop<true, 4>(m, omega, eps1, eps2, rows, [&](Lane w) ALLOYCOLOR_LANE_INLINE {
    return RiouxGapGradient(p, constant, w);
  });
}

ALLOYCOLOR_KERNEL_CLONES
void RiouxEdgeWithGradient(std::size_t m, const double* omega, const double* v, double* eps1,
                           double* eps2, const GradientRows& rows) {
  const Lane p[3] = {v[0], v[1], v[2]};
  GradientLoop<true, 3>(m, omega, eps1, eps2, rows,
                        [&](Lane w) ALLOYCOLOR_LANE_INLINE { return RiouxEdgeGradient(p, w); });
}

ALLOYCOLOR_SIMD_CLONES
bool AllUsableLoop(std::size_t m, const double* __restrict eps1, const double* __restrict eps2) {
  int bad = 0;
#pragma omp simd reduction(| : bad)
  for (std::size_t i = 0; i < m; ++i) {
    const double a = std::abs(eps1[i]), b = std::abs(eps2[i]);
    // NaN fails both comparisons; 0 + 0i is no material.
    bad |= !(a <= kMaxUsablePermittivity && b <= kMaxUsablePermittivity) | (a + b == 0.0);
  }
  return bad == 0;
}

}  // namespace

namespace {

// The terms one after another on `m` photon energies.
void TermsOnRun(const PhysicalLayout& layout, const double* values, std::size_t m,
                const double* omega, double* eps1, double* eps2) {
  SetDrude(m, omega, values, eps1, eps2);
  for (int t = 1; t < layout.num_terms(); ++t) {
    const double* v = values + layout.term_offset(t);
    switch (layout.term_kind(t)) {
      case TermKind::kLorentz:
        AddLorentz(m, omega, v, eps1, eps2);
        break;
      case TermKind::kCriticalPoint:
        AddCriticalPoint(m, omega, v, eps1, eps2);
        break;
      case TermKind::kRiouxGap:
        AddRiouxGap(m, omega, v, eps1, eps2);
        break;
      case TermKind::kRiouxEdge:
        AddRiouxEdge(m, omega, v, eps1, eps2);
        break;
      case TermKind::kDrude:
        break;
    }
  }
}

}  // namespace

namespace {

// TermsOnRun with the gradient: rows of `stride` values, parameter k's at k * stride.
void GradientOnRun(const PhysicalLayout& layout, const double* values, std::size_t m,
                   const double* omega, double* eps1, double* eps2, double* grad1, double* grad2,
                   std::size_t stride) {
  for (int t = 0; t < layout.num_terms(); ++t) {
    const int o = layout.term_offset(t);
    const double* v = values + o;
    GradientRows rows;
    for (int j = 0; j < layout.term_size(t); ++j) {
      rows.d1[j] = grad1 + (o + j) * stride;
      rows.d2[j] = grad2 + (o + j) * stride;
    }
    switch (layout.term_kind(t)) {
      case TermKind::kDrude:
        DrudeWithGradient(m, omega, v, eps1, eps2, rows);
        break;
      case TermKind::kLorentz:
        LorentzWithGradient(m, omega, v, eps1, eps2, rows);
        break;
      case TermKind::kCriticalPoint:
        CriticalPointWithGradient(m, omega, v, eps1, eps2, rows);
        break;
      case TermKind::kRiouxGap:
        RiouxGapWithGradient(m, omega, v, eps1, eps2, rows);
        break;
      case TermKind::kRiouxEdge:
        RiouxEdgeWithGradient(m, omega, v, eps1, eps2, rows);
        break;
    }
  }
}

}  // namespace

void PhysicalGradientOnGrid(const PhysicalLayout& layout, const double* values, std::size_t m,
                            const double* omega_ev, double* eps1, double* eps2, double* grad1,
                            double* grad2) {
  constexpr std::size_t kLanes = 8;
  const std::size_t whole = m / kLanes * kLanes;
  if (whole > 0) GradientOnRun(layout, values, whole, omega_ev, eps1, eps2, grad1, grad2, m);
  if (whole == m) return;
  const std::size_t np = static_cast<std::size_t>(layout.num_parameters());
  alignas(64) double omega[kLanes], e1[kLanes], e2[kLanes];
  alignas(64) double g1[kPhysicalMaxParameters * kLanes], g2[kPhysicalMaxParameters * kLanes];
  for (std::size_t i = 0; i < kLanes; ++i) omega[i] = omega_ev[std::min(whole + i, m - 1)];
  GradientOnRun(layout, values, kLanes, omega, e1, e2, g1, g2, kLanes);
  const std::size_t rest = m - whole;
  std::copy(e1, e1 + rest, eps1 + whole);
  std::copy(e2, e2 + rest, eps2 + whole);
  for (std::size_t k = 0; k < np; ++k) {
    std::copy(g1 + k * kLanes, g1 + k * kLanes + rest, grad1 + k * m + whole);
    std::copy(g2 + k * kLanes, g2 + k * kLanes + rest, grad2 + k * m + whole);
  }
}

void PhysicalPermittivityOnGrid(const PhysicalLayout& layout, const double* values, std::size_t m,
                                const double* omega_ev, double* eps1, double* eps2) {
  // Whole vectors in place; the rest (fewer than kLanes) padded with its last energy to
  // one whole vector: a partial vector at the end of a loop would take the scalar path,
  // as slow per wavelength as a whole vector.
  constexpr std::size_t kLanes = 8;
  const std::size_t whole = m / kLanes * kLanes;
  if (whole > 0) TermsOnRun(layout, values, whole, omega_ev, eps1, eps2);
  if (whole == m) return;
  alignas(64) double omega[kLanes], e1[kLanes], e2[kLanes];
  for (std::size_t i = 0; i < kLanes; ++i) omega[i] = omega_ev[std::min(whole + i, m - 1)];
  TermsOnRun(layout, values, kLanes, omega, e1, e2);
  std::copy(e1, e1 + (m - whole), eps1 + whole);
  std::copy(e2, e2 + (m - whole), eps2 + whole);
}

bool AllUsable(std::size_t m, const double* eps1, const double* eps2) {
  return AllUsableLoop(m, eps1, eps2);
}

double LaneLog(double x) { return Ln(x); }
double LaneAtan2(double y, double x) { return Atan2(y, x); }

}  // namespace alloycolor::kernel
