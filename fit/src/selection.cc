// `auto` (BuildAuto) and the physical model's composition degree: candidates built with
// their folds, scored on them, and the first in order of preference within the folds' own
// scatter of the best chosen.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>

#include "alloycolor/color/sample_error.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/progress.h"
#include "folds.h"

namespace alloycolor::fit {
namespace {

constexpr double kAutoTolerance = 1.10;
constexpr int kCandidateIterations = 100;  // a physical degree candidate's solver budget
// An unfinished physical candidate whose own error on its samples is this many times what it
// must beat is not continued to convergence to see whether it gets there.
constexpr double kHopeless = 10;
// Nordheim's rule bows the damping quadratically in composition (the plasma frequency is
// nearly linear): the degree kept unless leave-one-out finds another clearly better.
constexpr int kPreferredDegree = 2;

// `model` (`method` built on the data set) with its folds, scored on them.
Scored ScoreWithFolds(const MethodInfo& method, const Dataset& dataset, const FitSettings& settings,
                      std::unique_ptr<AlloyModel> model) {
  Scored r;
  r.score.method = method.name;
  try {
    std::vector<Fold> folds;
    AddFolds(method, dataset, settings, model.get(), &folds);
    r.model = std::move(model);
    ScoreFolds(method.name, folds, *settings.colorimeter, &r);
  } catch (const Error& e) {
    r.score.error = e.what();
  }
  if (!r.score.error.empty()) r.model.reset();
  return r;
}

Scored BuildScored(const MethodInfo& method, const Dataset& dataset, const FitSettings& settings) {
  Scored r = RememberedBuild(method, dataset, settings);
  if (!r.score.error.empty()) r.model.reset();
  return r;
}

double Rms(const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v * v;
  return std::sqrt(sum / std::max<size_t>(values.size(), 1));
}

// How ChooseSimplest weighs a lead of the lowest over a candidate preferred to it.
//  - kAuto: on the folds' scores, a lead only where the lowest beats the candidate
//    outright (the lowest's worst fold below the candidate's best). With five rivals one
//    often wins every fold of a few by chance, and by more than the folds' differences
//    scatter: on a Cu-Zn series with 2 % scatter added, two folds favoured eps-spline,
//    which then erred 4.66 against smooth's 2.61. A lead that a reshuffling of the folds
//    could undo is no lead.
//  - kDegree (one rival, the physical model's degree 1): on the folds' squared scores (the
//    tolerance on their RMS), so that one bad fold counts as it does in a squared loss, a
//    lead beyond one standard error of the fold-by-fold differences (from two folds).
enum class Lead { kAuto, kDegree };

// The choice among candidates listed in order of preference (auto:
// MethodTraits::auto_rank; the physical degree: Nordheim's first): the first whose
// mean lies within kAutoTolerance of the lowest, or whom the lowest does not lead (`lead`):
// leave-one-out over few folds flatters the flexible candidates.
// `chosen` and `best` are candidates.size() when none could be scored.
struct Choice {
  size_t chosen, best;
  std::string rule;  // why the chosen, if it is not the best: "10 %" or the lead's test
  std::vector<size_t> acceptable;  // every candidate the rule accepts, in order; chosen first
};

// `except`: the folds' scores at that composition left out (NaN: none).
Choice ChooseSimplest(const std::vector<Scored>& candidates, Lead lead,
                      double except = std::nan("")) {
  const bool squared = lead == Lead::kDegree;
  const size_t none = candidates.size();
  Choice c{none, none, ""};
  std::vector<std::vector<double>> loss(candidates.size());
  std::vector<double> mean(candidates.size(), 0.0);
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (!candidates[i].score.error.empty()) continue;
    const Scored& r = candidates[i];
    for (size_t k = 0; k < r.values.size(); ++k) {
      if (k < r.held_x.size() && r.held_x[k] == except) continue;
      loss[i].push_back(squared ? r.values[k] * r.values[k] : r.values[k]);
    }
    for (double v : loss[i]) mean[i] += v / loss[i].size();
    if (!loss[i].empty() && (c.best == none || mean[i] < mean[c.best])) c.best = i;
  }
  if (c.best == none) return c;
  const auto led = [&](size_t i) {
    const std::vector<double>& a = loss[i];
    const std::vector<double>& b = loss[c.best];
    if (lead == Lead::kAuto) {
      return *std::max_element(b.begin(), b.end()) < *std::min_element(a.begin(), a.end());
    }
    if (a.size() != b.size() || a.size() < 2) return true;
    double d = 0, sq = 0;
    for (size_t k = 0; k < a.size(); ++k) d += a[k] - b[k];
    d /= a.size();
    for (size_t k = 0; k < a.size(); ++k) sq += std::pow(a[k] - b[k] - d, 2);
    return d > std::sqrt(sq / (a.size() - 1) / a.size());
  };
  const double tolerance = squared ? kAutoTolerance * kAutoTolerance : kAutoTolerance;
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (loss[i].empty()) continue;
    const bool close = mean[i] <= mean[c.best] * tolerance;
    if (close || !led(i)) {
      if (c.acceptable.empty()) {
        c.chosen = i;
        if (i != c.best) {
          c.rule = close                 ? "10 %"
                   : lead == Lead::kAuto ? "the range of the folds"
                                         : "one standard error of the folds' differences";
        }
      }
      c.acceptable.push_back(i);
    }
  }
  return c;
}

