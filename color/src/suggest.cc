#include "alloycolor/color/suggest.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/model/registry.h"

namespace alloycolor::color {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The model with its prediction error's compositions taken to be `measured`: what its error
// bars would be once samples there are measured (the misfit between compositions keeps
// its linear course: each new composition takes the misfit interpolated there).
std::unique_ptr<AlloyModel> AfterMeasuring(const AlloyModel& model,
                                           const std::vector<double>& added) {
  std::unique_ptr<AlloyModel> copy =
      RequireMethod(model.method()).read(model.ToJson(), model.source());
  copy->set_source(model.source());
  PredictionError e = model.prediction_error();
  if (!e.present() || added.empty()) return copy;
  std::vector<double> xs = e.compositions;
  xs.insert(xs.end(), added.begin(), added.end());
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  if (!e.misfit.empty()) {
    std::vector<std::vector<std::complex<double>>> misfit;
    for (double x : xs) {
      std::vector<std::complex<double>> row;
      for (double l : e.misfit_lambda_nm) row.push_back(e.MisfitAt(x, l));
      misfit.push_back(std::move(row));
    }
    e.misfit = std::move(misfit);
  }
  e.compositions = std::move(xs);
  e.held_out.clear();
  copy->set_prediction_error(std::move(e));
  return copy;
}

// The model with only the error bars' part that a new measurement can remove: the
// interpolation's (scale * B); the misfit, the replicates' scatter and the precision stay
// whatever is measured next.
std::unique_ptr<AlloyModel> Reducible(const AlloyModel& model) {
  std::unique_ptr<AlloyModel> copy = AfterMeasuring(model, {});
  PredictionError e = copy->prediction_error();
  if (!e.present()) return copy;
  e.misfit.clear();
  e.scatter.clear();
  e.misfit_lambda_nm.clear();
  e.precision = 0;
  copy->set_prediction_error(std::move(e));
  return copy;
}

// The relative eps one-sigma of a prediction error at x: its draws' normal terms.
double RelativeEpsSigma(const PredictionError& e, double x) {
  double mean_scale = 0;
  for (double s : e.scale) mean_scale += s / e.scale.size();
  return std::hypot(e.calibration * mean_scale * e.Bump(x), e.precision);
}

// The one-sigma of `model` at each of xs.
std::vector<double> SigmaAt(const Colorimeter& cm, const AlloyModel& model, bool colour,
                            const std::vector<double>& xs, const SuggestOptions& options,
                            ThreadBudget* threads) {
  std::vector<double> sigma(xs.size(), kNaN);
  ParallelTasks(
      xs.size(),
      [&](size_t i) {
        CheckCancel(options.cancel);
        sigma[i] = colour ? DeltaE00Sigma(cm, model, xs[i], 0.0)
                          : RelativeEpsSigma(model.prediction_error(), xs[i]);
      },
      threads);
  return sigma;
}

bool FarFrom(double x, const std::vector<double>& measured, double distance) {
  return std::all_of(measured.begin(), measured.end(),
                     [&](double m) { return std::abs(x - m) >= distance - 1e-12; });
}

// The middle of the widest gap between the measured compositions and the range's ends, if
// it lies far enough from them; NaN where there is no room.
double WidestGapMiddle(const AlloyModel& model, std::vector<double> measured, double distance) {
  measured.push_back(model.x_min());
  measured.push_back(model.x_max());
  std::sort(measured.begin(), measured.end());
  double best = kNaN, width = 0;
  for (size_t i = 1; i < measured.size(); ++i) {
    const double gap = measured[i] - measured[i - 1];
    const double middle = 0.5 * (measured[i] + measured[i - 1]);
    if (gap > width && FarFrom(middle, measured, distance)) best = middle, width = gap;
  }
  return best;
}

double Mean(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x / v.size();
  return sum;
}

}  // namespace

std::string SuggestRuleName(SuggestRule rule) {
  return rule == SuggestRule::kLargestSigma ? "largest-sigma" : "widest-gap";
}

SuggestRule ParseSuggestRule(const std::string& name) {
  for (SuggestRule r : {SuggestRule::kLargestSigma, SuggestRule::kWidestGap}) {
    if (SuggestRuleName(r) == name) return r;
  }
  throw Error("rule: '" + name + "' is neither largest-sigma nor widest-gap");
}

SuggestResult SuggestCompositions(const Colorimeter& colorimeter, const AlloyModel& model,
                                  const SuggestOptions& options) {
  if (options.count < 1 || options.count > 20) {
    throw Error("count: " + std::to_string(options.count) + " is not a whole number in [1, 20]");
  }
  SuggestResult result;
  std::vector<double> measured;
  for (const TrainingSample& t : model.training_samples()) measured.push_back(t.x_atomic);
  const bool sigma = model.HasUncertainty();
  const bool colour = CoversVisible(model.lambda_min_nm(), model.lambda_max_nm());
  result.metric = !sigma ? "none" : colour ? "delta_e00" : "relative_eps";
  SuggestRule rule = sigma ? options.rule : SuggestRule::kWidestGap;
  result.rule = SuggestRuleName(rule);
  if (!sigma) result.rule += " (" + model.NoErrorBarReason() + ")";
  for (int i = 0; i < kSuggestGrid; ++i) {
    result.scan_x.push_back(model.x_min() +
                            (model.x_max() - model.x_min()) * i / (kSuggestGrid - 1.0));
  }
  if (sigma)
    result.scan_sigma =
        SigmaAt(colorimeter, model, colour, result.scan_x, options, options.threads);
  // The rule looks at what a measurement can remove; the figures are the whole one-sigma's.
  std::vector<double> reducible, chosen;
  if (sigma && rule == SuggestRule::kLargestSigma) {
    reducible =
        SigmaAt(colorimeter, *Reducible(model), colour, result.scan_x, options, options.threads);
  }
  for (int n = 0; n < options.count; ++n) {
    std::vector<double> taken = measured;
    taken.insert(taken.end(), chosen.begin(), chosen.end());
    double x = kNaN;
    if (rule == SuggestRule::kWidestGap) {
      x = WidestGapMiddle(model, taken, options.min_distance);
    } else {
      double best = -1;
      for (size_t i = 0; i < result.scan_x.size(); ++i) {
        if (reducible[i] > best && FarFrom(result.scan_x[i], taken, options.min_distance)) {
          best = reducible[i], x = result.scan_x[i];
        }
      }
    }
    if (!std::isfinite(x)) break;  // no room left
    chosen.push_back(x);
    Suggestion s;
    s.x_atomic = x;
    if (sigma) {
      s.sigma = SigmaAt(colorimeter, model, colour, {x}, options, nullptr)[0];
      const std::unique_ptr<AlloyModel> after = AfterMeasuring(model, chosen);
      const std::vector<double> next =
          SigmaAt(colorimeter, *after, colour, result.scan_x, options, options.threads);
      s.max_sigma_before = *std::max_element(result.scan_sigma.begin(), result.scan_sigma.end());
      s.mean_sigma_before = Mean(result.scan_sigma);
      s.max_sigma_after = *std::max_element(next.begin(), next.end());
      s.mean_sigma_after = Mean(next);
      if (rule == SuggestRule::kLargestSigma && n + 1 < options.count) {
        reducible = SigmaAt(colorimeter, *Reducible(*after), colour, result.scan_x, options,
                            options.threads);
      }
    }
    result.suggestions.push_back(s);
  }
  return result;
}

}  // namespace alloycolor::color
