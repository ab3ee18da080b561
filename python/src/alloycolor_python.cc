// The compiled part of the `alloycolor` Python package (module alloycolor._alloycolor).
//
// A thin pybind11 layer over the libraries: every number comes from the same C++ code the
// command-line program runs (core readers and data sets, fit::BuildModel, the colour chain
// of color/, validate::ComputeValidation, render::Renderer, export/). The pure-Python
// wrapper in python/alloycolor/__init__.py adds numpy broadcasting and the data root.
// Long work (fits, validation, large colour arrays, rendering) runs without the GIL; a
// progress callback, when given, is called with the GIL held again. alloycolor::Error
// becomes the Python exception alloycolor.Error (a ValueError) with the same message, but
// for the command-line spellings some library messages still carry (--extrapolate,
// --smoothing, --columns N,K), which are put in the package's words (PythonWords).
// Nothing here keeps an OutputGuard: the package notes no inputs (m = load_model(p);
// m.save(p) replaces the file, atomically), and files written as a set (write_spd's eta
// and k) are refused when two are one file.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <complex>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/match.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/color/sweep.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/output.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/permittivity.h"
#include "alloycolor/core/setting.h"
#include "alloycolor/export/export_files.h"
#include "alloycolor/export/spectral_export.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/registry.h"
#include "alloycolor/render/image.h"
#include "alloycolor/render/renderer.h"
#include "alloycolor/validate/report.h"
#include "alloycolor/validate/validation.h"

namespace py = pybind11;

namespace alloycolor::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::string& DataRootStorage() {
  static std::string root;
  return root;
}

const std::string& DataRoot() {
  if (DataRootStorage().empty()) throw Error("alloycolor: the data root is not set");
  return DataRootStorage();
}

// Colorimeters are loaded once per (illuminant, observer) and kept: they are immutable.
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

// A progress callback for the library that calls a Python callable with the GIL held.
ProgressCallback PythonProgress(const py::object& callback) {
  if (callback.is_none()) return {};
  auto shared = std::make_shared<py::object>(callback);
  return [shared](const std::string& message) {
    py::gil_scoped_acquire gil;
    (*shared)(message);
  };
}

void CheckAngle(double angle_deg) {
  if (!(angle_deg >= 0.0 && angle_deg <= 90.0)) {
    throw Error("angle_deg: " + std::to_string(angle_deg) + " lies outside 0-90 degrees");
  }
}

// ---- colour ----------------------------------------------------------------------------

struct ColorArrays {
  py::array_t<double> xyz, lab, linear_srgb, paper_rgb, sigma;
  py::array_t<std::uint8_t> srgb8;
};

py::dict ColorDict(ColorArrays& c, bool with_sigma) {
  py::dict d;
  d["xyz"] = c.xyz;
  d["lab"] = c.lab;
  d["linear_srgb"] = c.linear_srgb;
  d["srgb8"] = c.srgb8;
  d["paper_rgb"] = c.paper_rgb;
  d["sigma"] = with_sigma ? py::object(c.sigma) : py::object(py::none());
  return d;
}

ColorArrays MakeColorArrays(py::ssize_t count) {
  ColorArrays c;
  c.xyz = py::array_t<double>({count, py::ssize_t{3}});
  c.lab = py::array_t<double>({count, py::ssize_t{3}});
  c.linear_srgb = py::array_t<double>({count, py::ssize_t{3}});
  c.paper_rgb = py::array_t<double>({count, py::ssize_t{3}});
  c.srgb8 = py::array_t<std::uint8_t>({count, py::ssize_t{3}});
  c.sigma = py::array_t<double>(count);
  return c;
}

struct ColorPointers {
  double *xyz, *lab, *lin, *paper, *sigma;
  std::uint8_t* srgb8;
};

ColorPointers Pointers(ColorArrays& c) {
  return {c.xyz.mutable_data(),       c.lab.mutable_data(),   c.linear_srgb.mutable_data(),
          c.paper_rgb.mutable_data(), c.sigma.mutable_data(), c.srgb8.mutable_data()};
}