// RMS of a model's error on the samples it was fitted to, over those its folds hold out
// (ErrorFolds), in the metric ScoreFolds uses: CIEDE2000 at normal incidence, or for data
// without colour the reflectance RMS over the sample's wavelengths inside the model's range.
double OwnErrorRms(const AlloyModel& model, const Dataset& dataset, const color::Colorimeter& cm) {
  const std::vector<double> held = ErrorFolds(dataset);
  double sum = 0;
  int count = 0;
  for (const Sample& s : dataset.samples) {
    if (std::find(held.begin(), held.end(), s.x_atomic) == held.end()) continue;
    const double e = color::ErrorAgainstSample(cm, model, s).score();
    if (!std::isfinite(e)) continue;
    sum += e * e;
    ++count;
  }
  return std::sqrt(sum / std::max(count, 1));
}

// A physical candidate scored on its folds unless its own error on the samples (converged:
// an unfinished fit is continued first, unless it misses by more than kHopeless times) already
// exceeds what it would have to beat, `preferred`'s leave-one-out RMS over kAutoTolerance: a
// held-out sample is no nearer than the fitted ones, so its folds could not make it win
// (Au-Ag at degree 1: own error 0.2 against 3e-5, where continuing the fit took more time than
// all the rest of auto), and they are not fitted.
Scored BuildUnlessOutdone(const MethodInfo& method, const Dataset& dataset,
                          const FitSettings& settings, const Scored& preferred) {
  if (!preferred.score.error.empty()) return BuildScored(method, dataset, settings);
  const double must_beat = Rms(preferred.values) / kAutoTolerance;
  Scored r;
  r.score.method = method.name;
  std::unique_ptr<AlloyModel> model;
  double own = 0;
  try {
    model = Build(method, dataset, settings);
    own = OwnErrorRms(*model, dataset, *settings.colorimeter);
    if (own >= must_beat && own < kHopeless * must_beat && !model->fit_summary().converged) {
      FitSettings full = settings;
      full.start = model.get();
      full.max_iterations = 0;
      model = Build(method, dataset, full);
      own = OwnErrorRms(*model, dataset, *settings.colorimeter);
    }
  } catch (const Error& e) {
    r.score.error = e.what();
    return r;
  }
  if (own >= must_beat) {
    char why[160];
    std::snprintf(why, sizeof why,
                  "its own RMS error on the samples, %.4g, already exceeds what it would have "
                  "to beat, %.4g",
                  own, must_beat);
    r.score.error = why;
    return r;
  }
  RecordInSampleError(dataset, settings, model.get());
  return ScoreWithFolds(method, dataset, settings, std::move(model));
}

