// alloycolor color: the colour of a polished metal from measured n, k (--nk) or of an
// alloy at any composition from a data set or a fitted model.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/text.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct ColorOptions {
  MaterialSource material;
  double angle_deg = 0.0;
  std::string illuminant = "D65";
  int observer = 2;
  bool json = false;
  bool quiet = false;
};

// printf into a string: every line is rendered before any is printed, so a failure
// prints nothing half-way.
template <typename... Args>
void Append(std::string* text, const char* format, Args... args) {
  char line[512];
  std::snprintf(line, sizeof line, format, args...);
  *text += line;
}

// `label_width`: the width of the first column, the composition as given.
void PrintHeader(std::string* text, const std::string& what, const ColorOptions& o,
                 int label_width = 10) {
  Append(text, "%s; illuminant %s, %d-degree observer, incidence %g degrees\n",
         MessageLine(what, 200).c_str(), o.illuminant.c_str(), o.observer, o.angle_deg);
  Append(text, "%-*s %8s %8s %8s %8s %8s %8s  %-8s %-15s %s\n", label_width, "x", "X", "Y", "Z",
         "L*", "a*", "b*", "sRGB", "sRGB8", "paper RGB");
}

// A composition as the user wrote it, with its atomic fraction beside it unless it was
// written as one: "18k (x = 0.6216)", "0.5".
std::string CompositionLabel(const std::string& given, double x) {
  char fraction[32];
  std::snprintf(fraction, sizeof fraction, "%.4g", x);
  double value = 0;
  if (ParseFiniteDouble(given, &value)) return given;
  return MessageLine(given, 40) + " (x = " + fraction + ")";
}

// Throws Error naming the composition when any printed figure is not finite.
void RequireFinite(const color::ColorResult& c, double sigma, const std::string& where) {
  const double values[] = {c.xyz.X, c.xyz.Y,       c.xyz.Z,       c.lab.L,       c.lab.a,
                           c.lab.b, c.paper_rgb.r, c.paper_rgb.g, c.paper_rgb.b, sigma};
  for (const double v : values) {
    if (!std::isfinite(v)) {
      throw Error(where +
                  ": the colour is not finite (the model or the colour tables give "
                  "NaN or infinity here)");
    }
  }
}

void PrintRow(std::string* text, const std::string& label, const color::ColorResult& c,
              double sigma, int label_width = 10) {
  char rgb8[32];
  std::snprintf(rgb8, sizeof rgb8, "%d,%d,%d", c.srgb8[0], c.srgb8[1], c.srgb8[2]);
  Append(text, "%-*s %8.4f %8.4f %8.4f %8.3f %8.3f %8.3f  %-8s %-15s %.3f,%.3f,%.3f", label_width,
         label.c_str(), c.xyz.X, c.xyz.Y, c.xyz.Z, c.lab.L, c.lab.a, c.lab.b,
         color::HexColor(c.srgb8).c_str(), rgb8, c.paper_rgb.r, c.paper_rgb.g, c.paper_rgb.b);
  if (sigma >= 0) Append(text, "  (1-sigma dE00 %.3g)", sigma);
  *text += "\n";
}

void Run(const ColorOptions& o) {
  const color::Colorimeter colorimeter = LoadColorimeter(o.illuminant, o.observer);
  CheckAngleDeg("--angle", o.angle_deg);
  nlohmann::json common = {
      {"illuminant", colorimeter.illuminant()},
      {"observer", o.observer},
      {"angle_deg", o.angle_deg},
      {"integrated_nm", {colorimeter.lambda_nm().front(), colorimeter.lambda_nm().back()}}};
  if (o.material.measured()) {
    const NkSpectrum nk = o.material.LoadMeasured(o.quiet);
    const color::ColorResult c = color::ColorFromXYZ(
        colorimeter,
        color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, nk), o.angle_deg));
    if (o.json) {
      nlohmann::json out = common;
      out["source"] = o.material.nk_file;
      out.update(color::ColorJson(c));
      RequireFinite(c, 0, o.material.nk_file);
      PrintOutput(JsonText(out, 2) + "\n");
    } else {
      RequireFinite(c, 0, o.material.nk_file);
      std::string text;
      PrintHeader(&text, o.material.nk_file, o);
      PrintRow(&text, "-", c, -1);
      PrintOutput(text);
    }
    return;
  }
  const auto model = o.material.LoadModel(o.quiet);
  const std::vector<double> xs = o.material.Compositions(*model, false);
  const std::vector<std::string> given = o.material.CompositionTexts();
  std::vector<std::string> labels;
  int label_width = 10;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    labels.push_back(CompositionLabel(given.at(i), xs[i]));
    label_width = std::max(label_width, static_cast<int>(labels.back().size()));
  }
  nlohmann::json results = nlohmann::json::array();
  std::string text;
  if (!o.json) {
    PrintHeader(&text, model->system().Name() + ", " + model->method() + " model", o, label_width);
  }
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const double x = xs[i];
    const color::ColorResult c = color::ColorFromXYZ(
        colorimeter,
        color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, *model, x), o.angle_deg));
    const double sigma = color::DeltaE00Sigma(colorimeter, *model, x, o.angle_deg);
    RequireFinite(c, sigma, model->source() + ": composition x = " + FormatNumber(x));
    if (o.json) {
      nlohmann::json r = {{"x", x},
                          {"x_given", given.at(i)},
                          {"x_weight", WeightFromAtomicFraction(x, model->system())}};
      r.update(color::ColorJson(c));
      if (sigma >= 0) {
        r["delta_e00_sigma"] = sigma;
      } else {
        r["delta_e00_sigma"] = nullptr;
        r["error_bar"] = model->NoErrorBarReason();
      }
      results.push_back(r);
    } else {
      PrintRow(&text, labels[i], c, sigma, label_width);
    }
  }
  if (!o.json && !model->HasUncertainty()) text += model->NoErrorBarReason() + "\n";
  if (o.json) {
    nlohmann::json out = common;
    out["system"] = model->system().Name();
    out["method"] = model->method();
    if (results.size() == 1) {
      out.update(results[0]);
    } else {
      out["results"] = results;
    }
    text = JsonText(out, 2) + "\n";
  }
  PrintOutput(text);
}

}  // namespace

void RegisterColor(CLI::App& app) {
  auto o = std::make_shared<ColorOptions>();
  CLI::App* cmd = app.add_subcommand(
      "color", "Colour of a polished metal: measured n, k (--nk) or an alloy at --x compositions");
  cmd->footer(
      "Colour of a polished metal: from measured n, k (--nk FILE), or of an alloy at "
      "composition(s) --x from a data set (--data, the method fit would choose by default) or a "
      "fitted "
      "model (--model). Spectral Fresnel reflectance integrated against the illuminant and "
      "observer; outputs XYZ (perfect reflector Y = 1), CIELAB (white = the illuminant's), "
      "linear and 8-bit sRGB (IEC 61966-2-1, no chromatic adaptation) and the paper's RGB.");
  o->material.AddOptions(cmd,
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
