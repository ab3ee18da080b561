// The compiled part of the `alloycolor` Python package (module alloycolor._alloycolor).
//
// A thin pybind11 layer over the libraries: every number comes from the same C++ code the
// command-line program runs (core readers and data sets, fit::BuildModel, the colour chain
// of color/, validate::ComputeValidation, render::Renderer, export/). The pure-Python
// wrapper in python/alloycolor/__init__.py adds numpy broadcasting and the data root.
// Long work (fits, validation, colours, matches, pictures, pages, exports) runs without
// the GIL on a thread of its own (RunInterruptible) while the caller's thread runs Python's
// signal handlers: Ctrl-C stops the work at its next step (the library's CancelCheck,
// core/progress.h) and raises KeyboardInterrupt, nothing written; a progress callback,
// when given, is called with the GIL held again. alloycolor::Error
// becomes the Python exception alloycolor.Error (a ValueError) with the same message, but
// for the command-line spellings some library messages still carry (--extrapolate,
// --smoothing, --columns N,K), which are put in the package's words (PythonWords).
// Every call that writes is handed an OutputGuard (_OutputGuard, made by the package for
// that call: core/output.h) holding the call's inputs as the program's guard holds a
// command's: the colour tables, the data set's manifest and samples, the model file read
// (m = load_model(p); m.save(p) is refused, as `fit --refit M --out M` is), a spectrum's
// file; an output that is one of them, a symlink, a device or a FIFO is refused before
// anything is written, and files written as a set (write_spd's eta and k) are refused
// when two are one file.
//
// One file per topic, each adding its functions and classes to the module (module.cc
// calls them in order): helpers.cc (what every topic shares: the data root, colorimeters,
// arrays, progress, JSON, the package's words), registry.cc (methods and their options),
// data.cc (n,k files, spectra, data sets), model.cc (fits, model files, the model class
// and its optics), colour.cc (colours, colour to composition, tolerance windows),
// outputs.cc (pictures, spectra and renderer files), validate.cc (held-out validation).
#ifndef ALLOYCOLOR_PYTHON_BINDINGS_H_
#define ALLOYCOLOR_PYTHON_BINDINGS_H_

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/core/setting.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::python {

namespace py = pybind11;

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
using SpectrumClass = py::class_<NkSpectrum>;
using ModelClass = py::class_<AlloyModel, std::shared_ptr<AlloyModel>>;

// ---- shared by every topic (helpers.cc) ---------------------------------------------------

// The folder of the bundled data and the CIE tables, set once by the package at import.
void SetDataRoot(const std::string& root);
const std::string& DataRootSetting();  // empty until set

// Colorimeters are loaded once per (illuminant, observer) and kept: they are immutable.
const color::Colorimeter& GetColorimeter(const std::string& illuminant, int observer_deg);

std::vector<double> ToVector(const Array& a);
Array ToArray(const std::vector<double>& v);

// A progress callback for the library that calls a Python callable with the GIL held.
ProgressCallback PythonProgress(const py::object& callback);

// Runs work(cancel) without the GIL on a thread of its own while the calling thread waits
// for it, running Python's signal handlers (PyErr_CheckSignals, with the GIL) every 20 ms.
// When a handler raises (Ctrl-C: KeyboardInterrupt), `cancel` throws Cancelled at the
// work's next check, the work unwinds (its temporaries removed: nothing is written) and
// the handler's exception is raised here once the work has stopped. An exception of the
// work itself (an Error, a progress callback's) is rethrown here. Called with the GIL.
// Work known to be short (`short_work`: a few colours) runs on the calling thread, without
// the GIL, its cancel check empty: a thread of its own would cost more than the work.
void RunInterruptible(const std::function<void(const CancelCheck& cancel)>& work,
                      bool short_work = false);

// `progress` (which may be empty) after `cancel`: a progress line is a step of the work.
ProgressCallback WithCancel(ProgressCallback progress, CancelCheck cancel);

py::object JsonToPython(const nlohmann::json& doc);

// A library message in the package's words: the command-line spellings of settings that
// the library's messages still name replaced by the keywords of this package.
std::string PythonWords(std::string message);

// A method option's value from Python: a bool, a number (int or float) or text (registry.cc).
OptionValue OptionFromPython(const py::handle& value);
OptionValues OptionsFromPython(const py::dict& options);

// ---- the topics, in the order module.cc adds them -----------------------------------------

void BindErrors(py::module_& m);                                               // helpers.cc
void BindRegistry(py::module_& m);                                             // registry.cc
SpectrumClass BindData(py::module_& m);                                        // data.cc
ModelClass BindModel(py::module_& m);                                          // model.cc
void BindColour(py::module_& m, SpectrumClass& spectrum, ModelClass& model);   // colour.cc
void BindOutputs(py::module_& m, SpectrumClass& spectrum, ModelClass& model);  // outputs.cc
void BindValidate(py::module_& m);                                             // validate.cc

}  // namespace alloycolor::python

#endif  // ALLOYCOLOR_PYTHON_BINDINGS_H_
