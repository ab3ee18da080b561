#include "alloycolor/fit/smooth_fit.h"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/units.h"
#include "alloycolor/fit/gp_regression.h"
#include "alloycolor/fit/smooth_costs.h"
#include "alloycolor/model/optics.h"

namespace alloycolor::fit {
namespace {

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

GridData InSpace(GridData g, SmoothSpace space) {
  g.space = space;
  g.parts.assign(g.eps.size(), {});
  g.weight.assign(g.eps.size(), {});
  for (size_t i = 0; i < g.eps.size(); ++i) {
    for (const std::complex<double> e : g.eps[i]) {
      const std::array<double, 2> p = PartsFromEps(space, e);
      g.parts[i].emplace_back(p[0], p[1]);
      g.weight[i].push_back(space == SmoothSpace::kEps ? 1.0 / std::norm(e) : 1.0);
    }
  }
  return g;
}

GridData PrepareData(const Dataset& dataset, const std::vector<double>& grid_nm) {
  GridData g;
  g.grid_nm = grid_nm;
  for (const Sample& s : dataset.samples) {
    if (!s.nk.Covers(grid_nm.front(), grid_nm.back())) {
      std::ostringstream msg;
      msg << s.file << ": covers " << s.nk.lambda_min_nm() << "-" << s.nk.lambda_max_nm()
          << " nm, the fit grid needs " << grid_nm.front() << "-" << grid_nm.back() << " nm";
      throw Error(msg.str());
    }
    g.x.push_back(s.x_atomic);
    std::vector<std::complex<double>> eps;
    for (double l : grid_nm) {
      const std::complex<double> nk = NkAt(s.nk, l);
      eps.push_back(nk * nk);
    }
    g.eps.push_back(std::move(eps));
  }
  g.x_lo = *std::min_element(g.x.begin(), g.x.end());
  g.x_hi = *std::max_element(g.x.begin(), g.x.end());
  return InSpace(std::move(g), SmoothSpace::kEps);
}

// The distinct compositions of the samples taking part, increasing.
std::vector<double> Compositions(const GridData& g, const std::vector<char>& in) {
  std::vector<double> xs;
  for (size_t i = 0; i < g.x.size(); ++i) {
    if (in[i]) xs.push_back(g.x[i]);
  }
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  return xs;
}

// Knots: the compositions, or max_knots of them spread evenly by rank (ends kept).
std::vector<double> Knots(const std::vector<double>& compositions, int max_knots) {
  const size_t k = std::min<size_t>(compositions.size(), static_cast<size_t>(max_knots));
  if (k == compositions.size()) return compositions;
  std::vector<double> knots;
  for (size_t c = 0; c < k; ++c) {
    const size_t index = static_cast<size_t>(
        std::lround(static_cast<double>(c) * (compositions.size() - 1) / (k - 1.0)));
    knots.push_back(compositions[index]);
  }
  return knots;
}

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

// Passive: a knot's eps2 below 0 (only where strong smoothing pulls the curve below
// near-zero data) is set to 0, or its arg eps held to [0, pi]; PCHIP then keeps eps2 >= 0
// between the knots too. Then the knots' PCHIP slopes, once for every evaluation of the
// solution.
void Finish(Solution* s) {
  const bool log = s->space == SmoothSpace::kLogEps;
  for (auto& node : s->part2) {
    for (double& v : node) v = log ? std::clamp(v, 0.0, kPi) : std::max(v, 0.0);
  }
  const size_t k = s->knots.size();
  s->slope1.assign(s->part1.size(), std::vector<double>(k));
  s->slope2.assign(s->part2.size(), std::vector<double>(k));
  for (size_t j = 0; j < s->part1.size(); ++j) {
    PchipSlopes(s->knots.data(), s->part1[j].data(), k, s->slope1[j].data());
    PchipSlopes(s->knots.data(), s->part2[j].data(), k, s->slope2[j].data());
  }
}

// Start values: at each knot the mean of the samples nearest to it (passive), or, for a
// refit, the earlier model's eps there.
void Start(const GridData& g, const std::vector<char>& in, const SmoothModel* start, Solution* s) {
  const size_t k = s->knots.size(), nodes = g.grid_nm.size();
  s->space = g.space;
  s->part1.assign(nodes, std::vector<double>(k, 0.0));
  s->part2.assign(nodes, std::vector<double>(k, 0.0));
  if (start != nullptr) {
    std::vector<double> lambda(nodes);
    for (size_t j = 0; j < nodes; ++j) {
      lambda[j] = std::clamp(g.grid_nm[j], start->lambda_min_nm(), start->lambda_max_nm());
    }
    for (size_t c = 0; c < k; ++c) {
      const auto eps = start->Permittivity(s->knots[c], lambda);
      for (size_t j = 0; j < nodes; ++j) {
        const std::array<double, 2> p = PartsFromEps(g.space, eps[j]);
        s->part1[j][c] = p[0];
        s->part2[j][c] = p[1];
      }
    }
    Finish(s);
    return;
  }
  std::vector<int> count(k, 0);
  for (size_t i = 0; i < g.x.size(); ++i) {
    if (!in[i]) continue;
    const size_t c = std::min_element(s->knots.begin(), s->knots.end(),
                                      [&](double a, double b) {
                                        return std::abs(a - g.x[i]) < std::abs(b - g.x[i]);
                                      }) -
                     s->knots.begin();
    ++count[c];
    for (size_t j = 0; j < nodes; ++j) {
      s->part1[j][c] += g.parts[i][j].real();
      s->part2[j][c] += g.parts[i][j].imag();
    }
  }
  for (size_t c = 0; c < k; ++c) {
    for (size_t j = 0; j < nodes; ++j) {
      s->part1[j][c] /= std::max(count[c], 1);
      s->part2[j][c] /= std::max(count[c], 1);
    }
  }
  Finish(s);
}

std::vector<double> KnotsU(const GridData& g, const std::vector<double>& knots) {
  std::vector<double> u(knots.size());
  for (size_t c = 0; c < knots.size(); ++c) u[c] = (knots[c] - g.x_lo) / (g.x_hi - g.x_lo);
  return u;
}

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
                                     std::vector<double> knots) {
  LinearSystems ls;
  ls.knots = std::move(knots);
  const size_t nodes = g.grid_nm.size(), k = ls.knots.size();
  const std::vector<double> u = KnotsU(g, ls.knots);
  ls.knot_of.assign(g.x.size(), 0);
  for (size_t i = 0; i < g.x.size(); ++i) {
    if (!in[i]) continue;
    ls.knot_of[i] = std::lower_bound(ls.knots.begin(), ls.knots.end(), g.x[i]) - ls.knots.begin();
    ++ls.samples;
  }
  ls.rtr = Eigen::MatrixXd::Zero(k, k);
  for (size_t c = 1; c + 1 < k; ++c) {
    const double h0 = u[c] - u[c - 1], h1 = u[c + 1] - u[c];
    const double scale = 2.0 / (h0 + h1) * std::sqrt(0.5 * (h0 + h1));
    Eigen::VectorXd row = Eigen::VectorXd::Zero(k);
    row[c - 1] = scale / h0;
    row[c] = -scale * (1 / h0 + 1 / h1);
    row[c + 1] = scale / h1;
    ls.rtr += row * row.transpose();
  }
  for (size_t j = 0; j < nodes; ++j) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(k, k);
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(k, 2);
    Eigen::Vector2d ywy = Eigen::Vector2d::Zero();
    double sum_sq = 0;
    for (size_t i = 0; i < g.x.size(); ++i) {
      if (!in[i]) continue;
      const std::complex<double> y = g.parts[i][j];
      const double w = g.weight[i][j];
      const size_t c = ls.knot_of[i];
      a(c, c) += w;
      b(c, 0) += w * y.real();
      b(c, 1) += w * y.imag();
      ywy += w * Eigen::Vector2d(y.real() * y.real(), y.imag() * y.imag());
      sum_sq += 1 / w;
    }
    ls.a.push_back(std::move(a));
    ls.b.push_back(std::move(b));
    ls.ywy.push_back(ywy);
    ls.mu_per_smoothing.push_back(k >= 3 ? static_cast<double>(ls.samples) / sum_sq : 0.0);
  }
  return ls;
}

