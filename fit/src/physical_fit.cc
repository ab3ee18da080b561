#include "alloycolor/fit/physical_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/core/text.h"
#include "alloycolor/core/units.h"
#include "alloycolor/model/optics.h"
#include "physical_problem.h"

namespace alloycolor::fit {
namespace {

using physical::AddQuadraticStarts;
using physical::Basis;
using physical::Bounds;
using physical::FitData;
using physical::FitEndSample;
using physical::FitProblem;
using physical::MakeBounds;
using physical::PrepareData;
using physical::SampleData;
using physical::SolveResult;

constexpr int kRaceIterations = 30;  // joint starts race this far before the best goes on

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

PhysicalFitResult FitPhysicalAtDegree(const Dataset& dataset, const PhysicalFitOptions& options);

// n and k above this (or above 1.5 times the largest of the data, for data that go
// higher, as metals do in the infrared) are a resonance the data do not have.
constexpr double kMaxPhysicalIndex = 50;

// Where the fitted model leaves physics inside its ranges, checked at 101 compositions
// and 201 wavelengths: eps2 < 0 (not passive), or n or k beyond the limit above; then a
// pole narrower than a model file may hold (PhysicalModel::NarrowestPole). Empty when it
// stays physical.
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
      const auto where = [&] {
        return " at x = " + FormatNumber(x) + ", " + FormatNumber(grid[j]) + " nm";
      };
      if (!std::isfinite(eps[j].real()) || !std::isfinite(eps[j].imag())) {
        return "gives a non-finite eps" + where();
      }
      if (eps[j].imag() < -1e-9 * std::abs(eps[j])) {
        return "is not passive (eps2 = " + FormatNumber(eps[j].imag()) + ")" + where();
      }
      if (nk.real() > limit || nk.imag() > limit) {
        return "has a resonance (n = " + FormatNumber(nk.real()) +
               ", k = " + FormatNumber(nk.imag()) + ", limit " + FormatNumber(limit) + ")" +
               where();
      }
    }
  }
  double width = 0, width_x = 0;
  if (!model.NarrowestPole(&width, &width_x).empty() && width < kPhysicalMinWidthEv) {
    return "has a pole narrower than " + FormatNumber(kPhysicalMinWidthEv) +
           " eV (G = " + FormatNumber(width) + " eV at x = " + FormatNumber(width_x) +
           ", its centre among the fitted wavelengths)";
  }
  return "";
}

}  // namespace

// The fit at options.degree; when it leaves physics inside its range (Unphysical) or does
// not converge, again one degree lower (a lower degree bends the parameters less between
// the samples), down to 1; at degree 1 a fit that is still unphysical is an error.
PhysicalFitResult FitPhysical(const Dataset& all, const PhysicalFitOptions& options) {
  PhysicalFitOptions o = options;
  std::vector<std::string> notes;
  // A composition-spread library: the samples of kPhysicalMaxCompositions compositions
  // spread by rank (the ends kept) determine the model's few coefficients as well as all
  // would, at a fraction of the cost.
  const std::vector<double> xs = DistinctCompositions(all);
  Dataset subset;
  if (xs.size() > static_cast<size_t>(kPhysicalMaxCompositions)) {
    std::vector<double> keep;
    for (int i = 0; i < kPhysicalMaxCompositions; ++i) {
      keep.push_back(xs[static_cast<size_t>(i) * (xs.size() - 1) / (kPhysicalMaxCompositions - 1)]);
    }
    std::vector<double> exclude;
    std::set_difference(xs.begin(), xs.end(), keep.begin(), keep.end(),
                        std::back_inserter(exclude));
    subset = WithoutSamples(all, exclude);
    notes.push_back("fitted to the samples at " + std::to_string(kPhysicalMaxCompositions) +
                    " of the " + std::to_string(xs.size()) +
                    " compositions, spread evenly by rank (the ends among them): more would "
                    "not move its coefficients, and would cost in proportion");
    Report(options.progress, "physical: " + notes.back());
  }
  const Dataset& dataset = subset.samples.empty() ? all : subset;
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
    CheckCancel(options.cancel);
    auto lo = FitEndSample(end_layout, lo_end, data, options.end_fits);
    CheckCancel(options.cancel);
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
                       const std::vector<std::vector<double>>& starts, int max_iterations,
                       const CancelCheck& cancel) {
  std::vector<std::unique_ptr<FitProblem>> problems;
  SolveResult best;
  best.cost = HUGE_VAL;
  size_t leader = 0;
  for (const auto& start : starts) {
    problems.push_back(std::make_unique<FitProblem>(layout, all, basis, bounds, start));
    SolveResult r = problems.back()->Solve(kRaceIterations, 1e-12, cancel);
    if (r.cost < best.cost) {
      best = std::move(r);
      leader = problems.size() - 1;
    }
  }
  if (std::isfinite(best.cost) && !best.converged) {
    const int done = best.iterations;
    best = problems[leader]->Solve(std::max(1, max_iterations - done), 1e-12, cancel);
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
  const SolveResult best =
      RaceStarts(layout, all, basis, bounds, starts, options.max_iterations, options.cancel);
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
