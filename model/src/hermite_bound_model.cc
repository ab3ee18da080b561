#include "hermite_bound_model.h"

#include <algorithm>
#include <cstring>

#include "alloycolor/core/simd.h"
#include "alloycolor/model/smooth_model.h"

namespace alloycolor {
namespace {

// out = w0 a + w1 b + w2 c + w3 d, term by term in HermiteAt's order.
ALLOYCOLOR_SIMD_CLONES
void WeightedSum(size_t m, double w0, const double* __restrict a, double w1,
                 const double* __restrict b, double w2, const double* __restrict c, double w3,
                 const double* __restrict d, double* __restrict out) {
  for (size_t i = 0; i < m; ++i) out[i] = w0 * a[i] + w1 * b[i] + w2 * c[i] + w3 * d[i];
}

// out = lo + (hi - lo) t.
ALLOYCOLOR_SIMD_CLONES
void Lerp(size_t m, const double* __restrict lo, const double* __restrict hi, double t,
          double* __restrict out) {
  for (size_t i = 0; i < m; ++i) out[i] = lo[i] + (hi[i] - lo[i]) * t;
}

// v = max(v, 0).
ALLOYCOLOR_SIMD_CLONES
void AtLeastZero(size_t m, double* __restrict v) {
  for (size_t i = 0; i < m; ++i) v[i] = v[i] < 0.0 ? 0.0 : v[i];
}

}  // namespace

HermiteBoundModel::HermiteBoundModel(std::vector<double> lambda_nm, std::vector<double> knots_x,
                                     std::vector<Knot> knots, bool linear, Output output)
    : BoundModel(std::move(lambda_nm)),
      knots_x_(std::move(knots_x)),
      knots_(std::move(knots)),
      linear_(linear),
      output_(output) {}

void HermiteBoundModel::Finish(double* eps1, double* eps2) const {
  const size_t m = lambda_nm().size();
  if (output_ == Output::kPassive) AtLeastZero(m, eps2);
  if (output_ != Output::kFromLog) return;
  for (size_t i = 0; i < m; ++i) {
    const std::complex<double> eps = EpsFromParts(SmoothSpace::kLogEps, eps1[i], eps2[i]);
    eps1[i] = eps.real();
    eps2[i] = eps.imag();
  }
}

void HermiteBoundModel::Permittivity(double x, double* eps1, double* eps2) const {
  const size_t m = lambda_nm().size(), n = knots_x_.size();
  const auto copy = [&](const Knot& k) {
    std::memcpy(eps1, k.eps1.data(), m * sizeof(double));
    std::memcpy(eps2, k.eps2.data(), m * sizeof(double));
  };
  if (linear_) {  // as the samples' linear interpolation: the nearest interval, its line
    size_t hi = std::upper_bound(knots_x_.begin(), knots_x_.end(), x) - knots_x_.begin();
    hi = std::clamp<size_t>(hi, 1, n - 1);
    const size_t lo = hi - 1;
    const double t = (x - knots_x_[lo]) / (knots_x_[hi] - knots_x_[lo]);
    if (t == 0.0) {
      copy(knots_[lo]);
    } else if (t == 1.0) {
      copy(knots_[hi]);
    } else {
      Lerp(m, knots_[lo].eps1.data(), knots_[hi].eps1.data(), t, eps1);
      Lerp(m, knots_[lo].eps2.data(), knots_[hi].eps2.data(), t, eps2);
    }
    return Finish(eps1, eps2);
  }
  // Beyond the ends: the line with the end slope (weights 1, dx on value and slope).
  if (x <= knots_x_.front() || x >= knots_x_.back()) {
    const bool below = x <= knots_x_.front();
    const Knot& k = below ? knots_.front() : knots_.back();
    const double dx = x - (below ? knots_x_.front() : knots_x_.back());
    const double* s1 = k.slope1.data();
    const double* s2 = k.slope2.data();
    WeightedSum(m, 1.0, k.eps1.data(), dx, s1, 0.0, k.eps1.data(), 0.0, s1, eps1);
    WeightedSum(m, 1.0, k.eps2.data(), dx, s2, 0.0, k.eps2.data(), 0.0, s2, eps2);
    return Finish(eps1, eps2);
  }
  const size_t hi = std::upper_bound(knots_x_.begin(), knots_x_.end(), x) - knots_x_.begin();
  const size_t lo = hi - 1;
  const double h = knots_x_[hi] - knots_x_[lo], t = (x - knots_x_[lo]) / h;
  const double t2 = t * t, t3 = t2 * t;
  const double w0 = 2 * t3 - 3 * t2 + 1, w1 = (t3 - 2 * t2 + t) * h, w2 = -2 * t3 + 3 * t2,
               w3 = (t3 - t2) * h;
  const Knot &a = knots_[lo], &b = knots_[hi];
  WeightedSum(m, w0, a.eps1.data(), w1, a.slope1.data(), w2, b.eps1.data(), w3, b.slope1.data(),
              eps1);
  WeightedSum(m, w0, a.eps2.data(), w1, a.slope2.data(), w2, b.eps2.data(), w3, b.slope2.data(),
              eps2);
  Finish(eps1, eps2);
}

}  // namespace alloycolor