// Solved directly from the normal equations (Eigen LDLT, K x K per part): the minimum
// Ceres reaches too, at a small fraction of the time (cross-validation solves it hundreds
// of times).
Solution SolveAtCompositions(const GridData& g, const std::vector<char>& in,
                             const std::vector<double>& smoothing_per_node,
                             std::vector<double> knots) {
  const LinearSystems ls = AssembleAtCompositions(g, in, std::move(knots));
  Solution s;
  s.space = g.space;
  s.knots = ls.knots;
  const size_t nodes = g.grid_nm.size(), k = s.knots.size();
  s.part1.assign(nodes, std::vector<double>(k));
  s.part2.assign(nodes, std::vector<double>(k));
  double cost = 0;
  for (size_t j = 0; j < nodes; ++j) {
    const double mu = std::max(smoothing_per_node[j], 0.0) * ls.mu_per_smoothing[j];
    const Eigen::MatrixXd v = (ls.a[j] + mu * ls.rtr).ldlt().solve(ls.b[j]);
    for (size_t c = 0; c < k; ++c) {
      s.part1[j][c] = v(c, 0);
      s.part2[j][c] = v(c, 1);
    }
    cost += 0.5 * mu * (v.col(0).dot(ls.rtr * v.col(0)) + v.col(1).dot(ls.rtr * v.col(1)));
  }
  Finish(&s);
  for (size_t i = 0; i < g.x.size(); ++i) {
    if (!in[i]) continue;
    for (size_t j = 0; j < nodes; ++j) {
      const std::complex<double> e = g.eps[i][j];
      const size_t c = ls.knot_of[i];
      const std::complex<double> m = EpsFromParts(s.space, s.part1[j][c], s.part2[j][c]);
      s.data_sum_sq += std::norm(m - e) / std::norm(e);
      s.data_residuals += 2;
    }
  }
  s.final_cost = cost + 0.5 * s.data_sum_sq;
  s.converged = true;
  s.termination = "direct solve";
  return s;
}

