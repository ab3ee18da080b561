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
#include "smooth_solve.h"

namespace alloycolor::fit {
namespace {

using smooth::AssembleAtCompositions;
using smooth::Compositions;
using smooth::EvidenceTerms;
using smooth::GridData;
using smooth::InSpace;
using smooth::Knots;
using smooth::LinearSystems;
using smooth::MostProbableSmoothings;
using smooth::PrepareData;
using smooth::SampleError;
using smooth::Solution;

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

// The samples taking part in a fold: all but those at its compositions.
std::vector<char> InFold(const GridData& g, const std::vector<double>& fold) {
  std::vector<char> in(g.x.size(), 1);
  for (size_t i = 0; i < g.x.size(); ++i) {
    if (std::count(fold.begin(), fold.end(), g.x[i])) in[i] = 0;
  }
  return in;
}

// Adds the errors of the samples left out of `in` under s to *total.
void AddLeftOut(const GridData& g, const std::vector<char>& in, const Solution& s,
                SampleError* total) {
  for (size_t i = 0; i < g.x.size(); ++i) {
    if (in[i]) continue;
    const SampleError e = ErrorOf(g, i, s);
    total->eps_sq += e.eps_sq;
    total->reflectance_sq += e.reflectance_sq;
    total->count += e.count;
  }
}

// The left-out samples' errors summed over the folds, each fold's solution made by
// `solve` from which samples take part; false where one could not be made (not converged).
bool LeftOutErrors(const GridData& g, const std::vector<std::vector<double>>& folds,
                   const std::function<Solution(const std::vector<char>&)>& solve,
                   SampleError* total) {
  for (const auto& fold : folds) {
    const std::vector<char> in = InFold(g, fold);
    const Solution s = solve(in);
    if (!s.converged) return false;
    AddLeftOut(g, in, s, total);
  }
  return true;
}

// The left-out errors of every candidate smoothing over the folds (as LeftOutErrors for
// each, the Ceres form's best point counting either way), with knots at the compositions
// each fold's linear systems assembled once for all candidates.
std::vector<SampleError> CandidateErrors(const GridData& g,
                                         const std::vector<std::vector<double>>& folds,
                                         const std::vector<double>& candidates,
                                         const SmoothFitOptions& options) {
  std::vector<SampleError> totals(candidates.size());
  Solution s;  // one for every solve, its storage reused
  for (const auto& fold : folds) {
    const std::vector<char> in = InFold(g, fold);
    const std::vector<double> compositions = Compositions(g, in);
    std::vector<double> knots = Knots(compositions, std::min(options.max_knots, kSmoothMaxKnots));
    const bool direct = knots.size() == compositions.size();
    LinearSystems systems;
    if (direct) systems = AssembleAtCompositions(g, in, knots);
    for (size_t c = 0; c < candidates.size(); ++c) {
      if (direct) {
        SolveAssembled(g, in, systems, std::vector<double>(g.grid_nm.size(), candidates[c]), false,
                       &s);
      } else {
        // The candidates increase: each starts from the previous one's curves.
        s = SolveCeres(g, in, candidates[c], options, knots, c > 0 ? &s : nullptr);
      }
      AddLeftOut(g, in, s, &totals[c]);
    }
  }
  return totals;
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
  const std::vector<double>& candidates = SmoothingCandidates();
  const std::vector<SampleError> totals = CandidateErrors(g, folds, candidates, options);
  for (size_t c = 0; c < candidates.size(); ++c) {
    const double candidate = candidates[c];
    const SampleError& total = totals[c];
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
  const size_t compositions = Compositions(g, std::vector<char>(g.x.size(), 1)).size();
  if (compositions > static_cast<size_t>(kSmoothMaxGpCompositions)) {
    Report(options.details, "cross-validation" + space + ": gaussian process not tried (" +
                                std::to_string(compositions) + " compositions, above " +
                                std::to_string(kSmoothMaxGpCompositions) +
                                ": its cost grows as their cube)");
    return false;
  }
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
  // space (where the space is given, nothing reads the score).
  if (!cross_validate && !folds.empty() && !options.space) {
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
          : "ceres levenberg-marquardt per wavelength node and part, dense normal cholesky "
            "(eigen)";
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
  if (compositions.size() > static_cast<size_t>(kSmoothMaxGpCompositions) &&
      options.smoothing < 0) {
    result.model->AddWarnings(
        {"the Gaussian-process form was not tried: " + std::to_string(compositions.size()) +
         " compositions, above " + std::to_string(kSmoothMaxGpCompositions) +
         " (its cost grows as the cube of their number)"});
  }
  if (!s.converged) {
    result.model->AddWarnings({"the fit stopped before convergence: " + s.termination});
  }
  return result;
}

}  // namespace alloycolor::fit
