// The bindings of the method registry and the library's checks of settings.
#include "alloycolor/model/registry.h"

#include <pybind11/stl.h>

#include "alloycolor/core/setting.h"
#include "bindings.h"

namespace alloycolor::python {

void BindRegistry(py::module_& m) {
  m.attr("_max_fit_grid_nodes") = kMaxFitGridNodes;
  // The library's check of a number against a range, named as the caller gave it.
  m.def("_check_number",
        [](const std::string& name, double value, double lo, double hi, bool whole) {
          CheckNumber(name, value, NumberRange{lo, hi, whole});
        });

  // The library's checks of the fit's numeric settings, by their names ("degree", ...).
  // `label` is the keyword the value was given as ("degree", "lambda_range_nm[2] (step)").
  m.def("_check_fit_setting",
        [](const std::string& setting, double value, const std::string& label) {
          CheckNumber(label, value, FitSettingRange(setting));
        });

  m.def("methods", []() {
    py::list out;
    for (const MethodInfo& info : Methods()) {
      py::dict d;
      d["name"] = info.name;
      d["summary"] = info.summary;
      d["auto_rank"] = info.traits.auto_rank;
      d["validate_default"] = info.traits.validate_default;
      out.append(d);
    }
    return out;
  });
}

}  // namespace alloycolor::python