// The restricted log marginal likelihood (REML), up to a constant, of a smoothing at each
// node, knots at the compositions. The model: y = B v + e, e ~ N(0, sigma^2 W^-1) with one
// relative noise level sigma for every node and part, and v ~ N(0, sigma^2 (mu R)^+)
// about a flat prior on R's null space (straight lines, 2 dimensions). Integrating v out,
// summed over the node-parts (n samples, k knots):
//   -(n - 2) / 2 log sigma^2 - Q / (2 sigma^2) - 1/2 log|A + mu R| + (k - 2) / 2 log mu
// each, Q = y^T W y - b^T (A + mu R)^-1 b the penalised residual. A smoothing tending to 0
// has a finite limit when every knot holds one sample; evaluated at kSmallestSmoothing.
constexpr double kSmallestSmoothing = 1e-9;

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

// The per-node candidates that maximise the evidence with one noise level: every node's
// best candidate at each noise level of a fine logarithmic scan across the range the
// candidates' own residuals span, then coordinate ascent (sigma^2 = sum Q / dof, every
// node's best again) from the best of the scan. Empty when the data leave no residual at
// any smoothing (eps linear in composition: every smoothing gives the same fit).
std::vector<size_t> MostProbableSmoothings(const EvidenceTerms& terms) {
  double q_lo = HUGE_VAL, q_hi = 0;
  for (const auto& node : terms.q) {
    for (double v : node) {
      if (v > 0) q_lo = std::min(q_lo, v);
      q_hi = std::max(q_hi, v);
    }
  }
  if (!(q_hi > 0)) return {};
  // One node's share of the degrees of freedom.
  const double per_dof = static_cast<double>(terms.q.size()) / terms.Dof();
  const double lo = std::log(q_lo * per_dof) - 2, hi = std::log(q_hi * per_dof) + 2;
  std::vector<size_t> best_choice;
  double best = -HUGE_VAL;
  constexpr int kSteps = 400;
  for (int step = 0; step <= kSteps; ++step) {
    std::vector<size_t> choice = terms.BestAt(std::exp(lo + (hi - lo) * step / kSteps));
    const double total = terms.Total(choice);
    if (total > best) {
      best = total;
      best_choice = std::move(choice);
    }
  }
  for (int round = 0; round < 50; ++round) {
    std::vector<size_t> choice =
        terms.BestAt(std::max(terms.SumQ(best_choice) / terms.Dof(), 1e-300));
    const double total = terms.Total(choice);
    if (!(total > best)) break;
    best = total;
    best_choice = std::move(choice);
  }
  return best_choice;
}

// eps of the solution at composition x and node j.
std::complex<double> EpsAt(const Solution& s, size_t j, double x) {
  const size_t k = s.knots.size();
  return EpsFromParts(s.space,
                      HermiteAt(s.knots.data(), s.part1[j].data(), s.slope1[j].data(), k, x),
                      HermiteAt(s.knots.data(), s.part2[j].data(), s.slope2[j].data(), k, x));
}

