// The bindings of models: fits (fit::BuildModel), model files, the model class and its
// optical constants.
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <complex>
#include <utility>

#include "alloycolor/color/suggest.h"
#include "alloycolor/core/composition.h"
#include "alloycolor/core/output.h"
#include "alloycolor/core/permittivity.h"
#include "alloycolor/core/text.h"
#include "alloycolor/fit/lineage.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/registry.h"
#include "bindings.h"

namespace alloycolor::python {
namespace {

// The most values (compositions times wavelengths) computed on the calling thread: work
// of well under a millisecond (bindings.h RunInterruptible).
constexpr std::size_t kShortWork = 4096;

// result[i, j] at x[i], lambda_nm[j]: the index N = n + ik (eq. 13, 14) or eps itself.
py::array_t<std::complex<double>> ModelOptics(const AlloyModel& model, const Array& x_in,
                                              const Array& lambda_in, bool index) {
  const std::vector<double> xs = ToVector(x_in), lambda_nm = ToVector(lambda_in);
  for (double x : xs) model.CheckInRange(x);
  py::array_t<std::complex<double>> out(
      {static_cast<py::ssize_t>(xs.size()), static_cast<py::ssize_t>(lambda_nm.size())});
  std::complex<double>* data = out.mutable_data();
  RunInterruptible(
      [&](const CancelCheck& cancel) {
        const std::unique_ptr<BoundModel> bound = model.Bind(lambda_nm);
        std::vector<double> eps1(lambda_nm.size()), eps2(lambda_nm.size());
        for (std::size_t i = 0; i < xs.size(); ++i) {
          if (i % 256 == 0) cancel();
          bound->Permittivity(xs[i], eps1.data(), eps2.data());
          for (std::size_t j = 0; j < lambda_nm.size(); ++j) {
            const Complex<double> e{eps1[j], eps2[j]};
            const Complex<double> v = index ? IndexFromPermittivity(e) : e;
            data[i * lambda_nm.size() + j] = {v.re, v.im};
          }
        }
      },
      xs.size() * lambda_nm.size() <= kShortWork);
  return out;
}

}  // namespace

ModelClass BindModel(py::module_& m) {
  m.def("_fit", [](const Dataset& dataset, const std::string& method, const py::dict& options,
                   const py::object& progress, const std::shared_ptr<AlloyModel>& previous) {
    fit::FitSettings settings;
    ThreadBudget threads;  // every core, as the program's default
    settings.threads = &threads;
    settings.options = OptionsFromPython(options);
    const ProgressCallback python_progress = PythonProgress(progress);
    // As `alloycolor fit`: auto and the sigma calibration score colour under D65, 2 degrees.
    settings.colorimeter = &GetColorimeter("D65", 2);
    // As `alloycolor fit` (--refit): the samples checked, the lineage recorded.
    const fit::FitRecord record{previous.get(), NowUtcIso8601()};
    settings.start = previous && previous->method() == method ? previous.get() : nullptr;
    std::unique_ptr<AlloyModel> model;
    RunInterruptible([&](const CancelCheck& cancel) {
      settings.progress = WithCancel(python_progress, cancel);
      settings.cancel = cancel;
      model = fit::FitDataSet(method, dataset, settings, record);
    });
    return std::shared_ptr<AlloyModel>(std::move(model));
  });

  m.def("_load_model",
        [](const std::string& path) { return std::shared_ptr<AlloyModel>(ReadModelFile(path)); });

  ModelClass model(m, "_Model");
  model.def_property_readonly("method", &AlloyModel::method)
      .def_property_readonly("system", [](const AlloyModel& a) { return a.system().Name(); })
      .def_property_readonly("composition", &AlloyModel::composition)
      .def_property_readonly("x_min", &AlloyModel::x_min)
      .def_property_readonly("x_max", &AlloyModel::x_max)
      .def_property_readonly("lambda_min_nm", &AlloyModel::lambda_min_nm)
      .def_property_readonly("lambda_max_nm", &AlloyModel::lambda_max_nm)
      .def_property_readonly("warnings", &AlloyModel::warnings)
      .def_property_readonly("has_uncertainty", &AlloyModel::HasUncertainty)
      .def_property_readonly("no_error_bar", &AlloyModel::NoErrorBarReason)
      .def("_suggest",
           [](const AlloyModel& a, int count, const std::string& rule,
              const std::string& illuminant, int observer) {
             color::SuggestOptions options;
             options.count = count;
             options.rule = color::ParseSuggestRule(rule);
             const color::Colorimeter& cm = GetColorimeter(illuminant, observer);
             color::SuggestResult r;
             RunInterruptible([&](const CancelCheck& cancel) {
               ThreadBudget threads;
               options.threads = &threads;
               options.cancel = cancel;
               r = color::SuggestCompositions(cm, a, options);
             });
             py::list out;
             for (const color::Suggestion& s : r.suggestions) {
               py::dict d;
               d["x"] = s.x_atomic;
               d["x_given"] = a.composition() == "weight_fraction_a"
                                  ? WeightFromAtomicFraction(s.x_atomic, a.system())
                                  : s.x_atomic;
               d[r.metric == "relative_eps" ? "sigma_relative_eps" : "sigma_de00"] = s.sigma;
               d["max_sigma_before"] = s.max_sigma_before;
               d["max_sigma_after"] = s.max_sigma_after;
               d["mean_sigma_before"] = s.mean_sigma_before;
               d["mean_sigma_after"] = s.mean_sigma_after;
               d["rule"] = r.rule;
               out.append(d);
             }
             return out;
           })
      .def_property_readonly("training_x",
                             [](const AlloyModel& a) {
                               std::vector<double> xs;
                               for (const auto& s : a.training_samples()) xs.push_back(s.x_atomic);
                               return ToArray(xs);
                             })
      .def("to_json", [](const AlloyModel& a) { return JsonToPython(a.ToJson()); })
      .def("_save", [](const AlloyModel& a, const std::string& path,
                       OutputGuard& guard) { WriteFileAtomic(path, ModelFileText(a), &guard); })
      .def("parse_composition",
           [](const AlloyModel& a, const std::string& text) {
             return ParseComposition(text, a.system());
           })
      .def("_optics", &ModelOptics);
  return model;
}

}  // namespace alloycolor::python
