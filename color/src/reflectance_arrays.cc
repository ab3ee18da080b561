#include "alloycolor/color/reflectance_arrays.h"

#include <cmath>

#include "alloycolor/core/simd.h"

namespace alloycolor::color {
namespace {

// sums[q] = sum over i of w[q][i] r(i), in SIMD lanes: `omp simd` lets the compiler keep
// one partial sum per lane (the order of the additions is the only change).
#define ALLOYCOLOR_LANE_SUMS _Pragma("omp simd reduction(+ : sx, sy, sz)")

// NormalReflectance of the principal root N = n + i k of eps (IndexFromPermittivity):
// t = sqrt((|eps| + |eps1|) / 2) is the larger of n, |k| and 2 t times the other is |eps2|,
// so with numerator and denominator multiplied by 4 t^2 there is one division:
//   eps1 >= 0 (n = t):  R = (4 t^2 (t - 1)^2 + eps2^2) / (4 t^2 (t + 1)^2 + eps2^2)
//   eps1 < 0 (k = t):   R = ((|eps2| - 2 t)^2 + 4 t^4) / ((|eps2| + 2 t)^2 + 4 t^4)
// (sums of squares: no cancellation). eps = 0 (N = 0): R = 1.
ALLOYCOLOR_SIMD_CLONES
void NormalReflectanceSums(std::size_t m, const double* __restrict eps1,
                           const double* __restrict eps2, const double* __restrict wx,
                           const double* __restrict wy, const double* __restrict wz,
                           double sums[3]) {
  double sx = 0, sy = 0, sz = 0;
  ALLOYCOLOR_LANE_SUMS
  for (std::size_t i = 0; i < m; ++i) {
    const double e1 = eps1[i], e2 = eps2[i];
    const double a = std::sqrt(e1 * e1 + e2 * e2);
    const double t = std::sqrt((a + std::abs(e1)) * 0.5);
    const double t2 = 4.0 * t * t, e22 = e2 * e2, b = std::abs(e2);
    const double num = e1 >= 0.0 ? t2 * (t - 1.0) * (t - 1.0) + e22
                                 : (b - 2.0 * t) * (b - 2.0 * t) + 0.25 * t2 * t2;
    const double den = e1 >= 0.0 ? t2 * (t + 1.0) * (t + 1.0) + e22
                                 : (b + 2.0 * t) * (b + 2.0 * t) + 0.25 * t2 * t2;
    const double q = num / den;
    const double r = den == 0.0 ? 1.0 : q;
    sx += wx[i] * r;
    sy += wy[i] * r;
    sz += wz[i] * r;
  }
  sums[0] = sx;
  sums[1] = sy;
  sums[2] = sz;
}

// FresnelReflectance(N, c).Average() with N^2 = eps: S = sqrt(eps - sin^2) (the principal
// root, as Sqrt in complex.h), Rs = |c - S|^2 / |c + S|^2, Rp = |eps c - S|^2 / |eps c + S|^2.
// Sqrt's t is one part of S and the other is |Im| / (2 t) (signed), so every term is
// multiplied by T = 2 t: S' = T S has the parts 2 t^2 and Im, |S'|^2 = 4 t^2 |eps - sin^2|,
// and with P = c T eps,
//   |cT -+ S'|^2 = A -+ B,  A = (cT)^2 + |S'|^2,  B = 2 cT Re S',
//   |P -+ S'|^2  = C -+ D,  C = |P|^2 + |S'|^2,   D = 2 Re(P conj S'),
//   (Rs + Rp) / 2 = (AC - BD) / ((A + B)(C + D)):  one division.
// The two 0/0 limits as FresnelReflectance: Rs = 0 where its denominator is 0, Rp = Rs
// where its is; S = 0 (then T = 1) where eps = sin^2.
ALLOYCOLOR_SIMD_CLONES
void ObliqueReflectanceSums(std::size_t m, const double* __restrict eps1,
                            const double* __restrict eps2, double c, const double* __restrict wx,
                            const double* __restrict wy, const double* __restrict wz,
                            double sums[3]) {
  const double sin2 = 1.0 - c * c;
  double sx = 0, sy = 0, sz = 0;
  ALLOYCOLOR_LANE_SUMS
  for (std::size_t i = 0; i < m; ++i) {
    const double e1 = eps1[i], e2 = eps2[i];
    const double zr = e1 - sin2;
    const double a = std::sqrt(zr * zr + e2 * e2);
    const double t = std::sqrt((a + std::abs(zr)) * 0.5);
    const bool zero = a == 0.0;
    const double tt = 2.0 * t * t;
    const double sre = zero ? 0.0 : zr >= 0.0 ? tt : std::abs(e2);
    const double sim = zero ? 0.0 : zr >= 0.0 ? e2 : (e2 < 0.0 ? -tt : tt);
    const double ct = zero ? c : 2.0 * c * t;
    const double s2 = 2.0 * tt * a;  // |S'|^2
    const double A = ct * ct + s2, B = 2.0 * ct * sre;
    const double C = ct * ct * (e1 * e1 + e2 * e2) + s2, D = 2.0 * ct * (e1 * sre + e2 * sim);
    const double ds = A + B, dp = C + D;
    const double num = ds == 0.0 ? C - D : dp == 0.0 ? A - B : A * C - B * D;
    const double den = ds == 0.0 ? 2.0 * dp : dp == 0.0 ? ds : ds * dp;
    const double q = num / den;
    const double r = den == 0.0 ? 0.0 : q;
    sx += wx[i] * r;
    sy += wy[i] * r;
    sz += wz[i] * r;
  }
  sums[0] = sx;
  sums[1] = sy;
  sums[2] = sz;
}

}  // namespace

void ReflectanceSums(std::size_t m, const double* eps1, const double* eps2, double cos_psi,
                     bool normal, const double* wx, const double* wy, const double* wz,
                     double sums[3]) {
  if (normal) {
    NormalReflectanceSums(m, eps1, eps2, wx, wy, wz, sums);
  } else {
    ObliqueReflectanceSums(m, eps1, eps2, cos_psi, wx, wy, wz, sums);
  }
}

}  // namespace alloycolor::color