// Fewer knots than compositions: samples between knots make the cost nonlinear (the PCHIP
// slopes depend on the knot values), and Ceres minimises it.
Solution SolveCeres(const GridData& g, const std::vector<char>& in, double smoothing,
                    const SmoothFitOptions& options, std::vector<double> knots) {
  Solution s;
  s.knots = std::move(knots);
  Start(g, in, options.start, &s);
  const size_t nodes = g.grid_nm.size(), k = s.knots.size();
  const std::vector<double> knots_u = KnotsU(g, s.knots);

  ceres::Problem problem;
  std::vector<ceres::ResidualBlockId> data_blocks;
  for (size_t j = 0; j < nodes; ++j) {
    double* e1 = s.part1[j].data();
    double* e2 = s.part2[j].data();
    problem.AddParameterBlock(e1, static_cast<int>(k));
    problem.AddParameterBlock(e2, static_cast<int>(k));
    double sum_sq = 0;
    int count = 0;
    for (size_t i = 0; i < g.x.size(); ++i) {
      if (!in[i]) continue;
      data_blocks.push_back(problem.AddResidualBlock(
          SmoothDataResidual::Create(s.knots, g.x[i], g.parts[i][j], std::sqrt(g.weight[i][j])),
          nullptr, e1, e2));
      sum_sq += 1 / g.weight[i][j];
      ++count;
    }
    if (smoothing > 0 && k >= 3) {
      // Relative to the node's RMS |eps| (in eps), as the data residuals are.
      const double weight = std::sqrt(smoothing * count / sum_sq);
      problem.AddResidualBlock(SmoothRoughnessResidual::Create(knots_u, weight), nullptr, e1, e2);
    }
  }
  ceres::Solver::Options solver_options;
  // Eigen's sparse Cholesky: no threaded BLAS underneath, so the result is the same to
  // the last bit on every run.
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = 1e-10;
  solver_options.gradient_tolerance = 1e-12;
  solver_options.parameter_tolerance = 1e-10;
  solver_options.num_threads = 1;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);
  if (summary.termination_type == ceres::FAILURE ||
      summary.termination_type == ceres::USER_FAILURE) {
    throw Error("smooth fit failed: " + summary.message);
  }
  s.final_cost = summary.final_cost;
  s.iterations = static_cast<int>(summary.iterations.size()) - 1;
  s.converged = summary.termination_type == ceres::CONVERGENCE;
  s.termination = ceres::TerminationTypeToString(summary.termination_type);
  s.data_residuals = 2 * data_blocks.size();
  Finish(&s);
  for (size_t i = 0; i < g.x.size(); ++i) {
    if (!in[i]) continue;
    for (size_t j = 0; j < nodes; ++j) {
      s.data_sum_sq += std::norm(EpsAt(s, j, g.x[i]) - g.eps[i][j]) / std::norm(g.eps[i][j]);
    }
  }
  return s;
}

Solution Solve(const GridData& g, const std::vector<char>& in, double smoothing,
               const SmoothFitOptions& options) {
  const std::vector<double> compositions = Compositions(g, in);
  std::vector<double> knots = Knots(compositions, std::min(options.max_knots, kSmoothMaxKnots));
  if (knots.size() == compositions.size()) {
    return SolveAtCompositions(g, in, std::vector<double>(g.grid_nm.size(), smoothing), knots);
  }
  return SolveCeres(g, in, smoothing, options, std::move(knots));
}

bool AllFinite(const Solution& s) {
  for (const auto* part : {&s.part1, &s.part2}) {
    for (const auto& node : *part) {
      for (double v : node) {
        if (!std::isfinite(v)) return false;
      }
    }
  }
  return true;
}

// The Gaussian-process form (fit/gp_regression.h): every node's two parts, scaled by the
// node's RMS |eps| (in eps; 1 in the logarithm), regressed on the scaled composition with one
// kernel, its length and noise chosen by the samples' own leave-one-out; the posterior mean sampled
// at kSmoothMaxKnots evenly spaced knots, between which PCHIP follows it (the mean is twice
// differentiable; eps2 held at 0 or above as in every form). Not converged (so not used)
// with fewer than three compositions or a kernel that cannot be factorised.
Solution SolveGp(const GridData& g, const std::vector<char>& in) {
  Solution s;
  s.space = g.space;
  s.termination = "gaussian process";
  const std::vector<double> compositions = Compositions(g, in);
  if (compositions.size() < 3) return s;
  const double lo = compositions.front(), span = compositions.back() - lo;
  const size_t nodes = g.grid_nm.size();
  std::vector<size_t> rows;
  std::vector<double> u;
  for (size_t i = 0; i < g.x.size(); ++i) {
    if (!in[i]) continue;
    rows.push_back(i);
    u.push_back((g.x[i] - lo) / span);
  }
  std::vector<double> scale(nodes, 0.0);
  for (size_t j = 0; j < nodes; ++j) {
    for (size_t i : rows) scale[j] += 1 / g.weight[i][j];
    scale[j] = std::sqrt(scale[j] / rows.size());
  }
  Eigen::MatrixXd y(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(2 * nodes));
  for (size_t r = 0; r < rows.size(); ++r) {
    for (size_t j = 0; j < nodes; ++j) {
      y(r, j) = g.parts[rows[r]][j].real() / scale[j];
      y(r, nodes + j) = g.parts[rows[r]][j].imag() / scale[j];
    }
  }
  const GpRegression gp = GpRegression::Chosen(u, y);
  if (!gp.ok()) return s;
  std::vector<double> uq(kSmoothMaxKnots);
  for (int c = 0; c < kSmoothMaxKnots; ++c) {
    uq[c] = static_cast<double>(c) / (kSmoothMaxKnots - 1);
    s.knots.push_back(c + 1 == kSmoothMaxKnots ? compositions.back() : lo + span * uq[c]);
  }
  const Eigen::MatrixXd mean = gp.Predict(uq);
  s.part1.assign(nodes, std::vector<double>(kSmoothMaxKnots));
  s.part2.assign(nodes, std::vector<double>(kSmoothMaxKnots));
  for (size_t j = 0; j < nodes; ++j) {
    for (int c = 0; c < kSmoothMaxKnots; ++c) {
      s.part1[j][c] = mean(c, static_cast<Eigen::Index>(j)) * scale[j];
      s.part2[j][c] = mean(c, static_cast<Eigen::Index>(nodes + j)) * scale[j];
    }
  }
  Finish(&s);
  if (!AllFinite(s)) return s;
  for (size_t i : rows) {
    for (size_t j = 0; j < nodes; ++j) {
      s.data_sum_sq += std::norm(EpsAt(s, j, g.x[i]) - g.eps[i][j]) / std::norm(g.eps[i][j]);
      s.data_residuals += 2;
    }
  }
  s.final_cost = 0.5 * s.data_sum_sq;
  s.converged = true;
  s.gp = gp.hyper();
  return s;
}

