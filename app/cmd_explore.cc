// alloycolor explore: writes the explorer page (export/explorer_page.h, which the library
// builds: Python's Model.explore writes the same bytes), one self-contained HTML file in
// which a composition slider shows the metal, its numbers, its spectra and how far it is
// from a second composition.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/export/explorer_page.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct ExploreOptions {
  ModelSource source;
  std::string out = "explorer.html";
  std::string illuminants = "A,D50,D65";
  int observer = 2;
  std::string roughness = "0,0.2";
  exports::ExplorerOptions page;  // size, tolerance, threads; roughness from the text
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

double Milliseconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

void Run(const ExploreOptions& o) {
  exports::ExplorerOptions page = o.page;
  page.roughness = ParseNumberList(o.roughness, "--roughness");
  exports::CheckExplorerOptions(page, OptionSpelling::kFlag);
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

  std::unique_ptr<Dataset> data;  // the measured spectra beside the prediction (--data)
  if (!o.source.data_dir.empty()) {
    data = std::make_unique<Dataset>(LoadDatasetArg(o.source.data_dir));
    page.data = data.get();
    page.data_name = o.source.data_dir;
  }
  page.source = o.source.model_path.empty()
                    ? "data " + o.source.data_dir + ", " + model->method() + " fit"
                    : o.source.model_path;
  const auto start = std::chrono::steady_clock::now();
  const exports::ExplorerPage built = exports::BuildExplorerPage(*model, colorimeters, page);
  const double ms = Milliseconds(start);
  if (!o.quiet) {
    std::cerr << "alloycolor: explorer tables: " << built.compositions << " compositions x "
              << built.angles << " angles x " << built.illuminants << " illuminants x "
              << built.finishes << " finishes in " << Format("%.0f", ms) << " ms; largest error at "
              << built.check_points << " check points: dE00 " << Format("%.3g", built.max_de00)
              << ", 8-bit " << built.max_srgb8_difference << "\n";
    std::cerr << "alloycolor: page of " << Format("%.2f", built.html.size() / 1e6) << " MB\n";
  }
  if (!built.tolerance_met && !o.quiet) {
    Warn("the explorer's tables reached their size limit before meeting --tolerance " +
         Format("%g", page.tolerance_de00) +
         ": the page's colours may differ from 'alloycolor color' by up to dE00 " +
         Format("%.3g", built.max_de00) + " (measured), as the page says");
  }
  WriteOutput(o.out, built.html, o.quiet);
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
  cmd->add_option("--size", o->page.size,
                  "Width and height in pixels of each sphere and ring picture (64-1024)")
      ->capture_default_str();
  cmd->add_option("--tolerance", o->page.tolerance_de00,
                  "Largest CIEDE2000 error allowed while choosing the table's density")
      ->capture_default_str();
  cmd->add_option("--threads", o->page.threads, "Threads to compute with (0: all the hardware's)")
      ->capture_default_str();
  cmd->add_flag("--quiet", o->quiet, "No warnings or progress on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
