// alloycolor render: a picture of a sphere or a ring made of a metal (measured n, k) or of
// alloys at one or more compositions side by side, every pixel shaded from the spectral
// Fresnel reflectance at its angle of incidence.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/text.h"
#include "alloycolor/render/image.h"
#include "alloycolor/render/renderer.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct RenderCommandOptions {
  MaterialSource material;
  std::string shape = "sphere";
  int size = 512;
  std::string light = "studio";
  std::string illuminant = "D65";
  int observer = 2;
  double roughness = 0.0;
  std::string background;  // default depends on the light
  int bit_depth = 8;
  int threads = 0;
  bool direct = false;
  std::string out;
  bool quiet = false;
};

struct Material {
  std::string label;
  std::vector<std::complex<double>> index;
};

std::string Format(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

render::RenderOptions CheckedOptions(const RenderCommandOptions& o) {
  render::RenderOptions options;
  try {
    options.shape = render::ShapeFromName(o.shape);
  } catch (const Error& e) {
    throw Error(std::string("--shape: ") + e.what());
  }
  try {
    options.lighting = render::LightingFromName(o.light);
  } catch (const Error& e) {
    throw Error(std::string("--light: ") + e.what());
  }
  try {
    options.background = o.background.empty() ? render::DefaultBackground(options.lighting)
                                              : render::BackgroundFromName(o.background);
  } catch (const Error& e) {
    throw Error(std::string("--background: ") + e.what());
  }
  options.size = o.size;
  options.roughness = o.roughness;
  options.threads = o.threads;
  render::CheckRenderOptions(options, o.direct, OptionSpelling::kFlag);
  if (o.bit_depth != 8 && o.bit_depth != 16) {
    throw Error("--bit-depth: " + std::to_string(o.bit_depth) + " is not 8 or 16");
  }
  return options;
}

std::vector<Material> LoadMaterials(const RenderCommandOptions& o,
                                    const color::Colorimeter& colorimeter,
                                    std::string* description) {
  std::vector<Material> materials;
  if (o.material.measured()) {
    const NkSpectrum nk = o.material.LoadMeasured(o.quiet);
    materials.push_back({o.material.nk_file, color::IndexOnGrid(colorimeter, nk)});
    *description = "measured n, k from " + o.material.nk_file;
    return materials;
  }
  const auto model = o.material.LoadModel(o.quiet);
  for (double x : o.material.Compositions(*model, false)) {
    materials.push_back(
        {render::AlloyLabel(*model, x), color::IndexOnGrid(colorimeter, *model, x)});
  }
  *description = model->system().Name() + ", " + model->method() + " model" +
                 (o.material.source.model_path.empty() ? " from data " + o.material.source.data_dir
                                                       : " from " + o.material.source.model_path) +
                 "; x = atomic fraction of " + model->system().a.symbol + ": " + o.material.x_text;
  return materials;
}

// The library's accuracy guard; a refusal names the program's way out.
render::CheckedTable TableOrRefusal(const render::DirectReflection& direct,
                                    const std::string& label) {
  try {
    return render::GuardedTable(direct, label);
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + " (--direct)");
  }
}

// render writes PNG only: a name with another extension (x.jpg) is refused, not given
// PNG bytes under a name that says otherwise.
void CheckPngName(const std::string& out) {
  const std::string extension = Lower(std::filesystem::path(out).extension().string());
  if (!extension.empty() && extension != ".png") {
    throw Error("--out " + Quote(out, 100) +
                ": render writes PNG only; give a name ending in .png");
  }
}

double Milliseconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

