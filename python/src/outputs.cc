// The bindings of outputs: pictures (render/renderer.h), spectra on the export grid and
// the renderer files `alloycolor export` writes (export/export_files.h).
#include <pybind11/stl.h>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/output.h"
#include "alloycolor/export/explorer_page.h"
#include "alloycolor/export/export_files.h"
#include "alloycolor/export/spectral_export.h"
#include "alloycolor/render/image.h"
#include "alloycolor/render/renderer.h"
#include "bindings.h"

namespace alloycolor::python {
namespace {

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
  // As `alloycolor render` takes its options, each refused naming its keyword.
  const auto named = [](const char* keyword, const auto& from_name, const std::string& name) {
    try {
      return from_name(name);
    } catch (const Error& e) {
      throw Error(keyword + std::string(": ") + e.what());
    }
  };
  render::RenderOptions options;
  options.shape = named("shape", render::ShapeFromName, shape);
  options.size = size;
  options.lighting = named("lighting", render::LightingFromName, lighting);
  options.roughness = roughness;
  options.background = background.empty()
                           ? render::DefaultBackground(options.lighting)
                           : named("background", render::BackgroundFromName, background);
  render::CheckRenderOptions(options, direct);
  render::LinearImage image;
  RunInterruptible([&](const CancelCheck& cancel) {
    options.cancel = cancel;
    const color::Colorimeter& colorimeter = GetColorimeter(illuminant, observer_deg);
    const render::Renderer renderer(colorimeter, options);
    const render::DirectReflection reflection = renderer.Direct(index_on(colorimeter));
    cancel();
    image = direct ? renderer.Render(reflection)
                   : renderer.Render(render::GuardedTable(reflection, label).table);
  });
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
                       const std::string& format, const std::string& scene_dir, double roughness,
                       OutputGuard& guard) {
  const exports::ExportSettings settings{format, scene_dir, roughness};
  nlohmann::json doc;
  RunInterruptible([&](const CancelCheck& cancel) {
    // As `alloycolor export`: the truth under D65, 2 degrees.
    const color::Colorimeter& d65 = GetColorimeter("D65", 2);
    const exports::ExportMaterial material = material_on(d65);
    cancel();
    const exports::ExportFiles e = exports::BuildExport(d65, material, prefix, settings);
    cancel();
    WriteFileSetAtomic(e.files, &guard);
    doc = e.summary;
    doc["notes"] = material.spectra.notes;
  });
  return JsonToPython(doc);
}

// Writes the explorer page `alloycolor explore` writes (export/explorer_page.h) and returns
// what its tables measured.
py::dict WriteExplorer(const AlloyModel& model, const std::string& path,
                       const std::vector<std::string>& illuminants, int observer_deg,
                       exports::ExplorerOptions options, OutputGuard& guard) {
  exports::CheckExplorerOptions(options);
  CheckOutputPath(path, &guard);  // before the work: not an input, a symlink or a device
  std::vector<color::Colorimeter> colorimeters;
  for (const std::string& name : illuminants) {
    try {
      colorimeters.push_back(GetColorimeter(name, observer_deg));
    } catch (const Error& e) {
      throw Error(std::string("illuminants: ") + e.what());
    }
  }
  exports::ExplorerPage page;
  RunInterruptible([&](const CancelCheck& cancel) {
    options.cancel = cancel;
    page = exports::BuildExplorerPage(model, colorimeters, options);
    cancel();
    WriteFileAtomic(path, page.html, &guard);
  });
  py::dict d;
  d["compositions"] = page.compositions;
  d["angles"] = page.angles;
  d["illuminants"] = page.illuminants;
  d["finishes"] = page.finishes;
  d["check_points"] = page.check_points;
  d["max_de00"] = page.max_de00;
  d["max_srgb8_difference"] = page.max_srgb8_difference;
  d["tolerance_met"] = page.tolerance_met;
  d["bytes"] = page.html.size();
  return d;
}

}  // namespace

void BindOutputs(py::module_& m, SpectrumClass& spectrum, ModelClass& model) {
  m.attr("_max_tile_size") = render::kMaxTileSize;
  // The inputs of one call that writes (core/output.h): what the program's guard notes
  // for the command that reads them, the colour tables noted at once.
  py::class_<OutputGuard>(m, "_OutputGuard")
      .def(py::init([]() {
        auto guard = std::make_unique<OutputGuard>();
        guard->NoteFolder(DataRootSetting() + "/cie");
        return guard;
      }))
      .def("note", &OutputGuard::NoteInput)
      .def("note_dataset", &OutputGuard::NoteInputs)
      .def("check",
           [](OutputGuard& guard, const std::string& path) { CheckOutputPath(path, &guard); });
  spectrum
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
                         const std::string& scene_dir, double roughness, OutputGuard& guard) {
        return WriteExport(
            [&](const color::Colorimeter& d65) { return exports::MeasuredExportMaterial(d65, nk); },
            prefix, format, scene_dir, roughness, guard);
      });
  model
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
              const std::string& format, const std::string& scene_dir, double roughness,
              OutputGuard& guard) {
             a.CheckInRange(x);
             return WriteExport(
                 [&](const color::Colorimeter& d65) {
                   return exports::AlloyExportMaterial(d65, a, x, origin);
                 },
                 prefix, format, scene_dir, roughness, guard);
           })
      .def("_description",
           [](const AlloyModel& a, double x, const std::string& origin) {
             return exports::AlloyDescription(a, x, origin);
           })
      .def("_explore",
           [](const AlloyModel& a, const std::string& path,
              const std::vector<std::string>& illuminants, int observer_deg,
              const std::vector<double>& roughness, int size, double tolerance, int threads,
              const std::string& source, const Dataset* data, const std::string& data_name,
              OutputGuard& guard) {
             exports::ExplorerOptions options;
             options.roughness = roughness;
             options.size = size;
             options.tolerance_de00 = tolerance;
             options.threads = threads;
             options.source = source;
             options.data = data;
             options.data_name = data_name;
             return WriteExplorer(a, path, illuminants, observer_deg, options, guard);
           })
      .def("_write_spd",
           [](const AlloyModel& a, double x, const std::string& material,
              const std::string& eta_path, const std::string& k_path, OutputGuard& guard) {
             a.CheckInRange(x);
             const exports::ConductorSpectra s = exports::ModelSpectra(a, x, material);
             const std::string eta = exports::SpdText(s, true), k = exports::SpdText(s, false);
             // One set: both replaced or neither; one file given twice is refused.
             WriteFileSetAtomic({{eta_path, eta}, {k_path, k}}, &guard);
           });
}

}  // namespace alloycolor::python
