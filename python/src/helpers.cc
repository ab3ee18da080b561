// What every topic of the bindings shares (bindings.h): the data root, the colorimeters,
// numpy arrays, progress callbacks, JSON, and the errors in the package's words.
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <optional>
#include <string_view>
#include <thread>
#include <utility>

#include "alloycolor/core/error.h"
#include "bindings.h"

namespace alloycolor::python {
namespace {

std::string& DataRootStorage() {
  static std::string root;
  return root;
}

const std::string& DataRoot() {
  if (DataRootStorage().empty()) throw Error("alloycolor: the data root is not set");
  return DataRootStorage();
}

}  // namespace

void SetDataRoot(const std::string& root) { DataRootStorage() = root; }

const std::string& DataRootSetting() { return DataRootStorage(); }

const color::Colorimeter& GetColorimeter(const std::string& illuminant, int observer_deg) {
  static std::mutex mutex;
  static std::map<std::pair<std::string, int>, std::unique_ptr<color::Colorimeter>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[{illuminant, observer_deg}];
  if (!slot) {
    slot = std::make_unique<color::Colorimeter>(
        color::Colorimeter::Load(DataRoot(), illuminant, observer_deg));
  }
  return *slot;
}

std::vector<double> ToVector(const Array& a) {
  return std::vector<double>(a.data(), a.data() + a.size());
}

Array ToArray(const std::vector<double>& v) {
  Array out(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}

ProgressCallback PythonProgress(const py::object& callback) {
  if (callback.is_none()) return {};
  auto shared = std::make_shared<py::object>(callback);
  return [shared](const std::string& message) {
    py::gil_scoped_acquire gil;
    (*shared)(message);
  };
}

void RunInterruptible(const std::function<void(const CancelCheck& cancel)>& work, bool short_work) {
  if (short_work) {
    py::gil_scoped_release release;
    work([] {});
    return;
  }
  struct State {
    std::mutex mutex;
    std::condition_variable done_changed;
    bool done = false;
    std::exception_ptr error;
    std::atomic<bool> cancelled{false};
  } state;
  const CancelCheck cancel = [&state] {
    if (state.cancelled.load(std::memory_order_relaxed)) throw Cancelled();
  };
  std::optional<py::error_already_set> interrupt;  // what a signal handler raised
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
        work(cancel);
      } catch (...) {
        state.error = std::current_exception();
      }
      const std::lock_guard<std::mutex> lock(state.mutex);
      state.done = true;
      state.done_changed.notify_all();
    });
    std::unique_lock<std::mutex> lock(state.mutex);
    constexpr auto kSignalCheck = std::chrono::milliseconds(20);
    while (!state.done_changed.wait_for(lock, kSignalCheck, [&] { return state.done; })) {
      if (interrupt) continue;
      lock.unlock();
      {
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) interrupt.emplace();  // fetches the exception
      }
      if (interrupt) state.cancelled.store(true);
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (interrupt) throw *interrupt;
  if (state.error) std::rethrow_exception(state.error);
}

ProgressCallback WithCancel(ProgressCallback progress, CancelCheck cancel) {
  return [progress = std::move(progress), cancel = std::move(cancel)](const std::string& line) {
    cancel();
    if (progress) progress(line);
  };
}

py::object JsonToPython(const nlohmann::json& doc) {
  return py::module_::import("json").attr("loads")(JsonText(doc));
}

std::string PythonWords(std::string message) {
  static constexpr std::pair<std::string_view, std::string_view> kSpellings[] = {
      {" (use --extrapolate)",
       " (the Python package evaluates a model within its training range only)"},
      {"--lambda-from/--lambda-to/--lambda-step: ", "lambda_range_nm: "},
      {"--lambda-from/--lambda-to: ", "lambda_range_nm: "},
      {"--lambda-step: ", "lambda_range_nm: step: "},
      {"--smoothing: ", "smoothing: "},
      {"--space: ", "space: "},
      {"--degree: ", "degree: "},
      {"choose the columns with --columns N,K", "choose the columns with columns=(N, K)"},
      {"`alloycolor fit --method smooth`", "alloycolor.fit(data, \"smooth\")"},
  };
  for (const auto& [flag, words] : kSpellings) {
    for (std::size_t at = message.find(flag); at != std::string::npos;
         at = message.find(flag, at + words.size())) {
      message.replace(at, flag.size(), words);
    }
  }
  return message;
}

void BindErrors(py::module_& m) {
  py::register_exception<Error>(m, "Error", PyExc_ValueError);
  // Registered after, so tried first: the same exception, the message in Python's words.
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const Error& e) {
      const py::object error = py::module_::import("alloycolor._alloycolor").attr("Error");
      PyErr_SetString(error.ptr(), PythonWords(e.what()).c_str());
    }
  });
  m.def("_python_words", &PythonWords);
  m.def("_set_data_root", &SetDataRoot);
  m.def("_data_root", &DataRootSetting);
}

}  // namespace alloycolor::python