// Sums over the nodes of sample i: squared relative eps error (both parts) and squared
// normal-incidence reflectance error.
struct SampleError {
  double eps_sq = 0, reflectance_sq = 0;
  int count = 0;
};

SampleError ErrorOf(const GridData& g, size_t i, const Solution& s) {
  SampleError e;
  for (size_t j = 0; j < g.grid_nm.size(); ++j) {
    const std::complex<double> model = EpsAt(s, j, g.x[i]);
    e.eps_sq += 0.5 * std::norm(model - g.eps[i][j]) / std::norm(g.eps[i][j]);
    const double r_model =
        NormalReflectance(IndexFromPermittivity(Complex<double>{model.real(), model.imag()}));
    const double r_data = NormalReflectance(
        IndexFromPermittivity(Complex<double>{g.eps[i][j].real(), g.eps[i][j].imag()}));
    e.reflectance_sq += (r_model - r_data) * (r_model - r_data);
    ++e.count;
  }
  return e;
}

// Cross-validation folds: each interior composition alone, or ten interleaved groups of
// them when there are more than twenty. A fold lists the compositions it leaves out.
std::vector<std::vector<double>> Folds(const std::vector<double>& compositions) {
  std::vector<double> interior(compositions.begin() + 1, compositions.end() - 1);
  std::vector<std::vector<double>> folds;
  if (interior.size() <= 20) {
    for (double x : interior) folds.push_back({x});
    return folds;
  }
  folds.resize(10);
  for (size_t c = 0; c < interior.size(); ++c) folds[c % 10].push_back(interior[c]);
  return folds;
}

// The left-out samples' errors summed over the folds, each fold's solution made by
// `solve` from which samples take part; false where one could not be made (not converged).
bool LeftOutErrors(const GridData& g, const std::vector<std::vector<double>>& folds,
                   const std::function<Solution(const std::vector<char>&)>& solve,
                   SampleError* total) {
  for (const auto& fold : folds) {
    std::vector<char> in(g.x.size(), 1);
    for (size_t i = 0; i < g.x.size(); ++i) {
      if (std::count(fold.begin(), fold.end(), g.x[i])) in[i] = 0;
    }
    const Solution s = solve(in);
    if (!s.converged) return false;
    for (size_t i = 0; i < g.x.size(); ++i) {
      if (in[i]) continue;
      const SampleError e = ErrorOf(g, i, s);
      total->eps_sq += e.eps_sq;
      total->reflectance_sq += e.reflectance_sq;
      total->count += e.count;
    }
  }
  return true;
}

}  // namespace

// A more flexible form (the Gaussian process) must beat the simpler one's left-out error by
// this factor: with few folds leave-one-out flatters the more flexible.
constexpr double kSimplerMargin = 1.1;
// ln eps must cut the left-out error of eps by a third. eps is the default (across
// composition it varies most gently between two metals); between two metals the spaces
// differ by noise or favour eps (the bundled pairs: eps 0.3-1.45 times ln eps, with one
// or two folds deciding), while where a sample is not metallic eps errs several times more
// (1.9-6.3 times on Querry's zinc).
constexpr double kLogSpaceMargin = 1.5;
// Cross-validation chooses with this many folds or more; below, the marginal likelihood.
constexpr size_t kMinFolds = 3;

