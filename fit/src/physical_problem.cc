#include "physical_problem.h"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/units.h"
#include "alloycolor/fit/physical_costs.h"
#include "cancel_callback.h"

namespace alloycolor::fit::physical {

FitData PrepareData(const Dataset& dataset, const PhysicalFitOptions& options) {
  const WavelengthRange range = CommonRange(dataset);
  const double lo = range.lo_nm, hi = range.hi_nm;
  FitData data;
  double from = options.lambda_from_nm, to = options.lambda_to_nm;
  if (from == 0 && to == 0) {
    from = std::max(lo, 300.0);
    to = std::min(hi, 1000.0);
    if (!(to - from >= 200.0)) {
      from = lo;
      to = hi;
    }
  } else if (!(from > 0 && to > from)) {
    throw Error("physical fit: the wavelength range needs 0 < from < to");
  }
  data.infrared = from >= 1000.0 - 1e-9;
  double step = options.lambda_step_nm;
  if (step == 0) step = data.infrared ? (to - from) / 200.0 : kGridStepNm;
  if (!(step > 0) || (to - from) / step > 1e5) {
    throw Error("physical fit: the wavelength step must be positive (and not tiny)");
  }
  data.grid_nm = UniformGrid(from, to, step);
  if (data.grid_nm.size() < 3) {
    throw Error("physical fit: the wavelength grid needs 3 points or more");
  }
  data.omega_min = OmegaEvFromLambdaNm(data.grid_nm.back());
  data.omega_max = OmegaEvFromLambdaNm(data.grid_nm.front());
  for (const Sample& s : dataset.samples) {
    if (!s.nk.Covers(data.grid_nm.front(), data.grid_nm.back())) {
      std::ostringstream msg;
      msg << s.file << ": covers " << s.nk.lambda_min_nm() << "-" << s.nk.lambda_max_nm()
          << " nm, the fit needs " << data.grid_nm.front() << "-" << data.grid_nm.back() << " nm";
      throw Error(msg.str());
    }
    SampleData sd;
    sd.x = s.x_atomic;
    sd.file = s.file;
    int dropped = 0;
    for (double l : data.grid_nm) {
      const std::complex<double> nk = NkAt(s.nk, l);
      const std::complex<double> e = nk * nk;
      if (!std::isfinite(e.real()) || !std::isfinite(e.imag()) || std::abs(e) == 0.0) {
        ++dropped;
        continue;
      }
      sd.lambda_nm.push_back(l);
      sd.omega_ev.push_back(OmegaEvFromLambdaNm(l));
      sd.eps.push_back(e);
    }
    if (dropped > 0) {
      data.warnings.push_back(s.file + ": " + std::to_string(dropped) +
                              " wavelengths with eps zero or not finite left out");
    }
    if (sd.eps.empty()) throw Error(s.file + ": no usable data in the fit range");
    data.samples.push_back(std::move(sd));
  }
  return data;
}

namespace {

// Upper limit of a positive parameter's constant coefficient.
double UpperLimit(const PhysicalParameter& p, double omega_max) {
  const std::string name = p.name;
  if (name == "eps_inf") return 100.0;
  if (name == "wp_eV") return 50.0;
  if (name == "gamma_eV" || name == "G_eV") return 10.0;
  if (name == "A") return 1e4;
  return 3.0 * omega_max;  // E0_eV, Eg_eV
}

}  // namespace

Bounds MakeBounds(const PhysicalLayout& layout, double omega_max) {
  const int nb = layout.basis_size();
  Bounds b;
  b.lower.assign(layout.num_coefficients(), -HUGE_VAL);
  b.upper.assign(layout.num_coefficients(), HUGE_VAL);
  for (int k = 0; k < layout.num_parameters(); ++k) {
    const PhysicalParameter& p = layout.parameters()[k];
    if (p.map == ParameterMap::kFree) {
      for (int d = 0; d < nb; ++d) {
        b.lower[k * nb + d] = -kPi;
        b.upper[k * nb + d] = kPi;
      }
    } else {
      b.lower[k * nb] = 0.0;
      b.upper[k * nb] = UpperLimit(p, omega_max);
    }
  }
  return b;
}

FitProblem::FitProblem(const PhysicalLayout& layout, const std::vector<const SampleData*>& samples,
                       const Basis& basis, const Bounds& bounds, std::vector<double> start)
    : coeffs_(std::move(start)) {
  for (size_t i = 0; i < coeffs_.size(); ++i) {
    coeffs_[i] = std::clamp(coeffs_[i], bounds.lower[i], bounds.upper[i]);
  }
  double* block = coeffs_.data();
  problem_.AddParameterBlock(block, static_cast<int>(coeffs_.size()));
  for (size_t i = 0; i < coeffs_.size(); ++i) {
    if (std::isfinite(bounds.lower[i])) {
      problem_.SetParameterLowerBound(block, static_cast<int>(i), bounds.lower[i]);
    }
    if (std::isfinite(bounds.upper[i])) {
      problem_.SetParameterUpperBound(block, static_cast<int>(i), bounds.upper[i]);
    }
  }
  for (const SampleData* s : samples) {
    double p[kPhysicalMaxDegree + 1];
    LegendreBasis(layout.basis_size() == 1 ? 0.0 : basis.U(s->x), layout.degree(), p);
    problem_.AddResidualBlock(CreatePhysicalSampleCost(layout, p, s->omega_ev, s->eps), nullptr,
                              block);
    residuals_ += 2 * s->eps.size();
    block_sizes_.push_back(2 * s->eps.size());
  }
}

SolveResult FitProblem::Solve(int max_iterations, double tolerance, const CancelCheck& cancel) {
  ceres::Solver::Options options;
  const CancelCallback cancel_callback(cancel, &options);
  // One dense parameter block: Eigen dense normal equations, no threads, the same bytes
  // every run.
  options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  options.dense_linear_algebra_library_type = ceres::EIGEN;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = tolerance;
  options.gradient_tolerance = tolerance * 1e-2;
  options.parameter_tolerance = tolerance;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem_, &summary);
  cancel_callback.Rethrow();
  SolveResult r;
  r.coeffs = coeffs_;
  r.cost = summary.termination_type == ceres::FAILURE ? HUGE_VAL : summary.final_cost;
  if (!std::isfinite(r.cost)) r.cost = HUGE_VAL;
  r.iterations = static_cast<int>(summary.iterations.size()) - 1;
  r.converged = summary.termination_type == ceres::CONVERGENCE;
  r.termination = ceres::TerminationTypeToString(summary.termination_type);
  return r;
}

