// The bindings of held-out validation (validate::ComputeValidation and its reports).
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include "alloycolor/core/error.h"
#include "alloycolor/core/output.h"
#include "alloycolor/core/setting.h"
#include "alloycolor/fit/lineage.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/registry.h"
#include "alloycolor/validate/report.h"
#include "alloycolor/validate/validation.h"
#include "bindings.h"

namespace alloycolor::python {

void BindValidate(py::module_& m) {
  m.def("_validate",
        [](const Dataset& dataset, const std::vector<std::string>& methods,
           const std::vector<std::string>& holdout, const std::string& mode,
           const std::vector<double>& angles_deg, const std::string& illuminant, int observer_deg,
           const std::string& html_path, const std::string& json_path, const py::object& progress,
           OutputGuard& guard) {
          for (const std::string& method : methods) {
            if (method != fit::kAutoMethod) RequireMethod(method);
          }
          for (double a : angles_deg) CheckAngleDeg("angles_deg", a);
          // Before the work: no report replaces an input, a symlink or a device.
          for (const std::string* path : {&html_path, &json_path}) {
            if (!path->empty()) CheckOutputPath(*path, &guard);
          }
          // As `alloycolor validate`: no names, leave each interior composition out (with
          // its replicates); otherwise one split of files and compositions.
          std::vector<validate::SampleSplit> splits;
          if (holdout.empty()) {
            splits = validate::LeaveOneOutSplits(dataset);
          } else {
            try {
              splits = {validate::HoldoutSplit(dataset, holdout)};
            } catch (const Error& e) {
              throw Error(std::string("holdout: ") + e.what());
            }
          }
          validate::ValidationOptions options;
          // As `alloycolor validate`: fits score colour under D65, 2 degrees.
          const color::Colorimeter& d65 = GetColorimeter("D65", 2);
          ThreadBudget threads;  // every core, as the program's default
          options.threads = &threads;
          options.methods = methods;
          options.angles_deg = angles_deg;
          options.mode = mode;
          const ProgressCallback python_progress = PythonProgress(progress);
          nlohmann::json json;
          RunInterruptible([&](const CancelCheck& cancel) {
            const ProgressCallback callback = WithCancel(python_progress, cancel);
            options.details = callback;  // a Python caller gets every split's line too
            options.cancel = cancel;
            options.build = fit::SharedFitBuilder(d65, &threads, cancel);
            options.fit_whole = fit::WholeDataSetFitter(d65, &threads, cancel);  // the opening
            const color::Colorimeter& colorimeter = GetColorimeter(illuminant, observer_deg);
            const validate::ValidationReport report =
                validate::ComputeValidation(dataset, splits, colorimeter, options, callback);
            json = validate::ValidationJson(report);
            std::vector<OutputFile> files;
            if (!html_path.empty()) files.push_back({html_path, validate::ValidationHtml(report)});
            if (!json_path.empty()) files.push_back({json_path, JsonText(json, 2) + "\n"});
            cancel();
            if (!files.empty()) WriteFileSetAtomic(files, &guard);
          });
          return JsonToPython(json);
        });
}

}  // namespace alloycolor::python
