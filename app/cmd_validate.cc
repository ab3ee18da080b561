// alloycolor validate: refit every method without held-out samples, predict them and write
// a validation report (report.json and a self-contained report.html); see report.h.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/fit/lineage.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/registry.h"
#include "common.h"
#include "report.h"

namespace alloycolor::app {
namespace {

struct ValidateOptions {
  std::string data_dir;
  std::string holdout_text;
  bool loo = false;
  std::string methods;  // empty: the registry's defaults (DefaultValidationMethods)
  std::string angles = "0,45";
  std::string illuminant = "D65";
  int observer = 2;
  std::string out;
  bool quiet = false;
  bool verbose = false;
  int threads = 0;
};

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    const size_t b = part.find_first_not_of(" \t");
    const size_t e = part.find_last_not_of(" \t");
    parts.push_back(b == std::string::npos ? "" : part.substr(b, e - b + 1));
  }
  if (!text.empty() && text.back() == ',') parts.push_back("");
  return parts;
}

std::vector<validate::SampleSplit> Splits(const ValidateOptions& o, const Dataset& dataset) {
  if (o.loo && !o.holdout_text.empty()) throw Error("give --holdout or --loo, not both");
  if (o.holdout_text.empty()) return validate::LeaveOneOutSplits(dataset);
  try {
    return {validate::HoldoutSplit(dataset, SplitList(o.holdout_text))};
  } catch (const Error& e) {
    throw Error(std::string("--holdout: ") + e.what());
  }
}

// Creates the report folder and checks that files can be written there, before the work.
void PrepareOutput(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  CreateOutputFolder(dir, "--out");  // removed again when the run stops before writing
  const std::string probe = (fs::path(dir) / ".alloycolor-write-check").string();
  WriteFileAtomic(probe, "", &ProgramGuard());
  fs::remove(probe, ec);
  for (const char* name : {"report.json", "report.html"}) {
    CheckOutputPath((fs::path(dir) / name).string());  // no symlink or device to replace
  }
}

// printf into a string.
__attribute__((format(printf, 2, 3))) void Appendf(std::string* text, const char* format, ...) {
  va_list args, again;
  va_start(args, format);
  va_copy(again, args);
  const int n = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  if (n > 0) {
    const std::size_t at = text->size();
    text->resize(at + static_cast<std::size_t>(n) + 1);
    std::vsnprintf(text->data() + at, static_cast<std::size_t>(n) + 1, format, again);
    text->resize(at + static_cast<std::size_t>(n));
  }
  va_end(again);
}

// The summary table printed after the report is written.
std::string SummaryText(const nlohmann::json& report) {
  std::string text;
  const auto& methods = report["methods"];
  Appendf(&text, "%-18s", "metric (mean)");
  for (const auto& m : methods) Appendf(&text, " %16s", m.get<std::string>().c_str());
  Appendf(&text, "\n");
  // delta_e00 per angle first, then the spectral metrics.
  std::vector<std::string> keys;
  for (const auto& [metric, row] : report["summary"].items()) {
    if (metric.rfind("delta_e00", 0) == 0) keys.push_back(metric);
  }
  for (const char* k : {"reflectance_rms", "reflectance_max", "n_max_abs", "k_max_abs"}) {
    if (report["summary"].contains(k)) keys.push_back(k);
  }
  for (const std::string& metric : keys) {
    const auto& row = report["summary"][metric];
    Appendf(&text, "%-18s", metric.c_str());
    for (const auto& m : methods) {
      const auto& cell = row[m.get<std::string>()];
      char buf[48];
      if (cell["mean"].is_null()) {
        std::snprintf(buf, sizeof buf, "-");
      } else {
        std::snprintf(buf, sizeof buf, "%.4g (%d/%d)", cell["mean"].get<double>(),
                      cell["wins"].get<int>(), cell["count"].get<int>());
      }
      Appendf(&text, " %16s", buf);
    }
    Appendf(&text, "\n");
  }
  // How often the observed colour error lay within the method's 1 and 2 sigma.
  const auto& honesty = report["sigma_honesty"];
  std::vector<std::string> angles;
  for (const auto& [method, per_angle] : honesty.items()) {
    for (const auto& [angle, cell] : per_angle.items()) {
      if (std::find(angles.begin(), angles.end(), angle) == angles.end()) angles.push_back(angle);
    }
  }
  for (const std::string& angle : angles) {
    for (const char* key : {"within_1_sigma", "within_2_sigma"}) {
      Appendf(
          &text, "%-18s",
          (std::string(key == std::string("within_1_sigma") ? "in_1sigma_" : "in_2sigma_") + angle)
              .c_str());
      for (const auto& m : methods) {
        const std::string name = m.get<std::string>();
        char buf[48];
        if (!honesty.contains(name) || !honesty[name].contains(angle)) {
          std::snprintf(buf, sizeof buf, "-");
        } else {
          const auto& cell = honesty[name][angle];
          std::snprintf(buf, sizeof buf, "%d/%d", cell[key].get<int>(), cell["count"].get<int>());
        }
        Appendf(&text, " %16s", buf);
      }
      Appendf(&text, "\n");
    }
  }
  // The composition recovered from each held-out sample's colour (report.json's
  // composition_recovery): mean |error| in at%, and how many lay within two sigma.
  const auto& recovery = report["composition_recovery"];
  if (!recovery.empty()) {
    for (const bool sigma_row : {false, true}) {
      Appendf(&text, "%-18s", sigma_row ? "recovered_in_2sig" : "recovery_at%");
      for (const auto& m : methods) {
        const std::string name = m.get<std::string>();
        char buf[48];
        if (!recovery.contains(name)) {
          std::snprintf(buf, sizeof buf, "-");
        } else if (sigma_row) {
          std::snprintf(buf, sizeof buf, "%d/%d", recovery[name]["within_2_sigma"].get<int>(),
                        recovery[name]["with_sigma"].get<int>());
        } else {
          std::snprintf(buf, sizeof buf, "%.3g",
                        recovery[name]["mean_abs_error_at_percent"].get<double>());
        }
        Appendf(&text, " %16s", buf);
      }
      Appendf(&text, "\n");
    }
  }
  if (!report["delta_e00_available"].get<bool>()) {
    Appendf(&text, "delta_e00: %s\n",
            report["metric_ranges"]["delta_e00"].get<std::string>().c_str());
  }
  return text;
}

