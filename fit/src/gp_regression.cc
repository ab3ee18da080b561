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

}  // namespace

GpRegression::GpRegression(std::vector<double> u, const Eigen::MatrixXd& y, const GpHyper& hyper)
    : u_(std::move(u)), hyper_(hyper) {
  const Eigen::Index n = static_cast<Eigen::Index>(u_.size());
  Eigen::MatrixXd k(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) k(i, j) = Kernel(u_[i], u_[j], hyper_.length);
    // A jitter far below any data's precision keeps the interpolating kernel invertible.
    k(i, i) += hyper_.noise + 1e-10;
  }
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(k);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().array() > 0).all()) return;
  alpha_ = ldlt.solve(y);
  inv_diag_ = ldlt.solve(Eigen::MatrixXd::Identity(n, n)).diagonal();
  ok_ = alpha_.allFinite() && inv_diag_.allFinite() && (inv_diag_.array() > 0).all();
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

GpRegression GpRegression::Chosen(const std::vector<double>& u, const Eigen::MatrixXd& y,
                                  double* criterion) {
  double best = HUGE_VAL;
  GpHyper chosen;
  for (const GpHyper& h : Candidates()) {
    const GpRegression gp(u, y, h);
    if (!gp.ok()) continue;
    const double c = gp.LeaveOneOutCriterion();
    if (c < best) {
      best = c;
      chosen = h;
    }
  }
  if (criterion != nullptr) *criterion = best;
  return GpRegression(u, y, chosen);
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
  const auto [lo, hi] = std::minmax_element(u_.begin(), u_.end());
  const Eigen::MatrixXd r = LeaveOneOutResiduals();
  double sum = 0;
  for (size_t i = 0; i < u_.size(); ++i) {
    if (u_[i] == *lo || u_[i] == *hi) continue;
    sum += r.row(static_cast<Eigen::Index>(i)).squaredNorm();
  }
  return std::isfinite(sum) ? sum : HUGE_VAL;
}

}  // namespace alloycolor::fit
