// alloycolor tolerance: how precisely a composition must be held for its colour to stay
// within a CIEDE2000 of its own under every illuminant and angle given (color/match.h).
#include <cctype>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "alloycolor/color/match.h"
#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/text.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct ToleranceCommandOptions {
  ModelSource source;
  std::string x_text;
  double de00 = 1.0;
  std::string angles = "0";
  std::string illuminants = "D65";
  int observer = 2;
  bool json = false;
  bool quiet = false;
};

std::vector<std::string> Names(const std::string& text) {
  std::vector<std::string> names;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    names.push_back(std::string(Trim(text.substr(start, comma - start))));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return names;
}

void Run(const ToleranceCommandOptions& o) {
  if (const size_t comma = o.x_text.find(','); comma != std::string::npos) {
    const std::string_view whole = Trim(std::string_view(o.x_text).substr(0, comma));
    const std::string_view fraction = Trim(std::string_view(o.x_text).substr(comma + 1));
    if (!whole.empty() && whole.find_first_not_of("0123456789") == std::string_view::npos &&
        !fraction.empty() && std::isdigit(static_cast<unsigned char>(fraction.front())) &&
        fraction.find(',') == std::string_view::npos) {
      throw Error("--x: " + Quote(o.x_text) + " has a decimal comma: write " + std::string(whole) +
                  "." + std::string(fraction) + " (the decimal mark is a point)");
    }
    throw Error("--x: give one composition, not the list " + Quote(o.x_text));
  }
  const std::vector<double> angles = ParseNumberList(o.angles, "--angles");
  for (const double a : angles) CheckAngleDeg("--angles", a);
  std::vector<color::Colorimeter> colorimeters;
  for (const std::string& name : Names(o.illuminants)) {
    if (name.empty()) throw Error("--illuminants: an empty name in " + Quote(o.illuminants));
    colorimeters.push_back(LoadColorimeter(name, o.observer));
  }
  const auto model = o.source.Load(o.quiet);
  const double x = ParseCompositionArg(o.x_text, model->system(), "--x");
  CheckComposition(*model, x, false);
  color::ToleranceOptions options;
  options.de00 = o.de00;
  options.angles_deg = angles;
  const color::ToleranceWindow w = color::Tolerance(colorimeters, *model, x, options);
  const AlloySystem& system = model->system();
  std::string conditions;
  for (const color::Colorimeter& c : colorimeters) {
    conditions += (conditions.empty() ? "" : ", ") + c.illuminant();
  }
  conditions += " at " + o.angles + " degrees";
  if (o.json) {
    nlohmann::json out = {{"system", system.Name()},
                          {"method", model->method()},
                          {"x_atomic", x},
                          {"x_low", w.x_low},
                          {"x_high", w.x_high},
                          {"x_low_composition", CompositionJson(w.x_low, system)},
                          {"x_high_composition", CompositionJson(w.x_high, system)},
                          {"clipped_low", w.clipped_low},
                          {"clipped_high", w.clipped_high},
                          {"limit_low", w.limit_low},
                          {"limit_high", w.limit_high},
                          {"de00", o.de00},
                          {"de00_per_at_percent", w.de00_per_x / 100.0},
                          {"angles_deg", angles},
                          {"illuminants", Names(o.illuminants)},
                          {"observer", o.observer},
                          {"x_range", {model->x_min(), model->x_max()}}};
    out["model_sigma_de00"] = NumberOrNull(w.model_sigma_de00);
    out["x_sigma"] = NumberOrNull(w.x_sigma);
    if (!model->HasUncertainty()) out["error_bar"] = model->NoErrorBarReason();
    std::cout << out.dump(2) << "\n";
    return;
  }
  char line[256];
  std::string text = system.Name() + ", " + model->method() +
                     " model at x = " + DescribeComposition(x, system) + "\n";
  std::snprintf(line, sizeof line,
                "colour within dE00 %g of its own (%s) for x in [%.5f, %.5f]: %+.3f / %+.3f at%%\n",
                o.de00, conditions.c_str(), w.x_low, w.x_high, 100 * (w.x_low - x),
                100 * (w.x_high - x));
  text += line;
  text += "  low end:  " + DescribeComposition(w.x_low, system) +
          (w.clipped_low ? ", clipped at the model's range" : ", set by " + w.limit_low) + "\n";
  text += "  high end: " + DescribeComposition(w.x_high, system) +
          (w.clipped_high ? ", clipped at the model's range" : ", set by " + w.limit_high) + "\n";
  std::snprintf(line, sizeof line,
                "colour changes by %.3g dE00 per at%% at x (the fastest of %s)\n",
                w.de00_per_x / 100.0, conditions.c_str());
  text += line;
  if (std::isfinite(w.model_sigma_de00)) {
    std::snprintf(line, sizeof line,
                  "the model's own one-sigma there: dE00 %.3g, a composition of +- %.3g at%%\n",
                  w.model_sigma_de00, 100 * w.x_sigma);
    text += line;
  } else {
    text += model->NoErrorBarReason() + "\n";
  }
  std::cout << text;
}

}  // namespace

void RegisterTolerance(CLI::App& app) {
  auto o = std::make_shared<ToleranceCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tolerance", "The composition window within which the colour stays within --de");
  cmd->footer(
      "The composition window around --x within which the colour stays within --de (CIEDE2000) "
      "of its own at every angle and illuminant given, and how fast colour changes with "
      "composition there; clipped at the model's range, and says so.");
  o->source.AddOptions(cmd, true, /*with_extrapolate=*/false);
  cmd->add_option("--x", o->x_text, "Composition: 0.75, 75at%, 75wt% or 18k")->required();
  cmd->add_option("--de", o->de00, "Largest colour difference allowed (CIEDE2000)")
      ->check(NumberIn(color::kToleranceDeRange))
      ->capture_default_str();
  cmd->add_option("--angles", o->angles, "Angles of incidence in degrees, comma-separated")
      ->capture_default_str();
  cmd->add_option("--illuminants", o->illuminants,
                  "CIE illuminants, comma-separated: A, C, D50, D65, E, F2, F11")
      ->capture_default_str();
  cmd->add_option("--observer", o->observer, "CIE observer: 2 (1931) or 10 (1964)")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print one JSON object");
  cmd->add_flag("--quiet", o->quiet, "No warnings or progress on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
