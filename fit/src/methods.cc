#include "alloycolor/fit/methods.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "alloycolor/core/error.h"
#include "alloycolor/fit/physical_fit.h"
#include "alloycolor/fit/smooth_fit.h"
#include "alloycolor/model/registry.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/validate/validation.h"

namespace alloycolor::fit {
namespace {

template <SampleModel::Kind kind>
std::unique_ptr<AlloyModel> BuildSampleModel(const Dataset& dataset, const FitSettings&) {
  return std::make_unique<SampleModel>(kind, dataset);
}

std::unique_ptr<AlloyModel> BuildSmooth(const Dataset& dataset, const FitSettings& settings) {
  SmoothFitOptions options;
  if (settings.smoothing != -1) {
    if (!(std::isfinite(settings.smoothing) && settings.smoothing >= 0)) {
      throw Error("--smoothing: need a finite value >= 0");
    }
    options.smoothing = settings.smoothing;
  }
  options.progress = settings.progress;
  if (settings.lambda_from_nm != 0 || settings.lambda_to_nm != 0) {
    const double step = settings.lambda_step_nm > 0 ? settings.lambda_step_nm : 5.0;
    if (!(settings.lambda_to_nm > settings.lambda_from_nm) || !(settings.lambda_step_nm >= 0)) {
      throw Error("--lambda-from/--lambda-to/--lambda-step: need from < to, step > 0");
    }
    options.grid_nm = UniformGrid(settings.lambda_from_nm, settings.lambda_to_nm, step);
  }
  std::unique_ptr<SmoothModel> start;
  if (settings.start) {
    if (settings.start->method() != "smooth") {
      throw Error("a smooth refit needs a smooth model to start from, not a " +
                  settings.start->method() + " model");
    }
    start = std::make_unique<SmoothModel>(settings.start->ToJson(), "the start model");
    options.start = start.get();
    if (options.grid_nm.empty()) options.grid_nm = start->grid_nm();
  }
  return std::move(FitSmooth(dataset, options).model);
}

std::unique_ptr<AlloyModel> BuildPhysical(const Dataset& dataset, const FitSettings& settings) {
  PhysicalFitOptions options;
  if (settings.degree >= 0) options.degree = settings.degree;
  options.terms = settings.terms;
  options.covariance = settings.covariance;
  options.progress = settings.progress;
  if (settings.lambda_from_nm != 0 || settings.lambda_to_nm != 0) {
    if (!(settings.lambda_from_nm > 0) || !(settings.lambda_to_nm > settings.lambda_from_nm)) {
      throw Error("--lambda-from/--lambda-to: need 0 < from < to");
    }
    options.lambda_from_nm = settings.lambda_from_nm;
    options.lambda_to_nm = settings.lambda_to_nm;
  }
  if (settings.lambda_step_nm != 0) {
    if (!(settings.lambda_step_nm > 0)) throw Error("--lambda-step: need a positive step");
    options.lambda_step_nm = settings.lambda_step_nm;
  }
  return std::move(FitPhysical(dataset, options).model);
}

}  // namespace

const std::vector<MethodBuilder>& Builders() {
  static const std::vector<MethodBuilder> kBuilders = {
      {"paper", &BuildSampleModel<SampleModel::Kind::kPaper>},
      {"eps-linear", &BuildSampleModel<SampleModel::Kind::kEpsLinear>},
      {"eps-pchip", &BuildSampleModel<SampleModel::Kind::kEpsPchip>},
      {"eps-spline", &BuildSampleModel<SampleModel::Kind::kEpsSpline>},
      {"smooth", &BuildSmooth},
      {"physical", &BuildPhysical},
  };
  return kBuilders;
}

std::unique_ptr<AlloyModel> BuildModel(const std::string& method, const Dataset& dataset,
                                       const FitSettings& settings) {
  if (method == kAutoMethod) return BuildAuto(dataset, settings);
  RequireMethod(method);
  for (const MethodBuilder& b : Builders()) {
    if (b.name == method) return b.build(dataset, settings);
  }
  throw Error("method '" + method + "' cannot be fitted to data");
}

constexpr double kAutoTolerance = 1.10;

std::unique_ptr<AlloyModel> BuildAuto(const Dataset& dataset, const FitSettings& settings) {
  // Simplest first: ties go to the earlier.
  const std::vector<std::string> order = {"eps-pchip", "eps-linear", "eps-spline",
                                          "paper",     "smooth",     "physical"};
  MethodSelection selection;
  std::vector<std::vector<double>> splits;
  for (size_t i = 1; i + 1 < dataset.samples.size(); ++i) {
    splits.push_back({dataset.samples[i].x_atomic});
  }
  std::string chosen = "eps-pchip";
  if (settings.colorimeter == nullptr) throw Error("auto: no colorimeter to score colours with");
  if (splits.empty()) {
    selection.metric = "none";
    selection.reason = "eps-pchip: " + std::to_string(dataset.samples.size()) +
                       " compositions leave none to hold out (every interpolation is then the "
                       "straight line between the samples)";
  } else {
    FitSettings inner = settings;
    inner.progress = {};
    inner.start = nullptr;
    validate::ValidationOptions options;
    options.build = [&inner](const std::string& method, const Dataset& training) {
      return BuildModel(method, training, inner);
    };
    options.angles_deg = {0.0};
    options.mode = "loo";
    options.sigma_draws = 0;
    double best = 1e300;
    const MethodScore* best_score = nullptr;
    for (const std::string& method : order) {
      Report(settings.progress, "auto: scoring " + method + " by leave-one-out over " +
                                    std::to_string(splits.size()) + " interior samples");
      options.methods = {method};
      MethodScore score;
      score.method = method;
      try {
        const validate::ValidationReport report =
            validate::ComputeValidation(dataset, splits, *settings.colorimeter, options, {});
        double sum = 0;
        for (const auto& h : report.holdouts) {
          const auto it = h.results.find(method);
          if (it == h.results.end() || !it->second.error.empty()) continue;
          const validate::MethodResult& r = it->second;
          const double v = !r.delta_e00.empty() ? r.delta_e00[0] : r.reflectance_rms;
          if (!std::isfinite(v)) continue;
          sum += v;
          score.max = score.folds == 0 ? v : std::max(score.max, v);
          ++score.folds;
          if (!r.delta_e00.empty()) selection.metric = "delta_e00 at normal incidence";
        }
        if (score.folds < static_cast<int>(splits.size())) {
          score.error = "failed on " + std::to_string(splits.size() - score.folds) + " of " +
                        std::to_string(splits.size()) + " folds";
        } else {
          score.mean = sum / score.folds;
        }
      } catch (const Error& e) {
        score.error = e.what();
      }
      selection.scores.push_back(score);
    }
    if (selection.metric.empty()) selection.metric = "reflectance_rms at normal incidence";
    // The simplest method within kAutoTolerance of the lowest score: leave-one-out with few
    // samples flatters the flexible methods.
    for (const MethodScore& s : selection.scores) {
      if (s.error.empty()) best = std::min(best, s.mean);
    }
    for (const MethodScore& s : selection.scores) {
      if (s.error.empty() && s.mean <= best * kAutoTolerance) {
        best_score = &s;
        break;
      }
    }
    if (best_score == nullptr) throw Error(dataset.manifest_path + ": auto: no method could be scored");
    chosen = best_score->method;
    char reason[160];
    std::snprintf(reason, sizeof reason, "%s: lowest leave-one-out mean %s, %.4g over %d folds",
                  chosen.c_str(), selection.metric.c_str(), best_score->mean, best_score->folds);
    selection.reason = reason;
  }
  Report(settings.progress, "auto: " + selection.reason);
  std::unique_ptr<AlloyModel> model = BuildModel(chosen, dataset, settings);
  FitSummary summary = model->fit_summary();
  summary.selection = selection;
  model->set_fit_summary(std::move(summary));
  return model;
}

}  // namespace alloycolor::fit
