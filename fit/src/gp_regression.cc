#include "alloycolor/fit/gp_regression.h"

#include <algorithm>
#include <cmath>

namespace alloycolor::fit {
namespace {

double Kernel(double a, double b, double length) {
  const double d = std::sqrt(5.0) * std::abs(a - b) / length;
  const double matern = (1 + d + d * d / 3) * std::exp(-d);
  return matern + kMeanPrior * (1 + a * b + a * a * b * b);
}

// The kernel without its noise: symmetric, each entry computed once.
Eigen::MatrixXd NoiselessKernel(const std::vector<double>& u, double length) {
  const Eigen::Index n = static_cast<Eigen::Index>(u.size());
  Eigen::MatrixXd k(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j <= i; ++j) k(i, j) = k(j, i) = Kernel(u[i], u[j], length);
  }
  return k;
}

// With the noise on the diagonal, and a jitter far below any data's precision that keeps
// the interpolating kernel invertible.
Eigen::MatrixXd WithNoise(Eigen::MatrixXd k, double noise) {
  for (Eigen::Index i = 0; i < k.rows(); ++i) k(i, i) += noise + 1e-10;
  return k;
}

Eigen::MatrixXd KernelMatrix(const std::vector<double>& u, const GpHyper& hyper) {
  return WithNoise(NoiselessKernel(u, hyper.length), hyper.noise);
}

// K^-1, or an empty matrix where K cannot be factorised.
Eigen::MatrixXd Inverse(const Eigen::MatrixXd& k) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(k);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().array() > 0).all()) return {};
  Eigen::MatrixXd inverse = ldlt.solve(Eigen::MatrixXd::Identity(k.rows(), k.cols()));
  if (!inverse.allFinite() || !(inverse.diagonal().array() > 0).all()) return {};
  return inverse;
}

bool Interior(const std::vector<double>& u, size_t i) {
  const auto [lo, hi] = std::minmax_element(u.begin(), u.end());
  return u[i] != *lo && u[i] != *hi;
}

// Interior(u, i) for every i.
std::vector<char> InteriorFlags(const std::vector<double>& u) {
  std::vector<char> interior(u.size(), 0);
  if (u.empty()) return interior;
  const auto [lo, hi] = std::minmax_element(u.begin(), u.end());
  for (size_t i = 0; i < u.size(); ++i) interior[i] = u[i] != *lo && u[i] != *hi;
  return interior;
}

}  // namespace

GpRegression::GpRegression(std::vector<double> u, const Eigen::MatrixXd& y, const GpHyper& hyper)
    : u_(std::move(u)), hyper_(hyper) {
  const Eigen::MatrixXd inverse = Inverse(KernelMatrix(u_, hyper_));
  if (inverse.size() == 0) return;
  alpha_ = inverse * y;
  inv_diag_ = inverse.diagonal();
  ok_ = alpha_.allFinite();
}

const std::vector<GpHyper>& GpRegression::Candidates() {
  static const std::vector<GpHyper> kCandidates = [] {
    std::vector<GpHyper> c;
    for (double length : {0.1, 0.15, 0.2, 0.3, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0}) {
      for (double noise : {0.0, 1e-6, 1e-4, 1e-3, 1e-2, 3e-2, 0.1, 0.3}) {
        c.push_back({length, noise});
      }
    }
    return c;
  }();
  return kCandidates;
}

// The criterion from G = Y Y^T alone: sum over series of (K^-1 Y)_i^2 is (K^-1 G K^-1)_ii,
// so each candidate costs a few n x n products, whatever the number of series.
GpRegression GpRegression::Chosen(const std::vector<double>& u, const Eigen::MatrixXd& y,
                                  double* criterion) {
  const Eigen::MatrixXd gram = y * y.transpose();
  const std::vector<char> interior = InteriorFlags(u);
  double best = HUGE_VAL;
  GpHyper chosen;
  double length = -1;
  Eigen::MatrixXd noiseless;
  for (const GpHyper& h : Candidates()) {
    // The candidates run through the noises at each length: the kernel once per length.
    if (h.length != length) {
      length = h.length;
      noiseless = NoiselessKernel(u, length);
    }
    const Eigen::MatrixXd inverse = Inverse(WithNoise(noiseless, h.noise));
    if (inverse.size() == 0) continue;
    const Eigen::MatrixXd m = inverse * gram * inverse;
    double c = 0;
    for (size_t i = 0; i < u.size(); ++i) {
      const Eigen::Index k = static_cast<Eigen::Index>(i);
      if (interior[i]) c += m(k, k) / (inverse(k, k) * inverse(k, k));
    }
    if (std::isfinite(c) && c < best) {
      best = c;
      chosen = h;
    }
  }
  GpRegression gp(u, y, chosen);
  if (criterion != nullptr) *criterion = gp.LeaveOneOutCriterion();
  return gp;
}

Eigen::MatrixXd GpRegression::Predict(const std::vector<double>& uq) const {
  Eigen::MatrixXd kq(static_cast<Eigen::Index>(uq.size()), static_cast<Eigen::Index>(u_.size()));
  for (size_t q = 0; q < uq.size(); ++q) {
    for (size_t i = 0; i < u_.size(); ++i) kq(q, i) = Kernel(uq[q], u_[i], hyper_.length);
  }
  return kq * alpha_;
}

Eigen::MatrixXd GpRegression::LeaveOneOutResiduals() const {
  return inv_diag_.cwiseInverse().asDiagonal() * alpha_;
}

double GpRegression::LeaveOneOutCriterion() const {
  if (!ok_) return HUGE_VAL;
  const Eigen::MatrixXd r = LeaveOneOutResiduals();
  double sum = 0;
  for (size_t i = 0; i < u_.size(); ++i) {
    if (Interior(u_, i)) sum += r.row(static_cast<Eigen::Index>(i)).squaredNorm();
  }
  return std::isfinite(sum) ? sum : HUGE_VAL;
}

}  // namespace alloycolor::fit