// The physical fit's composition degree chosen by the data: degrees 2 and 1 (2 needs four
// compositions, so that every fold fits it too), each built with its folds and scored on
// them by the RMS of the folds' errors. Degree 2 (kPreferredDegree) stays unless degree 1
// is lower by more than 10 % and by more than one standard error of the folds' paired
// differences (ChooseSimplest with 2 first, Lead::kDegree: a degree that misses one fold
// badly is not saved by the others): leave-one-out over a few folds is too noisy to
// overrule the physics on less. Degree 3 is not offered: on Nb-Sn the folds chose it where a
// held-out end sample left a wide gap, and it bent across that gap (reflectance RMS 0.42
// against 0.13); --degree asks for it. Fewer than four compositions cannot tell degrees
// apart: the default degree then. The table and the reason go into the fit summary.
Scored BuildChoosingDegree(const MethodInfo& method, const Dataset& dataset,
                           const FitSettings& settings) {
  const int compositions = static_cast<int>(DistinctCompositions(dataset).size());
  const int top = std::min(kPreferredDegree, compositions - 2);
  if (settings.colorimeter == nullptr || ErrorFolds(dataset).size() < 2 || top < 2) {
    return BuildScored(method, dataset, settings);
  }
  // Candidates on a fifth of the iterations and without covariance: a degree that does
  // not fit the data shows it long before, and the chosen one is finished below.
  std::vector<Scored> candidates;
  std::vector<int> degrees;
  for (int degree : {kPreferredDegree, 1}) {
    if (degree <= top) degrees.push_back(degree);
  }
  for (int degree : degrees) {
    Report(settings.progress, method.name + ": degree " + std::to_string(degree) +
                                  ", leave-one-out over " +
                                  std::to_string(ErrorFolds(dataset).size()) + " compositions");
    FitSettings at = settings;
    at.options.Set("degree", degree);
    at.progress = {};
    at.details = {};
    at.options.Set("covariance", false);
    at.max_iterations = kCandidateIterations;
    Scored r = candidates.empty() ? BuildScored(method, dataset, at)
                                  : BuildUnlessOutdone(method, dataset, at, candidates.front());
    if (r.model && r.model->fit_summary().degree != degree) {
      r.score.error = "lowered to degree " + std::to_string(r.model->fit_summary().degree) +
                      " (it left physics or did not converge)";
      r.model.reset();
    }
    candidates.push_back(std::move(r));
  }
  const Choice c = ChooseSimplest(candidates, Lead::kDegree);
  if (c.chosen == candidates.size()) {
    // No degree could be scored: the default fit says why (or succeeds on its own).
    return BuildScored(method, dataset, settings);
  }
  Scored chosen = std::move(candidates[c.chosen]);
  const int degree = chosen.model->fit_summary().degree;
  {
    // Finished from where the candidate stopped, with the covariance; its folds' prediction
    // error carries over (the folds started from the candidate). The finished fit may still
    // leave physics where the candidate had not (on Au-Ag with 2 % scatter added, eps2 < 0
    // at the silver end at degree 1): then the physical model is refused, as any fit that
    // leaves physics is, and auto goes on without it.
    FitSettings full = settings;
    full.options.Set("degree", degree);
    full.start = chosen.model.get();
    std::unique_ptr<AlloyModel> finished;
    try {
      finished = Build(method, dataset, full);
      RecordInSampleError(dataset, settings, finished.get());
    } catch (const Error& e) {
      Scored refused;
      refused.score.method = method.name;
      refused.score.error = e.what();
      return refused;
    }
    if (chosen.model->prediction_error().present()) {
      CarryPredictionError(dataset, chosen.model->prediction_error(), finished.get());
    }
    chosen.model = std::move(finished);
  }
  char reason[200];
  std::snprintf(reason, sizeof reason, "leave-one-out RMS %s %.4g over %d folds%s%s",
                chosen.metric.c_str(), Rms(chosen.values), chosen.score.folds,
                c.rule.empty() ? ", the lowest" : ", Nordheim's degree 2 within ", c.rule.c_str());
  FitSummary summary = chosen.model->fit_summary();
  nlohmann::json table = nlohmann::json::array();
  for (size_t i = 0; i < candidates.size(); ++i) {
    const Scored& r = i == c.chosen ? chosen : candidates[i];
    const MethodScore& s = r.score;
    nlohmann::json row = {{"degree", degrees[i]}};
    if (s.error.empty()) {
      row["rms"] = Rms(r.values);
      row["mean"] = s.mean;
      row["max"] = s.max;
      row["folds"] = s.folds;
    } else {
      row["error"] = s.error;
    }
    table.push_back(row);
  }
  summary.details["degree_chosen_by"] = reason;
  summary.details["degree_selection"] = table;
  chosen.model->set_fit_summary(std::move(summary));
  Report(settings.progress, method.name + ": degree " + std::to_string(degree) + ": " + reason);
  return chosen;
}

}  // namespace

