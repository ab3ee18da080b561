#include "alloycolor/model/registry.h"

#include <algorithm>
#include <mutex>

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

MethodTraits Traits(int auto_rank, double gap_exponent) {
  MethodTraits t;
  t.auto_rank = auto_rank;
  t.gap_exponent = gap_exponent;
  return t;
}

std::vector<MethodInfo> BuiltInMethods() {
  MethodTraits smooth = Traits(0, 1);
  smooth.chosen_on_one_fold = true;
  MethodTraits physical = Traits(5, 1);
  physical.validate_default = false;  // minutes per split on a large set
  physical.warm_start_folds = true;
  physical.chooses_degree = true;
  return {
      {"paper",
       "the paper's baseline: per-sample Drude inversion (eq. 11, 12), tau and m* "
       "interpolated linearly in composition",
       &ReadSampleModel<SampleModel::Kind::kPaper>, nullptr, Traits(4, 2)},
      {"eps-linear", "eps interpolated linearly in composition at every wavelength",
       &ReadSampleModel<SampleModel::Kind::kEpsLinear>, nullptr, Traits(2, 2)},
      {"eps-pchip",
       "eps1 and eps2 interpolated in composition by a monotone cubic (PCHIP) at every "
       "wavelength",
       &ReadSampleModel<SampleModel::Kind::kEpsPchip>, nullptr, Traits(1, 1)},
      {"eps-spline",
       "eps1 and eps2 interpolated in composition by a natural cubic spline at every "
       "wavelength",
       &ReadSampleModel<SampleModel::Kind::kEpsSpline>, nullptr, Traits(3, 1)},
      {"smooth",
       "eps1 and eps2 fitted as monotone cubic curves of composition through knots at every "
       "wavelength, a regression whose smoothing leave-one-composition-out (or, with few "
       "compositions, the marginal likelihood) chooses, or a "
       "Gaussian process across composition where leave-one-out prefers it (dense series)",
       &ReadModel<SmoothModel>, nullptr, smooth},
      {"physical",
       "Ceres fit of a Drude + interband model whose parameters vary smoothly with "
       "composition",
       &ReadModel<PhysicalModel>, nullptr, physical},
  };
}

// The registry: the built-in methods, then those registered. Registration is rare and
// happens before concurrent use; the mutex keeps two registrations from mixing.
struct Registry {
  std::mutex mutex;
  std::vector<MethodInfo> methods = BuiltInMethods();
};

Registry& TheRegistry() {
  static Registry registry;
  return registry;
}

}  // namespace

const std::vector<MethodInfo>& Methods() { return TheRegistry().methods; }

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

void RegisterMethod(MethodInfo info) {
  if (info.name.empty() || info.name == "auto" || info.name == "all") {
    throw Error("a method needs a name other than '" + info.name + "'");
  }
  if (info.read == nullptr) throw Error("method '" + info.name + "': no model file reader");
  Registry& registry = TheRegistry();
  const std::lock_guard<std::mutex> lock(registry.mutex);
  for (MethodInfo& m : registry.methods) {
    if (m.name == info.name) {
      m = std::move(info);
      return;
    }
  }
  registry.methods.push_back(std::move(info));
}

std::vector<std::string> DefaultValidationMethods() {
  std::vector<std::string> names;
  for (const MethodInfo& m : Methods()) {
    if (m.traits.validate_default) names.push_back(m.name);
  }
  return names;
}

std::vector<const MethodInfo*> AutoCandidates() {
  std::vector<const MethodInfo*> candidates;
  for (const MethodInfo& m : Methods()) {
    if (m.traits.auto_rank >= 0) candidates.push_back(&m);
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const MethodInfo* a, const MethodInfo* b) {
                     return a->traits.auto_rank < b->traits.auto_rank;
                   });
  return candidates;
}

}  // namespace alloycolor
