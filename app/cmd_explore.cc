// alloycolor explore: writes the explorer page (explore_page.h), one self-contained HTML
// file in which a composition slider shows the metal, its numbers, its spectra and how far
// it is from a second composition.
#include <algorithm>
#include <chrono>
#include <complex>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/render/composition_table.h"
#include "alloycolor/render/renderer.h"
#include "common.h"
#include "explore_page.h"

namespace alloycolor::app {
namespace {

constexpr int kMinTileSize = 64;
constexpr int kMaxTileSize = 1024;
constexpr int kMirrorEnvironmentWidth = 512;
constexpr int kRoughEnvironmentWidth = 256;

struct ExploreOptions {
  ModelSource source;
  std::string out = "explorer.html";
  std::string illuminants = "A,D50,D65";
  int observer = 2;
  std::string roughness = "0,0.2";
  int size = 320;
  double tolerance = 0.02;
  int threads = 0;
  bool quiet = false;
};

std::string Format(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

std::vector<std::string> SplitNames(const std::string& text) {
  std::vector<std::string> names;
  std::string part;
  for (char c : text + ",") {
    if (c == ',') {
      if (part.empty()) throw Error("--illuminants: empty name in '" + text + "'");
      names.push_back(part);
      part.clear();
    } else if (c != ' ') {
      part += c;
    }
  }
  return names;
}

std::string FinishName(double alpha) {
  if (alpha == 0.0) return "polished";
  if (alpha <= 0.25) return "satin";
  if (alpha <= 0.5) return "matte";
  return "rough";
}

ExploreSample SampleFromIndex(double x, const std::string& label, bool measured,
                              const std::vector<double>& lambda_nm,
                              const std::vector<std::complex<double>>& index) {
  ExploreSample s{x, label, measured, lambda_nm, {}, {}, color::ReflectanceSpectrum(index, 0.0)};
  for (const auto& nk : index) {
    s.n.push_back(nk.real());
    s.k.push_back(nk.imag());
  }
  return s;
}

std::string Percent(double x) { return Format("%.4g", 100.0 * x) + " at%"; }

// The spectra drawn beside the prediction: measured when the data set is at hand (--data)
// or the model keeps them (paper, eps-linear); else the model at the training compositions.
std::vector<ExploreSample> Samples(const ExploreOptions& o, const AlloyModel& model,
                                   const render::CompositionTable& table, std::string* note) {
  std::vector<ExploreSample> samples;
  const double lo = table.lambda_nm.front(), hi = table.lambda_nm.back();
  const auto in_range = [&](const std::vector<double>& lambda, const std::vector<double>& n,
                            const std::vector<double>& k, double x, const std::string& label) {
    std::vector<double> l2;
    std::vector<std::complex<double>> index;
    for (std::size_t i = 0; i < lambda.size(); ++i) {
      if (lambda[i] < lo - 1e-9 || lambda[i] > hi + 1e-9) continue;
      l2.push_back(lambda[i]);
      index.emplace_back(n[i], k[i]);
    }
    if (l2.size() >= 2) samples.push_back(SampleFromIndex(x, label, true, l2, index));
  };
  const std::string a = model.system().a.symbol;
  if (!o.source.data_dir.empty()) {
    const Dataset dataset = LoadDatasetArg(o.source.data_dir);
    for (const Sample& s : dataset.samples) {
      in_range(s.nk.lambda_nm, s.nk.n, s.nk.k, s.x_atomic,
               "measured " + a + " " + Percent(s.x_atomic) + " (" + s.file + ")");
    }
    *note = "Measured spectra from the data set " + o.source.data_dir + ".";
    return samples;
  }
  const nlohmann::json params = model.ToJson()["parameters"];
  if (params.contains("samples") && params["samples"].is_array()) {
    for (const auto& s : params["samples"]) {
      in_range(s["lambda_nm"].get<std::vector<double>>(), s["n"].get<std::vector<double>>(),
               s["k"].get<std::vector<double>>(), s["x"].get<double>(),
               "measured " + a + " " + Percent(s["x"].get<double>()) + " (" +
                   s["source"].get<std::string>() + ")");
    }
    *note = "Measured spectra as kept in the model file.";
    return samples;
  }
  for (const TrainingSample& t : model.training_samples()) {
    samples.push_back(SampleFromIndex(t.x_atomic,
                                      "the model at the training composition " + a + " " +
                                          Percent(t.x_atomic) + " (" + t.file + ")",
                                      false, table.lambda_nm,
                                      model.Index(t.x_atomic, table.lambda_nm)));
  }
  *note = "The " + model.method() +
          " model file keeps no spectra: the dotted lines are the model at its training "
          "compositions, not the measurements (give --data to draw those).";
  return samples;
}

double Milliseconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

void Run(const ExploreOptions& o) {
  if (o.size < kMinTileSize || o.size > kMaxTileSize) {
    throw Error("--size: " + std::to_string(o.size) + " lies outside " +
                std::to_string(kMinTileSize) + "-" + std::to_string(kMaxTileSize) + " pixels");
  }
  if (!(o.tolerance >= 1e-4 && o.tolerance <= 0.5)) {
    throw Error("--tolerance: " + Format("%g", o.tolerance) + " lies outside 0.0001-0.5 (dE00)");
  }
  if (o.threads < 0) throw Error("--threads: " + std::to_string(o.threads) + " is negative");
  render::CompositionTableOptions table_options;
  table_options.roughness = ParseNumberList(o.roughness, "--roughness");
  std::sort(table_options.roughness.begin(), table_options.roughness.end());
  table_options.roughness.erase(
      std::unique(table_options.roughness.begin(), table_options.roughness.end()),
      table_options.roughness.end());
  for (double r : table_options.roughness) {
    if (!(r >= 0.0 && r <= render::kMaxRoughness)) {
      throw Error("--roughness: " + Format("%g", r) + " lies outside 0-1 (GGX alpha)");
    }
  }
  if (table_options.roughness.front() != 0.0) {
    table_options.roughness.insert(table_options.roughness.begin(), 0.0);
  }
  table_options.tolerance_de00 = o.tolerance;
  table_options.threads = o.threads;
  CheckOutputFolder(o.out, "--out");
  std::vector<color::Colorimeter> colorimeters;
  for (const std::string& name : SplitNames(o.illuminants)) {
    try {
      colorimeters.push_back(LoadColorimeter(name, o.observer));
    } catch (const Error& e) {
      throw Error(std::string("--illuminants: ") + e.what());
    }
  }
  const auto model = o.source.Load(o.quiet);
  CheckOutputPath(o.out);  // before the work: not an input, a symlink or a device

  const auto start = std::chrono::steady_clock::now();
  const render::CompositionTable table =
      render::BuildCompositionTable(*model, colorimeters, table_options);
  const double table_ms = Milliseconds(start);

  ExplorePageInputs in;
  in.model = model.get();
  in.source = o.source.model_path.empty()
                  ? "data " + o.source.data_dir + ", " + model->method() + " fit"
                  : o.source.model_path;
  in.observer_deg = o.observer;
  in.table = &table;
  for (double r : table.roughness) {
    in.finish_names.push_back(FinishName(r));
  }
  in.samples = Samples(o, *model, table, &in.samples_note);
  in.sphere = render::TraceNormals(render::Shape::kSphere, o.size);
  in.ring = render::TraceNormals(render::Shape::kRing, o.size);
  for (double r : table.roughness) {
    // A rough finish blurs the light tent, so its map can be coarser.
    const int width = r > 0.0 ? kRoughEnvironmentWidth : kMirrorEnvironmentWidth;
    in.environment_maps.push_back(
        {width, width / 2,
         render::LatLongRadiance(render::Lighting::kStudio, r, width, width / 2, o.threads)});
  }
  in.generator = std::string("alloycolor ") + ALLOYCOLOR_VERSION;
  const std::string html = ExplorePageHtml(in);
  if (!o.quiet) {
    std::cerr << "alloycolor: explorer tables: " << table.x_nodes.size() << " compositions x "
              << table.mu_nodes << " angles x " << table.illuminants.size() << " illuminants x "
              << table.roughness.size() << " finishes in " << Format("%.0f", table_ms)
              << " ms; largest error at " << table.check_points << " check points: dE00 "
              << Format("%.3g", table.max_de00) << ", 8-bit " << table.max_srgb8_difference << "\n";
    std::cerr << "alloycolor: page of " << Format("%.2f", html.size() / 1e6) << " MB\n";
  }
  if (!table.tolerance_met && !o.quiet) {
    Warn("the explorer's tables reached their size limit before meeting --tolerance " +
         Format("%g", o.tolerance) + ": the page's colours may differ from 'alloycolor color' " +
         "by up to dE00 " + Format("%.3g", table.max_de00) + " (measured), as the page says");
  }
  WriteOutput(o.out, html, o.quiet);
}

}  // namespace

void RegisterExplore(CLI::App& app) {
  auto o = std::make_shared<ExploreOptions>();
  CLI::App* cmd = app.add_subcommand(
      "explore", "Write the explorer page: one offline HTML file with a composition slider");
  cmd->footer(
      "Writes the explorer page: one self-contained HTML file (works offline, no external "
      "files) with a composition slider over the model's range (measured compositions "
      "marked; at%, wt% and karat for gold), a polished sphere and ring shaded per pixel, "
      "the colour's hex, 8-bit and linear sRGB, CIELAB and one-sigma dE00, n, k and "
      "reflectance plots beside the measured samples, and a second composition to compare "
      "(dE00 with a plain verdict). The page interpolates tables the program computes with "
      "the 'color' and 'render' chain; their largest error is measured and printed. The "
      "view is kept in the address: #x=0.75&x2=0.6&ill=D65&angle=0&light=studio&rough=0.");
  o->source.AddOptions(cmd, true);
  cmd->add_option("--out", o->out, "Output HTML file")->capture_default_str();
  cmd->add_option("--illuminants", o->illuminants,
                  "Illuminants offered by the page's selector, comma-separated (A, C, D50, "
                  "D65, E, F2, F11)")
      ->capture_default_str();
  cmd->add_option("--observer", o->observer, "CIE observer: 2 (1931) or 10 (1964)")
      ->capture_default_str();
  cmd->add_option("--roughness", o->roughness,
                  "Finishes offered for the pictures, as GGX roughness alpha 0-1, "
                  "comma-separated (0, polished, is always included)")
      ->capture_default_str();
  cmd->add_option("--size", o->size,
                  "Width and height in pixels of each sphere and ring picture (64-1024)")
      ->capture_default_str();
  cmd->add_option("--tolerance", o->tolerance,
                  "Largest CIEDE2000 error allowed while choosing the table's density")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "Threads to compute with (0: all the hardware's)")
      ->capture_default_str();
  cmd->add_flag("--quiet", o->quiet, "No warnings or progress on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
