// alloycolor chart: the composition chart, a strip of swatches from one element to the
// other with the composition under each (like the handbook figure of the paper), as SVG
// (with labels) or PNG (swatches only; compositions in the file's text chunks).
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/render/image.h"
#include "common.h"
#include "report.h"

namespace alloycolor::app {
namespace {

struct ChartOptions {
  ModelSource source;
  std::string from_text, to_text;
  int steps = 11;
  double angle_deg = 0.0;
  std::string illuminant = "D65";
  int observer = 2;
  std::string labels;
  std::string out;
  bool quiet = false;
};

void Run(const ChartOptions& o) {
  if (o.out.empty()) throw Error("--out: give the chart file (.svg or .png)");
  const std::string ext = std::filesystem::path(o.out).extension().string();
  if (ext != ".svg" && ext != ".png") {
    throw Error("--out " + o.out + ": the chart is written as .svg or .png");
  }
  if (o.steps < 2 || o.steps > 1000) {
    throw Error("--steps: " + std::to_string(o.steps) + " is not between 2 and 1000");
  }
  CheckAngleDeg("--angle", o.angle_deg);
  if (!o.labels.empty() && o.labels != "atomic" && o.labels != "weight") {
    throw Error("--labels: '" + o.labels + "' is not atomic or weight");
  }
  const color::Colorimeter colorimeter = LoadColorimeter(o.illuminant, o.observer);
  const auto model = o.source.Load(o.quiet);
  const auto [from, to] = CompositionRange(*model, o.from_text, o.to_text, o.source.extrapolate);
  const bool weight =
      o.labels.empty() ? model->composition() == "weight_fraction_a" : o.labels == "weight";
  const CompositionChart chart =
      validate::ComputeChart(*model, colorimeter, from, to, o.steps, o.angle_deg, weight);
  if (ext == ".svg") {
    WriteOutput(o.out, ChartSvg(chart), o.quiet);
    return;
  }
  std::string compositions;
  for (const validate::ChartSwatch& s : chart.swatches) {
    char buf[80];
    std::snprintf(buf, sizeof buf, "%s%.6g %s", compositions.empty() ? "" : ", ", s.x_atomic,
                  color::HexColor(s.srgb8).c_str());
    compositions += buf;
  }
  const std::string png = render::PngBytes(
      ChartImage(chart, 64, 8),
      {{"Title", chart.system + " colour by composition"},
       {"Description", chart.method + " model; " + chart.illuminant + ", " +
                           std::to_string(chart.observer_deg) +
                           "-degree observer; swatches left to right at atomic fraction of " +
                           chart.element_a + ": " + compositions},
       {"Software", "alloycolor " ALLOYCOLOR_VERSION}});
  WriteOutput(o.out, png, o.quiet);
}

}  // namespace

void RegisterChart(CLI::App& app) {
  auto o = std::make_shared<ChartOptions>();
  CLI::App* cmd = app.add_subcommand(
      "chart", "A strip of colour swatches from one composition to another (SVG or PNG)");
  cmd->footer(
      "Composition chart: a strip of sRGB swatches of the polished alloy from one "
      "composition to another, like the handbook chart of Au-Ag colours. SVG carries the "
      "composition under each swatch and the elements at the ends; PNG is the swatches only "
      "(compositions in its text chunks).");
  o->source.AddOptions(cmd, true);
  cmd->add_option("--from", o->from_text,
                  "First composition (0.25, 25at%, 25wt%, 6k; default: the model's lowest)");
  cmd->add_option("--to", o->to_text, "Last composition (default: the model's highest)");
  cmd->add_option("--steps", o->steps, "Number of swatches")->capture_default_str();
  cmd->add_option("--angle", o->angle_deg, "Angle of incidence in degrees (0-90)")
      ->capture_default_str();
  AddColorimetryOptions(cmd, &o->illuminant, &o->observer);
  cmd->add_option("--labels", o->labels,
                  "Label compositions in atomic or weight percent (default: as the data "
                  "set's manifest)");
  cmd->add_option("--out", o->out, "Chart file: .svg or .png (written atomically)")->required();
  cmd->add_flag("--quiet", o->quiet, "No warnings or progress on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
