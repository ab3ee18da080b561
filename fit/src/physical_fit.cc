#include "alloycolor/fit/physical_fit.h"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/core/text.h"
#include "alloycolor/core/units.h"
#include "alloycolor/fit/physical_costs.h"
#include "alloycolor/model/optics.h"

namespace alloycolor::fit {
namespace {

constexpr int kEndStarts = 3;        // grid-search starts refined per end sample
constexpr int kRaceIterations = 30;  // joint starts race this far before the best goes on

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

struct Basis {
  double x_lo, x_hi;
  double U(double x) const { return CompositionArgument(x, x_lo, x_hi); }
};

// Upper limit of a positive parameter's constant coefficient.
double UpperLimit(const PhysicalParameter& p, double omega_max) {
  const std::string name = p.name;
  if (name == "eps_inf") return 100.0;
  if (name == "wp_eV") return 50.0;
  if (name == "gamma_eV" || name == "G_eV") return 10.0;
  if (name == "A") return 1e4;
  return 3.0 * omega_max;  // E0_eV, Eg_eV
}

struct Bounds {
  std::vector<double> lower, upper;  // per coefficient; +-inf where unbounded
};

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

  SolveResult Solve(int max_iterations, double tolerance) {
    ceres::Solver::Options options;
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
    SolveResult r;
    r.coeffs = coeffs_;
    r.cost = summary.termination_type == ceres::FAILURE ? HUGE_VAL : summary.final_cost;
    if (!std::isfinite(r.cost)) r.cost = HUGE_VAL;
    r.iterations = static_cast<int>(summary.iterations.size()) - 1;
    r.converged = summary.termination_type == ceres::CONVERGENCE;
    r.termination = ceres::TerminationTypeToString(summary.termination_type);
    return r;
  }

