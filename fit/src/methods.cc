#include "alloycolor/fit/methods.h"

#include <cmath>

#include "alloycolor/core/error.h"
#include "alloycolor/fit/physical_fit.h"
#include "alloycolor/fit/smooth_fit.h"
#include "alloycolor/model/registry.h"
#include "alloycolor/model/sample_models.h"

namespace alloycolor::fit {
namespace {

template <SampleModel::Kind kind>
std::unique_ptr<AlloyModel> BuildSampleModel(const Dataset& dataset, const FitSettings&) {
  return std::make_unique<SampleModel>(kind, dataset);
}

std::unique_ptr<AlloyModel> BuildSmooth(const Dataset& dataset, const FitSettings& settings) {
  SmoothFitOptions options;
  options.degree = settings.degree;
  options.max_degree = settings.max_degree;
  if (settings.smoothing != -1) {
    if (!(std::isfinite(settings.smoothing) && settings.smoothing >= 0)) {
      throw Error("--smoothing: need a finite value >= 0");
    }
    options.smoothing = settings.smoothing;
  }
  options.covariance = settings.covariance;
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
    if (options.degree < 0) options.degree = start->degree();
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
      {"smooth", &BuildSmooth},
      {"physical", &BuildPhysical},
  };
  return kBuilders;
}

std::unique_ptr<AlloyModel> BuildModel(const std::string& method, const Dataset& dataset,
                                       const FitSettings& settings) {
  RequireMethod(method);
  for (const MethodBuilder& b : Builders()) {
    if (b.name == method) return b.build(dataset, settings);
  }
  throw Error("method '" + method + "' cannot be fitted to data");
}

}  // namespace alloycolor::fit
