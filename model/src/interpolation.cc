#include "alloycolor/model/interpolation.h"

#include <algorithm>
#include <cmath>

#include "alloycolor/core/error.h"

namespace alloycolor {

void NaturalSplineSlopes(const double* x, const double* y, size_t n, double* d) {
  // The second derivatives from their tridiagonal system, m[0] = m[n-1] = 0.
  std::vector<double> h(n - 1);
  for (size_t i = 0; i + 1 < n; ++i) h[i] = x[i + 1] - x[i];
  std::vector<double> m(n, 0.0);
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
  for (size_t i = 0; i + 1 < n; ++i) {
    d[i] = (y[i + 1] - y[i]) / h[i] - h[i] * (2 * m[i] + m[i + 1]) / 6;
  }
  d[n - 1] = (y[n - 1] - y[n - 2]) / h[n - 2] + h[n - 2] * (m[n - 2] + 2 * m[n - 1]) / 6;
}

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
      slopes_.resize(n);
      PchipSlopes(xs_.data(), ys_.data(), n, slopes_.data());
      break;
    case Interpolation::kNaturalSpline:
      slopes_.resize(n);
      NaturalSplineSlopes(xs_.data(), ys_.data(), n, slopes_.data());
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
  return HermiteAt(xs_.data(), ys_.data(), slopes_.data(), n, x);
}

}  // namespace alloycolor