std::vector<double> FitProblem::Covariance(bool* pseudo_inverse) {
  const int nc = static_cast<int>(coeffs_.size());
  ceres::CRSMatrix crs;
  problem_.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, nullptr, nullptr, &crs);
  Eigen::MatrixXd jtj = Eigen::MatrixXd::Zero(nc, nc);
  for (int row = 0; row < crs.num_rows; ++row) {
    for (int a = crs.rows[row]; a < crs.rows[row + 1]; ++a) {
      for (int b = crs.rows[row]; b < crs.rows[row + 1]; ++b) {
        jtj(crs.cols[a], crs.cols[b]) += crs.values[a] * crs.values[b];
      }
    }
  }
  const Eigen::VectorXd eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(jtj, Eigen::EigenvaluesOnly).eigenvalues();
  const double min_reciprocal_condition = 1e-14;
  *pseudo_inverse = !(eigenvalues.minCoeff() >= min_reciprocal_condition * eigenvalues.maxCoeff());
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::DENSE_SVD;
  options.min_reciprocal_condition_number = min_reciprocal_condition;
  options.null_space_rank = -1;
  options.num_threads = 1;
  ceres::Covariance covariance(options);
  const std::vector<std::pair<const double*, const double*>> blocks = {
      {coeffs_.data(), coeffs_.data()}};
  std::vector<double> out(static_cast<size_t>(nc) * nc);
  if (!covariance.Compute(blocks, &problem_) ||
      !covariance.GetCovarianceBlock(coeffs_.data(), coeffs_.data(), out.data())) {
    return {};
  }
  return out;
}

double FitProblem::ResidualAutocorrelation() {
  std::vector<double> r;
  problem_.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, &r, nullptr, nullptr);
  double num = 0, den = 0;
  size_t at = 0;
  for (size_t size : block_sizes_) {
    for (size_t i = 0; i < size; ++i) {
      den += r[at + i] * r[at + i];
      if (i + 2 < size) num += r[at + i] * r[at + i + 2];
    }
    at += size;
  }
  return den > 0 ? num / den : 0.0;
}

}  // namespace alloycolor::fit::physical