void Run(const ValidateOptions& o) {
  ThreadBudget threads(o.threads);
  if (o.out.empty()) throw Error("--out: give the report folder");
  const Dataset dataset = LoadDatasetArg(o.data_dir);
  if (!o.quiet) {
    for (const std::string& w : dataset.warnings) Warn(w);
  }
  validate::ValidationOptions options;
  const color::Colorimeter d65 = LoadColorimeter("D65", 2);
  options.build = fit::SharedFitBuilder(d65, &threads);
  options.threads = &threads;
  options.methods = MethodList(o.methods, "--methods");
  options.angles_deg = ParseNumberList(o.angles, "--angles");
  for (double a : options.angles_deg) CheckAngleDeg("--angles", a);
  options.mode = o.holdout_text.empty() ? "loo" : "holdout";
  const std::vector<validate::SampleSplit> splits = Splits(o, dataset);
  const color::Colorimeter colorimeter = LoadColorimeter(o.illuminant, o.observer);
  PrepareOutput(o.out);

  const auto start = std::chrono::steady_clock::now();
  ProgressCallback progress;
  if (!o.quiet) {
    progress = [start](const std::string& message) {
      const double s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "alloycolor: %6.1f s  %s\n", s, message.c_str());
    };
  }
  if (o.verbose) options.details = progress;
  // The report opens with the whole data set as a fit of it sees it.
  options.fit_whole = fit::WholeDataSetFitter(d65, &threads);
  const ValidationReport report =
      validate::ComputeValidation(dataset, splits, colorimeter, options, progress);
  // Both files are rendered before either is written, and written as a set.
  const nlohmann::json json = ValidationJson(report);
  const std::string json_text = JsonText(json, 1) + "\n";
  const std::string html_text = ValidationHtml(report);
  namespace fs = std::filesystem;
  WriteOutputs({{(fs::path(o.out) / "report.json").string(), json_text},
                {(fs::path(o.out) / "report.html").string(), html_text}},
               o.quiet);
  PrintOutput(SummaryText(json));
}

}  // namespace

void RegisterValidate(CLI::App& app) {
  auto o = std::make_shared<ValidateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "validate", "Report on held-out compositions: every method refitted without them and scored");
  cmd->footer(
      "Validation report on held-out compositions: every method is refitted without the "
      "held-out samples (the same split for all), predicts them, and is scored by CIEDE2000 "
      "colour difference at each angle, reflectance RMS and maximum error (380-780 nm, or the "
      "data's range for infrared sets), max |dn|, |dk|, and its own one-sigma colour "
      "uncertainty where it has one. Writes OUT/report.json and a self-contained "
      "OUT/report.html (tables, swatches, inline SVG plots); prints the mean of each metric "
      "per method (with wins/count) and how many held-out colour errors fell within each "
      "method's 1 and 2 sigma.");
  cmd->add_option("--data", o->data_dir,
                  "Data set: folder with dataset.json, a manifest, or a bundled set's name")
      ->required();
  cmd->add_option("--holdout", o->holdout_text,
                  "Hold out these samples together, comma-separated: a sample's file (that "
                  "replicate alone) or a composition (every replicate there; the manifest's "
                  "numbers or 75at%, 75wt%, 18k); not every sample of an end composition");
  cmd->add_flag("--loo", o->loo,
                "Leave one out: hold out each interior composition in turn, with all its "
                "replicates (the default)");
  std::string defaults;  // the methods the registry has validate run when none is named
  for (const std::string& m : DefaultValidationMethods()) {
    defaults += (defaults.empty() ? "" : ", ") + m;
  }
  cmd->add_option("--methods", o->methods,
                  "Methods to compare, comma-separated, or all (every method and auto, which "
                  "runs its own leave-one-out inside every fold, on the training samples only); "
                  "default: " +
                      defaults);
  cmd->add_option("--angles", o->angles, "Angles of incidence for colour, degrees")
      ->capture_default_str();
  AddColorimetryOptions(cmd, &o->illuminant, &o->observer);
  cmd->add_option("--out", o->out, "Report folder (created if missing)")->required();
  cmd->add_option("--threads", o->threads,
                  "Threads for the splits and their fits (0: all the hardware's)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  CLI::Option* quiet = cmd->add_flag("--quiet", o->quiet, "No progress or warnings on stderr");
  cmd->add_flag("--verbose", o->verbose, "Also a line for every split fitted and scored")
      ->excludes(quiet);
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
