#include "smooth_solve.h"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/units.h"
#include "alloycolor/fit/gp_regression.h"
#include "alloycolor/fit/smooth_costs.h"
#include "alloycolor/model/interpolation.h"
#include "alloycolor/model/optics.h"

namespace alloycolor::fit::smooth {

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

namespace {

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
  s->slope1.resize(s->part1.size());
  s->slope2.resize(s->part2.size());
  for (size_t j = 0; j < s->part1.size(); ++j) {
    s->slope1[j].resize(k);
    s->slope2[j].resize(k);
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
}  // namespace

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

namespace {

// Solved directly from the normal equations (Eigen LDLT, K x K per part): the minimum
// Ceres reaches too, at a small fraction of the time (cross-validation solves it hundreds
// of times, each fold's systems assembled once for every candidate smoothing).
// Solves (diag(a) + mu R) v = b for the two columns of b in place: R the second-difference
// Gram matrix, symmetric with two bands (r0 its diagonal, r1 and r2 the bands above), so
// the matrix is symmetric positive definite (every knot holds a sample: a > 0) and
// pentadiagonal, and L D L^T without pivoting costs O(k).
void SolvePentadiagonal(size_t k, const double* a, double mu, const double* r0, const double* r1,
                        const double* r2, double* b1, double* b2) {
  double d[kSmoothMaxKnots], l1[kSmoothMaxKnots], l2[kSmoothMaxKnots];
  for (size_t i = 0; i < k; ++i) {
    // Row i of L: l1[i] = L(i, i-1), l2[i] = L(i, i-2).
    double m_i1 = i >= 1 ? mu * r1[i - 1] : 0.0;        // M(i, i-1)
    const double m_i2 = i >= 2 ? mu * r2[i - 2] : 0.0;  // M(i, i-2)
    l2[i] = i >= 2 ? m_i2 / d[i - 2] : 0.0;
    if (i >= 2) m_i1 -= l2[i] * l1[i - 1] * d[i - 2];
    l1[i] = i >= 1 ? m_i1 / d[i - 1] : 0.0;
    d[i] = a[i] + mu * r0[i] - (i >= 1 ? l1[i] * l1[i] * d[i - 1] : 0.0) -
           (i >= 2 ? l2[i] * l2[i] * d[i - 2] : 0.0);
  }
  for (double* b : {b1, b2}) {
    for (size_t i = 1; i < k; ++i) b[i] -= l1[i] * b[i - 1] + (i >= 2 ? l2[i] * b[i - 2] : 0.0);
    for (size_t i = 0; i < k; ++i) b[i] /= d[i];
    for (size_t i = k; i-- > 0;) {
      if (i + 1 < k) b[i] -= l1[i + 1] * b[i + 1];
      if (i + 2 < k) b[i] -= l2[i + 2] * b[i + 2];
    }
  }
}
}  // namespace

// Into *s (its storage reused); with `statistics` the cost and the data's misfit too, which
// the cross-validation does not read.
void SolveAssembled(const GridData& g, const std::vector<char>& in, const LinearSystems& ls,
                    const std::vector<double>& smoothing_per_node, bool statistics, Solution* s) {
  s->space = g.space;
  s->knots = ls.knots;
  const size_t nodes = g.grid_nm.size(), k = s->knots.size();
  double r0[kSmoothMaxKnots], r1[kSmoothMaxKnots], r2[kSmoothMaxKnots];
  for (size_t c = 0; c < k; ++c) {
    r0[c] = ls.rtr(c, c);
    r1[c] = c + 1 < k ? ls.rtr(c, c + 1) : 0.0;
    r2[c] = c + 2 < k ? ls.rtr(c, c + 2) : 0.0;
  }
  s->part1.resize(nodes);
  s->part2.resize(nodes);
  double cost = 0, a[kSmoothMaxKnots];
  for (size_t j = 0; j < nodes; ++j) {
    const double mu = std::max(smoothing_per_node[j], 0.0) * ls.mu_per_smoothing[j];
    s->part1[j].resize(k);
    s->part2[j].resize(k);
    double* v1 = s->part1[j].data();
    double* v2 = s->part2[j].data();
    for (size_t c = 0; c < k; ++c) {
      a[c] = ls.a[j](c, c);
      v1[c] = ls.b[j](c, 0);
      v2[c] = ls.b[j](c, 1);
    }
    SolvePentadiagonal(k, a, mu, r0, r1, r2, v1, v2);
    if (statistics) {
      const Eigen::Map<const Eigen::VectorXd> e1(v1, k), e2(v2, k);
      cost += 0.5 * mu * (e1.dot(ls.rtr * e1) + e2.dot(ls.rtr * e2));
    }
  }
  Finish(s);
  s->data_sum_sq = 0;
  s->data_residuals = 0;
  for (size_t i = 0; statistics && i < g.x.size(); ++i) {
    if (!in[i]) continue;
    for (size_t j = 0; j < nodes; ++j) {
      const std::complex<double> e = g.eps[i][j];
      const size_t c = ls.knot_of[i];
      const std::complex<double> m = EpsFromParts(s->space, s->part1[j][c], s->part2[j][c]);
      s->data_sum_sq += std::norm(m - e) / std::norm(e);
      s->data_residuals += 2;
    }
  }
  s->final_cost = cost + 0.5 * s->data_sum_sq;
  s->converged = true;
  s->termination = "direct solve";
}

Solution SolveAtCompositions(const GridData& g, const std::vector<char>& in,
                             const std::vector<double>& smoothing_per_node,
                             std::vector<double> knots) {
  Solution s;
  SolveAssembled(g, in, AssembleAtCompositions(g, in, std::move(knots)), smoothing_per_node, true,
                 &s);
  return s;
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
// `warm`: a solution on the same knots to start from (the cross-validation's previous
// candidate smoothing on the same fold); null for Start's.
Solution SolveCeres(const GridData& g, const std::vector<char>& in, double smoothing,
                    const SmoothFitOptions& options, std::vector<double> knots,
                    const Solution* warm) {
  Solution s;
  s.knots = std::move(knots);
  if (warm != nullptr && warm->knots == s.knots) {
    s.space = g.space;
    s.part1 = warm->part1;
    s.part2 = warm->part2;
  } else {
    Start(g, in, options.start, &s);
  }
  const size_t nodes = g.grid_nm.size(), k = s.knots.size();
  const std::vector<double> knots_u = KnotsU(g, s.knots);

  // Each node's two parts are independent of each other and of every other node's: one
  // small problem each, solved densely (and each converging on its own: twice the budget).
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  solver_options.dense_linear_algebra_library_type = ceres::EIGEN;
  solver_options.max_num_iterations = 2 * options.max_iterations;
  solver_options.function_tolerance = 1e-10;
  solver_options.gradient_tolerance = 1e-12;
  solver_options.parameter_tolerance = 1e-10;
  solver_options.num_threads = 1;
  solver_options.logging_type = ceres::SILENT;
  s.converged = true;
  s.termination = ceres::TerminationTypeToString(ceres::CONVERGENCE);
  for (size_t j = 0; j < nodes; ++j) {
    CheckCancel(options.cancel);
    double sum_sq = 0;
    int count = 0;
    for (size_t i = 0; i < g.x.size(); ++i) {
      if (!in[i]) continue;
      sum_sq += 1 / g.weight[i][j];
      ++count;
    }
    for (int part = 0; part < 2; ++part) {
      double* values = (part == 0 ? s.part1 : s.part2)[j].data();
      ceres::Problem problem;
      problem.AddParameterBlock(values, static_cast<int>(k));
      for (size_t i = 0; i < g.x.size(); ++i) {
        if (!in[i]) continue;
        const std::complex<double> y = g.parts[i][j];
        problem.AddResidualBlock(
            new SmoothDataResidual(s.knots, g.x[i], part == 0 ? y.real() : y.imag(),
                                   std::sqrt(g.weight[i][j])),
            nullptr, values);
        s.data_residuals += 1;
      }
      if (smoothing > 0 && k >= 3) {
        // Relative to the node's RMS |eps| (in eps), as the data residuals are.
        const double weight = std::sqrt(smoothing * count / sum_sq);
        problem.AddResidualBlock(SmoothRoughnessResidual::Create(knots_u, weight), nullptr, values);
      }
      ceres::Solver::Summary summary;
      ceres::Solve(solver_options, &problem, &summary);
      if (summary.termination_type == ceres::FAILURE ||
          summary.termination_type == ceres::USER_FAILURE) {
        throw Error("smooth fit failed: " + summary.message);
      }
      s.final_cost += summary.final_cost;
      s.iterations = std::max(s.iterations, static_cast<int>(summary.iterations.size()) - 1);
      if (summary.termination_type != ceres::CONVERGENCE) {
        s.converged = false;
        s.termination = ceres::TerminationTypeToString(summary.termination_type);
      }
    }
  }
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
  CheckCancel(options.cancel);
  const std::vector<double> compositions = Compositions(g, in);
  std::vector<double> knots = Knots(compositions, std::min(options.max_knots, kSmoothMaxKnots));
  if (knots.size() == compositions.size()) {
    return SolveAtCompositions(g, in, std::vector<double>(g.grid_nm.size(), smoothing), knots);
  }
  return SolveCeres(g, in, smoothing, options, std::move(knots));
}

namespace {

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
}  // namespace

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

}  // namespace alloycolor::fit::smooth
