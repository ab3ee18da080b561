// Inside the fit library: the smooth fit's data on its grid and its solutions
// (smooth_solve.cc: the direct solve with knots at the compositions, Ceres with fewer knots,
// the Gaussian process), the marginal likelihood's terms (smooth_evidence.cc). FitSmooth
// (smooth_fit.cc) chooses among them.
#ifndef ALLOYCOLOR_FIT_SRC_SMOOTH_SOLVE_H_
#define ALLOYCOLOR_FIT_SRC_SMOOTH_SOLVE_H_

#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

#include "alloycolor/core/dataset.h"
#include "alloycolor/fit/gp_regression.h"
#include "alloycolor/fit/smooth_fit.h"
#include "alloycolor/model/smooth_model.h"

namespace alloycolor::fit::smooth {

// The data on the grid: eps of every sample at every node, and the same in the space the
// curves are fitted in with each value's weight.
struct GridData {
  std::vector<double> grid_nm;
  std::vector<double> x;                               // per sample
  std::vector<std::vector<std::complex<double>>> eps;  // [sample][node]
  double x_lo = 0, x_hi = 1;
  SmoothSpace space = SmoothSpace::kEps;
  // [sample][node]: the two parts in `space` (part1 + i part2), and the weight of their
  // squared misfit: 1 / |eps|^2 for eps (a relative error), 1 for the logarithm (relative
  // already: d ln eps = d eps / eps).
  std::vector<std::vector<std::complex<double>>> parts;
  std::vector<std::vector<double>> weight;
};

struct Solution {
  SmoothSpace space = SmoothSpace::kEps;
  std::vector<double> knots;
  std::vector<std::vector<double>> part1, part2;    // [node][knot], in `space`
  std::vector<std::vector<double>> slope1, slope2;  // their PCHIP slopes (Finish)
  double final_cost = 0, data_sum_sq = 0;
  size_t data_residuals = 0;
  int iterations = 0;
  bool converged = false;
  std::string termination;
  GpHyper gp;  // the Gaussian-process form's hyperparameters (termination "gaussian process")
};

// The data on the grid from the samples (throws Error naming a sample that does not cover
// it), and the same in another space.
GridData PrepareData(const Dataset& dataset, const std::vector<double>& grid_nm);
GridData InSpace(GridData g, SmoothSpace space);

// The distinct compositions of the samples taking part (in[i]), increasing.
std::vector<double> Compositions(const GridData& g, const std::vector<char>& in);
// Knots: the compositions, or max_knots of them spread evenly by rank (ends kept).
std::vector<double> Knots(const std::vector<double>& compositions, int max_knots);

// Knots at the compositions themselves: every sample sits on a knot, the model there is
// the knot value, and the cost is linear least squares in each node's two parts
// separately: per node, (A + mu R) v = b with A = B^T W B (W the samples' weights,
// GridData::weight; B the sample-to-knot selection), b = B^T W y, R the roughness rows'
// Gram matrix (SmoothRoughnessResidual with weight 1) and mu the node's smoothing weight.
struct LinearSystems {
  std::vector<double> knots;
  std::vector<size_t> knot_of;           // per sample taking part
  Eigen::MatrixXd rtr;                   // R
  std::vector<Eigen::MatrixXd> a, b;     // [node]: k x k, k x 2 (the two parts)
  std::vector<Eigen::Vector2d> ywy;      // [node]: y^T W y of the two parts
  std::vector<double> mu_per_smoothing;  // [node]: mu / smoothing (count / sum 1 / W)
  size_t samples = 0;
};

LinearSystems AssembleAtCompositions(const GridData& g, const std::vector<char>& in,
                                     std::vector<double> knots);
// The systems solved for one smoothing per node, into *s (its storage reused); with
// `statistics` the cost and the data's misfit too, which the cross-validation does not read.
void SolveAssembled(const GridData& g, const std::vector<char>& in, const LinearSystems& ls,
                    const std::vector<double>& smoothing_per_node, bool statistics, Solution* s);
// Assembled and solved (knots at the compositions of the samples taking part).
Solution SolveAtCompositions(const GridData& g, const std::vector<char>& in,
                             const std::vector<double>& smoothing_per_node,
                             std::vector<double> knots);

// Fewer knots than compositions: Ceres. `warm`: a solution on the same knots to start from
// (null: the mean of the samples nearest each knot, or options.start's curves).
Solution SolveCeres(const GridData& g, const std::vector<char>& in, double smoothing,
                    const SmoothFitOptions& options, std::vector<double> knots,
                    const Solution* warm = nullptr);
// The fit at one smoothing, whichever way the knots make it.
Solution Solve(const GridData& g, const std::vector<char>& in, double smoothing,
               const SmoothFitOptions& options);
// The Gaussian-process form (smooth_fit.h); not converged where it cannot be made.
Solution SolveGp(const GridData& g, const std::vector<char>& in);

// eps of the solution at composition x and node j.
std::complex<double> EpsAt(const Solution& s, size_t j, double x);

// Sums over the nodes of sample i: squared relative eps error (both parts) and squared
// normal-incidence reflectance error.
struct SampleError {
  double eps_sq = 0, reflectance_sq = 0;
  int count = 0;
};

// Sample i's errors under the solution, summed over the nodes.
SampleError ErrorOf(const GridData& g, size_t i, const Solution& s);

// The restricted log marginal likelihood (REML), up to a constant, of a smoothing at each
// node, knots at the compositions. The model: y = B v + e, e ~ N(0, sigma^2 W^-1) with one
// relative noise level sigma for every node and part, and v ~ N(0, sigma^2 (mu R)^+)
// about a flat prior on R's null space (straight lines, 2 dimensions). Integrating v out,
// summed over the node-parts (n samples, k knots):
//   -(n - 2) / 2 log sigma^2 - Q / (2 sigma^2) - 1/2 log|A + mu R| + (k - 2) / 2 log mu
// each, Q = y^T W y - b^T (A + mu R)^-1 b the penalised residual. A smoothing tending to 0
// has a finite limit when every knot holds one sample; evaluated at kSmallestSmoothing.
inline constexpr double kSmallestSmoothing = 1e-9;

// Each node's terms at each candidate smoothing: its two parts' Q summed, and
// -1/2 log|A + mu R| + (k - 2) / 2 log mu for both parts.
struct EvidenceTerms {
  std::vector<std::vector<double>> q, rest;  // [node][candidate]
  size_t samples = 0, knots = 0;