// BuildChoosingDegree through settings.memo: the choice is deterministic, so the
// remembered result (a copy through the model file) is what a new one would give. Keyed by
// the samples (composition, wavelengths, n, k) and every setting the fit reads; a refit
// (settings.start) is not remembered.
Scored RememberedDegreeChoice(const MethodInfo& method, const Dataset& dataset,
                              const FitSettings& settings) {
  if (!settings.memo || settings.start != nullptr) {
    return BuildChoosingDegree(method, dataset, settings);
  }
  return ThroughMemo(
      method, settings, FitMemoKey(method, dataset, settings), &FitMemo::degree_choices,
      [&] { return BuildChoosingDegree(method, dataset, settings); },
      [](const Scored& r) { return r.model != nullptr; });
}

bool ChoosesDegree(const MethodInfo& method, const FitSettings& settings) {
  return method.traits.chooses_degree && !settings.options.Has("degree") && !settings.fold;
}

namespace {

// The model's larger in-sample error at the two end compositions, which no fold holds
// out, in the metric of the folds' scores, and whether it is a miss (RecordInSampleError).
double EndMiss(const AlloyModel& model, const Dataset& dataset, bool* misses) {
  const std::vector<double> xs = DistinctCompositions(dataset);
  double worst = 0;
  *misses = false;
  for (const InSampleError& r : model.in_sample()) {
    if (r.x_atomic != xs.front() && r.x_atomic != xs.back()) continue;
    const bool colour = std::isfinite(r.delta_e00);
    const double e = colour ? r.delta_e00 : r.reflectance_rms;
    worst = std::max(worst, e);
    *misses |= e > (colour ? kInSampleMissDe00 : kInSampleMissReflectance);
  }
  return worst;
}

// auto's rule: the simplest within the folds' scatter of the best (ChooseSimplest); the
// folds cannot hold out the ends, so among the candidates the folds cannot tell apart, one
// that contradicts the user's own end samples gives way to one that does not. `except`:
// the folds at that composition left out (NaN: none).
Choice ChooseAmong(const std::vector<Scored>& candidates, const std::vector<bool>& misses_end,
                   double except = std::nan("")) {
  Choice c = ChooseSimplest(candidates, Lead::kAuto, except);
  if (c.chosen < candidates.size() && misses_end[c.chosen]) {
    for (size_t i : c.acceptable) {
      if (!misses_end[i]) {
        c.chosen = i;
        c.rule = "the ends' own samples";
        break;
      }
    }
  }
  return c;
}

// Why auto chose what it chose, one line.
std::string ChoiceReason(const MethodSelection& selection, const Choice& c,
                         const std::vector<const MethodInfo*>& order) {
  const MethodScore& chosen_score = selection.scores[c.chosen];
  const MethodScore& best_score = selection.scores[c.best];
  const std::string& chosen_name = order[c.chosen]->name;
  const std::string& best_name = order[c.best]->name;
  char reason[320];
  if (c.rule.empty()) {
    std::snprintf(reason, sizeof reason, "%s: lowest mean %s, %.4g over %d held-out samples",
                  chosen_name.c_str(), selection.metric.c_str(), chosen_score.mean,
                  chosen_score.folds);
  } else if (c.rule == "one fold") {
    std::snprintf(reason, sizeof reason,
                  "%s: one fold (three compositions) compares the straight lines between the "
                  "ends, not the curves through three samples; %s scored %.4g, %s %.4g",
                  chosen_name.c_str(), chosen_name.c_str(), chosen_score.mean, best_name.c_str(),
                  best_score.mean);
  } else if (c.rule == "the ends' own samples") {
    std::snprintf(reason, sizeof reason,
                  "%s: mean %s %.4g over %d held-out samples, within the folds' tolerance of "
                  "the lowest (%s, %.4g), the first in auto's order true to the end samples",
                  chosen_name.c_str(), selection.metric.c_str(), chosen_score.mean,
                  chosen_score.folds, best_name.c_str(), best_score.mean);
  } else if (c.rule == "the range of the folds") {
    std::snprintf(reason, sizeof reason,
                  "%s: mean %s %.4g over %d held-out samples, the first in auto's order that "
                  "the lowest (%s, %.4g) does not beat outright: within the range of the folds, "
                  "its best fold no worse than the lowest's worst",
                  chosen_name.c_str(), selection.metric.c_str(), chosen_score.mean,
                  chosen_score.folds, best_name.c_str(), best_score.mean);
  } else {
    std::snprintf(reason, sizeof reason,
                  "%s: mean %s %.4g over %d held-out samples, the first in auto's order "
                  "within %s of the lowest (%s, %.4g)",
                  chosen_name.c_str(), selection.metric.c_str(), chosen_score.mean,
                  chosen_score.folds, c.rule.c_str(), best_name.c_str(), best_score.mean);
  }
  return reason;
}

}  // namespace