const std::vector<double>& SmoothingCandidates() {
  static const std::vector<double> kCandidates = {0, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1};
  return kCandidates;
}

namespace {

// The fit in one space: the smoothing and form chosen there, and the left-out RMS
// reflectance error of that choice over the interior compositions (HUGE_VAL where there
// are none), by which the spaces are compared.
struct SpaceFit {
  SmoothFitResult result;  // what chose the smoothing and form; no model yet
  Solution solution;
  double smoothing = 0;
  std::string chosen_by;
  bool use_gp = false;
  double score = HUGE_VAL;
};

// The smoothing with the least left-out reflectance error over the folds (smoothing where
// none scores), each candidate's errors recorded in f->result and the least in f->score.
double CrossValidatedSmoothing(const GridData& g, const std::vector<std::vector<double>>& folds,
                               const std::string& space, const SmoothFitOptions& options,
                               double smoothing, SpaceFit* f) {
  for (double candidate : SmoothingCandidates()) {
    SampleError total;
    LeftOutErrors(
        g, folds,
        [&](const std::vector<char>& in) {
          Solution s = Solve(g, in, candidate, options);
          s.converged = true;  // the Ceres form's best point counts either way
          return s;
        },
        &total);
    const double rms = std::sqrt(total.eps_sq / total.count);
    const double rms_r = std::sqrt(total.reflectance_sq / total.count);
    f->result.cross_validation.push_back({candidate, rms, rms_r});
    std::ostringstream msg;
    msg << "cross-validation" << space << ": smoothing " << candidate
        << ", leave-one-out RMS error: relative eps " << rms << ", reflectance " << rms_r;
    Report(options.details, msg.str());
    if (rms_r < f->score) {
      f->score = rms_r;
      smoothing = candidate;
    }
  }
  return smoothing;
}

// The most probable smoothing at each wavelength by the restricted marginal likelihood
// (recorded in result), and their median.
double MarginalLikelihoodSmoothing(const GridData& g, const std::vector<double>& compositions,
                                   const std::string& space, const SmoothFitOptions& options,
                                   SmoothFitResult* result) {
  const std::vector<char> all(g.x.size(), 1);
  const std::vector<double>& grid = g.grid_nm;
  const LinearSystems ls = AssembleAtCompositions(g, all, compositions);
  const EvidenceTerms terms(ls, SmoothingCandidates());
  const std::vector<size_t> choice = MostProbableSmoothings(terms);
  for (size_t j = 0; j < grid.size(); ++j) {
    result->smoothing_per_node.push_back(choice.empty() ? 0.0 : SmoothingCandidates()[choice[j]]);
  }
  std::ostringstream msg;
  msg << "marginal likelihood" << space << ", the most probable smoothing per wavelength:";
  for (double candidate : SmoothingCandidates()) {
    const int nodes = static_cast<int>(std::count(result->smoothing_per_node.begin(),
                                                  result->smoothing_per_node.end(), candidate));
    result->evidence.push_back({candidate, nodes});
    if (nodes > 0) msg << " " << candidate << " at " << nodes << ",";
  }
  msg << " of " << grid.size() << " wavelengths";
  Report(options.details, msg.str());
  std::vector<double> sorted = result->smoothing_per_node;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  return sorted[sorted.size() / 2];
}

// Whether the Gaussian-process form, scored on the folds (its errors recorded in
// f->result), beats f->score by more than kSimplerMargin.
bool GaussianProcessWins(const GridData& g, const std::vector<std::vector<double>>& folds,
                         const std::string& space, const SmoothFitOptions& options, SpaceFit* f) {
  SmoothFitResult& result = f->result;
  SampleError total;
  const bool scored = LeftOutErrors(
      g, folds, [&](const std::vector<char>& in) { return SolveGp(g, in); }, &total);
  if (!scored || total.count == 0) return false;
  result.gp_rms = std::sqrt(total.eps_sq / total.count);
  result.gp_rms_reflectance = std::sqrt(total.reflectance_sq / total.count);
  const bool use_gp = result.gp_rms_reflectance * kSimplerMargin < f->score;
  std::ostringstream msg;
  msg << "cross-validation" << space << ": gaussian process, leave-one-out RMS error: relative eps "
      << result.gp_rms << ", reflectance " << result.gp_rms_reflectance
      << (use_gp ? " (chosen)" : "");
  Report(options.details, msg.str());
  return use_gp;
}

SpaceFit FitInSpace(const GridData& g, const SmoothFitOptions& options) {
  const std::string space = std::string(" (") + SmoothSpaceName(g.space) + ")";
  const std::vector<char> all(g.x.size(), 1);
  const std::vector<double> compositions = Compositions(g, all);
  SpaceFit f;
  SmoothFitResult& result = f.result;
  double smoothing = options.smoothing;
  std::string chosen_by = "user";
  const auto folds = Folds(compositions);
  const bool cross_validate = smoothing < 0 && folds.size() >= kMinFolds;
  if (cross_validate) {
    chosen_by = "leave-one-composition-out cross-validation";
    smoothing = CrossValidatedSmoothing(g, folds, space, options, smoothing, &f);
  } else if (smoothing < 0 && compositions.size() >= 3 && g.x.size() >= 4 &&
             compositions.size() <= static_cast<size_t>(options.max_knots)) {
    // Too few interior compositions for cross-validation to decide: the marginal
    // likelihood, which weighs every sample (the ends too) at every wavelength.
    chosen_by =
        "restricted marginal likelihood (too few interior compositions to "
        "cross-validate)";
    smoothing = MarginalLikelihoodSmoothing(g, compositions, space, options, &result);
  } else if (smoothing < 0) {
    smoothing = 0;
    chosen_by = "default: too few samples (or knots) to choose a smoothing";
  }
  // Not cross-validated: the chosen smoothing scored on the same folds, for the choice of
  // space.
  if (!cross_validate && !folds.empty()) {
    SampleError total;
    const bool scored = LeftOutErrors(
        g, folds,
        [&](const std::vector<char>& in) {
          if (result.smoothing_per_node.empty()) {
            Solution s = Solve(g, in, smoothing, options);
            s.converged = true;
            return s;
          }
          return SolveAtCompositions(g, in, result.smoothing_per_node, Compositions(g, in));
        },
        &total);
    if (scored && total.count > 0) f.score = std::sqrt(total.reflectance_sq / total.count);
  }
  // The Gaussian-process form, scored on the same folds, replaces the PCHIP form where it
  // beats the best smoothing by more than kSimplerMargin.
  bool use_gp = cross_validate && GaussianProcessWins(g, folds, space, options, &f);
  Solution s;
  if (use_gp) {
    s = SolveGp(g, all);
    smoothing = 0;
    if (s.converged) f.score = result.gp_rms_reflectance;
  }
  if (!s.converged) {
    use_gp = false;
    s = result.smoothing_per_node.empty()
            ? Solve(g, all, smoothing, options)
            : SolveAtCompositions(g, all, result.smoothing_per_node, compositions);
  }
  f.solution = std::move(s);
  f.smoothing = smoothing;
  f.chosen_by = std::move(chosen_by);
  f.use_gp = use_gp;
  return f;
}

}  // namespace