void Store(const color::ColorResult& r, std::size_t i, const ColorPointers& p) {
  const double xyz[3] = {r.xyz.X, r.xyz.Y, r.xyz.Z};
  const double lab[3] = {r.lab.L, r.lab.a, r.lab.b};
  const double lin[3] = {r.linear_srgb.r, r.linear_srgb.g, r.linear_srgb.b};
  const double paper[3] = {r.paper_rgb.r, r.paper_rgb.g, r.paper_rgb.b};
  for (int c = 0; c < 3; ++c) {
    p.xyz[3 * i + c] = xyz[c];
    p.lab[3 * i + c] = lab[c];
    p.lin[3 * i + c] = lin[c];
    p.paper[3 * i + c] = paper[c];
    p.srgb8[3 * i + c] = r.srgb8[c];
  }
}

// Colours of a model at x[i] seen at angle[i] (1-D arrays of one length). Compositions are
// grouped by angle; an angle with many compositions uses ColorSweep's XYZ table (error at
// most color::kSweepTableTolerance, checked while it is built) unless exact is asked for.
py::dict ModelColors(const AlloyModel& model, const Array& x_in, const Array& angle_in,
                     const std::string& illuminant, int observer_deg, bool sigma, bool exact) {
  if (x_in.size() != angle_in.size()) throw Error("color: x and angle_deg differ in length");
  const std::vector<double> xs = ToVector(x_in), angles = ToVector(angle_in);
  for (double a : angles) CheckAngle(a);
  for (double x : xs) model.CheckInRange(x);
  const bool with_sigma = sigma && model.HasUncertainty();
  ColorArrays arrays = MakeColorArrays(static_cast<py::ssize_t>(xs.size()));
  const ColorPointers p = Pointers(arrays);
  {
    py::gil_scoped_release release;
    const color::Colorimeter& colorimeter = GetColorimeter(illuminant, observer_deg);
    std::map<double, std::vector<std::size_t>> by_angle;
    for (std::size_t i = 0; i < xs.size(); ++i) by_angle[angles[i]].push_back(i);
    for (const auto& [angle, indices] : by_angle) {
      color::ColorSweep sweep(colorimeter, model, angle);
      if (!exact && indices.size() >= 1000) {
        double lo = xs[indices[0]], hi = lo;
        for (std::size_t i : indices) lo = std::min(lo, xs[i]), hi = std::max(hi, xs[i]);
        if (hi > lo) sweep.BuildTable(lo, hi);
      }
      for (std::size_t i : indices) {
        const color::XYZ xyz = sweep.has_table() ? sweep.XYZAt(xs[i]) : sweep.ExactXYZ(xs[i]);
        Store(color::ColorFromXYZ(colorimeter, xyz), i, p);
        p.sigma[i] = with_sigma ? color::DeltaE00Sigma(colorimeter, model, xs[i], angle) : 0.0;
      }
    }
  }
  return ColorDict(arrays, with_sigma);
}

py::dict SpectrumColors(const NkSpectrum& nk, const Array& angle_in, const std::string& illuminant,
                        int observer_deg) {
  const std::vector<double> angles = ToVector(angle_in);
  for (double a : angles) CheckAngle(a);
  ColorArrays arrays = MakeColorArrays(static_cast<py::ssize_t>(angles.size()));
  const ColorPointers p = Pointers(arrays);
  {
    py::gil_scoped_release release;
    const color::Colorimeter& colorimeter = GetColorimeter(illuminant, observer_deg);
    const std::vector<std::complex<double>> index = color::IndexOnGrid(colorimeter, nk);
    for (std::size_t i = 0; i < angles.size(); ++i) {
      Store(color::ColorFromXYZ(colorimeter, color::MaterialXYZ(colorimeter, index, angles[i])), i,
            p);
    }
  }
  return ColorDict(arrays, false);
}

// ---- from colour to composition ------------------------------------------------------------

