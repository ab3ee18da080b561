#include "alloycolor/fit/smooth_fit.h"

#include "alloycolor/fit/smooth_costs.h"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/model/optics.h"
#include "alloycolor/core/units.h"

namespace alloycolor::fit {
namespace {

// The data on the grid: eps of every sample at every node, and whether it is usable.
struct GridData {
  std::vector<double> grid_nm, omega_ev;
  std::vector<double> x;                              // per sample
  std::vector<std::vector<std::complex<double>>> eps;  // [sample][node]
  std::vector<std::vector<char>> usable;               // [sample][node]
  std::vector<std::string> warnings;
};

GridData PrepareData(const Dataset& dataset, const std::vector<double>& grid_nm) {
  GridData g;
  g.grid_nm = grid_nm;
  for (double l : grid_nm) g.omega_ev.push_back(OmegaEvFromLambdaNm(l));
  size_t total_usable = 0;
  for (const Sample& s : dataset.samples) {
    if (!s.nk.Covers(grid_nm.front(), grid_nm.back())) {
      std::ostringstream msg;
      msg << s.file << ": covers " << s.nk.lambda_min_nm() << "-" << s.nk.lambda_max_nm()
          << " nm, the fit grid needs " << grid_nm.front() << "-" << grid_nm.back() << " nm";
      throw Error(msg.str());
    }
    g.x.push_back(s.x_atomic);
    std::vector<std::complex<double>> eps;
    std::vector<char> ok;
    double start = -1, last = -1;
    std::string reason;
    auto flush = [&]() {
      if (start < 0) return;
      std::ostringstream msg;
      msg << s.file << " (x = " << s.x_atomic << "): " << reason << " at " << start << "-"
          << last << " nm contradicts the Drude model; left out of the fit there";
      g.warnings.push_back(msg.str());
      start = -1;
    };
    for (double l : grid_nm) {
      const std::complex<double> nk = NkAt(s.nk, l);
      const std::complex<double> e = nk * nk;
      const bool usable = DrudeInvertible(e.real(), e.imag());
      eps.push_back(e);
      ok.push_back(usable);
      total_usable += usable;
      if (usable) {
        flush();
        continue;
      }
      const std::string why = e.real() >= 1 ? "eps1 >= 1" : "eps2 <= 0";
      if (start >= 0 && why != reason) flush();
      if (start < 0) start = l;
      reason = why;
      last = l;
    }
    flush();
    g.eps.push_back(std::move(eps));
    g.usable.push_back(std::move(ok));
  }
  if (total_usable == 0) {
    throw Error(dataset.manifest_path +
                ": no sample is usable at any wavelength (eps1 >= 1 or eps2 <= 0 "
                "everywhere): nothing to fit");
  }
  return g;
}

// Which samples take part (all, or all but one for cross-validation).
std::vector<char> AllSamples(const GridData& g) { return std::vector<char>(g.x.size(), 1); }

struct Basis {
  double x_lo, x_hi;
  double U(double x) const { return CompositionArgument(x, x_lo, x_hi); }
};

// Least-squares start from the pointwise inversion; nodes with no usable sample copy the
// nearest node that has one.
std::vector<std::vector<double>> StartFromInversion(const GridData& g,
                                                    const std::vector<char>& in,
                                                    const Basis& basis, int nb) {
  const size_t nodes = g.grid_nm.size();
  std::vector<std::vector<double>> coeffs(nodes);
  std::vector<char> have(nodes, 0);
  for (size_t j = 0; j < nodes; ++j) {
    std::vector<int> rows;
    for (size_t i = 0; i < g.x.size(); ++i) {
      if (in[i] && g.usable[i][j]) rows.push_back(static_cast<int>(i));
    }
    if (rows.empty()) continue;
    Eigen::MatrixXd a(rows.size(), nb);
    Eigen::MatrixXd y(rows.size(), 2);
    for (size_t r = 0; r < rows.size(); ++r) {
      const int i = rows[r];
      double p[kSmoothMaxDegree + 1];
      LegendreBasis(basis.U(g.x[i]), nb - 1, p);
      for (int d = 0; d < nb; ++d) a(r, d) = p[d];
      const DrudePoint dp = InvertDrude(g.omega_ev[j], g.eps[i][j].real(), g.eps[i][j].imag());
      y(r, 0) = std::log(dp.gamma_ev);
      y(r, 1) = std::log(dp.wp2_ev2);
    }
    Eigen::MatrixXd ata = a.transpose() * a;
    for (int d = 1; d < nb; ++d) ata(d, d) += 1e-6;
    const Eigen::MatrixXd sol = ata.ldlt().solve(a.transpose() * y);
    coeffs[j].resize(2 * nb);
    for (int d = 0; d < nb; ++d) {
      coeffs[j][d] = sol(d, 0);
      coeffs[j][nb + d] = sol(d, 1);
    }
    have[j] = 1;
  }
  for (size_t j = 0; j < nodes; ++j) {
    if (have[j]) continue;
    for (size_t step = 1; step < nodes; ++step) {
      if (j >= step && have[j - step]) {
        coeffs[j] = coeffs[j - step];
        break;
      }
      if (j + step < nodes && have[j + step]) {
        coeffs[j] = coeffs[j + step];
        break;
      }
    }
  }
  return coeffs;
}

// Start from an earlier model: its eps at the grid and at 2 nb compositions spread over
// the new training range, inverted and projected on the new basis.
std::vector<std::vector<double>> StartFromModel(const SmoothModel& old, const GridData& g,
                                                const Basis& basis, int nb) {
  const int points = 2 * nb + 1;
  GridData probe;
  probe.grid_nm = g.grid_nm;
  probe.omega_ev = g.omega_ev;
  std::vector<double> lambda(g.grid_nm.size());
  for (size_t j = 0; j < lambda.size(); ++j) {
    lambda[j] = std::clamp(g.grid_nm[j], old.lambda_min_nm(), old.lambda_max_nm());
  }
  for (int p = 0; p < points; ++p) {
    const double x = basis.x_lo + (basis.x_hi - basis.x_lo) * p / (points - 1.0);
    probe.x.push_back(x);
    probe.eps.push_back(old.Permittivity(x, lambda));
    std::vector<char> ok;
    for (const auto& e : probe.eps.back()) ok.push_back(DrudeInvertible(e.real(), e.imag()));
    probe.usable.push_back(ok);
  }
  return StartFromInversion(probe, AllSamples(probe), basis, nb);
}

// Covariance of each node's coefficients: ceres::Covariance on the node's own data (and
// ridge) residuals at the solution, scaled by that node's `variance`. The curvature prior that couples
// neighbouring nodes is left out, which makes the estimate slightly conservative, keeps
// the cost linear in the number of nodes and the result independent of memory layout.
template <int kNb>
std::vector<std::vector<double>> NodeCovariances(const GridData& g, const std::vector<char>& in,
                                                 const Basis& basis,
                                                 const SmoothFitOptions& options,
                                                 std::vector<double> flat,
                                                 const std::vector<double>& variance);

struct SolveStats {
  double final_cost = 0, data_sum_sq = 0;
  int iterations = 0;
  bool converged = false;
  std::string termination;
  size_t data_residuals = 0;
  double residual_variance = 0;
  std::vector<std::vector<double>> covariance;
};

template <int kNb>
std::vector<std::vector<double>> NodeCovariances(const GridData& g, const std::vector<char>& in,
                                                 const Basis& basis,
                                                 const SmoothFitOptions& options,
                                                 std::vector<double> flat,
                                                 const std::vector<double>& variance) {
  const size_t nodes = g.grid_nm.size();
  std::vector<std::vector<double>> result(nodes);
  for (size_t j = 0; j < nodes; ++j) {
    double* block = flat.data() + j * 2 * kNb;
    ceres::Problem problem;
    problem.AddParameterBlock(block, 2 * kNb);
    for (size_t i = 0; i < g.x.size(); ++i) {
      if (!in[i] || !g.usable[i][j]) continue;
      double p[kSmoothMaxDegree + 1];
      LegendreBasis(basis.U(g.x[i]), kNb - 1, p);
      problem.AddResidualBlock(EpsResidual<kNb>::Create(p, g.omega_ev[j], g.eps[i][j]), nullptr,
                               block);
    }
    if constexpr (kNb > 1) {
      problem.AddResidualBlock(
          RidgeResidual<kNb>::Create(std::sqrt(std::max(options.ridge, 1e-12))), nullptr, block);
    }
    ceres::Covariance::Options cov_options;
    cov_options.algorithm_type = ceres::DENSE_SVD;
    cov_options.null_space_rank = -1;  // pseudo-inverse where the node is under-determined
    cov_options.num_threads = 1;
    ceres::Covariance covariance(cov_options);
    std::vector<std::pair<const double*, const double*>> pairs = {{block, block}};
    std::vector<double> cov(4 * kNb * kNb, 0.0);
    if (covariance.Compute(pairs, &problem)) {
      covariance.GetCovarianceBlock(block, block, cov.data());
      for (double& v : cov) v *= variance[j];
    }
    result[j] = std::move(cov);
  }
  return result;
}

template <int kNb>
SolveStats Solve(const GridData& g, const std::vector<char>& in, const Basis& basis,
                 const SmoothFitOptions& options, bool want_covariance, const std::vector<double>& min_variance,
                 std::vector<std::vector<double>>* coeffs) {
  const size_t nodes = g.grid_nm.size();
  // All nodes' coefficients in one buffer, in node order: Ceres orders parameter blocks by
  // address in places (the covariance), and this keeps that order the same on every run.
  std::vector<double> flat(nodes * 2 * kNb);
  for (size_t j = 0; j < nodes; ++j) {
    std::copy((*coeffs)[j].begin(), (*coeffs)[j].end(), flat.begin() + j * 2 * kNb);
  }
  auto node = [&](size_t j) { return flat.data() + j * 2 * kNb; };
  ceres::Problem::Options problem_options;
  ceres::Problem problem(problem_options);
  std::vector<ceres::ResidualBlockId> data_blocks;
  for (size_t j = 0; j < nodes; ++j) {
    double* block = node(j);
    problem.AddParameterBlock(block, 2 * kNb);
    for (size_t i = 0; i < g.x.size(); ++i) {
      if (!in[i] || !g.usable[i][j]) continue;
      double p[kSmoothMaxDegree + 1];
      LegendreBasis(basis.U(g.x[i]), kNb - 1, p);
      data_blocks.push_back(problem.AddResidualBlock(
          EpsResidual<kNb>::Create(p, g.omega_ev[j], g.eps[i][j]), nullptr, block));
    }
    if (kNb > 1 && options.ridge > 0) {
      if constexpr (kNb > 1) {
        problem.AddResidualBlock(RidgeResidual<kNb>::Create(std::sqrt(options.ridge)),
                                 nullptr, block);
      }
    }
  }
  if (options.smoothing > 0) {
    for (size_t j = 1; j + 1 < nodes; ++j) {
      problem.AddResidualBlock(CurvatureResidual<kNb>::Create(std::sqrt(options.smoothing)),
                               nullptr, node(j - 1), node(j), node(j + 1));
    }
  }
  ceres::Solver::Options solver_options;
  // Eigen's sparse Cholesky: no threaded BLAS underneath, so the result is the same to
  // the last bit on every run (SuiteSparse through OpenBLAS is not).
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = 1e-12;
  solver_options.gradient_tolerance = 1e-14;
  solver_options.parameter_tolerance = 1e-12;
  solver_options.num_threads = 1;  // deterministic: the same inputs give the same bytes
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);
  if (summary.termination_type == ceres::FAILURE ||
      summary.termination_type == ceres::USER_FAILURE) {
    throw Error("smooth fit failed: " + summary.message);
  }
  for (size_t j = 0; j < nodes; ++j) {
    std::copy(node(j), node(j) + 2 * kNb, (*coeffs)[j].begin());
  }
  SolveStats stats;
  stats.final_cost = summary.final_cost;
  stats.iterations = static_cast<int>(summary.iterations.size()) - 1;
  stats.converged = summary.termination_type == ceres::CONVERGENCE;
  stats.termination = ceres::TerminationTypeToString(summary.termination_type);
  stats.data_residuals = 2 * data_blocks.size();
  ceres::Problem::EvaluateOptions eval;
  eval.residual_blocks = data_blocks;
  std::vector<double> residuals;
  problem.Evaluate(eval, nullptr, &residuals, nullptr, nullptr);
  for (double r : residuals) stats.data_sum_sq += r * r;

