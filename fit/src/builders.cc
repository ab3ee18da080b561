// One builder per built-in method, attached to its registry entry (model/registry.h).
#include <algorithm>
#include <cmath>
#include <memory>

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

// The smooth fit's grid from the fit grid's options (checked: CheckFitGrid); empty for its
// default (DefaultGrid), which a step alone keeps the range of.
std::vector<double> SmoothGrid(const OptionValues& options, const Dataset& dataset) {
  const bool range = options.Has("lambda_from_nm");
  if (!range && !options.Has("lambda_step_nm")) return {};
  const std::vector<double> fallback = range ? std::vector<double>{} : DefaultGrid(dataset);
  return UniformGrid(range ? options.Number("lambda_from_nm") : fallback.front(),
                     range ? options.Number("lambda_to_nm") : fallback.back(),
                     options.Number("lambda_step_nm", kGridStepNm));
}

std::unique_ptr<AlloyModel> BuildSmooth(const Dataset& dataset, const FitSettings& settings) {
  const OptionValues& given = settings.options;
  SmoothFitOptions options;
  options.smoothing = given.Number("smoothing", -1);
  std::string space = given.Text("space", "");
  // A fold with no interior composition cannot choose the space of its curves: it takes
  // the one of the model it scores.
  if (const SmoothModel* parent = SmoothModel::From(settings.parent);
      parent != nullptr && space.empty() && DistinctCompositions(dataset).size() < 3) {
    space = SmoothSpaceName(parent->space());
  }
  // A fold of a dense series (more compositions than the curves have knots) keeps the
  // smoothing and space chosen on all the samples, as cross-validating them again on all
  // but one or two compositions of so many would, at the cost of a hundred fits each.
  if (const SmoothModel* parent = SmoothModel::From(settings.parent);
      parent != nullptr && settings.fold && options.smoothing < 0 &&
      parent->fit_summary().details.value("form", "") != "gaussian process" &&
      DistinctCompositions(dataset).size() > parent->knots_x().size()) {
    options.smoothing = parent->smoothing();
    if (space.empty()) space = SmoothSpaceName(parent->space());
  }
  if (space == "eps") options.space = SmoothSpace::kEps;
  if (space == "log_eps") options.space = SmoothSpace::kLogEps;
  options.progress = settings.progress;
  options.details = settings.details;
  options.cancel = settings.cancel;
  options.grid_nm = SmoothGrid(given, dataset);
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
  const OptionValues& given = settings.options;
  PhysicalFitOptions options;
  options.degree = given.Whole("degree", options.degree);
  options.terms = given.Text("terms", options.terms);
  options.covariance = given.Flag("covariance", true) && !settings.fold;
  options.check_physics = !settings.fold;
  if (settings.memo) options.end_fits = FitMemoEndFits(*settings.memo);
  if (settings.max_iterations > 0) options.max_iterations = settings.max_iterations;
  // A fold starts at its parent's solution (warm): a fifth of the iterations is plenty
  // where the form fits, and where it does not (a degree too low) the fold's error is
  // plain long before.
  if (settings.fold) options.max_iterations = std::max(1, options.max_iterations / 5);
  options.progress = settings.progress;
  options.cancel = settings.cancel;
  options.start = PhysicalModel::From(settings.start);
  options.lambda_from_nm = given.Number("lambda_from_nm", 0);
  options.lambda_to_nm = given.Number("lambda_to_nm", 0);
  options.lambda_step_nm = given.Number("lambda_step_nm", 0);
  return std::move(FitPhysical(dataset, options).model);
}

// The built-in methods' builders, attached to their registry entries before `main`.
bool AttachBuiltInBuilders() {
  const std::pair<const char*, MethodBuilder> builders[] = {
      {"paper", &BuildSampleModel<SampleModel::Kind::kPaper>},
      {"eps-linear", &BuildSampleModel<SampleModel::Kind::kEpsLinear>},
      {"eps-pchip", &BuildSampleModel<SampleModel::Kind::kEpsPchip>},
      {"eps-spline", &BuildSampleModel<SampleModel::Kind::kEpsSpline>},
      {"smooth", &BuildSmooth},
      {"physical", &BuildPhysical},
  };
  for (const auto& [name, build] : builders) AttachBuilder(name, build);
  return true;
}

const bool kBuiltInBuildersAttached = AttachBuiltInBuilders();

}  // namespace

bool BuiltInBuildersAttached() { return kBuiltInBuildersAttached; }

}  // namespace alloycolor::fit
