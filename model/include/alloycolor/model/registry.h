// The one registry of methods: every model of eps(lambda, x) has an entry here, and it is
// the one place that knows a method. An entry carries its name (the "method" of the model
// file and of --method), a one-line summary, its reader from a model file, its builder
// from data (set by the fit library, which alone builds models: fit/methods.h) and its
// traits: where `auto` ranks it, the shape of its error bars, whether `validate` runs it
// by default, how its leave-one-out folds are fitted. Reading a model file, listing
// methods, `auto`'s candidates, `validate`'s defaults and every face ask the registry;
// nothing else compares method names.
//
// Adding a method: its model files (model/include/alloycolor/model/*, model/src/*), its
// builder (fit/src/builders.cc) and one entry in Methods() (model/src/registry.cc); or, from
// outside the library, RegisterMethod with the builder given.
#ifndef ALLOYCOLOR_MODEL_REGISTRY_H_
#define ALLOYCOLOR_MODEL_REGISTRY_H_

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/core/dataset.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor {

namespace fit {
struct FitSettings;  // fit/methods.h: the options a user gives any method
}

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
  // Builds the model on a data set (fit/methods.h BuildModel calls it); null for a method
  // whose builder the fit library has not attached yet (it does so before building).
  MethodBuilder build = nullptr;
  MethodTraits traits;
};

// Every method, in the order they are listed to users (registration order).
const std::vector<MethodInfo>& Methods();

// The entry for `name`, or nullptr: an unknown name is an explicit miss.
const MethodInfo* FindMethod(const std::string& name);

// "paper, eps-linear, ..." for messages and --help.
std::string MethodNamesText();

// Throws Error("unknown method 'x' (paper, eps-linear, ...)") for an unknown name.
const MethodInfo& RequireMethod(const std::string& name);

// Adds a method (a new name), or completes an entry of that name (a builder where it had
// none; the other fields as given). Registration happens before any concurrent use of the
// registry (at start-up, or in a test before its fits); references from Methods() stay
// valid until the next registration.
void RegisterMethod(MethodInfo info);

// The methods `validate` runs by default, in registry order.
std::vector<std::string> DefaultValidationMethods();

// The candidates of `auto`, simplest first.
std::vector<const MethodInfo*> AutoCandidates();

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_REGISTRY_H_