SmoothFitResult FitSmooth(const Dataset& dataset, const SmoothFitOptions& options) {
  const std::vector<double> grid = options.grid_nm.empty() ? DefaultGrid(dataset) : options.grid_nm;
  if (grid.size() < 2) throw Error("smooth fit: the wavelength grid needs 2 points or more");
  if (options.max_knots < 2 || options.max_knots > kSmoothMaxKnots) {
    throw Error("smooth fit: the knots must number 2.." + std::to_string(kSmoothMaxKnots));
  }
  const GridData g = PrepareData(dataset, grid);
  const std::vector<char> all(g.x.size(), 1);
  const std::vector<double> compositions = Compositions(g, all);
  if (compositions.size() < 2) {
    throw Error(dataset.manifest_path + ": the smooth fit needs at least two compositions");
  }

  Report(options.progress, "smooth: fitting " + std::to_string(g.x.size()) + " samples at " +
                               std::to_string(compositions.size()) + " compositions x " +
                               std::to_string(grid.size()) + " wavelengths");
  // The space: eps, unless ln eps predicts the left-out compositions better by
  // kLogSpaceMargin (or the caller fixed it).
  const SmoothSpace first = options.space.value_or(SmoothSpace::kEps);
  SpaceFit fit = FitInSpace(first == SmoothSpace::kEps ? g : InSpace(g, first), options);
  std::string space_chosen_by = "given";
  nlohmann::json space_scores = nlohmann::json::object();
  if (!options.space && fit.score < HUGE_VAL) {
    SpaceFit log = FitInSpace(InSpace(g, SmoothSpace::kLogEps), options);
    space_scores = {{"eps", fit.score}, {"log_eps", log.score}};
    const bool use_log = log.score * kLogSpaceMargin < fit.score;
    std::ostringstream reason;
    reason << "leave-one-out RMS reflectance error " << fit.score << " in eps, " << log.score
           << " in ln eps: " << (use_log ? "ln eps" : "eps");
    space_chosen_by = reason.str();
    Report(options.details, "space: " + space_chosen_by);
    if (use_log) fit = std::move(log);
  } else if (!options.space) {
    space_chosen_by = "default: no interior composition to hold out";
  }
  SmoothFitResult result = std::move(fit.result);
  Solution& s = fit.solution;
  const double smoothing = fit.smoothing;
  const bool use_gp = fit.use_gp;
  Report(options.details,
         "fitted " + std::to_string(g.x.size()) + " samples x " + std::to_string(grid.size()) +
             " wavelengths in " + (s.space == SmoothSpace::kLogEps ? "ln eps" : "eps") + ", " +
             (use_gp ? std::string("gaussian process across composition")
                     : "smoothing " + std::to_string(smoothing) +
                           (result.smoothing_per_node.empty() ? ""
                                                              : " (median of the wavelengths')")));

  FitSummary summary;
  summary.solver =
      use_gp ? "gaussian process across composition (Matern 5/2 about a quadratic trend), "
               "Eigen LDLT, its mean at evenly spaced knots"
      : s.termination == "direct solve"
          ? "linear least squares per node (knots at the compositions), Eigen LDLT"
          : "ceres levenberg-marquardt, sparse normal cholesky (eigen)";
  summary.degree = 3;  // cubic in composition between knots
  summary.final_cost = s.final_cost;
  summary.iterations = s.iterations;
  summary.converged = s.converged;
  summary.termination = s.termination;
  summary.rms_relative_eps =
      std::sqrt(s.data_sum_sq / std::max<double>(1.0, static_cast<double>(s.data_residuals)));
  nlohmann::json& details = summary.details;
  details["space"] = SmoothSpaceName(s.space);
  details["space_chosen_by"] = space_chosen_by;
  if (!space_scores.empty()) details["space_leave_one_out_rms_reflectance"] = space_scores;
  details["smoothing"] = smoothing;
  details["smoothing_chosen_by"] = fit.chosen_by;
  details["knots"] = s.knots.size();
  details["data_residuals"] = s.data_residuals;
  nlohmann::json per_sample = nlohmann::json::array();
  for (size_t i = 0; i < g.x.size(); ++i) {
    const SampleError e = ErrorOf(g, i, s);
    per_sample.push_back({{"x", g.x[i]},
                          {"file", dataset.samples[i].file},
                          {"rms_relative_eps", std::sqrt(e.eps_sq / e.count)}});
  }
  details["rms_per_sample"] = per_sample;
  nlohmann::json cv = nlohmann::json::array();
  for (const auto& row : result.cross_validation) {
    cv.push_back({{"smoothing", row.smoothing},
                  {"rms_relative_eps", row.rms},
                  {"rms_reflectance", row.rms_reflectance}});
  }
  details["cross_validation"] = cv;
  if (!result.evidence.empty()) {
    nlohmann::json evidence = nlohmann::json::array();
    for (const auto& row : result.evidence) {
      evidence.push_back({{"smoothing", row.smoothing}, {"wavelengths", row.nodes}});
    }
    details["marginal_likelihood"] = evidence;
  }
  details["form"] = use_gp ? "gaussian process" : "pchip";
  if (result.gp_rms_reflectance >= 0) {
    nlohmann::json gp = {{"rms_relative_eps", result.gp_rms},
                         {"rms_reflectance", result.gp_rms_reflectance}};
    if (use_gp) {
      gp["length"] = s.gp.length;
      gp["noise"] = s.gp.noise;
    }
    details["gaussian_process"] = gp;
  }

  result.model = std::make_unique<SmoothModel>(dataset, grid, std::move(s.knots), s.space,
                                               std::move(s.part1), std::move(s.part2), smoothing);
  result.model->set_fit_summary(std::move(summary));
  if (!s.converged) {
    result.model->AddWarnings({"the fit stopped before convergence: " + s.termination});
  }
  return result;
}

double SmoothingLogEvidence(const Dataset& dataset, const std::vector<double>& grid_nm,
                            const std::vector<double>& smoothing_per_node) {
  if (smoothing_per_node.size() != grid_nm.size()) {
    throw Error("smoothing evidence: one smoothing per wavelength needed");
  }
  const GridData g = PrepareData(dataset, grid_nm);
  const std::vector<char> all(g.x.size(), 1);
  const std::vector<double> compositions = Compositions(g, all);
  if (compositions.size() < 3 || g.x.size() < 3) {
    throw Error(dataset.manifest_path + ": the smoothing evidence needs three compositions");
  }
  const EvidenceTerms terms(AssembleAtCompositions(g, all, compositions), smoothing_per_node);
  std::vector<size_t> choice(grid_nm.size());
  for (size_t j = 0; j < choice.size(); ++j) choice[j] = j;
  return terms.Total(choice);
}

}  // namespace alloycolor::fit
