// The Gaussian-process regression of the smooth fit (fit/gp_regression.h): interpolation
// without noise, exact polynomials of its trend, the closed-form leave-one-out against
// refits without each sample, and hyperparameters that follow the data's noise.
#include "alloycolor/fit/gp_regression.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace alloycolor::fit {
namespace {

const std::vector<double> kU = {0.0, 0.1, 0.25, 0.3, 0.55, 0.7, 0.9, 1.0};

Eigen::MatrixXd Columns(const std::vector<double>& u, double (*f)(double), double (*g)(double)) {
  Eigen::MatrixXd y(static_cast<Eigen::Index>(u.size()), 2);
  for (size_t i = 0; i < u.size(); ++i) {
    y(static_cast<Eigen::Index>(i), 0) = f(u[i]);
    y(static_cast<Eigen::Index>(i), 1) = g(u[i]);
  }
  return y;
}

double Wave(double u) { return std::sin(4 * u) + 0.3 * u; }
double Bow(double u) { return std::exp(-u) * (1 + 2 * u * (1 - u)); }

TEST(GpRegression, WithoutNoiseItPassesThroughTheSamples) {
  const Eigen::MatrixXd y = Columns(kU, Wave, Bow);
  for (double length : {0.1, 0.5, 3.0}) {
    const GpRegression gp(kU, y, {length, 0.0});
    ASSERT_TRUE(gp.ok());
    const Eigen::MatrixXd at = gp.Predict(kU);
    // The 1e-10 jitter on the diagonal, against a trend prior of 1e4: about 1e-6.
    EXPECT_LT((at - y).cwiseAbs().maxCoeff(), 1e-5) << "length " << length;
  }
}

// The quadratic trend has a broad prior: data on a parabola are the parabola everywhere.
TEST(GpRegression, AParabolaIsReproducedBetweenTheSamples) {
  const Eigen::MatrixXd y = Columns(
      kU, [](double u) { return 1 + 2 * u - 3 * u * u; }, [](double u) { return -0.5 * u; });
  const GpRegression gp(kU, y, {0.3, 0.0});
  const Eigen::MatrixXd at = gp.Predict({0.05, 0.42, 0.8, 0.97});
  for (int q = 0; q < 4; ++q) {
    const double u = std::vector<double>{0.05, 0.42, 0.8, 0.97}[q];
    EXPECT_NEAR(at(q, 0), 1 + 2 * u - 3 * u * u, 1e-4) << u;
    EXPECT_NEAR(at(q, 1), -0.5 * u, 1e-4) << u;
  }
}

// Rasmussen & Williams eq. 5.12 against the regression refitted without each sample.
TEST(GpRegression, ClosedFormLeaveOneOutEqualsRefitsWithoutEachSample) {
  const Eigen::MatrixXd y = Columns(kU, Wave, Bow);
  for (const GpHyper hyper : {GpHyper{0.3, 1e-3}, GpHyper{1.0, 0.0}, GpHyper{0.15, 0.1}}) {
    const GpRegression gp(kU, y, hyper);
    const Eigen::MatrixXd loo = gp.LeaveOneOutResiduals();
    double interior = 0;
    for (size_t i = 0; i < kU.size(); ++i) {
      std::vector<double> u;
      std::vector<Eigen::Index> rows;
      for (size_t k = 0; k < kU.size(); ++k) {
        if (k == i) continue;
        u.push_back(kU[k]);
        rows.push_back(static_cast<Eigen::Index>(k));
      }
      const GpRegression without(u, y(rows, Eigen::all), hyper);
      const Eigen::MatrixXd p = without.Predict({kU[i]});
      for (int c = 0; c < 2; ++c) {
        const double refit = y(static_cast<Eigen::Index>(i), c) - p(0, c);
        EXPECT_NEAR(loo(static_cast<Eigen::Index>(i), c), refit, 1e-6 * (1 + std::abs(refit)))
            << "sample " << i << ", length " << hyper.length << ", noise " << hyper.noise;
        if (i != 0 && i + 1 != kU.size()) interior += refit * refit;
      }
    }
    EXPECT_NEAR(gp.LeaveOneOutCriterion(), interior, 1e-6 * (1 + interior));
  }
}

// Leave-one-out chooses a noise near zero for exact data and a large one for scatter of
// standard deviation 0.3 (variance 0.09, against the process's 1).
TEST(GpRegression, TheChosenNoiseFollowsTheData) {
  std::vector<double> u;
  for (int i = 0; i <= 20; ++i) u.push_back(i / 20.0);
  const Eigen::MatrixXd exact = Columns(u, Wave, Bow);
  EXPECT_LE(GpRegression::Chosen(u, exact).hyper().noise, 1e-4);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 0.3);
  Eigen::MatrixXd noisy = exact;
  for (Eigen::Index i = 0; i < noisy.size(); ++i) noisy(i) += normal(rng);
  double criterion = 0;
  const GpRegression gp = GpRegression::Chosen(u, noisy, &criterion);
  EXPECT_GE(gp.hyper().noise, 1e-2);
  // Chosen scores candidates from Y Y^T alone; its choice is the lowest of the explicit
  // leave-one-out criterion over the grid.
  double lowest = HUGE_VAL;
  for (const GpHyper& h : GpRegression::Candidates()) {
    lowest = std::min(lowest, GpRegression(u, noisy, h).LeaveOneOutCriterion());
  }
  EXPECT_NEAR(criterion, lowest, 1e-9 * lowest);
}

}  // namespace
}  // namespace alloycolor::fit
