// alloycolor match: the composition of an alloy whose colour (or reflectance spectrum) is
// closest to a target, with its one-sigma and every other local minimum within a margin
// (color/match.h).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/color/match.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/text.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct MatchCommandOptions {
  ModelSource source;
  std::string lab, xyz, hex, reflectance, nk, columns;
  double angle_deg = 0.0;
  std::string illuminant = "D65";
  int observer = 2;
  double target_sigma = 0.0;
  double margin = 1.0;
  bool json = false;
  bool quiet = false;
};

std::vector<double> Three(const std::string& text, const std::string& option) {
  const std::vector<double> v = ParseNumberList(text, option);
  if (v.size() != 3) {
    throw Error(option + ": " + Quote(MessageLine(text, 60)) + " is not three numbers " +
                (option == "--lab" ? "L,a,b" : "X,Y,Z"));
  }
  return v;
}

// The target of --lab, --xyz or --hex as CIELAB, checked as match.h says (CheckTargetLab);
// every message names the option and blames the target.
color::Lab ColourTarget(const MatchCommandOptions& o, const color::Colorimeter& colorimeter,
                        std::string* target_text) {
  const std::string option = !o.lab.empty() ? "--lab" : !o.xyz.empty() ? "--xyz" : "--hex";
  try {
    color::Lab target{};
    if (!o.lab.empty()) {
      const std::vector<double> v = Three(o.lab, "--lab");
      target = {v[0], v[1], v[2]};
      *target_text =
          "L*a*b* " + FormatNumber(v[0]) + "," + FormatNumber(v[1]) + "," + FormatNumber(v[2]);
    } else if (!o.xyz.empty()) {
      const std::vector<double> v = Three(o.xyz, "--xyz");
      target = color::LabFromTargetXYZ(colorimeter, {v[0], v[1], v[2]});
      *target_text =
          "XYZ " + FormatNumber(v[0]) + "," + FormatNumber(v[1]) + "," + FormatNumber(v[2]);
    } else {
      target = color::LabFromHex(colorimeter, o.hex);
      *target_text = "sRGB " + MessageLine(o.hex, 20);
    }
    color::CheckTargetLab(target);
    return target;
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind(option + ":", 0) == 0) throw;
    throw Error(option + ": " + what);
  }
}

std::string SigmaText(double x_sigma) {
  if (std::isnan(x_sigma)) return "";
  if (!std::isfinite(x_sigma)) return " (colour does not change with composition here)";
  char text[64];
  std::snprintf(text, sizeof text, " +- %.3g at%%", 100 * x_sigma);
  return text;
}

std::string DistanceText(const color::Match& m, bool spectrum) {
  char text[96];
  if (spectrum) {
    std::snprintf(text, sizeof text, "reflectance RMS %.4f", m.reflectance_rms);
    std::string out = text;
    if (std::isfinite(m.de00)) {
      std::snprintf(text, sizeof text, ", dE00 %.3g", m.de00);
      out += text;
    }
    return out;
  }
  std::snprintf(text, sizeof text, "dE00 %.3g", m.de00);
  return text;
}

