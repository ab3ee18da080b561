#include "alloycolor/model/registry.h"

#include <algorithm>
#include <atomic>
#include <mutex>

#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"
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

// ---- the built-in methods' options ----------------------------------------------------------

std::string TermsProblem(const std::string& text) {
  if (text == "auto") return "";
  try {
    ParseInterbandTerms(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

OptionSpec Declare(const char* name, const char* flag, OptionKind kind, std::string help) {
  OptionSpec spec;
  spec.name = name;
  spec.flag = flag;
  spec.kind = kind;
  spec.help = std::move(help);
  return spec;
}

OptionSpec Number(const char* name, const char* flag, NumberRange range, std::string help) {
  OptionSpec spec =
      Declare(name, flag, range.whole ? OptionKind::kWhole : OptionKind::kNumber, std::move(help));
  spec.range = range;
  return spec;
}

// The fit grid of the fitted methods.
std::vector<OptionSpec> FitGridOptions() {
  return {
      Number("lambda_from_nm", "--lambda-from", {1, 1e6, false},
             "first wavelength of the fit grid, nm, given with the last (default: the range "
             "the samples share; physical: within 300-1000 nm, or all of it for infrared data)"),
      Number("lambda_to_nm", "--lambda-to", {1, 1e6, false},
             "last wavelength of the fit grid, nm, given with the first"),
      Number("lambda_step_nm", "--lambda-step", {0.01, 1e5, false},
             "step of the fit grid, nm, at most " + std::to_string(kMaxFitGridNodes) +
                 " nodes over its range (default 5; physical: range/200 in the infrared)"),
  };
}

std::vector<OptionSpec> SmoothOptions() {
  std::vector<OptionSpec> options = {
      Number("smoothing", "--smoothing", {0, 1e6, false},
             "weight of the roughness penalty across composition, 0 (interpolate) to 1e6 "
             "(default: chosen by leave-one-composition-out cross-validation, or with fewer "
             "than five compositions by the marginal likelihood)"),
  };
  OptionSpec space = Declare(
      "space", "--space", OptionKind::kChoice,
      "what its curves across composition describe: eps (eps1, eps2) or log_eps (ln|eps| and "
      "arg eps: geometric interpolation, for samples whose |eps| differ by orders of magnitude "
      "or one of which is not metallic) (default: log_eps where its leave-one-out error is at "
      "least a third below eps's, else eps)");
  space.choices = {"eps", "log_eps"};
  options.push_back(space);
  for (OptionSpec& grid : FitGridOptions()) options.push_back(std::move(grid));
  return options;
}

std::vector<OptionSpec> PhysicalOptions() {
  std::vector<OptionSpec> options = {
      Number("degree", "--degree", {0, kPhysicalMaxDegree, true},
             "degree of every parameter's polynomial in composition (default: 2, as Nordheim's "
             "rule bows the damping, or 1 where leave-one-composition-out finds it more than "
             "10 % and one standard error better; lowered, with a warning, where the fit "
             "leaves physics)"),
  };
  OptionSpec terms =
      Declare("terms", "--terms", OptionKind::kText,
              "interband terms: lorentz, cp (Etchegoin 2006 critical point), rioux-gap, rioux-edge "
              "(Rioux 2014); none for the Drude term alone; auto: none for infrared data, else the "
              "best of rioux-gap,rioux-edge / cp,cp / lorentz,lorentz,lorentz on the end samples");
  terms.check = &TermsProblem;
  terms.values = "auto, none, or up to " + std::to_string(kPhysicalMaxInterbandTerms) +
                 " of lorentz, cp, rioux-gap, rioux-edge, comma-separated";
  terms.default_value = OptionValue::Text("auto");
  options.push_back(terms);
  for (OptionSpec& grid : FitGridOptions()) options.push_back(std::move(grid));
  OptionSpec covariance = Declare("covariance", "--no-covariance", OptionKind::kFlag,
                                  "the parameters' covariance, computed unless turned off");
  covariance.default_value = OptionValue::Flag(true);
  options.push_back(covariance);
  return options;
}

std::vector<MethodInfo> BuiltInMethods() {
  MethodTraits smooth = Traits(0, 1);
  smooth.chosen_on_one_fold = true;
  MethodTraits linear = Traits(2, 2);
  linear.fold_reach = 0;
  MethodTraits pchip = Traits(1, 1);
  pchip.fold_reach = 1;
  MethodTraits physical = Traits(5, 1);
  physical.validate_default = false;  // minutes per split on a large set
  physical.warm_start_folds = true;
  physical.chooses_degree = true;
  return {
      {"paper",
       "the paper's baseline: per-sample Drude inversion (eq. 11, 12), tau and m* "
       "interpolated linearly in composition",
       &ReadSampleModel<SampleModel::Kind::kPaper>,
       nullptr,
       Traits(4, 2),
       {}},
      {"eps-linear",
       "eps interpolated linearly in composition at every wavelength",
       &ReadSampleModel<SampleModel::Kind::kEpsLinear>,
       nullptr,
       linear,
       {}},
      {"eps-pchip",
       "eps1 and eps2 interpolated in composition by a monotone cubic (PCHIP) at every "
       "wavelength",
       &ReadSampleModel<SampleModel::Kind::kEpsPchip>,
       nullptr,
       pchip,
       {}},
      {"eps-spline",
       "eps1 and eps2 interpolated in composition by a natural cubic spline at every "
       "wavelength",
       &ReadSampleModel<SampleModel::Kind::kEpsSpline>,
       nullptr,
       Traits(3, 1),
       {}},
      {"smooth",
       "eps1 and eps2 fitted as monotone cubic curves of composition through knots at every "
       "wavelength, a regression whose smoothing leave-one-composition-out (or, with few "
       "compositions, the marginal likelihood) chooses, or a "
       "Gaussian process across composition where leave-one-out prefers it (dense series)",
       &ReadModel<SmoothModel>, nullptr, smooth, SmoothOptions()},
      {"physical",
       "Ceres fit of a Drude + interband model whose parameters vary smoothly with "
       "composition",
       &ReadModel<PhysicalModel>, nullptr, physical, PhysicalOptions()},
  };
}

// ---- the registry -----------------------------------------------------------------------------

void CheckDeclarations(const std::vector<MethodInfo>& methods, const MethodInfo& info) {
  for (size_t i = 0; i < info.options.size(); ++i) {
    const OptionSpec& spec = info.options[i];
    if (spec.name.empty() || spec.flag.rfind("--", 0) != 0) {
      throw Error("method '" + info.name + "': an option needs a name and a --flag");
    }
    for (size_t j = 0; j < i; ++j) {
      if (info.options[j].name == spec.name || info.options[j].flag == spec.flag) {
        throw Error("method '" + info.name + "': option '" + spec.name + "' declared twice");
      }
    }
    for (const MethodInfo& m : methods) {
      if (m.name == info.name) continue;
      for (const OptionSpec& other : m.options) {
        if ((other.name == spec.name || other.flag == spec.flag) && !SameDeclaration(other, spec)) {
          throw Error("method '" + info.name + "': option '" + spec.name +
                      "' is declared otherwise by method '" + m.name +
                      "' (an option has one declaration)");
        }
      }
    }
  }
}

// The registry: the built-in methods, then those registered at start-up. It is sealed by
// its first read; a registration takes the mutex and finds it unsealed, and the first read
// takes the mutex once to seal it, so no read overlaps a registration.
struct Registry {
  std::mutex mutex;
  std::atomic<bool> sealed{false};
  std::vector<MethodInfo> methods = BuiltInMethods();
};

Registry& TheRegistry() {
  static Registry registry;
  return registry;
}

const std::vector<MethodInfo>& SealedMethods() {
  Registry& registry = TheRegistry();
  if (!registry.sealed.load(std::memory_order_acquire)) {
    const std::lock_guard<std::mutex> lock(registry.mutex);
    registry.sealed.store(true, std::memory_order_release);
  }
  return registry.methods;
}

void CheckUnsealed(const Registry& registry, const std::string& name) {
  if (registry.sealed.load(std::memory_order_acquire)) {
    throw Error("method '" + name +
                "': registered after the registry was first read; register methods at "
                "start-up (MethodRegistration)");
  }
}

std::string Joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

}  // namespace

const std::vector<MethodInfo>& Methods() { return SealedMethods(); }

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
  if (info.name.empty() || info.name == kAutoMethodName || info.name == kAllMethodsName ||
      info.name.find(',') != std::string::npos) {
    throw Error("a method needs a name other than '" + info.name + "'");
  }
  if (info.read == nullptr) throw Error("method '" + info.name + "': no model file reader");
  Registry& registry = TheRegistry();
  const std::lock_guard<std::mutex> lock(registry.mutex);
  CheckUnsealed(registry, info.name);
  CheckDeclarations(registry.methods, info);
  for (MethodInfo& m : registry.methods) {
    if (m.name == info.name) {
      m = std::move(info);
      return;
    }
  }
  registry.methods.push_back(std::move(info));
}

void AttachBuilder(const std::string& name, MethodBuilder build) {
  Registry& registry = TheRegistry();
  const std::lock_guard<std::mutex> lock(registry.mutex);
  CheckUnsealed(registry, name);
  for (MethodInfo& m : registry.methods) {
    if (m.name == name) {
      m.build = build;
      return;
    }
  }
  throw Error("no method '" + name + "' to attach a builder to");
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

// ---- options ------------------------------------------------------------------------------------

std::vector<DeclaredOption> DeclaredOptions() {
  std::vector<DeclaredOption> options;
  for (const MethodInfo& m : Methods()) {
    for (const OptionSpec& spec : m.options) {
      auto it = std::find_if(options.begin(), options.end(),
                             [&](const DeclaredOption& o) { return o.spec.name == spec.name; });
      if (it == options.end()) it = options.insert(options.end(), {spec, {}});
      it->methods.push_back(m.name);
    }
  }
  return options;
}

const OptionSpec* FindOption(const std::string& name) {
  for (const MethodInfo& m : Methods()) {
    for (const OptionSpec& spec : m.options) {
      if (spec.name == name) return &spec;
    }
  }
  return nullptr;
}

OptionValues CheckMethodOptions(const std::string& method, const OptionValues& given,
                                OptionSpelling spelling) {
  const bool is_auto = method == kAutoMethodName;
  std::vector<const MethodInfo*> takers;  // the methods whose options apply
  if (is_auto) {
    takers = AutoCandidates();
  } else {
    takers = {&RequireMethod(method)};
  }
  const auto taken_by = [&takers](const std::string& name) -> const OptionSpec* {
    for (const MethodInfo* m : takers) {
      for (const OptionSpec& spec : m->options) {
        if (spec.name == name) return &spec;
      }
    }
    return nullptr;
  };
  const std::vector<DeclaredOption> declared = DeclaredOptions();
  for (const auto& [name, value] : given.all()) {
    const auto it = std::find_if(declared.begin(), declared.end(),
                                 [&](const DeclaredOption& o) { return o.spec.name == name; });
    if (it == declared.end()) {
      std::vector<std::string> known;
      for (const DeclaredOption& o : declared) known.push_back(Spelled(o.spec, spelling));
      throw Error(Quote(name) + ": no method takes this option (" + Joined(known) + ")");
    }
    const std::string& spelled = Spelled(it->spec, spelling);
    if (taken_by(name) == nullptr) {
      throw Error(spelled + ": an option of " + Joined(it->methods) + "; " +
                  (is_auto ? "auto does not run " +
                                 std::string(it->methods.size() == 1 ? "it" : "them") +
                                 " (not one of its candidates)"
                           : method + " does not take it"));
    }
    if (const std::string problem = OptionProblem(it->spec, value); !problem.empty()) {
      throw Error(spelled + ": " + problem);
    }
  }
  OptionValues checked = given;
  for (const MethodInfo* m : takers) {
    for (const OptionSpec& spec : m->options) {
      if (spec.default_value && !checked.Has(spec.name)) {
        checked.Set(spec.name, *spec.default_value);
      }
    }
  }
  return checked;
}

std::vector<std::string> MethodList(const std::string& text, const std::string& option) {
  std::vector<std::string> names;
  if (Trim(text).empty()) {
    names = DefaultValidationMethods();
  } else if (Trim(text) == kAllMethodsName) {
    for (const MethodInfo& m : Methods()) names.push_back(m.name);
    names.push_back(kAutoMethodName);
  } else {
    std::string_view rest = text;
    for (std::size_t comma; (comma = rest.find(',')) != rest.npos; rest.remove_prefix(comma + 1)) {
      names.emplace_back(Trim(rest.substr(0, comma)));
    }
    names.emplace_back(Trim(rest));
  }
  std::vector<std::string> methods;
  for (const std::string& name : names) {
    if (name.empty()) throw Error(option + ": empty method name in " + Quote(text));
    if (name != kAutoMethodName) {
      try {
        RequireMethod(name);
      } catch (const Error& e) {
        throw Error(option + ": " + e.what());
      }
    }
    if (std::find(methods.begin(), methods.end(), name) == methods.end()) methods.push_back(name);
  }
  if (methods.empty()) throw Error(option + ": no method given");
  return methods;
}

}  // namespace alloycolor
