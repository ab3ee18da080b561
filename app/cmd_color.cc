// alloycolor color: the colour of a polished metal from measured n, k (--nk) or of an
// alloy at any composition from a data set or a fitted model.
#include <cstdio>
#include <cmath>
#include <iostream>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/io.h"
#include "alloycolor/color/material_color.h"
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

void PrintHeader(std::string* text, const std::string& what, const ColorOptions& o) {
  Append(text, "%s; illuminant %s, %d-degree observer, incidence %g degrees\n",
         MessageLine(what, 200).c_str(), o.illuminant.c_str(), o.observer, o.angle_deg);
  Append(text, "%-10s %8s %8s %8s %8s %8s %8s  %-8s %-15s %s\n", "x", "X", "Y", "Z", "L*", "a*",
         "b*", "sRGB", "sRGB8", "paper RGB");
}

// Throws Error naming the composition when any printed figure is not finite.
void RequireFinite(const color::ColorResult& c, double sigma, const std::string& where) {
  const double values[] = {c.xyz.X,       c.xyz.Y,       c.xyz.Z,       c.lab.L, c.lab.a,
                           c.lab.b,       c.paper_rgb.r, c.paper_rgb.g, c.paper_rgb.b, sigma};
  for (const double v : values) {
    if (!std::isfinite(v)) {
      throw Error(where + ": the colour is not finite (the model or the colour tables give "
                          "NaN or infinity here)");
    }
  }
}

void PrintRow(std::string* text, const std::string& label, const color::ColorResult& c,
              double sigma) {
  char rgb8[32];
  std::snprintf(rgb8, sizeof rgb8, "%d,%d,%d", c.srgb8[0], c.srgb8[1], c.srgb8[2]);
  Append(text, "%-10s %8.4f %8.4f %8.4f %8.3f %8.3f %8.3f  %-8s %-15s %.3f,%.3f,%.3f",
         label.c_str(), c.xyz.X, c.xyz.Y, c.xyz.Z, c.lab.L, c.lab.a, c.lab.b,
         color::HexColor(c.srgb8).c_str(), rgb8, c.paper_rgb.r, c.paper_rgb.g, c.paper_rgb.b);
  if (sigma >= 0) Append(text, "  (1-sigma dE00 %.3g)", sigma);
  *text += "\n";
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
  nlohmann::json results = nlohmann::json::array();
  std::string text;
  if (!o.json) PrintHeader(&text, model->system().Name() + ", " + model->method() + " model", o);
  for (double x : xs) {
    const color::ColorResult c = color::ColorFromXYZ(
        colorimeter, color::MaterialXYZ(colorimeter,
                                         color::IndexOnGrid(colorimeter, *model, x),
                                         o.angle_deg));
    const double sigma = color::DeltaE00Sigma(colorimeter, *model, x, o.angle_deg);
    RequireFinite(c, sigma, model->source() + ": composition x = " + FormatNumber(x));
    if (o.json) {
      nlohmann::json r = {{"x", x},
                          {"x_weight", WeightFromAtomicFraction(x, model->system())}};
      r.update(color::ColorJson(c));
      if (sigma >= 0) r["delta_e00_sigma"] = sigma;
      results.push_back(r);
    } else {
      char label[32];
      std::snprintf(label, sizeof label, "%.4g", x);
      PrintRow(&text, label, c, sigma);
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
    text = JsonText(out, 2) + "\n";
  }
  PrintOutput(text);
}

}  // namespace

void RegisterColor(CLI::App& app) {
  auto o = std::make_shared<ColorOptions>();
  CLI::App* cmd = app.add_subcommand(
      "color",
      "Colour of a polished metal: from measured n, k (--nk FILE), or of an alloy at "
      "composition(s) --x from a data set (--data, the method fit would choose by default) or a fitted "
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
