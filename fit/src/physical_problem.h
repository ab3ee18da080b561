// Inside the fit library: the pieces of the physical fit (physical_fit.h) its files share:
// the data on the fit grid, the bounds, one Ceres problem over some samples
// (physical_problem.cc), and the starts, from the end samples' and the middle sample's own
// fits (physical_starts.cc). physical_fit.cc joins them.
#ifndef ALLOYCOLOR_FIT_SRC_PHYSICAL_PROBLEM_H_
#define ALLOYCOLOR_FIT_SRC_PHYSICAL_PROBLEM_H_

#include <ceres/ceres.h>

#include <complex>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "alloycolor/core/dataset.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/fit/physical_fit.h"
#include "alloycolor/model/physical_model.h"

namespace alloycolor::fit::physical {

// The data of one sample on the fit grid: every finite point.
struct SampleData {
  double x;
  std::string file;
  std::vector<double> omega_ev;
  std::vector<double> lambda_nm;
  std::vector<std::complex<double>> eps;
};

struct FitData {
  std::vector<double> grid_nm;
  double omega_min = 0, omega_max = 0;
  bool infrared = false;
  std::vector<SampleData> samples;
  std::vector<std::string> warnings;
};

FitData PrepareData(const Dataset& dataset, const PhysicalFitOptions& options);

struct Basis {
  double x_lo, x_hi;
  double U(double x) const { return CompositionArgument(x, x_lo, x_hi); }
};
struct Bounds {
  std::vector<double> lower, upper;  // per coefficient; +-inf where unbounded
};

// Bounds of the coefficients (physical_fit.h): the phases' in [-pi, pi], the constant
// coefficients of positive parameters in [0, an upper limit].
Bounds MakeBounds(const PhysicalLayout& layout, double omega_max);

struct SolveResult {
  std::vector<double> coeffs;
  double cost = 0;
  int iterations = 0;
  bool converged = false;
  std::string termination;
};

// One Ceres problem over some samples: the joint fit, or an end sample alone.
class FitProblem {
 public:
  FitProblem(const PhysicalLayout& layout, const std::vector<const SampleData*>& samples,
             const Basis& basis, const Bounds& bounds, std::vector<double> start);
  // `cancel` (may be empty) is called between iterations; its exception stops the solve
  // and propagates.
  SolveResult Solve(int max_iterations, double tolerance, const CancelCheck& cancel = {});
  // The covariance of the coefficients, unscaled ((J^T J)^-1, or its pseudo-inverse when
  // J is rank-deficient); empty if it fails. *pseudo_inverse says whether J is
  // rank-deficient: lambda_min / lambda_max of J^T J below the Ceres default
  // min_reciprocal_condition_number (1e-14). Asked for the pseudo-inverse directly
  // (null_space_rank = -1), Ceres drops exactly those eigenvalues, and for a well-
  // conditioned J that is the plain inverse; this way it never logs a failed attempt.
  std::vector<double> Covariance(bool* pseudo_inverse);
  size_t residuals() const { return residuals_; }
  // Lag-1 autocorrelation of the residuals along wavelength, real and imaginary parts
  // apart, pooled over the samples: rho = sum r_i r_(i+1) / sum r_i^2.
  double ResidualAutocorrelation();

 private:
  std::vector<double> coeffs_;
  ceres::Problem problem_;
  size_t residuals_ = 0;
  std::vector<size_t> block_sizes_;
};

// Fits one sample alone (degree 0) from a grid search's starts (and extra_start, if
// given); returns the distinct solutions, best first. windows, if given, holds for each
// interband term the range of E0 (eV) its starts must lie in. Throws Error naming the
// sample if none converges.
std::vector<SolveResult> FitSingle(const PhysicalLayout& layout, const SampleData& s,
                                   const FitData& data,
                                   const std::vector<std::pair<double, double>>& windows = {},
                                   const std::vector<double>* extra_start = nullptr);

// FitSingle of an end sample, through `remembered` when there is one.
std::vector<SolveResult> FitEndSample(const PhysicalLayout& layout, const SampleData& s,
                                      const FitData& data, EndSampleFits* remembered);

// Adds quadratics through the ends' (r_lo, r_hi) and a middle sample's own fits to the
// joint starts: they carry the parameters' curvature that the straight line lacks.
void AddQuadraticStarts(const PhysicalLayout& layout, const Basis& basis, const FitData& data,
                        const std::vector<double>& r_lo, const std::vector<double>& r_hi,
                        std::vector<std::vector<double>>* starts);

}  // namespace alloycolor::fit::physical

#endif  // ALLOYCOLOR_FIT_SRC_PHYSICAL_PROBLEM_H_
