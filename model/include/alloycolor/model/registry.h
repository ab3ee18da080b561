// The one registry of methods: every model of eps(lambda, x) has an entry here, and it is
// the one place that knows a method. An entry carries its name (the "method" of the model
// file and of --method), a one-line summary, its reader from a model file, its builder
// from data (fit/methods.h: fitting is the only place that builds a model), its traits
// (where `auto` ranks it, the shape of its error bars, whether `validate` runs it by
// default, how its leave-one-out folds are fitted) and the options it takes, each
// declared once (core/setting.h OptionSpec: name, kind, range or choices, default, help).
// Reading a model file, listing methods, `auto`'s candidates, `validate`'s defaults,
// checking a method's options and every face ask the registry; nothing else compares
// method names, and the faces' options are generated from the declarations.
//
// The registry is complete before `main` (or a Python module's import) returns: the
// built-in entries are made on first use, the fit library attaches their builders from a
// static initializer (fit/src/builders.cc), and a method from outside registers the same
// way (MethodRegistration at namespace scope). The first read seals it: from then on it
// never changes, so reading it is safe from any thread, and a later registration is an
// error rather than a race.
//
// Adding a method: its model files (model/include/alloycolor/model/*, model/src/*), its
// builder (fit/src/builders.cc) and one entry in the built-in table (model/src/registry.cc);
// or, from outside the library, one file pair holding the model, its builder and one
// MethodRegistration (tests/toy_method.cc does so; docs/architecture.md).
#ifndef ALLOYCOLOR_MODEL_REGISTRY_H_
#define ALLOYCOLOR_MODEL_REGISTRY_H_

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "alloycolor/core/dataset.h"
#include "alloycolor/core/setting.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor {

namespace fit {
struct FitSettings;  // fit/methods.h: the options given and how the fit runs
}

// `auto`, which the fit library runs over the candidates (fit/methods.h BuildAuto), and
// `all` (every method, then auto), where a face takes a list of methods: no method is
// named either.
inline constexpr const char* kAutoMethodName = "auto";
inline constexpr const char* kAllMethodsName = "all";

// What the rest of the toolkit needs to know of a method, so that nothing else asks its name.
struct MethodTraits {
  // Its place in `auto`'s order of preference: the first candidate within the folds'
  // tolerance of the lowest score wins, so rank 0 is the default that a rival displaces
  // only on the folds' evidence (the built-ins: smooth, a regression, as real data with
  // scatter favour it; then the interpolations, simplest first). Negative: not a candidate.
  int auto_rank = -1;
  // The power of the gap between neighbouring training compositions in its error bars'
  // shape B (model/alloy_model.h, PredictionError), and its most where the fit measures
  // it (wherever two neighbouring compositions can be held out together): 2 for a method
  // that interpolates linearly (its error on a smooth curve grows as h^2), 1 for the
  // others.
  double gap_exponent = 1;
  // `validate` (and Python's validate) runs it when no method is named.
  bool validate_default = true;
  // Its leave-one-out folds start from the model fitted to all samples (warm), as a
  // nonlinear fit with many local minima must.
  bool warm_start_folds = false;
  // Its fit has a composition degree that the folds choose (unless the user gives one);
  // a fold must hold degree + 2 compositions to score the model delivered.
  bool chooses_degree = false;
  // Its prediction between two neighbouring training compositions rests on theirs and this
  // many more each side alone (eps-linear 0, eps-pchip 1: its slopes at a composition are
  // its neighbours'); -1: on every composition. A fold is then fitted to those around the
  // compositions it holds out: the same model there, at a cost that does not grow with the
  // series (fit/folds.h).
  int fold_reach = -1;
  // With three compositions, `auto`'s one fold compares only the straight lines between the
  // ends; a method that chooses its own smoothing by other evidence is taken there.
  bool chosen_on_one_fold = false;
};

using MethodReader = std::unique_ptr<AlloyModel> (*)(const nlohmann::json& doc,
                                                     const std::string& source);
using MethodBuilder = std::unique_ptr<AlloyModel> (*)(const Dataset& dataset,
                                                      const fit::FitSettings& settings);

struct MethodInfo {
  std::string name;     // "smooth"
  std::string summary;  // one line, for --help
  // Reads the model from a model file's document (format and version already checked);
  // throws Error naming `source` and the field at fault.
  MethodReader read = nullptr;
  // Builds the model on a data set (fit/methods.h BuildModel calls it, its options
  // checked); for the built-in methods, attached by the fit library at start-up.
  MethodBuilder build = nullptr;
  MethodTraits traits;
  // The options it takes, each once. An option several methods take (the fit grid) is
  // declared alike by each; the registry refuses two declarations that differ.
  std::vector<OptionSpec> options;
};

// Every method, in the order they are listed to users (registration order).
const std::vector<MethodInfo>& Methods();

// The entry for `name`, or nullptr: an unknown name is an explicit miss.
const MethodInfo* FindMethod(const std::string& name);

// "paper, eps-linear, ..." for messages and --help.
std::string MethodNamesText();

// Throws Error("unknown method 'x' (paper, eps-linear, ...)") for an unknown name.
const MethodInfo& RequireMethod(const std::string& name);

// Adds a method (a new name), or replaces the entry of that name (the fit library gives the
// built-in entries their builders so). Throws Error for a reserved or empty name, a method
// without a reader, an option declared twice or unlike another method's declaration of it,
// and once the registry has been read (it is sealed then: register at start-up).
void RegisterMethod(MethodInfo info);

// Gives the entry `name` its builder, under RegisterMethod's rules (the fit library
// attaches the built-in methods' builders so, before `main`).
void AttachBuilder(const std::string& name, MethodBuilder build);

// Registers a method from a static initializer, before `main`:
//   const MethodRegistration kToy{ToyMethodInfo()};
struct MethodRegistration {
  explicit MethodRegistration(MethodInfo info) { RegisterMethod(std::move(info)); }
};

// ---- the methods' options ---------------------------------------------------------------

// An option with the methods that declare it.
struct DeclaredOption {
  OptionSpec spec;
  std::vector<std::string> methods;  // registry order
};

// Every method's options, each once, in the order first declared.
std::vector<DeclaredOption> DeclaredOptions();

// The declaration of option `name`, or nullptr when no method declares one.
const OptionSpec* FindOption(const std::string& name);

// The options `given` for `method` checked against its declarations, once, before any
// work: an option no method declares, one `method` does not take (naming the methods that
// do) and a value outside its declaration are refused with an Error naming the option as
// `spelling` spells it. For auto (kAutoMethodName) an option is taken when one of its
// candidates takes it; one only methods outside auto take is refused, naming them.
// Returns the options given plus the declared defaults of those the method (auto: any
// candidate) takes and was not given.
OptionValues CheckMethodOptions(const std::string& method, const OptionValues& given,
                                OptionSpelling spelling = OptionSpelling::kName);

// A list of methods as the faces take it: comma-separated names (auto among them), "all"
// (every method, then auto) or "" (DefaultValidationMethods); each once, in the order
// given. Throws Error naming `option` for an unknown or empty name.
std::vector<std::string> MethodList(const std::string& text, const std::string& option);

// The methods `validate` runs by default, in registry order.
std::vector<std::string> DefaultValidationMethods();

// The candidates of `auto`, simplest first.
std::vector<const MethodInfo*> AutoCandidates();

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_REGISTRY_H_