// The best match for each target colour (rows of an (N, 3) CIELAB array), with the number
// of local minima within the margin and, with all_minima, every one of them.
py::dict ModelMatch(const AlloyModel& model, const Array& lab_in, double angle_deg,
                    const std::string& illuminant, int observer_deg, double target_sigma,
                    double margin, bool sigma, bool all_minima) {
  if (lab_in.ndim() != 2 || lab_in.shape(1) != 3) {
    throw Error("match: the targets must be an (N, 3) array of CIELAB L*, a*, b*");
  }
  const py::ssize_t n = lab_in.shape(0);
  py::array_t<double> x(n), x_sigma(n), de00(n), lab({n, py::ssize_t{3}});
  py::array_t<bool> reachable(n);
  py::array_t<int> minima(n);
  std::vector<std::vector<color::Match>> every(all_minima ? n : 0);
  const double* in = lab_in.data();
  double *px = x.mutable_data(), *ps = x_sigma.mutable_data(), *pd = de00.mutable_data(),
         *pl = lab.mutable_data();
  bool* pr = reachable.mutable_data();
  int* pm = minima.mutable_data();
  {
    py::gil_scoped_release release;
    color::MatchOptions options;
    options.angle_deg = angle_deg;
    options.target_sigma_de00 = target_sigma;
    options.margin = margin;
    options.with_sigma = sigma;
    const color::Colorimeter& colorimeter = GetColorimeter(illuminant, observer_deg);
    // Without the one-sigma, blocks of targets over the cores, a matcher each (a matcher's
    // sweep has scratch space, so one is not shared between threads).
    constexpr int kBlock = 2048;
    ParallelFor(static_cast<int>(n), kBlock, !sigma && n >= 2 * kBlock ? ThreadCount(0) : 1,
                [&](int begin, int end) {
                  const color::ColourMatcher matcher(colorimeter, model, options);
                  for (py::ssize_t i = begin; i < end; ++i) {
                    std::vector<color::Match> found =
                        matcher.Find({in[3 * i], in[3 * i + 1], in[3 * i + 2]});
                    const color::Match& best = found.front();
                    px[i] = best.x_atomic;
                    ps[i] = best.x_sigma;
                    pd[i] = best.de00;
                    pl[3 * i] = best.lab.L;
                    pl[3 * i + 1] = best.lab.a;
                    pl[3 * i + 2] = best.lab.b;
                    pr[i] = best.de00 <= color::kReachableDeltaE00;
                    pm[i] = static_cast<int>(found.size());
                    if (all_minima) every[i] = std::move(found);
                  }
                });
  }
  py::dict d;
  d["x"] = x;
  d["x_sigma"] = x_sigma;
  d["de00"] = de00;
  d["lab"] = lab;
  d["reachable"] = reachable;
  d["n_minima"] = minima;
  if (all_minima) {
    py::list lists;
    for (const auto& found : every) {
      py::list rows;
      for (const color::Match& m : found) {
        py::dict r;
        r["x_atomic"] = m.x_atomic;
        r["x_sigma"] = m.x_sigma;
        r["de00"] = m.de00;
        rows.append(r);
      }
      lists.append(rows);
    }
    d["matches"] = lists;
  }
  return d;
}

// The tolerance window around each composition.
py::dict ModelTolerance(const AlloyModel& model, const Array& x_in, double de00,
                        const std::vector<double>& angles_deg,
                        const std::vector<std::string>& illuminants, int observer_deg) {
  const std::vector<double> xs = ToVector(x_in);
  const py::ssize_t n = static_cast<py::ssize_t>(xs.size());
  py::array_t<double> low(n), high(n), speed(n);
  py::array_t<bool> clipped_low(n), clipped_high(n);
  {
    py::gil_scoped_release release;
    std::vector<color::Colorimeter> colorimeters;
    for (const std::string& name : illuminants) {
      colorimeters.push_back(GetColorimeter(name, observer_deg));
    }
    color::ToleranceOptions options;
    options.de00 = de00;
    options.angles_deg = angles_deg;
    for (py::ssize_t i = 0; i < n; ++i) {
      const color::ToleranceWindow w = color::Tolerance(colorimeters, model, xs[i], options);
      low.mutable_data()[i] = w.x_low;
      high.mutable_data()[i] = w.x_high;
      speed.mutable_data()[i] = w.de00_per_x / 100.0;
      clipped_low.mutable_data()[i] = w.clipped_low;
      clipped_high.mutable_data()[i] = w.clipped_high;
    }
  }
  py::dict d;
  d["x_low"] = low;
  d["x_high"] = high;
  d["de00_per_at_percent"] = speed;
  d["clipped_low"] = clipped_low;
  d["clipped_high"] = clipped_high;
  return d;
}

