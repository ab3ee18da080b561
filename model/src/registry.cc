#include "alloycolor/model/registry.h"

#include "alloycolor/core/error.h"
#include "alloycolor/model/physical_model.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/model/smooth_model.h"

namespace alloycolor {
namespace {

template <SampleModel::Kind kind>
std::unique_ptr<AlloyModel> ReadSampleModel(const nlohmann::json& doc, const std::string& source) {
  return std::make_unique<SampleModel>(kind, doc, source);
}

template <typename Model>
std::unique_ptr<AlloyModel> ReadModel(const nlohmann::json& doc, const std::string& source) {
  return std::make_unique<Model>(doc, source);
}

}  // namespace

const std::vector<MethodInfo>& Methods() {
  static const std::vector<MethodInfo> kMethods = {
      {"paper",
       "the paper's baseline: per-sample Drude inversion (eq. 11, 12), tau and m* "
       "interpolated linearly in composition",
       &ReadSampleModel<SampleModel::Kind::kPaper>},
      {"eps-linear", "eps interpolated linearly in composition at every wavelength",
       &ReadSampleModel<SampleModel::Kind::kEpsLinear>},
      {"eps-pchip",
       "eps1 and eps2 interpolated in composition by a monotone cubic (PCHIP) at every "
       "wavelength",
       &ReadSampleModel<SampleModel::Kind::kEpsPchip>},
      {"eps-spline",
       "eps1 and eps2 interpolated in composition by a natural cubic spline at every "
       "wavelength",
       &ReadSampleModel<SampleModel::Kind::kEpsSpline>},
      {"smooth",
       "eps1 and eps2 fitted as monotone cubic curves of composition through knots at every "
       "wavelength, a regression whose smoothing leave-one-composition-out (or, with few "
       "compositions, the marginal likelihood) chooses, or a "
       "Gaussian process across composition where leave-one-out prefers it (dense series)",
       &ReadModel<SmoothModel>},
      {"physical",
       "Ceres fit of a Drude + interband model whose parameters vary smoothly with "
       "composition",
       &ReadModel<PhysicalModel>},
  };
  return kMethods;
}

const MethodInfo* FindMethod(const std::string& name) {
  for (const MethodInfo& m : Methods()) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::string MethodNamesText() {
  std::string text;
  for (const MethodInfo& m : Methods()) text += (text.empty() ? "" : ", ") + m.name;
  return text;
}

const MethodInfo& RequireMethod(const std::string& name) {
  const MethodInfo* m = FindMethod(name);
  if (!m) throw Error("unknown method '" + name + "' (" + MethodNamesText() + ")");
  return *m;
}

}  // namespace alloycolor
