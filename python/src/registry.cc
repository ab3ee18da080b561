// The bindings of the method registry: the methods, their options as declared (from which
// the package's keywords, its stubs and docs/methods.md's table are generated) and the
// library's checks of settings.
#include "alloycolor/model/registry.h"

#include <pybind11/stl.h>

#include <map>

#include "alloycolor/color/match.h"
#include "alloycolor/color/suggest.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/setting.h"
#include "bindings.h"

namespace alloycolor::python {
namespace {

const char* KindName(OptionKind kind) {
  switch (kind) {
    case OptionKind::kWhole:
      return "whole";
    case OptionKind::kNumber:
      return "number";
    case OptionKind::kChoice:
      return "choice";
    case OptionKind::kText:
      return "text";
    case OptionKind::kFlag:
      return "flag";
  }
  return "?";
}

py::object ValueToPython(const OptionValue& value) {
  switch (value.type) {
    case OptionValue::Type::kNumber:
      return py::float_(value.number);
    case OptionValue::Type::kText:
      return py::str(value.text);
    case OptionValue::Type::kFlag:
      return py::bool_(value.flag);
  }
  return py::none();
}

py::dict OptionDict(const DeclaredOption& declared) {
  const OptionSpec& spec = declared.spec;
  py::dict d;
  d["name"] = spec.name;
  d["flag"] = spec.flag;
  d["kind"] = KindName(spec.kind);
  d["range"] = spec.kind == OptionKind::kWhole || spec.kind == OptionKind::kNumber
                   ? py::object(py::make_tuple(spec.range.lo, spec.range.hi))
                   : py::object(py::none());
  d["choices"] = spec.choices;
  d["values"] = OptionValuesText(spec);
  d["default"] = spec.default_value ? ValueToPython(*spec.default_value) : py::none();
  d["help"] = spec.help;
  d["methods"] = declared.methods;
  return d;
}

}  // namespace

OptionValue OptionFromPython(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return OptionValue::Flag(value.cast<bool>());
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
    return OptionValue::Number(value.cast<double>());
  }
  if (py::isinstance<py::str>(value)) return OptionValue::Text(value.cast<std::string>());
  return OptionValue::Text(py::str(py::repr(value)).cast<std::string>());
}

OptionValues OptionsFromPython(const py::dict& options) {
  OptionValues values;
  for (const auto& [name, value] : options) {
    values.Set(name.cast<std::string>(), OptionFromPython(value));
  }
  return values;
}

void BindRegistry(py::module_& m) {
  m.def("methods", []() {
    py::list out;
    for (const MethodInfo& info : Methods()) {
      py::dict d;
      d["name"] = info.name;
      d["summary"] = info.summary;
      d["auto_rank"] = info.traits.auto_rank;
      d["validate_default"] = info.traits.validate_default;
      py::list options;
      for (const OptionSpec& spec : info.options) options.append(spec.name);
      d["options"] = options;
      out.append(d);
    }
    return out;
  });

  // Every method's options as declared, each once (DeclaredOptions).
  m.def("_method_options", []() {
    py::list out;
    for (const DeclaredOption& declared : DeclaredOptions()) out.append(OptionDict(declared));
    return out;
  });

  // One option's value checked against its declaration, named `label` (the keyword it was
  // given as: "degree", "lambda_range_nm[2] (step)"); a number as Python spells it, so that
  // the words are the program's for that text (OptionTextProblem: NaN too).
  m.def("_check_option",
        [](const std::string& name, const py::object& value, const std::string& label) {
          const OptionSpec* spec = FindOption(name);
          if (spec == nullptr) throw Error(label + ": no method takes this option");
          const OptionValue given = OptionFromPython(value);
          const std::string problem =
              given.type == OptionValue::Type::kNumber &&
                      (spec->kind == OptionKind::kWhole || spec->kind == OptionKind::kNumber)
                  ? OptionTextProblem(*spec, py::str(py::repr(value)).cast<std::string>())
                  : OptionProblem(*spec, given);
          if (!problem.empty()) throw Error(label + ": " + problem);
        });

  // A setting of match, tolerance or suggest, given as Python spells it, checked against
  // the range every face takes for it, in the program's words for the same text.
  m.def("_check_setting", [](const std::string& name, const std::string& text) {
    static const std::map<std::string, NumberRange> kRanges = {
        {"target_sigma", color::kTargetSigmaRange},
        {"margin", color::kMatchMarginRange},
        {"de", color::kToleranceDeRange},
        {"count", color::kSuggestCountRange},
    };
    const std::string problem = NumberProblem(text, kRanges.at(name));
    if (!problem.empty()) throw Error(name + ": " + problem);
  });

  // The library's check of a number against a range, named as the caller gave it.
  m.def("_check_number",
        [](const std::string& name, double value, double lo, double hi, bool whole) {
          CheckNumber(name, value, NumberRange{lo, hi, whole});
        });

  // A list of methods as `validate` takes it (MethodList): names, "all" or "".
  m.def("_method_list", &MethodList);
}

}  // namespace alloycolor::python