// ---- optical constants -------------------------------------------------------------------

// result[i, j] at x[i], lambda_nm[j]: the index N = n + ik (eq. 13, 14) or eps itself.
py::array_t<std::complex<double>> ModelOptics(const AlloyModel& model, const Array& x_in,
                                              const Array& lambda_in, bool index) {
  const std::vector<double> xs = ToVector(x_in), lambda_nm = ToVector(lambda_in);
  for (double x : xs) model.CheckInRange(x);
  py::array_t<std::complex<double>> out(
      {static_cast<py::ssize_t>(xs.size()), static_cast<py::ssize_t>(lambda_nm.size())});
  std::complex<double>* data = out.mutable_data();
  {
    py::gil_scoped_release release;
    const std::unique_ptr<BoundModel> bound = model.Bind(lambda_nm);
    std::vector<double> eps1(lambda_nm.size()), eps2(lambda_nm.size());
    for (std::size_t i = 0; i < xs.size(); ++i) {
      bound->Permittivity(xs[i], eps1.data(), eps2.data());
      for (std::size_t j = 0; j < lambda_nm.size(); ++j) {
        const Complex<double> e{eps1[j], eps2[j]};
        const Complex<double> v = index ? IndexFromPermittivity(e) : e;
        data[i * lambda_nm.size() + j] = {v.re, v.im};
      }
    }
  }
  return out;
}

py::object JsonToPython(const nlohmann::json& doc) {
  return py::module_::import("json").attr("loads")(JsonText(doc));
}

// A library message in the package's words: the command-line spellings of settings that
// the library's messages still name replaced by the keywords of this package.
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

py::dict SpectrumDict(const NkSpectrum& nk, const std::vector<std::string>& warnings) {
  py::dict d;
  d["source"] = nk.source;
  d["lambda_nm"] = ToArray(nk.lambda_nm);
  d["n"] = ToArray(nk.n);
  d["k"] = ToArray(nk.k);
  d["warnings"] = warnings;
  return d;
}

py::array_t<std::uint8_t> ToNumpy(const render::ImageRGBA8& image) {
  py::array_t<std::uint8_t> out({image.height, image.width, 4});
  std::copy(image.rgba.begin(), image.rgba.end(), out.mutable_data());
  return out;
}

py::array_t<float> ToNumpy(const render::LinearImage& image) {
  py::array_t<float> out({image.height, image.width, 4});
  std::copy(image.rgba.begin(), image.rgba.end(), out.mutable_data());
  return out;
}

// One tile as `alloycolor render` shades it: from the guarded table (render::GuardedTable),
// or by direct spectral evaluation at every pixel. index_on gives n + ik on a colorimeter's
// grid; label names the material in errors; an empty background is the lighting's default.
template <typename IndexOn>
py::object RenderTile(const IndexOn& index_on, const std::string& label, const std::string& shape,
                      int size, const std::string& lighting, double roughness,
                      const std::string& background, const std::string& illuminant,
                      int observer_deg, bool direct, bool linear) {
  render::RenderOptions options;
  options.shape = render::ShapeFromName(shape);
  options.size = size;
  options.lighting = render::LightingFromName(lighting);
  options.roughness = roughness;
  options.background = background.empty() ? render::DefaultBackground(options.lighting)
                                          : render::BackgroundFromName(background);
  render::LinearImage image;
  {
    py::gil_scoped_release release;
    const color::Colorimeter& colorimeter = GetColorimeter(illuminant, observer_deg);
    const render::Renderer renderer(colorimeter, options);
    const render::DirectReflection reflection = renderer.Direct(index_on(colorimeter));
    image = direct ? renderer.Render(reflection)
                   : renderer.Render(render::GuardedTable(reflection, label).table);
  }
  return linear ? py::object(ToNumpy(image)) : py::object(ToNumpy(render::EncodeSRGB8(image)));
}

