// The starts of the physical fit (physical_fit.h): the end samples' own fits from a grid
// search, remembered for a whole job, and quadratics through them and a middle sample's.
#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#include "alloycolor/core/error.h"
#include "alloycolor/model/optics.h"
#include "physical_problem.h"

namespace alloycolor::fit {

struct EndSampleFits {
  std::mutex mutex;
  std::map<std::string, std::vector<physical::SolveResult>> fits;
};

std::shared_ptr<EndSampleFits> MakeEndSampleFits() { return std::make_shared<EndSampleFits>(); }

namespace physical {
namespace {

constexpr int kEndStarts = 3;  // grid-search starts refined per end sample

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

}  // namespace

// Fits one sample alone from the grid search's starts (and extra_start, if given);
// returns the distinct solutions, best first. Throws Error naming the sample if none.
std::vector<SolveResult> FitSingle(const PhysicalLayout& layout, const SampleData& s,
                                   const FitData& data,
                                   const std::vector<std::pair<double, double>>& windows,
                                   const std::vector<double>* extra_start) {
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

}  // namespace physical
}  // namespace alloycolor::fit
