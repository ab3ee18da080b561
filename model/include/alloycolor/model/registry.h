// The one registry of methods: every model of eps(lambda, x) has an entry here with its
// name (the "method" of the model file and of --method), a one-line summary, and its
// reader from a model file. Reading a model file, listing methods in --help and checking a
// method name all go through it; the builders (fitting a model to data) are registered
// beside it in fit/methods.h under the same names.
//
// Adding a method: its own model files (model/include/alloycolor/model/*, model/src/*),
// one entry in Methods() (model/src/registry.cc) and one builder in fit/src/methods.cc.
#ifndef ALLOYCOLOR_MODEL_REGISTRY_H_
#define ALLOYCOLOR_MODEL_REGISTRY_H_

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "alloycolor/model/alloy_model.h"

namespace alloycolor {

struct MethodInfo {
  std::string name;     // "smooth"
  std::string summary;  // one line, for --help
  // Reads the model from a model file's document (format and version already checked);
  // throws Error naming `source` and the field at fault.
  std::unique_ptr<AlloyModel> (*read)(const nlohmann::json& doc, const std::string& source);
};

// Every method, in the order they are listed to users.
const std::vector<MethodInfo>& Methods();

// The entry for `name`, or nullptr: an unknown name is an explicit miss.
const MethodInfo* FindMethod(const std::string& name);

// "paper, eps-linear, ..." for messages and --help.
std::string MethodNamesText();

// Throws Error("unknown method 'x' (paper, eps-linear, ...)") for an unknown name.
const MethodInfo& RequireMethod(const std::string& name);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_REGISTRY_H_
