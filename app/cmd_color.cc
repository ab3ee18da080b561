// alloycolor color: the colour of a polished metal from measured n, k (--nk) or of an
// alloy at any composition from a data set or a fitted model.
#include <cstdio>
#include <iostream>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/color/material_color.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct ColorOptions {
  NkFileOption nk;
  ModelSource source;
  std::string x_text;
  double angle_deg = 0.0;
  std::string illuminant = "D65";
  int observer = 2;
  bool json = false;
  bool quiet = false;
};

void PrintHeader(const std::string& what, const ColorOptions& o) {
  std::printf("%s; illuminant %s, %d-degree observer, incidence %g degrees\n", what.c_str(),
              o.illuminant.c_str(), o.observer, o.angle_deg);
  std::printf("%-10s %8s %8s %8s %8s %8s %8s  %-8s %-15s %s\n", "x", "X", "Y", "Z", "L*",
              "a*", "b*", "sRGB", "sRGB8", "paper RGB");
}

void PrintRow(const std::string& label, const color::ColorResult& c, double sigma) {
  char rgb8[32];
  std::snprintf(rgb8, sizeof rgb8, "%d,%d,%d", c.srgb8[0], c.srgb8[1], c.srgb8[2]);
  std::printf("%-10s %8.4f %8.4f %8.4f %8.3f %8.3f %8.3f  %-8s %-15s %.3f,%.3f,%.3f",
              label.c_str(), c.xyz.X, c.xyz.Y, c.xyz.Z, c.lab.L, c.lab.a, c.lab.b,
              color::HexColor(c.srgb8).c_str(), rgb8, c.paper_rgb.r, c.paper_rgb.g,
              c.paper_rgb.b);
  if (sigma >= 0) std::printf("  (1-sigma dE00 %.3f)", sigma);
  std::printf("\n");
}

void Run(const ColorOptions& o) {
  const color::Colorimeter colorimeter = LoadColorimeter(o.illuminant, o.observer);
  if (!(o.angle_deg >= 0.0 && o.angle_deg <= 90.0)) {
    std::ostringstream msg;
    msg << "--angle: " << o.angle_deg << " lies outside 0-90 degrees";
    throw Error(msg.str());
  }
  nlohmann::json common = {{"illuminant", colorimeter.illuminant()},
                           {"observer", o.observer},
                           {"angle_deg", o.angle_deg},
                           {"integrated_nm",
                            {colorimeter.lambda_nm().front(), colorimeter.lambda_nm().back()}}};
  o.nk.Validate();
  if (!o.nk.file.empty()) {
    if (!o.source.model_path.empty() || !o.source.data_dir.empty() || !o.x_text.empty()) {
      throw Error("--nk takes no --model, --data or --x");
    }
    std::vector<std::string> warnings;
    const NkSpectrum nk = o.nk.Read(&warnings);
    if (!o.quiet) {
      for (const auto& w : warnings) Warn(w);
    }
    const color::ColorResult c = color::ColorFromXYZ(
        colorimeter,
        color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, nk), o.angle_deg));
    if (o.json) {
      nlohmann::json out = common;
      out["source"] = o.nk.file;
      out.update(color::ColorJson(c));
      std::cout << out.dump(2) << "\n";
    } else {
      PrintHeader(o.nk.file, o);
      PrintRow("-", c, -1);
    }
    return;
  }
  const auto model = o.source.Load(o.quiet);
  if (o.x_text.empty()) throw Error("--x: give the composition(s), e.g. --x 0.75 or 18k");
  const std::vector<double> xs = ParseCompositions(o.x_text, model->system());
  nlohmann::json results = nlohmann::json::array();
  if (!o.json) {
    PrintHeader(model->system().Name() + ", " + model->method() + " model", o);
  }
  for (double x : xs) {
    CheckComposition(*model, x, o.source.extrapolate);
    const color::ColorResult c = color::ColorFromXYZ(
        colorimeter, color::MaterialXYZ(colorimeter,
                                         color::IndexOnGrid(colorimeter, *model, x),
                                         o.angle_deg));
    const double sigma = color::DeltaE00Sigma(colorimeter, *model, x, o.angle_deg);
    if (o.json) {
      nlohmann::json r = {{"x", x},
                          {"x_weight", WeightFromAtomicFraction(x, model->system())}};
      r.update(color::ColorJson(c));
      if (sigma >= 0) r["delta_e00_sigma"] = sigma;
      results.push_back(r);
    } else {
      char label[32];
      std::snprintf(label, sizeof label, "%.4g", x);
      PrintRow(label, c, sigma);
    }
  }
  if (o.json) {
    nlohmann::json out = common;
    out["system"] = model->system().Name();
    out["method"] = model->method();
    if (results.size() == 1) {
      out.update(results[0]);
    } else {
      out["results"] = results;
    }
    std::cout << out.dump(2) << "\n";
  }
}

}  // namespace

void RegisterColor(CLI::App& app) {
  auto o = std::make_shared<ColorOptions>();
  CLI::App* cmd = app.add_subcommand(
      "color",
      "Colour of a polished metal: from measured n, k (--nk FILE), or of an alloy at "
      "composition(s) --x from a data set (--data, paper baseline by default) or a fitted "
      "model (--model). Spectral Fresnel reflectance integrated against the illuminant and "
      "observer; outputs XYZ (perfect reflector Y = 1), CIELAB (white = the illuminant's), "
      "linear and 8-bit sRGB (IEC 61966-2-1, no chromatic adaptation) and the paper's RGB.");
  o->nk.AddOptions(cmd);
  o->source.AddOptions(cmd, true);
  cmd->add_option("--x", o->x_text,
                  "Composition(s) of the system's first element, comma-separated: 0.75, "
                  "75at%, 75wt%, 18k");
  cmd->add_option("--angle", o->angle_deg, "Angle of incidence in degrees (0-90)")
      ->capture_default_str();
  AddColorimetryOptions(cmd, &o->illuminant, &o->observer);
  cmd->add_flag("--json", o->json, "Print one JSON object");
  cmd->add_flag("--quiet", o->quiet, "No warnings or progress on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
