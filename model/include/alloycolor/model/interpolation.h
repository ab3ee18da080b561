// Interpolation across composition of values known at the samples' compositions, for the
// baselines that interpolate eps at each wavelength (sample_models.h):
//  - linear: the straight line between neighbouring samples;
//  - pchip: monotone piecewise cubic Hermite (Fritsch & Carlson, SIAM J. Numer. Anal. 17,
//    238 (1980)), slopes by the weighted harmonic mean of Fritsch & Butland (1984) as in
//    MATLAB's and SciPy's pchip, end slopes by the shape-preserving three-point formula:
//    no overshoot between samples, the shape of the data kept;
//  - natural cubic spline: C2 piecewise cubic with zero second derivative at the ends.
// Beyond the first and last composition every scheme continues as the straight line with
// its end slope. With two samples all three are the straight line.
#ifndef ALLOYCOLOR_MODEL_INTERPOLATION_H_
#define ALLOYCOLOR_MODEL_INTERPOLATION_H_

#include <algorithm>
#include <cstddef>
#include <vector>

namespace alloycolor {

// PCHIP slopes d[0..n) of (x[i], y[i]), x strictly increasing, n >= 2: the Fritsch-Butland
// weighted harmonic mean inside, the shape-preserving three-point formula at the ends.
// Templated (T = double or ceres::Jet) so the smooth fit differentiates the very scheme its
// model evaluates. Inside each interval the Hermite cubic then stays between the values at
// its ends (Fritsch & Carlson's condition holds), so bounds on the values hold everywhere.
template <typename T>
void PchipSlopes(const double* x, const T* y, size_t n, T* d) {
  if (n == 2) {
    d[0] = d[1] = (y[1] - y[0]) / (x[1] - x[0]);
    return;
  }
  const auto delta = [&](size_t i) { return (y[i + 1] - y[i]) / (x[i + 1] - x[i]); };
  for (size_t i = 1; i + 1 < n; ++i) {
    const T a = delta(i - 1), b = delta(i);
    if (a * b > T(0)) {
      const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
      const double w1 = 2 * h1 + h0, w2 = h1 + 2 * h0;
      d[i] = T(w1 + w2) / (T(w1) / a + T(w2) / b);
    } else {
      d[i] = T(0);
    }
  }
  const auto end = [](double h0, double h1, const T& m0, const T& m1) {
    T s = (T(2 * h0 + h1) * m0 - T(h0) * m1) / T(h0 + h1);
    if (s * m0 <= T(0)) return T(0);
    using std::abs;
    if (m0 * m1 <= T(0) && abs(s) > abs(T(3) * m0)) return T(3) * m0;
    return s;
  };
  d[0] = end(x[1] - x[0], x[2] - x[1], delta(0), delta(1));
  d[n - 1] = end(x[n - 1] - x[n - 2], x[n - 2] - x[n - 3], delta(n - 2), delta(n - 3));
}

// The cubic Hermite interpolant of values y and slopes d at x[0..n) evaluated at xq;
// beyond the ends the straight line with the end slope.
template <typename T>
T HermiteAt(const double* x, const T* y, const T* d, size_t n, double xq) {
  if (xq <= x[0]) return y[0] + d[0] * T(xq - x[0]);
  if (xq >= x[n - 1]) return y[n - 1] + d[n - 1] * T(xq - x[n - 1]);
  const size_t hi = std::upper_bound(x, x + n, xq) - x;
  const size_t lo = hi - 1;
  const double h = x[hi] - x[lo], t = (xq - x[lo]) / h;
  const double t2 = t * t, t3 = t2 * t;
  return T(2 * t3 - 3 * t2 + 1) * y[lo] + T((t3 - 2 * t2 + t) * h) * d[lo] +
         T(-2 * t3 + 3 * t2) * y[hi] + T((t3 - t2) * h) * d[hi];
}

// Slopes d[0..n) of the natural cubic spline through (x[i], y[i]), x strictly increasing,
// n >= 2 (zero second derivative at the ends): its Hermite form.
void NaturalSplineSlopes(const double* x, const double* y, size_t n, double* d);

enum class Interpolation { kLinear, kPchip, kNaturalSpline };

// A scheme fitted to (xs[i], ys[i]), xs strictly increasing, at least two points.
class Interpolant {
 public:
  Interpolant(Interpolation scheme, std::vector<double> xs, std::vector<double> ys);
  double operator()(double x) const;

 private:
  std::vector<double> xs_, ys_;
  std::vector<double> slopes_;  // dy/dx at each x (Hermite form of the cubic schemes)
  bool linear_ = false;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_INTERPOLATION_H_