  EvidenceTerms(const LinearSystems& ls, const std::vector<double>& candidates)
      : samples(ls.samples), knots(ls.knots.size()) {
    for (size_t j = 0; j < ls.a.size(); ++j) {
      q.emplace_back();
      rest.emplace_back();
      for (double candidate : candidates) {
        const double mu = std::max(candidate, kSmallestSmoothing) * ls.mu_per_smoothing[j];
        const Eigen::LLT<Eigen::MatrixXd> llt(ls.a[j] + mu * ls.rtr);
        const Eigen::MatrixXd v = llt.solve(ls.b[j]);
        double sum_q = 0;
        for (int part = 0; part < 2; ++part)
          sum_q += ls.ywy[j][part] - ls.b[j].col(part).dot(v.col(part));
        q.back().push_back(std::max(sum_q, 0.0));
        rest.back().push_back(-2 * llt.matrixLLT().diagonal().array().log().sum() +
                              (static_cast<double>(knots) - 2) * std::log(mu));
      }
    }
  }
  // The residual's degrees of freedom: n - 2 per node-part.
  double Dof() const {
    return (static_cast<double>(samples) - 2) * 2.0 * static_cast<double>(q.size());
  }
  double SumQ(const std::vector<size_t>& choice) const {
    double sum_q = 0;
    for (size_t j = 0; j < q.size(); ++j) sum_q += q[j][choice[j]];
    return sum_q;
  }
  // The log evidence of choice[j] (a candidate's index) at every node, sigma^2 profiled.
  double Total(const std::vector<size_t>& choice) const {
    double sum_rest = 0;
    for (size_t j = 0; j < q.size(); ++j) sum_rest += rest[j][choice[j]];
    return -0.5 * Dof() * (std::log(SumQ(choice) / Dof()) + 1) + sum_rest;
  }
  // At a given noise level, every node's best candidate.
  std::vector<size_t> BestAt(double sigma2) const {
    std::vector<size_t> choice(q.size(), 0);
    for (size_t j = 0; j < q.size(); ++j) {
      double best = -HUGE_VAL;
      for (size_t c = 0; c < q[j].size(); ++c) {
        const double value = -q[j][c] / (2 * sigma2) + rest[j][c];
        if (value > best) {
          best = value;
          choice[j] = c;
        }
      }
    }
    return choice;
  }
};

// The per-node candidates that maximise the evidence with one noise level (a candidate's
// index per node); empty when the data leave no residual at any smoothing.
std::vector<size_t> MostProbableSmoothings(const EvidenceTerms& terms);

}  // namespace alloycolor::fit::smooth

#endif  // ALLOYCOLOR_FIT_SRC_SMOOTH_SOLVE_H_
