// Gaussian-process regression across composition, the smooth fit's second form
// (fit/smooth_fit.h): many series y_c(u) (every wavelength node's eps1 and eps2, each
// scaled to unit RMS) share one kernel over the scaled composition u in [0, 1]:
//   k(u, u') = Matern52(|u - u'| / length) + kMeanPrior (1 + u u' + u^2 u'^2)
//              + noise * [u = u'],
// a Matern 5/2 process (twice differentiable) about a quadratic trend with a broad prior
// (Nordheim's rule bows resistivity quadratically; the plasma frequency is nearly linear),
// the noise variance in units of the process's. Each series' amplitude scales the whole
// kernel, so it cancels from the posterior mean, which is then one set of weights on the
// samples for every series: mean(u) = k(u)^T K^-1 Y.
//
// length and noise are chosen from a grid by leave-one-out over the interior samples (not
// the two ends, which every fit keeps): in closed form, the left-out residual of sample i
// is (K^-1 Y)_i / (K^-1)_ii (Rasmussen & Williams 2006, eq. 5.12), summed over all series.
#ifndef ALLOYCOLOR_FIT_GP_REGRESSION_H_
#define ALLOYCOLOR_FIT_GP_REGRESSION_H_

#include <Eigen/Dense>
#include <vector>

namespace alloycolor::fit {

inline constexpr double kMeanPrior = 1e4;  // prior variance of the quadratic trend

struct GpHyper {
  double length = 0.5;  // in units of the composition range
  double noise = 0;     // variance, relative to the process's
};

class GpRegression {
 public:
  // u: the samples' scaled compositions (any order, repeats allowed); y: one row per
  // sample, one column per series. Fixed hyperparameters.
  GpRegression(std::vector<double> u, const Eigen::MatrixXd& y, const GpHyper& hyper);

  // Hyperparameters chosen by the leave-one-out criterion over the grid (Candidates());
  // *criterion gets its value. Needs three distinct compositions (an interior sample).
  static GpRegression Chosen(const std::vector<double>& u, const Eigen::MatrixXd& y,
                             double* criterion = nullptr);
  static const std::vector<GpHyper>& Candidates();

  // Posterior mean at each of uq: one row per point, one column per series.
  Eigen::MatrixXd Predict(const std::vector<double>& uq) const;
  // Sum over the interior samples and every series of the squared left-out residual.
  double LeaveOneOutCriterion() const;
  // The left-out residuals (y_i minus the prediction without sample i), per sample.
  Eigen::MatrixXd LeaveOneOutResiduals() const;

  const GpHyper& hyper() const { return hyper_; }
  bool ok() const { return ok_; }  // false: the kernel matrix could not be factorised

 private:
  std::vector<double> u_;
  GpHyper hyper_;
  Eigen::MatrixXd alpha_;     // K^-1 Y
  Eigen::VectorXd inv_diag_;  // diagonal of K^-1
  bool ok_ = false;
};

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_GP_REGRESSION_H_