  if (want_covariance) {
    const double params = static_cast<double>(nodes * 2 * kNb);
    const double dof = std::max(static_cast<double>(stats.data_residuals) - params, 1.0);
    stats.residual_variance = stats.data_sum_sq / dof;
    std::vector<double> variance(nodes, stats.residual_variance);
    for (size_t j = 0; j < nodes && j < min_variance.size(); ++j) {
      variance[j] = std::max(variance[j], min_variance[j]);
    }
    stats.covariance = NodeCovariances<kNb>(g, in, basis, options, flat, variance);
  }
  return stats;
}

SolveStats SolveAny(int nb, const GridData& g, const std::vector<char>& in,
                    const Basis& basis, const SmoothFitOptions& options, bool want_covariance,
                    const std::vector<double>& min_variance,
                    std::vector<std::vector<double>>* coeffs) {
  switch (nb) {
    case 1: return Solve<1>(g, in, basis, options, want_covariance, min_variance, coeffs);
    case 2: return Solve<2>(g, in, basis, options, want_covariance, min_variance, coeffs);
    case 3: return Solve<3>(g, in, basis, options, want_covariance, min_variance, coeffs);
    case 4: return Solve<4>(g, in, basis, options, want_covariance, min_variance, coeffs);
    case 5: return Solve<5>(g, in, basis, options, want_covariance, min_variance, coeffs);
    case 6: return Solve<6>(g, in, basis, options, want_covariance, min_variance, coeffs);
    case 7: return Solve<7>(g, in, basis, options, want_covariance, min_variance, coeffs);
    case 8: return Solve<8>(g, in, basis, options, want_covariance, min_variance, coeffs);
    case 9: return Solve<9>(g, in, basis, options, want_covariance, min_variance, coeffs);
  }
  throw Error("smooth fit: degree must lie in 0.." + std::to_string(kSmoothMaxDegree));
}

// RMS relative eps error of sample i (usable nodes only) under the given coefficients.
double SampleRms(const GridData& g, size_t i, const Basis& basis, int nb,
                 const std::vector<std::vector<double>>& coeffs) {
  double p[kSmoothMaxDegree + 1];
  LegendreBasis(basis.U(g.x[i]), nb - 1, p);
  double sum = 0;
  int count = 0;
  for (size_t j = 0; j < g.grid_nm.size(); ++j) {
    if (!g.usable[i][j]) continue;
    const Complex<double> e = SmoothNodePermittivity(coeffs[j].data(), p, nb, g.omega_ev[j]);
    sum += std::norm(std::complex<double>(e.re, e.im) - g.eps[i][j]) / std::norm(g.eps[i][j]);
    ++count;
  }
  return count ? std::sqrt(sum / (2.0 * count)) : 0.0;
}

// Adds the left-out sample i's squared residual at each usable node (mean of the two
// parts), standardised by its leverage: r^2 / (1 + h), h = b^T (B^T B)^-1 b with b the
// basis at x_i and B the fold's design at that node. Averaged over folds this estimates
// the variance that, through the final fit's covariance, predicts its error between
// samples (the prediction variance there is variance * h of the final design).
void AddStandardisedSquares(const GridData& g, const std::vector<char>& in, size_t i,
                            const Basis& basis, int nb,
                            const std::vector<std::vector<double>>& coeffs,
                            std::vector<double>* sq, std::vector<int>* count) {
  double p[kSmoothMaxDegree + 1];
  LegendreBasis(basis.U(g.x[i]), nb - 1, p);
  const Eigen::Map<const Eigen::VectorXd> b(p, nb);
  for (size_t j = 0; j < g.grid_nm.size(); ++j) {
    if (!g.usable[i][j]) continue;
    Eigen::MatrixXd btb = Eigen::MatrixXd::Identity(nb, nb) * 1e-9;
    for (size_t s = 0; s < g.x.size(); ++s) {
      if (!in[s] || !g.usable[s][j]) continue;
      double q[kSmoothMaxDegree + 1];
      LegendreBasis(basis.U(g.x[s]), nb - 1, q);
      const Eigen::Map<const Eigen::VectorXd> row(q, nb);
      btb += row * row.transpose();
    }
    const double leverage = b.dot(btb.ldlt().solve(b));
    const Complex<double> e = SmoothNodePermittivity(coeffs[j].data(), p, nb, g.omega_ev[j]);
    const double scale = std::norm(g.eps[i][j]);
    (*sq)[j] += 0.5 * (std::pow(e.re - g.eps[i][j].real(), 2) +
                       std::pow(e.im - g.eps[i][j].imag(), 2)) /
                scale / (1.0 + leverage);
    ++(*count)[j];
  }
}

// RMS error of sample i's normal-incidence reflectance (usable nodes only): what colour
// depends on, and the score cross-validation minimises.
double SampleReflectanceRms(const GridData& g, size_t i, const Basis& basis, int nb,
                            const std::vector<std::vector<double>>& coeffs) {
  double p[kSmoothMaxDegree + 1];
  LegendreBasis(basis.U(g.x[i]), nb - 1, p);
  double sum = 0;
  int count = 0;
  for (size_t j = 0; j < g.grid_nm.size(); ++j) {
    if (!g.usable[i][j]) continue;
    const Complex<double> model =
        IndexFromPermittivity(SmoothNodePermittivity(coeffs[j].data(), p, nb, g.omega_ev[j]));
    const Complex<double> measured = IndexFromPermittivity(
        Complex<double>{g.eps[i][j].real(), g.eps[i][j].imag()});
    sum += std::pow(NormalReflectance(model) - NormalReflectance(measured), 2);
    ++count;
  }
  return count ? std::sqrt(sum / count) : 0.0;
}

}  // namespace