void Run(const MatchCommandOptions& o) {
  const int targets =
      !o.lab.empty() + !o.xyz.empty() + !o.hex.empty() + !o.reflectance.empty() + !o.nk.empty();
  if (targets != 1) {
    throw Error("give exactly one target: --lab, --xyz, --hex, --reflectance or --nk");
  }
  if (!o.columns.empty() && o.nk.empty()) throw Error("--columns applies to --nk FILE only");
  CheckAngleDeg("--angle", o.angle_deg);
  const color::Colorimeter colorimeter = LoadColorimeter(o.illuminant, o.observer);
  // Read the target before the (possibly slow) model, so a bad target fails at once.
  color::Lab target{};
  MeasuredReflectance spectrum;
  std::string target_text;
  std::vector<std::string> warnings;
  if (!o.lab.empty() || !o.xyz.empty() || !o.hex.empty()) {
    target = ColourTarget(o, colorimeter, &target_text);
  } else if (!o.nk.empty()) {
    const NkSpectrum nk =
        ReadNkFile(o.nk, o.columns.empty() ? NkColumns{} : ParseNkColumns(o.columns), &warnings);
    target = LabFromXYZ(
        color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, nk), o.angle_deg),
        colorimeter.White());
    target_text = "the colour of " + MessageLine(o.nk, 120);
  } else {
    spectrum = ReadReflectanceDelimited(o.reflectance, &warnings);
    target_text = "the reflectance spectrum " + MessageLine(o.reflectance, 120);
  }
  if (!o.quiet) {
    for (const std::string& w : warnings) Warn(w);
  }
  const bool is_spectrum = !o.reflectance.empty();
  const auto model = o.source.Load(o.quiet);
  color::MatchOptions options;
  options.angle_deg = o.angle_deg;
  options.target_sigma_de00 = o.target_sigma;
  options.margin = o.margin;
  const color::ColourMatcher matcher(colorimeter, *model, options);
  const std::vector<color::Match> matches =
      is_spectrum ? matcher.FindReflectance(spectrum.lambda_nm, spectrum.reflectance, o.reflectance)
                  : matcher.Find(target);
  const color::Match& best = matches.front();
  // Reachable: the colour left is under kReachableDeltaE00 (a spectrum without colour:
  // judged by its reflectance RMS, under 1 %).
  const bool reachable = std::isfinite(best.de00)
                             ? best.de00 <= color::kReachableDeltaE00
                             : best.reflectance_rms <= color::kReachableDeltaE00 / 100.0;
  const AlloySystem& system = model->system();
  const std::string verdict =
      reachable ? "reachable with " + system.Name()
                : "not reachable with " + system.Name() +
                      ": the closest is x = " + DescribeComposition(best.x_atomic, system) + ", " +
                      DistanceText(best, is_spectrum) + " left";
  if (o.json) {
    nlohmann::json rows = nlohmann::json::array();
    for (const color::Match& m : matches) {
      nlohmann::json r = CompositionJson(m.x_atomic, system);
      r["x_sigma"] = NumberOrNull(m.x_sigma);
      r["de00"] = NumberOrNull(m.de00);
      if (is_spectrum) r["reflectance_rms"] = m.reflectance_rms;
      r["model_sigma_de00"] = NumberOrNull(m.model_sigma_de00);
      r["de00_per_at_percent"] = m.de00_per_x / 100.0;
      r["lab"] = {m.lab.L, m.lab.a, m.lab.b};
      r["at_range_end"] = m.at_range_end;
      rows.push_back(r);
    }
    nlohmann::json out = {{"system", system.Name()},
                          {"method", model->method()},
                          {"illuminant", colorimeter.illuminant()},
                          {"observer", o.observer},
                          {"angle_deg", o.angle_deg},
                          {"target", target_text},
                          {"target_sigma_de00", o.target_sigma},
                          {"margin", o.margin},
                          {"margin_unit", is_spectrum ? "reflectance percent" : "de00"},
                          {"reachable", reachable},
                          {"verdict", verdict},
                          {"x_range", {model->x_min(), model->x_max()}},
                          {"error_bar", model->HasUncertainty() ? std::string("one sigma")
                                                                : model->NoErrorBarReason()},
                          {"matches", rows}};
    if (!is_spectrum) out["target_lab"] = {target.L, target.a, target.b};
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::string text = system.Name() + ", " + model->method() + " model; target " + target_text +
                     " (illuminant " + colorimeter.illuminant() + ", " +
                     std::to_string(o.observer) + "-degree observer, incidence " +
                     FormatNumber(o.angle_deg) + " degrees)\n";
  if (!reachable) text += verdict + "\n";
  text += "best: x = " + DescribeComposition(best.x_atomic, system) + SigmaText(best.x_sigma) +
          "; " + DistanceText(best, is_spectrum) + " left" +
          (best.at_range_end ? " (at the end of the model's range)" : "") + "\n";
  if (!model->HasUncertainty()) text += model->NoErrorBarReason() + "\n";
  const std::string margin_text = is_spectrum ? FormatNumber(o.margin) + " % reflectance RMS"
                                              : "dE00 " + FormatNumber(o.margin);
  if (matches.size() == 1)
    text += "no other local minimum within " + margin_text + " of the best\n";
  if (matches.size() > 1) {
    text += "other local minima within " + margin_text + " of the best:\n";
    for (size_t i = 1; i < matches.size(); ++i) {
      text += "  x = " + DescribeComposition(matches[i].x_atomic, system) +
              SigmaText(matches[i].x_sigma) + "; " + DistanceText(matches[i], is_spectrum) +
              " left\n";
    }
  }
  std::cout << text;
}

}  // namespace

void RegisterMatch(CLI::App& app) {
  auto o = std::make_shared<MatchCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "match", "The composition whose colour (or reflectance) is closest to a target");
  cmd->footer(
      "The composition whose colour is closest to a target (--lab, --xyz, --hex, or the colour "
      "of measured n, k with --nk) or whose reflectance is closest to a measured spectrum "
      "(--reflectance FILE), within the model's range: the colour difference left, the "
      "composition's one-sigma (the model's colour uncertainty and --target-sigma over the "
      "rate at which colour changes with composition) and every other local minimum within "
      "--margin. Says so plainly when nothing comes within dE00 1.");
  o->source.AddOptions(cmd, true, /*with_extrapolate=*/false);
  cmd->add_option("--lab", o->lab, "Target CIELAB L,a,b (under --illuminant and --observer)");
  cmd->add_option("--xyz", o->xyz, "Target CIE XYZ X,Y,Z (a perfect reflector has Y = 1)");
  cmd->add_option("--hex", o->hex, "Target 8-bit sRGB '#rrggbb'");
  cmd->add_option("--reflectance", o->reflectance,
                  "Measured reflectance spectrum: delimited text, a wavelength column and R "
                  "(fraction, or percent when named 'R (%)')");
  cmd->add_option("--nk", o->nk, "Measured n, k file: match its colour");
  cmd->add_option("--columns", o->columns, "With --nk: the n and k columns (N,K)");
  cmd->add_option("--angle", o->angle_deg, "Angle of incidence in degrees (0-90)")
      ->capture_default_str();
  AddColorimetryOptions(cmd, &o->illuminant, &o->observer);
  cmd->add_option("--target-sigma", o->target_sigma,
                  "One-sigma dE00 of the target's own measurement")
      ->check(NumberIn(color::kTargetSigmaRange))
      ->capture_default_str();
  cmd->add_option("--margin", o->margin,
                  "List other local minima within this dE00 of the best (for --reflectance: "
                  "percent of reflectance RMS)")
      ->check(NumberIn(color::kMatchMarginRange))
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print one JSON object");
  cmd->add_flag("--quiet", o->quiet, "No warnings or progress on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
