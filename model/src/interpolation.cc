#include "alloycolor/model/interpolation.h"

#include <algorithm>
#include <cmath>

#include "alloycolor/core/error.h"

namespace alloycolor {
namespace {

// Fritsch-Carlson / Fritsch-Butland slopes (as scipy.interpolate.PchipInterpolator).
std::vector<double> PchipSlopes(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = x.size();
  std::vector<double> h(n - 1), delta(n - 1), d(n, 0.0);
  for (size_t i = 0; i + 1 < n; ++i) {
    h[i] = x[i + 1] - x[i];
    delta[i] = (y[i + 1] - y[i]) / h[i];
  }
  if (n == 2) return {delta[0], delta[0]};
  for (size_t i = 1; i + 1 < n; ++i) {
    if (delta[i - 1] * delta[i] > 0) {
      const double w1 = 2 * h[i] + h[i - 1], w2 = h[i] + 2 * h[i - 1];
      d[i] = (w1 + w2) / (w1 / delta[i - 1] + w2 / delta[i]);
    }
  }
  // Ends: three-point formula, limited to keep the shape.
  const auto end = [](double h0, double h1, double m0, double m1) {
    double s = ((2 * h0 + h1) * m0 - h0 * m1) / (h0 + h1);
    if (s * m0 <= 0) {
      s = 0;
    } else if (m0 * m1 <= 0 && std::abs(s) > std::abs(3 * m0)) {
      s = 3 * m0;
    }
    return s;
  };
  d[0] = end(h[0], h[1], delta[0], delta[1]);
  d[n - 1] = end(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
  return d;
}

// Natural cubic spline slopes from the tridiagonal system for the second derivatives.
std::vector<double> SplineSlopes(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = x.size();
  std::vector<double> h(n - 1);
  for (size_t i = 0; i + 1 < n; ++i) h[i] = x[i + 1] - x[i];
  std::vector<double> m(n, 0.0);  // second derivatives, m[0] = m[n-1] = 0
  if (n > 2) {
    std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 0.0), r(n, 0.0);
    for (size_t i = 1; i + 1 < n; ++i) {
      a[i] = h[i - 1];
      b[i] = 2 * (h[i - 1] + h[i]);
      c[i] = h[i];
      r[i] = 6 * ((y[i + 1] - y[i]) / h[i] - (y[i] - y[i - 1]) / h[i - 1]);
    }
    for (size_t i = 1; i < n; ++i) {  // Thomas algorithm
      const double w = a[i] / b[i - 1];
      b[i] -= w * c[i - 1];
      r[i] -= w * r[i - 1];
    }
    m[n - 1] = r[n - 1] / b[n - 1];
    for (size_t i = n - 1; i-- > 0;) m[i] = (r[i] - c[i] * m[i + 1]) / b[i];
  }
  std::vector<double> d(n);
  for (size_t i = 0; i + 1 < n; ++i) {
    d[i] = (y[i + 1] - y[i]) / h[i] - h[i] * (2 * m[i] + m[i + 1]) / 6;
  }
  d[n - 1] = (y[n - 1] - y[n - 2]) / h[n - 2] + h[n - 2] * (m[n - 2] + 2 * m[n - 1]) / 6;
  return d;
}

}  // namespace

Interpolant::Interpolant(Interpolation scheme, std::vector<double> xs, std::vector<double> ys)
    : xs_(std::move(xs)), ys_(std::move(ys)) {
  const size_t n = xs_.size();
  if (n < 2 || ys_.size() != n) throw Error("interpolation needs two points or more");
  for (size_t i = 1; i < n; ++i) {
    if (!(xs_[i] > xs_[i - 1])) throw Error("interpolation needs increasing compositions");
  }
  switch (scheme) {
    case Interpolation::kLinear:
      slopes_.assign(n, 0.0);  // unused
      break;
    case Interpolation::kPchip:
      slopes_ = PchipSlopes(xs_, ys_);
      break;
    case Interpolation::kNaturalSpline:
      slopes_ = SplineSlopes(xs_, ys_);
      break;
  }
  linear_ = scheme == Interpolation::kLinear;
}

double Interpolant::operator()(double x) const {
  const size_t n = xs_.size();
  size_t hi = std::upper_bound(xs_.begin(), xs_.end(), x) - xs_.begin();
  hi = std::clamp<size_t>(hi, 1, n - 1);
  const size_t lo = hi - 1;
  const double h = xs_[hi] - xs_[lo];
  if (linear_) return ys_[lo] + (ys_[hi] - ys_[lo]) * (x - xs_[lo]) / h;
  if (x < xs_.front()) return ys_.front() + slopes_.front() * (x - xs_.front());
  if (x > xs_.back()) return ys_.back() + slopes_.back() * (x - xs_.back());
  const double t = (x - xs_[lo]) / h;
  if (t == 0.0) return ys_[lo];
  if (t == 1.0) return ys_[hi];
  const double t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * ys_[lo] + (t3 - 2 * t2 + t) * h * slopes_[lo] +
         (-2 * t3 + 3 * t2) * ys_[hi] + (t3 - t2) * h * slopes_[hi];
}

}  // namespace alloycolor
