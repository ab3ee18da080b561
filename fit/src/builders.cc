// One builder per built-in method, attached to its registry entry (model/registry.h).
#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>

#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/fit/physical_fit.h"
#include "alloycolor/fit/smooth_fit.h"
#include "alloycolor/model/physical_model.h"
#include "alloycolor/model/registry.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/model/smooth_model.h"
#include "folds.h"

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
  std::string space = settings.space;
  // A fold with no interior composition cannot choose the space of its curves: it takes
  // the one of the model it scores.
  if (const SmoothModel* parent = SmoothModel::From(settings.parent);
      parent != nullptr && space.empty() && DistinctCompositions(dataset).size() < 3) {
    space = SmoothSpaceName(parent->space());
  }
  if (space == "eps") {
    options.space = SmoothSpace::kEps;
  } else if (space == "log_eps") {
    options.space = SmoothSpace::kLogEps;
  } else if (!space.empty()) {
    throw Error("--space: '" + space + "' is none of eps, log_eps");
  }
  options.progress = settings.progress;
  options.details = settings.details;
  if (settings.lambda_from_nm != 0 || settings.lambda_to_nm != 0) {
    const double step = settings.lambda_step_nm > 0 ? settings.lambda_step_nm : 5.0;
    if (!(settings.lambda_to_nm > settings.lambda_from_nm) || !(settings.lambda_step_nm >= 0)) {
      throw Error("--lambda-from/--lambda-to/--lambda-step: need from < to, step > 0");
    }
    options.grid_nm = UniformGrid(settings.lambda_from_nm, settings.lambda_to_nm, step);
  }
  options.start = SmoothModel::From(settings.start);
  if (settings.start != nullptr && options.start == nullptr) {
    throw Error("a smooth refit needs a smooth model to start from, not a " +
                settings.start->method() + " model");
  }
  if (options.start != nullptr && options.grid_nm.empty()) {
    options.grid_nm = options.start->grid_nm();
  }
  return std::move(FitSmooth(dataset, options).model);
}

std::unique_ptr<AlloyModel> BuildPhysical(const Dataset& dataset, const FitSettings& settings) {
  PhysicalFitOptions options;
  if (settings.degree >= 0) options.degree = settings.degree;
  options.terms = settings.terms;
  options.covariance = settings.covariance && !settings.fold;
  options.check_physics = !settings.fold;
  if (settings.memo) options.end_fits = FitMemoEndFits(*settings.memo);
  if (settings.max_iterations > 0) options.max_iterations = settings.max_iterations;
  // A fold starts at its parent's solution (warm): a fifth of the iterations is plenty
  // where the form fits, and where it does not (a degree too low) the fold's error is
  // plain long before.
  if (settings.fold) options.max_iterations = std::max(1, options.max_iterations / 5);
  options.progress = settings.progress;
  options.start = PhysicalModel::From(settings.start);
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

void AttachBuiltInBuilders() {
  static std::once_flag once;
  std::call_once(once, [] {
    const std::pair<const char*, MethodBuilder> builders[] = {
        {"paper", &BuildSampleModel<SampleModel::Kind::kPaper>},
        {"eps-linear", &BuildSampleModel<SampleModel::Kind::kEpsLinear>},
        {"eps-pchip", &BuildSampleModel<SampleModel::Kind::kEpsPchip>},
        {"eps-spline", &BuildSampleModel<SampleModel::Kind::kEpsSpline>},
        {"smooth", &BuildSmooth},
        {"physical", &BuildPhysical},
    };
    for (const auto& [name, build] : builders) {
      MethodInfo info = RequireMethod(name);
      if (info.build == nullptr) {
        info.build = build;
        RegisterMethod(std::move(info));
      }
    }
  });
}

}  // namespace alloycolor::fit