void Run(const RenderCommandOptions& o) {
  const render::RenderOptions options = CheckedOptions(o);
  CheckOutputFolder(o.out, "--out");
  // An existing file may be an input, which the guard below names first.
  if (!std::filesystem::exists(o.out)) CheckPngName(o.out);
  const color::Colorimeter colorimeter = LoadColorimeter(o.illuminant, o.observer);
  std::string description;
  const std::vector<Material> materials = LoadMaterials(o, colorimeter, &description);
  CheckOutputPath(o.out);  // before the work: not an input, a symlink or a device
  CheckPngName(o.out);
  const long long pixels = static_cast<long long>(materials.size()) * options.size * options.size;
  if (pixels > render::kMaxImagePixels) {
    throw Error("--size: " + std::to_string(materials.size()) + " tiles of " +
                std::to_string(options.size) + "x" + std::to_string(options.size) +
                " pixels exceed the limit of " + std::to_string(render::kMaxImagePixels) +
                " pixels");
  }

  const auto start = std::chrono::steady_clock::now();
  const render::Renderer renderer(colorimeter, options);
  render::LinearImage sheet(options.size * static_cast<int>(materials.size()), options.size);
  double shading_ms = 0.0;
  for (std::size_t m = 0; m < materials.size(); ++m) {
    render::LinearImage tile;
    const render::DirectReflection direct = renderer.Direct(materials[m].index);
    if (o.direct) {
      const auto shade_start = std::chrono::steady_clock::now();
      tile = renderer.Render(direct);
      shading_ms += Milliseconds(shade_start);
    } else {
      const render::CheckedTable checked = TableOrRefusal(direct, materials[m].label);
      if (!o.quiet) {
        std::cerr << "alloycolor: " << materials[m].label << ": XYZ table of "
                  << checked.table.size()
                  << " angles, largest relative error against direct spectral evaluation "
                  << Format("%.2g", checked.error) << "\n";
      }
      const auto shade_start = std::chrono::steady_clock::now();
      tile = renderer.Render(checked.table);
      shading_ms += Milliseconds(shade_start);
    }
    render::Paste(tile, options.size * static_cast<int>(m), 0, &sheet);
  }
  if (!o.quiet) {
    std::cerr << "alloycolor: rendered " << materials.size() << " tile"
              << (materials.size() == 1 ? "" : "s") << " of " << options.size << "x" << options.size
              << " in " << Format("%.0f", Milliseconds(start)) << " ms (shading "
              << Format("%.1f", shading_ms) << " ms" << (o.direct ? ", direct spectral" : "")
              << ")\n";
  }

  std::string labels;
  for (const Material& m : materials) labels += (labels.empty() ? "" : "; ") + m.label;
  const std::vector<render::PngText> text = {
      {"Software", std::string("alloycolor ") + ALLOYCOLOR_VERSION},
      {"Title", labels},
      {"Description", description + ". " + render::ShapeName(options.shape) + ", light " + o.light +
                          ", illuminant " + colorimeter.illuminant() + ", " +
                          std::to_string(o.observer) + "-degree observer, roughness (GGX alpha) " +
                          Format("%g", options.roughness) +
                          ". Spectral Fresnel reflectance at each pixel's angle of incidence; sRGB "
                          "(IEC 61966-2-1), no chromatic adaptation."},
      {"Comment", "Tiles of " + std::to_string(options.size) + "x" + std::to_string(options.size) +
                      " pixels left to right; orthographic "
                      "view along -z; object half-width " +
                      Format("%g", render::kObjectFraction) +
                      " of the tile, centred; pixel centres at (i + 0.5, j + 0.5)."}};
  const std::string bytes = o.bit_depth == 16 ? render::PngBytes(render::EncodeSRGB16(sheet), text)
                                              : render::PngBytes(render::EncodeSRGB8(sheet), text);
  WriteOutput(o.out, bytes, o.quiet);
}

}  // namespace

void RegisterRender(CLI::App& app) {
  auto o = std::make_shared<RenderCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Picture (PNG) of a polished sphere or ring of a metal or alloy");
  cmd->footer(
      "Picture (PNG, sRGB) of a polished sphere or ring made of a metal (--nk FILE) or of an "
      "alloy at composition(s) --x side by side (--model or --data). Every pixel's colour is "
      "the spectral Fresnel reflectance at its angle of incidence integrated against the "
      "illuminant and observer (through a table of XYZ against cos(angle), checked against "
      "direct evaluation). --light uniform: a smooth surface in a uniform white environment, "
      "each pixel exactly the colour of R(angle) (sphere: centre at normal incidence, rim "
      "toward white). --light studio: a product-shot set (soft key and fill lights, "
      "gradient backdrop), with GGX microfacet roughness.");
  o->material.AddOptions(cmd,
                         "Composition(s) of the system's first element, comma-separated "
                         "(0.55,0.75; 75wt%; 18k): one tile each, left to right",
                         "--x,--xs");
  cmd->add_option("--shape", o->shape, "sphere or ring")->capture_default_str();
  cmd->add_option("--size", o->size, "Tile width and height in pixels (1-4096)")
      ->capture_default_str();
  cmd->add_option("--light", o->light, "studio or uniform")->capture_default_str();
  AddColorimetryOptions(cmd, &o->illuminant, &o->observer);
  cmd->add_option("--roughness", o->roughness,
                  "Surface roughness as GGX alpha, 0 (mirror polish) to 1")
      ->capture_default_str();
  cmd->add_option("--background", o->background,
                  "transparent or backdrop (default: backdrop in studio light, transparent "
                  "in uniform light)");
  cmd->add_option("--bit-depth", o->bit_depth, "Bits per PNG sample: 8 or 16")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "Threads to shade with (0: all the hardware's)")
      ->capture_default_str();
  cmd->add_flag("--direct", o->direct,
                "Evaluate the spectral Fresnel reflectance at every pixel instead of the "
                "table (slow; for checking)");
  cmd->add_option("--out", o->out, "Output PNG file")->required();
  cmd->add_flag("--quiet", o->quiet, "No warnings or progress on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