py::dict SpectraDict(const exports::ConductorSpectra& s) {
  py::dict d;
  d["material"] = s.material;
  d["lambda_nm"] = ToArray(s.lambda_nm);
  d["n"] = ToArray(s.n);
  d["k"] = ToArray(s.k);
  d["notes"] = s.notes;
  return d;
}

// Writes the files `alloycolor export` writes, as a set, and returns its --json document
// with the material's notes. material_on builds the material from the D65 colorimeter.
template <typename MaterialOn>
py::object WriteExport(const MaterialOn& material_on, const std::string& prefix,
                       const std::string& format, const std::string& scene_dir, double roughness) {
  const exports::ExportSettings settings{format, scene_dir, roughness};
  nlohmann::json doc;
  {
    py::gil_scoped_release release;
    // As `alloycolor export`: the truth under D65, 2 degrees.
    const color::Colorimeter& d65 = GetColorimeter("D65", 2);
    const exports::ExportMaterial material = material_on(d65);
    const exports::ExportFiles e = exports::BuildExport(d65, material, prefix, settings);
    WriteFileSetAtomic(e.files);
    doc = e.summary;
    doc["notes"] = material.spectra.notes;
  }
  return JsonToPython(doc);
}

}  // namespace

PYBIND11_MODULE(_alloycolor, m) {
  m.doc() = "Compiled core of the alloycolor package; use the alloycolor package itself.";
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
  m.attr("_max_fit_grid_nodes") = kMaxFitGridNodes;
  m.attr("_max_tile_size") = render::kMaxTileSize;
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

  m.def("_set_data_root", [](const std::string& root) { DataRootStorage() = root; });
  m.def("_data_root", []() { return DataRootStorage(); });

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
  m.def("illuminants", &color::IlluminantNames);
  m.def("_lab_from_hex", [](const std::string& hex, const std::string& illuminant, int observer) {
    const color::Lab lab = color::LabFromHex(GetColorimeter(illuminant, observer), hex);
    return std::vector<double>{lab.L, lab.a, lab.b};
  });
  m.def("_lab_from_xyz", [](double X, double Y, double Z, const std::string& illuminant,
                            int observer) {
    const color::Lab lab = color::LabFromTargetXYZ(GetColorimeter(illuminant, observer), {X, Y, Z});
    return std::vector<double>{lab.L, lab.a, lab.b};
  });

  m.def(
      "_read_nk",
      [](const std::string& path, const std::string& columns) {
        std::vector<std::string> warnings;
        const NkSpectrum nk = columns.empty()
                                  ? ReadNkFile(path, &warnings)
                                  : ReadNkFile(path, ParseNkColumns(columns), &warnings);
        return std::make_pair(nk, warnings);
      },
      py::arg("path"), py::arg("columns") = "");

  py::class_<NkSpectrum>(m, "_Spectrum")
      .def_readonly("source", &NkSpectrum::source)
      .def_property_readonly("lambda_nm", [](const NkSpectrum& s) { return ToArray(s.lambda_nm); })
      .def_property_readonly("n", [](const NkSpectrum& s) { return ToArray(s.n); })
      .def_property_readonly("k", [](const NkSpectrum& s) { return ToArray(s.k); })
      .def("_color", &SpectrumColors)
      .def("_render",
           [](const NkSpectrum& nk, const std::string& shape, int size, const std::string& lighting,
              double roughness, const std::string& background, const std::string& illuminant,
              int observer_deg, bool direct, bool linear) {
             return RenderTile(
                 [&](const color::Colorimeter& c) { return color::IndexOnGrid(c, nk); }, nk.source,
                 shape, size, lighting, roughness, background, illuminant, observer_deg, direct,
                 linear);
           })
      .def("_export", [](const NkSpectrum& nk, const std::string& prefix, const std::string& format,
                         const std::string& scene_dir, double roughness) {
        return WriteExport(
            [&](const color::Colorimeter& d65) { return exports::MeasuredExportMaterial(d65, nk); },
            prefix, format, scene_dir, roughness);
      });

  py::class_<Dataset>(m, "_Dataset")
      .def(py::init(&LoadDataset))
      .def_readonly("manifest_path", &Dataset::manifest_path)
      .def_readonly("name", &Dataset::name)
      .def_property_readonly("system", [](const Dataset& d) { return d.system.Name(); })
      .def_readonly("composition", &Dataset::composition)
      .def_readonly("warnings", &Dataset::warnings)
      .def_property_readonly("precision",
                             [](const Dataset& d) {
                               py::dict r;
                               r["n"] = d.precision_n;
                               r["k"] = d.precision_k;
                               return r;
                             })
      .def_property_readonly("x_atomic",
                             [](const Dataset& d) {
                               std::vector<double> xs;
                               for (const Sample& s : d.samples) xs.push_back(s.x_atomic);
                               return ToArray(xs);
                             })
      .def_property_readonly("samples",
                             [](const Dataset& d) {
                               py::list out;
                               for (const Sample& s : d.samples) {
                                 py::dict r;
                                 r["x_atomic"] = s.x_atomic;
                                 r["x_given"] = s.x_given;
                                 r["file"] = s.file;
                                 r["path"] = s.path;
                                 r["spectrum"] = s.nk;
                                 out.append(r);
                               }
                               return out;
                             })
      .def("parse_composition",
           [](const Dataset& d, const std::string& text) {
             return ParseComposition(text, d.system);
           })
      .def("sample_x",
           [](const Dataset& d, double x) -> py::object {
             const Sample* s = FindSample(d, x);
             return s ? py::cast(s->x_atomic) : py::none();
           })
      .def("without", [](const Dataset& d, const std::vector<double>& exclude_x) {
        return WithoutSamples(d, exclude_x);
      });

  m.def("_fit", [](const Dataset& dataset, const std::string& method, int degree, double smoothing,
                   const std::string& space, const std::string& terms, double lambda_from_nm,
                   double lambda_to_nm, double lambda_step_nm, bool covariance,
                   const py::object& progress) {
    if (method != fit::kAutoMethod) RequireMethod(method);
    fit::FitSettings settings;
    ThreadBudget threads;  // every core, as the program's default
    settings.threads = &threads;
    settings.degree = degree;
    settings.smoothing = smoothing;
    settings.space = space;
    settings.terms = terms;
    settings.lambda_from_nm = lambda_from_nm;
    settings.lambda_to_nm = lambda_to_nm;
    settings.lambda_step_nm = lambda_step_nm;
    settings.covariance = covariance;
    settings.progress = PythonProgress(progress);
    // As `alloycolor fit`: auto and the sigma calibration score colour under D65, 2 degrees.
    settings.colorimeter = &GetColorimeter("D65", 2);
    std::unique_ptr<AlloyModel> model;
    {
      py::gil_scoped_release release;
      model = fit::BuildModel(method, dataset, settings);
    }
    return std::shared_ptr<AlloyModel>(std::move(model));
  });

  m.def("_load_model",
        [](const std::string& path) { return std::shared_ptr<AlloyModel>(ReadModelFile(path)); });

  py::class_<AlloyModel, std::shared_ptr<AlloyModel>>(m, "_Model")
      .def_property_readonly("method", &AlloyModel::method)
      .def_property_readonly("system", [](const AlloyModel& a) { return a.system().Name(); })
      .def_property_readonly("composition", &AlloyModel::composition)
      .def_property_readonly("x_min", &AlloyModel::x_min)
      .def_property_readonly("x_max", &AlloyModel::x_max)
      .def_property_readonly("lambda_min_nm", &AlloyModel::lambda_min_nm)
      .def_property_readonly("lambda_max_nm", &AlloyModel::lambda_max_nm)
      .def_property_readonly("warnings", &AlloyModel::warnings)
      .def_property_readonly("has_uncertainty", &AlloyModel::HasUncertainty)
      .def_property_readonly("training_x",
                             [](const AlloyModel& a) {
                               std::vector<double> xs;
                               for (const auto& s : a.training_samples()) xs.push_back(s.x_atomic);
                               return ToArray(xs);
                             })
      .def("to_json", [](const AlloyModel& a) { return JsonToPython(a.ToJson()); })
      .def("save", [](const AlloyModel& a,
                      const std::string& path) { WriteFileAtomic(path, ModelFileText(a)); })
      .def("parse_composition",
           [](const AlloyModel& a, const std::string& text) {
             return ParseComposition(text, a.system());
           })
      .def("_optics", &ModelOptics)
      .def("_color", &ModelColors)
      .def("_match", &ModelMatch)
      .def("_tolerance", &ModelTolerance)
      .def("_render",
           [](const AlloyModel& a, double x, const std::string& shape, int size,
              const std::string& lighting, double roughness, const std::string& background,
              const std::string& illuminant, int observer_deg, bool direct, bool linear) {
             a.CheckInRange(x);
             return RenderTile(
                 [&](const color::Colorimeter& c) { return color::IndexOnGrid(c, a, x); },
                 render::AlloyLabel(a, x), shape, size, lighting, roughness, background, illuminant,
                 observer_deg, direct, linear);
           })
      .def("_spectra",
           [](const AlloyModel& a, double x, const std::string& material) {
             a.CheckInRange(x);
             return SpectraDict(exports::ModelSpectra(a, x, material));
           })
      .def("_export",
           [](const AlloyModel& a, double x, const std::string& origin, const std::string& prefix,
              const std::string& format, const std::string& scene_dir, double roughness) {
             a.CheckInRange(x);
             return WriteExport(
                 [&](const color::Colorimeter& d65) {
                   return exports::AlloyExportMaterial(d65, a, x, origin);
                 },
                 prefix, format, scene_dir, roughness);
           })
      .def("_description",
           [](const AlloyModel& a, double x, const std::string& origin) {
             return exports::AlloyDescription(a, x, origin);
           })
      .def("_write_spd", [](const AlloyModel& a, double x, const std::string& material,
                            const std::string& eta_path, const std::string& k_path) {
        a.CheckInRange(x);
        const exports::ConductorSpectra s = exports::ModelSpectra(a, x, material);
        const std::string eta = exports::SpdText(s, true), k = exports::SpdText(s, false);
        // One set: both replaced or neither; one file given twice is refused.
        WriteFileSetAtomic({{eta_path, eta}, {k_path, k}});
      });

  m.def("_validate",
        [](const Dataset& dataset, const std::vector<std::string>& methods,
           const std::vector<std::string>& holdout, const std::string& mode,
           const std::vector<double>& angles_deg, const std::string& illuminant, int observer_deg,
           const std::string& html_path, const std::string& json_path, const py::object& progress) {
          for (const std::string& method : methods) {
            if (method != fit::kAutoMethod) RequireMethod(method);
          }
          for (double a : angles_deg) {
            if (!(a >= 0 && a < 90))
              throw Error("angles_deg: " + std::to_string(a) + " lies outside 0-90 degrees");
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
          options.build = fit::SharedFitBuilder(d65, &threads);
          options.threads = &threads;
          options.methods = methods;
          options.angles_deg = angles_deg;
          options.mode = mode;
          const ProgressCallback callback = PythonProgress(progress);
          options.details = callback;  // a Python caller gets every split's line too
          nlohmann::json json;
          {
            py::gil_scoped_release release;
            const color::Colorimeter& colorimeter = GetColorimeter(illuminant, observer_deg);
            const validate::ValidationReport report =
                validate::ComputeValidation(dataset, splits, colorimeter, options, callback);
            json = validate::ValidationJson(report);
            std::vector<OutputFile> files;
            if (!html_path.empty()) files.push_back({html_path, validate::ValidationHtml(report)});
            if (!json_path.empty()) files.push_back({json_path, JsonText(json, 2) + "\n"});
            if (!files.empty()) WriteFileSetAtomic(files);
          }
          return JsonToPython(json);
        });
}

}  // namespace alloycolor::python