SmoothFitResult FitSmooth(const Dataset& dataset, const SmoothFitOptions& options) {
  if (dataset.samples.size() < 2) {
    throw Error(dataset.manifest_path + ": the smooth fit needs at least two samples");
  }
  auto progress = [&](const std::string& message) {
    if (options.progress) options.progress(message);
  };
  const std::vector<double> grid =
      options.grid_nm.empty() ? DefaultGrid(dataset) : options.grid_nm;
  if (grid.size() < 3) throw Error("smooth fit: the wavelength grid needs 3 points or more");
  const GridData g = PrepareData(dataset, grid);
  const Basis basis{dataset.samples.front().x_atomic, dataset.samples.back().x_atomic};
  const size_t n = g.x.size();

  SmoothFitResult result;
  int degree = options.degree;
  if (degree > kSmoothMaxDegree) {
    throw Error("smooth fit: degree must lie in 0.." + std::to_string(kSmoothMaxDegree));
  }
  // Leverage-standardised mean squared left-out residual at each node, chosen degree.
  std::vector<double> cv_variance;
  if (degree < 0) {
    // Leave-one-composition-out over the interior samples. A fold has one sample fewer,
    // so it is fitted with one degree less than the final fit: both then leave the same
    // number of degrees of freedom, and the score says how well a fit of that flexibility
    // predicts a composition it has not seen.
    const int max_degree =
        std::min<int>(std::min(options.max_degree, kSmoothMaxDegree), static_cast<int>(n) - 1);
    if (n < 3 || max_degree < 1) {
      degree = std::max(0, std::min<int>(static_cast<int>(n) - 1, 1));
    } else {
      double best = 1e300;
      for (int d = 1; d <= max_degree; ++d) {
        const int fold_nb = d;  // degree d - 1
        double sum = 0, sum_r = 0;
        int folds = 0;
        std::vector<double> node_sq(grid.size(), 0.0);
        std::vector<int> node_count(grid.size(), 0);
        for (size_t out = 1; out + 1 < n; ++out) {
          std::vector<char> in = AllSamples(g);
          in[out] = 0;
          auto coeffs = StartFromInversion(g, in, basis, fold_nb);
          SolveAny(fold_nb, g, in, basis, options, false, {}, &coeffs);
          AddStandardisedSquares(g, in, out, basis, fold_nb, coeffs, &node_sq, &node_count);
          const double rms = SampleRms(g, out, basis, fold_nb, coeffs);
          const double rms_r = SampleReflectanceRms(g, out, basis, fold_nb, coeffs);
          sum += rms * rms;
          sum_r += rms_r * rms_r;
          ++folds;
        }
        const double rms = std::sqrt(sum / folds);
        const double rms_r = std::sqrt(sum_r / folds);
        result.cross_validation.push_back({d, rms, rms_r});
        std::ostringstream msg;
        msg << "cross-validation: degree " << d << ", leave-one-out RMS error: relative eps "
            << rms << ", reflectance " << rms_r;
        progress(msg.str());
        if (rms_r < best) {
          best = rms_r;
          degree = d;
          cv_variance.assign(grid.size(), 0.0);
          for (size_t j = 0; j < grid.size(); ++j) {
            if (node_count[j]) cv_variance[j] = node_sq[j] / node_count[j];
          }
        }
      }
    }
  }
  const int nb = degree + 1;
  progress("fitting degree " + std::to_string(degree) + " on " + std::to_string(n) +
           " samples x " + std::to_string(grid.size()) + " wavelengths");
  auto coeffs = options.start ? StartFromModel(*options.start, g, basis, nb)
                              : StartFromInversion(g, AllSamples(g), basis, nb);
  const SolveStats stats =
      SolveAny(nb, g, AllSamples(g), basis, options, options.covariance, cv_variance, &coeffs);

  FitSummary summary;
  summary.solver = "ceres levenberg-marquardt, sparse normal cholesky (eigen)";
  summary.degree = degree;
  summary.final_cost = stats.final_cost;
  summary.iterations = stats.iterations;
  summary.converged = stats.converged;
  summary.termination = stats.termination;
  summary.rms_relative_eps =
      std::sqrt(stats.data_sum_sq / std::max<double>(1.0, static_cast<double>(stats.data_residuals)));
  nlohmann::json& fit = summary.details;
  fit["degree_chosen_by"] = options.degree < 0 ? "leave-one-out cross-validation" : "user";
  fit["smoothing"] = options.smoothing;
  fit["ridge"] = options.ridge;
  fit["data_residuals"] = stats.data_residuals;
  nlohmann::json per_sample = nlohmann::json::array();
  for (size_t i = 0; i < n; ++i) {
    per_sample.push_back({{"x", g.x[i]},
                          {"file", dataset.samples[i].file},
                          {"rms_relative_eps", SampleRms(g, i, basis, nb, coeffs)}});
  }
  fit["rms_per_sample"] = per_sample;
  nlohmann::json cv = nlohmann::json::array();
  for (const auto& row : result.cross_validation) {
    cv.push_back({{"degree", row.degree},
                  {"rms_relative_eps", row.rms},
                  {"rms_reflectance", row.rms_reflectance}});
  }
  fit["cross_validation"] = cv;
  if (stats.covariance.empty()) {
    fit["covariance"] = "none";
  } else {
    fit["covariance"] =
        "ceres::Covariance (dense SVD) of each wavelength node's coefficients on its data, "
        "scaled by the larger of the data residual variance and the node's leave-one-out "
        "residual variance standardised by leverage, r^2 / (1 + h)";
    fit["residual_variance"] = stats.residual_variance;
    double mean = 0;
    for (double v : cv_variance) mean += v / cv_variance.size();
    fit["cross_validation_variance_mean"] = mean;
  }

  result.model = std::make_unique<SmoothModel>(dataset, grid, degree, std::move(coeffs),
                                               stats.covariance);
  result.model->set_fit_summary(std::move(summary));
  result.model->AddWarnings(g.warnings);
  if (!stats.converged) {
    result.model->AddWarnings({"the fit stopped before convergence: " + stats.termination});
  }
  return result;
}

}  // namespace alloycolor::fit