  // The covariance of the coefficients, unscaled ((J^T J)^-1, or its pseudo-inverse when
  // J is rank-deficient); empty if it fails. *pseudo_inverse says whether J is
  // rank-deficient: lambda_min / lambda_max of J^T J below the Ceres default
  // min_reciprocal_condition_number (1e-14). Asked for the pseudo-inverse directly
  // (null_space_rank = -1), Ceres drops exactly those eigenvalues, and for a well-
  // conditioned J that is the plain inverse; this way it never logs a failed attempt.
  std::vector<double> Covariance(bool* pseudo_inverse) {
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
    *pseudo_inverse =
        !(eigenvalues.minCoeff() >= min_reciprocal_condition * eigenvalues.maxCoeff());
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

  size_t residuals() const { return residuals_; }

  // Lag-1 autocorrelation of the residuals along wavelength, real and imaginary parts
  // apart, pooled over the samples: rho = sum r_i r_(i+1) / sum r_i^2.
  double ResidualAutocorrelation() {
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

 private:
  std::vector<double> coeffs_;
  ceres::Problem problem_;
  size_t residuals_ = 0;
  std::vector<size_t> block_sizes_;
};

// Grid search for an end sample's starting points (degree 0, so coefficients are the r
// values). eps is linear in eps_inf, wp^2, each term's A (and, for a critical point, in
// A cos phi and A sin phi), so for every combination of the other parameters on a grid
// (gamma; each term's E0, G and, for rioux-gap, Eg - E0) those follow from a small
// weighted linear least-squares problem, solved from a cached Gram matrix. The best
// combinations with distinct centres are the starts.
class GridSearch {
 public:
  GridSearch(const PhysicalLayout& layout, const SampleData& s, const FitData& data)
      : layout_(layout), m_(s.eps.size()) {
    y_.resize(2 * m_);
    w_.resize(m_);
    for (size_t i = 0; i < m_; ++i) {
      w_[i] = 1.0 / std::abs(s.eps[i]);
      y_[i] = s.eps[i].real() * w_[i];
      y_[m_ + i] = s.eps[i].imag() * w_[i];
    }
    omega_ = s.omega_ev;
    // gamma from the pointwise inversion at the lowest photon energy.
    size_t low = 0;
    for (size_t i = 1; i < m_; ++i) {
      if (omega_[i] < omega_[low]) low = i;
    }
    double gamma = 0.1;
    if (DrudeInvertible(s.eps[low].real(), s.eps[low].imag())) {
      gamma = std::clamp(InvertDrude(omega_[low], s.eps[low].real(), s.eps[low].imag()).gamma_ev,
                         0.005, 3.0);
    }
    AddColumn([](double) { return std::complex<double>(1.0, 0.0); });  // eps_inf
    for (double f : {0.5, 1.0, 2.0}) {
      gammas_.push_back(gamma * f);
      const double g = gamma * f;
      AddColumn([g](double w) { return -1.0 / (w * std::complex<double>(w, g)); });
    }
    const double span = data.omega_max - data.omega_min;
    for (int i = 0; i < kCentres; ++i) {
      centres_.push_back(data.omega_min + span * (0.02 + 1.13 * i / (kCentres - 1)));
    }
    // Candidates of each term, by kind (terms of one kind share them).
    for (int t = 1; t < layout.num_terms(); ++t) {
      const TermKind kind = layout.term_kind(t);
      if (candidates_.count(kind)) continue;
      std::vector<Candidate>& list = candidates_[kind];
      for (int e = 0; e < kCentres; ++e) {
        for (double g : {0.05, 0.15, 0.5, 1.5}) {
          const std::vector<double> gaps = kind == TermKind::kRiouxGap
                                               ? std::vector<double>{0.1, 0.3, 1.0}
                                               : std::vector<double>{0.0};
          for (double gap : gaps) {
            Candidate c{e,
                        centres_[e],
                        g,
                        gap,
                        static_cast<int>(columns_.size()),
                        kind == TermKind::kCriticalPoint ? 2 : 1};
            // The term with A = 1 (phase 0, then pi/2 for a critical point).
            double v[4] = {1.0, c.e0, 0.0, 0.0};
            if (kind == TermKind::kRiouxGap) {
              v[2] = c.e0 + gap;
              v[3] = g;
            } else {
              v[2] = g;
            }
            AddColumn([&](double w) { return ToStd(InterbandPermittivity(kind, v, w)); });
            if (kind == TermKind::kCriticalPoint) {
              v[3] = kPi / 2;
              AddColumn([&](double w) { return ToStd(InterbandPermittivity(kind, v, w)); });
            }
            list.push_back(c);
          }
        }
      }
    }
    const int nc = static_cast<int>(columns_.size());
    Eigen::MatrixXd bank(2 * m_, nc);
    for (int c = 0; c < nc; ++c) bank.col(c) = columns_[c];
    gram_ = bank.transpose() * bank;
    rhs_ = bank.transpose() * y_;
    yy_ = y_.squaredNorm();
  }

  // Up to `count` starts (r values), best grid residual first, with distinct centres.
  // windows, if given, holds for each interband term the range [lo, hi] of E0 (eV) its
  // candidates must lie in.
  std::vector<std::vector<double>> Starts(
      int count, const std::vector<std::pair<double, double>>& windows = {}) {
    windows_ = windows;
    const int terms = layout_.num_terms() - 1;
    std::vector<int> pick(terms, 0);
    std::vector<Scored> scored;
    for (size_t g = 0; g < gammas_.size(); ++g) {
      std::fill(pick.begin(), pick.end(), 0);
      while (true) {
        if (Ordered(pick)) Score(static_cast<int>(g), pick, &scored);
        int t = terms - 1;
        while (t >= 0 && ++pick[t] == static_cast<int>(Candidates(t + 1).size())) pick[t--] = 0;
        if (t < 0) break;
      }
    }
    std::stable_sort(scored.begin(), scored.end(),
                     [](const Scored& a, const Scored& b) { return a.residual < b.residual; });
    std::vector<std::vector<double>> starts;
    std::vector<std::vector<int>> seen;
    for (const Scored& s : scored) {
      std::vector<int> centres;
      for (int t = 0; t < terms; ++t) centres.push_back(Candidates(t + 1)[s.pick[t]].centre);
      if (std::find(seen.begin(), seen.end(), centres) != seen.end()) continue;
      seen.push_back(centres);
      starts.push_back(StartOf(s));
      if (static_cast<int>(starts.size()) == count) break;
    }
    return starts;
  }

 private:
  static constexpr int kCentres = 12;
  static constexpr int kMaxColumns = 2 + 2 * kPhysicalMaxInterbandTerms;

  struct Candidate {
    int centre;  // index in centres_
    double e0, g, gap;
    int column, columns;
  };
  struct Scored {
    double residual;
    int gamma;
    std::vector<int> pick;
    std::vector<double> solution;  // eps_inf, wp^2, then each term's linear coefficients
  };

  template <typename T>
  static std::complex<double> ToStd(const Complex<T>& z) {
    return {z.re, z.im};
  }

  template <typename F>
  void AddColumn(F f) {
    Eigen::VectorXd c(2 * m_);
    for (size_t i = 0; i < m_; ++i) {
      const std::complex<double> v = f(omega_[i]);
      c[i] = v.real() * w_[i];
      c[m_ + i] = v.imag() * w_[i];
    }
    columns_.push_back(std::move(c));
  }

  const std::vector<Candidate>& Candidates(int term) const {
    return candidates_.at(layout_.term_kind(term));
  }

  // Terms of one kind in increasing order of centre, each centre used once; centres in
  // their windows.
  bool Ordered(const std::vector<int>& pick) const {
    for (size_t t = 0; t < pick.size(); ++t) {
      if (!windows_.empty()) {
        const double e0 = Candidates(static_cast<int>(t) + 1)[pick[t]].e0;
        if (e0 < windows_[t].first || e0 > windows_[t].second) return false;
      }
      for (size_t u = 0; u < t; ++u) {
        if (layout_.interband()[t] == layout_.interband()[u] &&
            !(Candidates(t + 1)[pick[t]].centre > Candidates(u + 1)[pick[u]].centre)) {
          return false;
        }
      }
    }
    return true;
  }

  void Score(int gamma, const std::vector<int>& pick, std::vector<Scored>* out) const {
    using Small =
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxColumns, kMaxColumns>;
    using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxColumns, 1>;
    int cols[kMaxColumns];
    int n = 0;
    cols[n++] = 0;
    cols[n++] = 1 + gamma;
    for (size_t t = 0; t < pick.size(); ++t) {
      const Candidate& c = Candidates(static_cast<int>(t) + 1)[pick[t]];
      for (int j = 0; j < c.columns; ++j) cols[n++] = c.column + j;
    }
    // eps_inf >= 1: solve freely, or with eps_inf = 1 when that is violated.
    for (int fixed = 0; fixed < 2; ++fixed) {
      const int first = fixed;  // with eps_inf fixed, column 0 leaves the unknowns
      const int k = n - first;
      Small a(k, k);
      SmallVec b(k);
      for (int i = 0; i < k; ++i) {
        b[i] = rhs_[cols[first + i]] - (fixed ? gram_(cols[first + i], 0) : 0.0);
        for (int j = 0; j < k; ++j) a(i, j) = gram_(cols[first + i], cols[first + j]);
      }
      for (int i = 0; i < k; ++i) a(i, i) *= 1.0 + 1e-12;
      const SmallVec x = a.ldlt().solve(b);
      if (!x.allFinite()) return;
      const double eps_inf = fixed ? 1.0 : x[0];
      if (!fixed && eps_inf < 1.0) continue;
      const double wp2 = x[1 - first];
      if (!(wp2 > 0)) return;
      // Non-negative strengths (a critical point's sign lives in its phase).
      int at = 2;
      for (size_t t = 0; t < pick.size(); ++t) {
        const Candidate& c = Candidates(static_cast<int>(t) + 1)[pick[t]];
        if (c.columns == 1 && x[at - first] < 0) return;
        at += c.columns;
      }
      // Residual: yy - 2 x.b_full + x' G x, with the fixed eps_inf folded in.
      double residual = yy_ - 2.0 * x.dot(b) + x.dot(a * x);
      if (fixed) residual += gram_(0, 0) - 2.0 * rhs_[0];
      Scored s{residual, gamma, pick, {}};
      s.solution.push_back(eps_inf);
      for (int i = 1 - first; i < k; ++i) s.solution.push_back(x[i]);
      out->push_back(std::move(s));
      return;
    }
  }

  std::vector<double> StartOf(const Scored& s) const {
    const int np = layout_.num_parameters();
    std::vector<double> v(np, 0.0), r(np, 0.0);
    v[0] = s.solution[0];
    v[1] = std::sqrt(s.solution[1]);
    v[2] = gammas_[s.gamma];
    int at = 2;
    for (int t = 1; t < layout_.num_terms(); ++t) {
      const Candidate& c = Candidates(t)[s.pick[t - 1]];
      const int o = layout_.term_offset(t);
      const TermKind kind = layout_.term_kind(t);
      v[o + 1] = c.e0;
      if (kind == TermKind::kCriticalPoint) {
        const double a = s.solution[at], b = s.solution[at + 1];
        v[o] = std::hypot(a, b);
        v[o + 2] = c.g;
        v[o + 3] = std::atan2(b, a);
      } else if (kind == TermKind::kRiouxGap) {
        v[o] = s.solution[at];
        v[o + 2] = c.e0 + c.gap;
        v[o + 3] = c.g;
      } else {
        v[o] = s.solution[at];
        v[o + 2] = c.g;
      }
      at += c.columns;
    }
    for (int k = 0; k < np; ++k) {
      const PhysicalParameter& p = layout_.parameters()[k];
      switch (p.map) {
        case ParameterMap::kPositive:
          r[k] = SoftPositiveInverse(std::max(v[k], 1e-3));
          break;
        case ParameterMap::kOnePlusPositive:
          r[k] = SoftPositiveInverse(std::max(v[k] - 1.0, 1e-3));
          break;
        case ParameterMap::kAbove:
          r[k] = SoftPositiveInverse(std::max(v[k] - v[p.reference], 1e-3));
          break;
        case ParameterMap::kFree:
          r[k] = v[k];
          break;
      }
    }
    return r;
  }

  const PhysicalLayout& layout_;
  const size_t m_;
  Eigen::VectorXd y_;
  std::vector<double> w_, omega_, gammas_, centres_;
  std::vector<Eigen::VectorXd> columns_;
  std::map<TermKind, std::vector<Candidate>> candidates_;
  std::vector<std::pair<double, double>> windows_;
  Eigen::MatrixXd gram_;
  Eigen::VectorXd rhs_;
  double yy_ = 0;
};

// Fits one sample alone from the grid search's starts (and extra_start, if given);
// returns the distinct solutions, best first. Throws Error naming the sample if none.
std::vector<SolveResult> FitSingle(const PhysicalLayout& layout, const SampleData& s,
                                   const FitData& data,
                                   const std::vector<std::pair<double, double>>& windows = {},
                                   const std::vector<double>* extra_start = nullptr) {
  const Bounds bounds = MakeBounds(layout, data.omega_max);
  std::vector<SolveResult> results;
  GridSearch grid(layout, s, data);
  std::vector<std::vector<double>> starts = grid.Starts(kEndStarts, windows);
  if (extra_start) starts.push_back(*extra_start);
  for (const auto& start : starts) {
    FitProblem problem(layout, {&s}, Basis{0, 1}, bounds, start);
    SolveResult r = problem.Solve(100, 1e-9);
    if (std::isfinite(r.cost)) results.push_back(std::move(r));
  }
  std::stable_sort(results.begin(), results.end(),
                   [](const SolveResult& a, const SolveResult& b) { return a.cost < b.cost; });
  // Keep distinct solutions only (several starts reach the same minimum).
  std::vector<SolveResult> distinct;
  for (auto& r : results) {
    bool seen = false;
    for (const auto& d : distinct) seen |= std::abs(d.cost - r.cost) <= 1e-6 * d.cost + 1e-15;
    if (!seen) distinct.push_back(std::move(r));
  }
  if (distinct.empty()) throw Error(s.file + ": the physical fit of this end sample failed");
  return distinct;
}

}  // namespace

struct EndSampleFits {
  std::mutex mutex;
  std::map<std::string, std::vector<SolveResult>> fits;
};

std::shared_ptr<EndSampleFits> MakeEndSampleFits() { return std::make_shared<EndSampleFits>(); }

namespace {

// FitSingle of an end sample, through `remembered` when there is one: the remembered
// result is the one a new fit would give. Keyed by everything FitSingle reads of its inputs.
std::vector<SolveResult> FitEndSample(const PhysicalLayout& layout, const SampleData& s,
                                      const FitData& data, EndSampleFits* remembered) {
  if (remembered == nullptr) return FitSingle(layout, s, data);
  std::string key = InterbandTermsText(layout.interband());
  const auto add = [&key](const void* bytes, size_t size) {
    key.append(static_cast<const char*>(bytes), size);
  };
  const int degree = layout.degree();
  add(&degree, sizeof degree);
  add(&data.omega_min, sizeof data.omega_min);
  add(&data.omega_max, sizeof data.omega_max);
  add(s.omega_ev.data(), s.omega_ev.size() * sizeof(double));
  add(s.eps.data(), s.eps.size() * sizeof(std::complex<double>));
  {
    const std::lock_guard<std::mutex> lock(remembered->mutex);
    const auto it = remembered->fits.find(key);
    if (it != remembered->fits.end()) return it->second;
  }
  std::vector<SolveResult> fits = FitSingle(layout, s, data);
  const std::lock_guard<std::mutex> lock(remembered->mutex);
  remembered->fits.emplace(std::move(key), fits);
  return fits;
}

// Bayesian information criterion of a fit with n residuals and p parameters.
double Bic(double cost, size_t n, int p) {
  return n * std::log(std::max(2.0 * cost, 1e-300) / n) + p * std::log(static_cast<double>(n));
}

// RMS relative eps error, and largest |dn|, |dk| of one sample under the model.
struct SampleFit {
  double rms = 0, max_dn = 0, max_dk = 0;
};

SampleFit SampleMisfit(const PhysicalModel& model, const SampleData& s) {
  SampleFit f;
  const auto eps = model.Permittivity(s.x, s.lambda_nm);
  double sum = 0;
  for (size_t i = 0; i < eps.size(); ++i) {
    sum += std::norm(eps[i] - s.eps[i]) / std::norm(s.eps[i]);
    const Complex<double> a = IndexFromPermittivity(Complex<double>{eps[i].real(), eps[i].imag()});
    const Complex<double> b =
        IndexFromPermittivity(Complex<double>{s.eps[i].real(), s.eps[i].imag()});
    f.max_dn = std::max(f.max_dn, std::abs(a.re - b.re));
    f.max_dk = std::max(f.max_dk, std::abs(a.im - b.im));
  }
  f.rms = std::sqrt(sum / (2.0 * eps.size()));
  return f;
}

}  // namespace

namespace {

PhysicalFitResult FitPhysicalAtDegree(const Dataset& dataset, const PhysicalFitOptions& options);

// n and k above this (or above 1.5 times the largest of the data, for data that go
// higher, as metals do in the infrared) are a resonance the data do not have.
constexpr double kMaxPhysicalIndex = 50;

// Where the fitted model leaves physics inside its ranges, checked at 101 compositions
// and 201 wavelengths: eps2 < 0 (not passive), or n or k beyond the limit above. Empty
// when it stays physical.
std::string Unphysical(const PhysicalModel& model, const Dataset& dataset) {
  std::vector<double> grid;
  for (int j = 0; j <= 200; ++j) {
    grid.push_back(model.lambda_min_nm() +
                   (model.lambda_max_nm() - model.lambda_min_nm()) * j / 200.0);
  }
  double data_max = 0;
  for (const Sample& s : dataset.samples) {
    for (double l : grid) {
      const std::complex<double> nk = NkAt(s.nk, l);
      data_max = std::max({data_max, nk.real(), nk.imag()});
    }
  }
  const double limit = std::max(kMaxPhysicalIndex, 1.5 * data_max);
  for (int i = 0; i <= 100; ++i) {
    const double x = model.x_min() + (model.x_max() - model.x_min()) * i / 100.0;
    const std::vector<std::complex<double>> eps = model.Permittivity(x, grid);
    for (size_t j = 0; j < grid.size(); ++j) {
      const std::complex<double> nk = std::sqrt(eps[j]);
      std::ostringstream where;
      where << " at x = " << FormatNumber(x) << ", " << FormatNumber(grid[j]) << " nm";
      if (!std::isfinite(eps[j].real()) || !std::isfinite(eps[j].imag())) {
        return "gives a non-finite eps" + where.str();
      }
      if (eps[j].imag() < -1e-9 * std::abs(eps[j])) {
        return "is not passive (eps2 = " + FormatNumber(eps[j].imag()) + ")" + where.str();
      }
      if (nk.real() > limit || nk.imag() > limit) {
        return "has a resonance (n = " + FormatNumber(nk.real()) +
               ", k = " + FormatNumber(nk.imag()) + ", limit " + FormatNumber(limit) + ")" +
               where.str();
      }
    }
  }
  return "";
}

}  // namespace

// The fit at options.degree; when it leaves physics inside its range (Unphysical) or does
// not converge, again one degree lower (a lower degree bends the parameters less between
// the samples), down to 1; at degree 1 a fit that is still unphysical is an error.
PhysicalFitResult FitPhysical(const Dataset& dataset, const PhysicalFitOptions& options) {
  PhysicalFitOptions o = options;
  std::vector<std::string> notes;
  for (;;) {
    PhysicalFitResult result = FitPhysicalAtDegree(dataset, o);
    const std::string problem = o.check_physics ? Unphysical(*result.model, dataset) : "";
    const bool converged = result.model->fit_summary().converged;
    const int degree = result.model->fit_summary().degree;
    if ((problem.empty() && converged) || degree <= 1) {
      if (!problem.empty()) {
        throw Error(dataset.manifest_path + ": the physical fit " + problem +
                    (notes.empty() ? "" : " (lower degrees tried too)") +
                    "; use another method (eps-pchip, smooth)");
      }
      result.model->AddWarnings(notes);
      return result;
    }
    notes.push_back("the physical fit at degree " + std::to_string(degree) + " " +
                    (problem.empty() ? std::string("did not converge") : problem) +
                    "; refitted at degree " + std::to_string(degree - 1));
    Report(options.progress, notes.back());
    o.degree = degree - 1;
  }
}

namespace {

// The start model when it can warm-start this fit: the same degree, ends and terms.
const PhysicalModel* UsableWarmStart(const PhysicalFitOptions& options, int degree,
                                     const SampleData& lo_end, const SampleData& hi_end) {
  const PhysicalModel* warm = options.start;
  if (warm != nullptr && (warm->layout().degree() != degree || warm->x_min() != lo_end.x ||
                          warm->x_max() != hi_end.x ||
                          (options.terms != "auto" &&
                           ParseInterbandTerms(options.terms) != warm->layout().interband()))) {
    warm = nullptr;
  }
  return warm;
}

// The interband terms of the joint fit and the end samples' fits with them.
struct TermChoice {
  std::string option;  // "auto", the terms asked for, or the warm start's
  std::vector<std::string> candidates;
  std::vector<TermKind> kinds;
  std::vector<SolveResult> lo_fits, hi_fits;
  nlohmann::json auto_scores = nlohmann::json::array();
};

// Chooses the interband terms: the warm start's, the user's, or auto's lowest BIC of the
// end samples' fits.
TermChoice ChooseTerms(const FitData& data, const PhysicalFitOptions& options,
                       const PhysicalModel* warm) {
  const SampleData& lo_end = data.samples.front();
  const SampleData& hi_end = data.samples.back();
  TermChoice choice;
  choice.option = warm != nullptr ? InterbandTermsText(warm->layout().interband()) : options.terms;
  if (choice.option == "auto") {
    if (data.infrared) {
      choice.candidates.push_back("none");
    } else {
      for (const char* c : kAutoTerms) choice.candidates.push_back(c);
    }
  } else {
    choice.candidates.push_back(choice.option);
  }
  double best_bic = HUGE_VAL;
  for (const std::string& candidate : choice.candidates) {
    const std::vector<TermKind> k = ParseInterbandTerms(candidate);
    if (warm != nullptr) {
      choice.kinds = k;
      break;
    }
    const PhysicalLayout end_layout(k, 0);
    std::ostringstream msg;
    msg << "fitting the end samples (x = " << lo_end.x << ", " << hi_end.x << ") with terms "
        << InterbandTermsText(k);
    Report(options.progress, msg.str());
    auto lo = FitEndSample(end_layout, lo_end, data, options.end_fits);
    auto hi = FitEndSample(end_layout, hi_end, data, options.end_fits);
    const int p = end_layout.num_parameters();
    const double bic = Bic(lo.front().cost, 2 * lo_end.eps.size(), p) +
                       Bic(hi.front().cost, 2 * hi_end.eps.size(), p);
    choice.auto_scores.push_back({{"terms", InterbandTermsText(k)},
                                  {"end_costs", {lo.front().cost, hi.front().cost}},
                                  {"bic", bic}});
    if (bic < best_bic) {
      best_bic = bic;
      choice.kinds = k;
      choice.lo_fits = std::move(lo);
      choice.hi_fits = std::move(hi);
    }
  }
  return choice;
}

// Adds quadratics through the ends' and a middle sample's own fits to the joint starts:
// they carry the parameters' curvature that the straight line lacks.
void AddQuadraticStarts(const PhysicalLayout& layout, const Basis& basis, const FitData& data,
                        const std::vector<double>& r_lo, const std::vector<double>& r_hi,
                        std::vector<std::vector<double>>* starts) {
  const int n = static_cast<int>(data.samples.size());
  const int np = layout.num_parameters();
  const int nb = layout.basis_size();
  const SampleData& lo_end = data.samples.front();
  const SampleData& hi_end = data.samples.back();
  int mid = 1;
  for (int i = 1; i < n - 1; ++i) {
    if (std::abs(basis.U(data.samples[i].x)) < std::abs(basis.U(data.samples[mid].x))) mid = i;
  }
  const double um = basis.U(data.samples[mid].x);
  if (!(std::abs(um) < 0.8)) return;
  const PhysicalLayout single(layout.interband(), 0);
  // The middle sample's terms keep their roles: each centre near the span of the
  // ends' centres, and the straight line as one more start.
  std::vector<double> v_lo(np), v_hi(np);
  PhysicalValuesFromRaw(single, r_lo.data(), v_lo.data());
  PhysicalValuesFromRaw(single, r_hi.data(), v_hi.data());
  std::vector<std::pair<double, double>> windows;
  for (int t = 1; t < layout.num_terms(); ++t) {
    const int k = layout.term_offset(t) + 1;
    windows.emplace_back(std::min(v_lo[k], v_hi[k]) - 0.3, std::max(v_lo[k], v_hi[k]) + 0.3);
  }
  const double t_mid = (data.samples[mid].x - lo_end.x) / (hi_end.x - lo_end.x);
  std::vector<double> line_mid(np);
  for (int k = 0; k < np; ++k) line_mid[k] = r_lo[k] + (r_hi[k] - r_lo[k]) * t_mid;
  std::vector<SolveResult> fits;
  try {
    fits = FitSingle(single, data.samples[mid], data, windows, &line_mid);
  } catch (const Error&) {
    // No start converged: the straight line alone.
  }
  Eigen::Matrix3d a;
  for (int row = 0; row < 3; ++row) {
    const double u = row == 0 ? -1.0 : row == 1 ? um : 1.0;
    double p[3];
    LegendreBasis(u, 2, p);
    for (int d = 0; d < 3; ++d) a(row, d) = p[d];
  }
  const Eigen::Matrix3d inverse = a.inverse();
  for (size_t f = 0; f < fits.size() && f < 3; ++f) {
    if (!(fits[f].cost <= 100.0 * fits.front().cost)) break;
    std::vector<double> start(layout.num_coefficients(), 0.0);
    for (int k = 0; k < np; ++k) {
      const Eigen::Vector3d c = inverse * Eigen::Vector3d(r_lo[k], fits[f].coeffs[k], r_hi[k]);
      for (int d = 0; d < 3; ++d) start[k * nb + d] = c[d];
    }
    starts->push_back(start);
  }
}

// The joint fit's starts: the warm start, or the straight line between the ends' best fits
// and quadratics through the ends and the middle sample's best fits.
std::vector<std::vector<double>> JointStarts(const PhysicalLayout& layout, const Basis& basis,
                                             const FitData& data, const PhysicalModel* warm,
                                             const TermChoice& terms) {
  std::vector<std::vector<double>> starts;
  if (warm != nullptr) {
    starts.push_back(warm->coeffs());
    return starts;
  }
  const int np = layout.num_parameters();
  const int nb = layout.basis_size();
  const std::vector<double>& r_lo = terms.lo_fits.front().coeffs;
  const std::vector<double>& r_hi = terms.hi_fits.front().coeffs;
  std::vector<double> start(layout.num_coefficients(), 0.0);
  for (int k = 0; k < np; ++k) {
    start[k * nb] = 0.5 * (r_lo[k] + r_hi[k]);
    if (nb > 1) start[k * nb + 1] = 0.5 * (r_hi[k] - r_lo[k]);
  }
  starts.push_back(start);
  if (data.samples.size() > 2 && layout.degree() >= 2) {
    AddQuadraticStarts(layout, basis, data, r_lo, r_hi, &starts);
  }
  return starts;
}

// The best joint solution: every start gets kRaceIterations; the best continues to
// convergence.
SolveResult RaceStarts(const PhysicalLayout& layout, const std::vector<const SampleData*>& all,
                       const Basis& basis, const Bounds& bounds,
                       const std::vector<std::vector<double>>& starts, int max_iterations) {
  std::vector<std::unique_ptr<FitProblem>> problems;
  SolveResult best;
  best.cost = HUGE_VAL;
  size_t leader = 0;
  for (const auto& start : starts) {
    problems.push_back(std::make_unique<FitProblem>(layout, all, basis, bounds, start));
    SolveResult r = problems.back()->Solve(kRaceIterations, 1e-12);
    if (r.cost < best.cost) {
      best = std::move(r);
      leader = problems.size() - 1;
    }
  }
  if (std::isfinite(best.cost) && !best.converged) {
    const int done = best.iterations;
    best = problems[leader]->Solve(std::max(1, max_iterations - done), 1e-12);
    best.iterations += done;
  }
  return best;
}

// The joint solution's residual statistics and (when asked for) its coefficients' covariance.
struct JointCovariance {
  size_t residuals = 0;
  double residual_variance = 0;
  double rho = 0;        // the residuals' lag-1 autocorrelation along wavelength
  double inflation = 1;  // (1 + rho) / (1 - rho)
  std::vector<double> covariance;
  bool pseudo_inverse = false;
};

// The covariance at the joint solution, scaled by the residual variance and inflated for
// residuals correlated along wavelength.
JointCovariance CovarianceAt(const PhysicalLayout& layout,
                             const std::vector<const SampleData*>& all, const Basis& basis,
                             const Bounds& bounds, const SolveResult& best, bool wanted,
                             std::vector<std::string>* warnings) {
  JointCovariance result;
  FitProblem final_problem(layout, all, basis, bounds, best.coeffs);
  result.residuals = final_problem.residuals();
  const double dof =
      std::max(1.0, static_cast<double>(result.residuals) - layout.num_coefficients());
  result.residual_variance = 2.0 * best.cost / dof;
  // Residuals correlated along wavelength (model error is smooth) carry less information
  // than their number says: inflate by the AR(1) factor (1 + rho) / (1 - rho).
  result.rho = std::clamp(final_problem.ResidualAutocorrelation(), 0.0, 0.99);
  result.inflation = (1.0 + result.rho) / (1.0 - result.rho);
  if (wanted) {
    result.covariance = final_problem.Covariance(&result.pseudo_inverse);
    for (double& c : result.covariance) c *= result.residual_variance * result.inflation;
    if (result.covariance.empty()) warnings->push_back("the covariance could not be computed");
  }
  return result;
}

// The fit summary's account of how the covariance was computed.
void DescribeCovariance(const JointCovariance& cov, nlohmann::json* fit) {
  if (cov.covariance.empty()) {
    (*fit)["covariance"] = "none";
    return;
  }
  (*fit)["covariance"] =
      cov.pseudo_inverse
          ? "ceres::Covariance dense SVD, pseudo-inverse (the Jacobian is rank-deficient: "
            "some combinations of coefficients are not determined by the data), scaled by "
            "the residual variance times (1 + rho) / (1 - rho), rho the residuals' lag-1 "
            "autocorrelation along wavelength"
          : "ceres::Covariance dense SVD, scaled by the residual variance times "
            "(1 + rho) / (1 - rho), rho the residuals' lag-1 autocorrelation along "
            "wavelength";
  (*fit)["covariance_rank_deficient"] = cov.pseudo_inverse;
  (*fit)["residual_variance"] = cov.residual_variance;
  (*fit)["residual_autocorrelation"] = cov.rho;
  (*fit)["variance_inflation"] = cov.inflation;
}

// The fit summary of the joint fit: solver, terms and how they were chosen, starts,
// per-sample misfits and covariance.
FitSummary JointFitSummary(const PhysicalModel& model, const FitData& data, int degree,
                           const SolveResult& best, const TermChoice& terms,
                           const PhysicalModel* warm, int joint_starts,
                           const JointCovariance& cov) {
  FitSummary summary;
  summary.solver = "ceres levenberg-marquardt, dense normal cholesky (eigen)";
  summary.degree = degree;
  summary.final_cost = best.cost;
  summary.iterations = best.iterations;
  summary.converged = best.converged;
  summary.termination = best.termination;
  summary.rms_relative_eps = std::sqrt(2.0 * best.cost / std::max<size_t>(1, cov.residuals));
  nlohmann::json& fit = summary.details;
  fit["terms"] = InterbandTermsText(terms.kinds);
  fit["terms_chosen_by"] = warm != nullptr ? "the start model (a warm start)"
                           : terms.option == "auto"
                               ? (data.infrared ? "auto: infrared data, drude only"
                                                : "auto: lowest BIC of the end samples' fits")
                               : "user";
  if (terms.candidates.size() > 1) fit["terms_candidates"] = terms.auto_scores;
  fit["lambda_step_nm"] = data.grid_nm.size() > 1 ? data.grid_nm[1] - data.grid_nm[0] : 0.0;
  fit["wavelengths"] = data.grid_nm.size();
  fit["joint_starts"] = joint_starts;
  fit["end_fit_minima"] = {terms.lo_fits.size(), terms.hi_fits.size()};
  fit["data_residuals"] = cov.residuals;
  nlohmann::json per_sample = nlohmann::json::array();
  for (const auto& s : data.samples) {
    const SampleFit f = SampleMisfit(model, s);
    per_sample.push_back({{"x", s.x},
                          {"file", s.file},
                          {"rms_relative_eps", f.rms},
                          {"max_abs_dn", f.max_dn},
                          {"max_abs_dk", f.max_dk}});
  }
  fit["rms_per_sample"] = per_sample;
  DescribeCovariance(cov, &fit);
  return summary;
}

PhysicalFitResult FitPhysicalAtDegree(const Dataset& dataset, const PhysicalFitOptions& options) {
  // Every sample (each replicate too) is an observation of its own; the degree is bounded
  // by the distinct compositions.
  const int compositions = static_cast<int>(DistinctCompositions(dataset).size());
  if (compositions < 2) {
    throw Error(dataset.manifest_path + ": the physical fit needs at least two compositions");
  }
  if (options.degree < 0 || options.degree > kPhysicalMaxDegree) {
    throw Error("physical fit: degree must lie in 0.." + std::to_string(kPhysicalMaxDegree));
  }
  const FitData data = PrepareData(dataset, options);
  std::vector<std::string> warnings = data.warnings;
  const int n = static_cast<int>(data.samples.size());
  int degree = options.degree;
  if (degree > compositions - 1) {
    degree = compositions - 1;
    warnings.push_back("degree lowered to " + std::to_string(degree) + ": only " +
                       std::to_string(compositions) + " compositions");
  }
  const SampleData& lo_end = data.samples.front();
  const SampleData& hi_end = data.samples.back();

  // A warm start of the same degree on the same ends gives the terms and the one start.
  const PhysicalModel* warm = UsableWarmStart(options, degree, lo_end, hi_end);
  // Interband terms, and the end samples' fits with them.
  const TermChoice terms = ChooseTerms(data, options, warm);
  const PhysicalLayout layout(terms.kinds, degree);
  const Basis basis{lo_end.x, hi_end.x};
  const Bounds bounds = MakeBounds(layout, data.omega_max);
  std::vector<const SampleData*> all;
  for (const auto& s : data.samples) all.push_back(&s);

  Report(options.progress, "joint fit: terms " + InterbandTermsText(terms.kinds) + ", degree " +
                               std::to_string(degree) + ", " + std::to_string(n) + " samples x " +
                               std::to_string(data.grid_nm.size()) + " wavelengths");
  const std::vector<std::vector<double>> starts = JointStarts(layout, basis, data, warm, terms);
  const SolveResult best = RaceStarts(layout, all, basis, bounds, starts, options.max_iterations);
  if (!std::isfinite(best.cost)) throw Error(dataset.manifest_path + ": the physical fit failed");

  const JointCovariance cov =
      CovarianceAt(layout, all, basis, bounds, best, options.covariance, &warnings);
  PhysicalFitResult result;
  result.terms = InterbandTermsText(terms.kinds);
  result.model = std::make_unique<PhysicalModel>(dataset, data.grid_nm.front(), data.grid_nm.back(),
                                                 layout, best.coeffs, cov.covariance);
  result.model->set_fit_summary(JointFitSummary(*result.model, data, degree, best, terms, warm,
                                                static_cast<int>(starts.size()), cov));
  if (cov.pseudo_inverse) {
    warnings.push_back(
        "the physical fit's Jacobian is rank-deficient; its covariance is a "
        "pseudo-inverse");
  }
  if (!best.converged)
    warnings.push_back("the fit stopped before convergence: " + best.termination);
  result.model->AddWarnings(warnings);
  return result;
}

}  // namespace

}  // namespace alloycolor::fit