double ChoiceCalibrationFactor(const std::vector<Scored>& candidates,
                               const std::vector<bool>& misses_end, size_t chosen) {
  const Scored& own = candidates[chosen];
  std::vector<double> held = own.held_x;
  std::sort(held.begin(), held.end());
  held.erase(std::unique(held.begin(), held.end()), held.end());
  if (held.size() < 2) return 1;
  double own_sq = 0, choice_sq = 0;
  for (double x : held) {
    const Choice c = ChooseAmong(candidates, misses_end, x);
    if (c.chosen >= candidates.size()) return 1;
    const Scored& other = candidates[c.chosen];
    if (other.held_x != own.held_x) return 1;  // scored on other folds
    for (size_t k = 0; k < own.values.size(); ++k) {
      if (own.held_x[k] != x) continue;
      own_sq += own.values[k] * own.values[k];
      choice_sq += other.values[k] * other.values[k];
    }
  }
  if (!(own_sq > 0)) return 1;
  return std::max(std::sqrt(choice_sq / own_sq), 1.0);
}

std::unique_ptr<AlloyModel> BuildAuto(const Dataset& dataset, const FitSettings& settings) {
  const std::vector<const MethodInfo*> order = AutoCandidates();  // preferred first
  if (settings.colorimeter == nullptr) throw Error("auto: no colorimeter to score colours with");
  if (order.empty()) throw Error("auto: no method is a candidate");
  MethodSelection selection;
  const size_t held_out = ErrorFolds(dataset).size();
  if (held_out == 0) {
    selection.metric = "none";
    selection.reason = order.front()->name + ": " +
                       std::to_string(DistinctCompositions(dataset).size()) +
                       " compositions leave none to hold out (every interpolation is then the "
                       "straight line between the samples)";
    std::unique_ptr<AlloyModel> model = BuildModel(order.front()->name, dataset, settings);
    FitSummary summary = model->fit_summary();
    summary.selection = selection;
    model->set_fit_summary(std::move(summary));
    return model;
  }
  // Every candidate built on all samples with its folds (which also give its prediction
  // error): the folds score it, and the chosen one is already built.
  FitSettings inner = settings;
  inner.progress = {};
  inner.details = {};
  inner.start = nullptr;
  std::vector<Scored> candidates;
  std::vector<bool> misses_end;
  const int compositions = static_cast<int>(DistinctCompositions(dataset).size());
  for (const MethodInfo* method : order) {
    Report(settings.progress, "auto: scoring " + method->name + " by leave-one-out over " +
                                  std::to_string(held_out) + " interior compositions");
    candidates.push_back(ChoosesDegree(*method, inner)
                             ? RememberedDegreeChoice(*method, dataset, inner)
                             : BuildScored(*method, dataset, inner));
    Scored& r = candidates.back();
    // The folds must score the model delivered: a fold holds compositions - 1, enough
    // for degree compositions - 2 at most (three compositions: the physical model is
    // delivered at degree 2 and its folds are degree-1 fits to two samples).
    if (method->traits.chooses_degree && r.model &&
        r.model->fit_summary().degree > compositions - 2) {
      r.score.error = "its folds (" + std::to_string(compositions - 1) +
                      " compositions each) cannot fit its degree " +
                      std::to_string(r.model->fit_summary().degree);
      r.model.reset();
    }
    // It contradicts an end sample where it misses it by more than the miss threshold and
    // by more than it errs on the samples its folds hold out: a regression's miss within
    // its own scatter is no contradiction.
    bool misses = false;
    if (r.model) r.score.end_miss = EndMiss(*r.model, dataset, &misses);
    misses_end.push_back(misses && r.score.end_miss > r.score.mean);
    selection.scores.push_back(r.score);
    if (selection.metric.empty()) selection.metric = candidates.back().metric;
  }
  Choice c = ChooseAmong(candidates, misses_end);
  // One fold (three compositions): it holds out the middle sample and predicts it from the
  // ends, where every interpolation is a straight line in its own space, so the fold
  // compares spaces, not the curves delivered through three samples, and one score has no
  // scatter to weigh a lead by (on Au-Ag's 0, 0.1, 1 it preferred paper's line, whose curve
  // then erred 11 on the held-out samples against smooth's 1.3). A method that chooses its
  // smoothing by other evidence (MethodTraits::chosen_on_one_fold) is taken there.
  if (held_out == 1) {
    for (size_t i = 0; i < order.size(); ++i) {
      if (order[i]->traits.chosen_on_one_fold && candidates[i].score.error.empty() &&
          c.chosen != i) {
        c.rule = "one fold";
        c.chosen = i;
        break;
      }
    }
  }
  if (c.chosen == order.size()) {
    throw Error(dataset.manifest_path + ": auto: no method could be scored");
  }
  selection.reason = ChoiceReason(selection, c, order);
  std::unique_ptr<AlloyModel> model = std::move(candidates[c.chosen].model);
  FitSummary summary = model->fit_summary();
  const double factor = ChoiceCalibrationFactor(candidates, misses_end, c.chosen);
  if (factor > 1 && model->prediction_error().present()) {
    PredictionError error = model->prediction_error();
    error.calibration = std::min(error.calibration * factor, 1e3);
    model->set_prediction_error(std::move(error));
    summary.details["calibration_times_for_the_choice"] = factor;
  }
  summary.selection = selection;
  model->set_fit_summary(std::move(summary));
  return model;
}

}  // namespace alloycolor::fit
