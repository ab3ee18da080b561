// alloycolor fit: fit a model to a data set and write it as a JSON model file; with
// --refit, refit starting from an earlier model and report what changed.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/output.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/text.h"
#include "alloycolor/fit/lineage.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/registry.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct FitOptions {
  std::string data_dir;
  std::string exclude_text;
  std::string method = "auto";
  std::string out;
  std::string refit;            // --refit MODEL
  std::string from_old;         // --from MODEL, --refit's old spelling (accepted with a note)
  OptionValues method_options;  // --degree, --smoothing, ...: the registry's declarations
  bool quiet = false;
  bool verbose = false;
  int threads = 0;
};

// "2.1 sigma" or "" where there is no error bar.
std::string SigmaRatio(double error, double sigma) {
  if (!(sigma > 0) || !std::isfinite(error)) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.2g sigma", error / sigma);
  return text;
}

// What the old model said of each sample the refit added (the new history entry), whether
// the method changed, and the largest change in n and k between the two models over their
// common range, at compositions spread over the new model's range.
void ReportChanges(const AlloyModel& old_model, const AlloyModel& model) {
  const HistoryEntry& entry = model.history().back();
  for (const AddedSample& a : entry.added) {
    char x[32];
    std::snprintf(x, sizeof x, "%.4g", a.x_atomic);
    std::string line = "refit: added " + a.file + " (x = " + x + "): ";
    if (std::isfinite(a.delta_e00)) {
      char figures[200];
      if (std::isfinite(a.sigma_de00)) {
        std::snprintf(figures, sizeof figures,
                      "the old %s model predicted it off by dE00 %.3g at one-sigma %.3g (%s; "
                      "reflectance RMS %.3g)",
                      old_model.method().c_str(), a.delta_e00, a.sigma_de00,
                      SigmaRatio(a.delta_e00, a.sigma_de00).c_str(), a.reflectance_rms);
      } else {
        std::snprintf(figures, sizeof figures,
                      "the old %s model predicted it off by dE00 %.3g (reflectance RMS %.3g)",
                      old_model.method().c_str(), a.delta_e00, a.reflectance_rms);
      }
      line += figures;
      line += ": " + a.verdict;
      if (a.verdict.rfind("beyond two sigma", 0) == 0) {
        line += ": the old model did not expect this measurement";
      }
    } else {
      line += a.verdict;
    }
    std::fprintf(stderr, "alloycolor: %s\n", line.c_str());
  }
  for (const TrainingSample& t : entry.changed) {
    std::fprintf(stderr, "alloycolor: refit: sample %s changed since the old model\n",
                 t.file.c_str());
  }
  for (const TrainingSample& t : entry.removed) {
    std::fprintf(stderr, "alloycolor: refit: removed sample %s (x = %s)\n", t.file.c_str(),
                 FormatNumber(t.x_atomic).c_str());
  }
  if (old_model.method() != model.method()) {
    std::fprintf(stderr, "alloycolor: refit: the method changed from %s to %s%s\n",
                 old_model.method().c_str(), model.method().c_str(),
                 model.fit_summary().selection.present() ? " (auto's choice on the new data)" : "");
  }
  if (old_model.fit_summary().present() && model.fit_summary().present()) {
    std::fprintf(stderr, "alloycolor: refit: final cost %.6g -> %.6g\n",
                 old_model.fit_summary().final_cost, model.fit_summary().final_cost);
  }
  const double lo = std::max(old_model.lambda_min_nm(), model.lambda_min_nm());
  const double hi = std::min(old_model.lambda_max_nm(), model.lambda_max_nm());
  if (!(lo < hi)) return;
  std::vector<double> grid = UniformGrid(lo, hi, (hi - lo) / 100.0);
  double dn = 0, dk = 0;
  for (int i = 0; i <= 10; ++i) {
    const double x = model.x_min() + (model.x_max() - model.x_min()) * i / 10.0;
    const auto a = old_model.Index(x, grid);
    const auto b = model.Index(x, grid);
    for (size_t j = 0; j < grid.size(); ++j) {
      dn = std::max(dn, std::abs(a[j].real() - b[j].real()));
      dk = std::max(dk, std::abs(a[j].imag() - b[j].imag()));
    }
  }
  std::fprintf(stderr,
               "alloycolor: refit: largest change of the prediction, %g-%g nm, x in [%g, %g]: "
               "|dn| %.3g, |dk| %.3g\n",
               lo, hi, model.x_min(), model.x_max(), dn, dk);
  const std::vector<double> a = old_model.FittedCoefficients();
  const std::vector<double> b = model.FittedCoefficients();
  if (!a.empty() && a.size() == b.size() && old_model.native_grid_nm() == model.native_grid_nm()) {
    double shift = 0;
    for (size_t i = 0; i < a.size(); ++i) shift = std::max(shift, std::abs(a[i] - b[i]));
    std::fprintf(stderr, "alloycolor: refit: largest coefficient shift %.3g\n", shift);
  }
}

// What the fit chose and how well it fits, on stderr: auto's choice, the fit's summary line
// and the model against its own samples; with `verbose`, auto's leave-one-out table too.
void ReportFit(const AlloyModel& model, double seconds, bool verbose) {
  const FitSummary& stats = model.fit_summary();
  if (stats.selection.present()) {
    if (verbose) {
      std::fprintf(stderr, "alloycolor: auto: leave-one-out %s on the training samples:\n",
                   stats.selection.metric.c_str());
      for (const MethodScore& m : stats.selection.scores) {
        if (m.error.empty()) {
          std::fprintf(stderr,
                       "alloycolor:   %-11s mean %.4g, worst %.4g (%d folds; ends %.3g)%s\n",
                       m.method.c_str(), m.mean, m.max, m.folds, m.end_miss,
                       m.method == model.method() ? "  <- chosen" : "");
        } else {
          std::fprintf(stderr, "alloycolor:   %-11s not scored: %s\n", m.method.c_str(),
                       m.error.c_str());
        }
      }
    }
    std::fprintf(stderr, "alloycolor: auto chose %s\n", stats.selection.reason.c_str());
  }
  if (stats.present()) {
    const std::string shape = stats.details.contains("space")
                                  ? stats.details.value("space", std::string("eps")) +
                                        ", smoothing " +
                                        FormatNumber(stats.details.value("smoothing", 0.0))
                                  : "degree " + std::to_string(stats.degree);
    std::fprintf(stderr,
                 "alloycolor: %s fit: %s, final cost %.6g, %d iterations, %s, "
                 "RMS relative eps error %.3g, %.3f s\n",
                 model.method().c_str(), shape.c_str(), stats.final_cost, stats.iterations,
                 stats.converged ? "converged" : "NOT converged", stats.rms_relative_eps, seconds);
  }
  if (model.in_sample().empty()) return;
  std::fprintf(stderr, "alloycolor: %s against its own samples (normal incidence, D65, 2 deg):\n",
               model.method().c_str());
  for (const InSampleError& r : model.in_sample()) {
    if (std::isfinite(r.delta_e00)) {
      std::fprintf(stderr, "alloycolor:   x = %-8.4g dE00 %-9.3g reflectance RMS %-9.3g %s\n",
                   r.x_atomic, r.delta_e00, r.reflectance_rms, r.file.c_str());
    } else {
      std::fprintf(stderr, "alloycolor:   x = %-8.4g reflectance RMS %-9.3g %s\n", r.x_atomic,
                   r.reflectance_rms, r.file.c_str());
    }
  }
}

// The samples the manifest set aside, each as the model (which never saw it) predicts it.
void ReportExcluded(const AlloyModel& model) {
  for (const SampleNote& n : model.excluded_samples()) {
    std::string line = "set aside: " + n.file + " (x = " + FormatNumber(n.x_atomic) +
                       "): " + n.reason + "; held out, the model predicts it off by ";
    char figures[80];
    if (std::isfinite(n.delta_e00)) {
      std::snprintf(figures, sizeof figures, "dE00 %.3g", n.delta_e00);
      line += figures;
      if (std::isfinite(n.sigma_de00)) {
        std::snprintf(figures, sizeof figures, " at one-sigma %.3g", n.sigma_de00);
        line += figures;
      }
    } else {
      std::snprintf(figures, sizeof figures, "reflectance RMS %.3g", n.reflectance_rms);
      line += figures;
    }
    std::fprintf(stderr, "alloycolor: %s\n", line.c_str());
  }
}

void Run(const FitOptions& o) {
  ThreadBudget threads(o.threads);
  if (o.out.empty()) throw Error("--out: give the model file to write");
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!o.from_old.empty()) {
    if (!o.refit.empty()) throw Error("--from is --refit's old name: give one of them");
    if (!o.quiet) Warn("--from is now --refit (the old name is accepted until version 0.3)");
  }
  const std::string& refit = o.refit.empty() ? o.from_old : o.refit;
  if (!refit.empty() && fs::equivalent(refit, o.out, ec)) {
    throw Error("--out " + o.out +
                " is the --refit model; write the refit elsewhere so the "
                "old model is kept");
  }
  Dataset dataset = LoadDatasetArg(o.data_dir);
  if (!o.quiet) {
    for (const auto& w : dataset.warnings) Warn(w);
  }
  if (!o.exclude_text.empty()) {
    std::vector<double> exclude;
    for (const Sample* s : SamplesAt(o.exclude_text, dataset, "--exclude")) {
      exclude.push_back(s->x_atomic);
    }
    dataset = WithoutSamples(dataset, exclude);
  }
  std::unique_ptr<AlloyModel> old_model;
  if (!refit.empty()) {
    old_model = LoadModelArg(refit, false, o.refit.empty() ? "--from" : "--refit");
  }
  // Before the fit: the model must not replace an input (the manifest, a sample, --refit).
  CheckOutputPath(o.out);
  // The method's options against its declarations, named by their flags, before the fit.
  fit::CheckFitOptions(o.method, o.method_options, dataset, OptionSpelling::kFlag);
  const auto start = std::chrono::steady_clock::now();
  fit::FitSettings settings;
  settings.threads = &threads;
  settings.options = o.method_options;
  settings.start = old_model.get();
  settings.progress = ProgressPrinter(o.quiet);
  settings.details = ProgressPrinter(!o.verbose);
  const color::Colorimeter colorimeter = LoadColorimeter("D65", 2);
  settings.colorimeter = &colorimeter;
  const std::unique_ptr<AlloyModel> model =
      fit::FitDataSet(o.method, dataset, settings, {old_model.get(), NowUtcIso8601()});
  // The file must be one the other commands can use: read back as they will read it.
  const std::string text = ModelFileText(*model);
  try {
    ModelFromJson(nlohmann::json::parse(text), "the fitted model");
  } catch (const std::exception& e) {
    throw Error(MessageLine(o.out, 120) + " not written: " + e.what());
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!o.quiet) {
    for (const auto& w : model->warnings()) Warn(w);
    ReportFit(*model, seconds, o.verbose);
  }
  if (!o.quiet) ReportExcluded(*model);
  // What --refit asked for: said even with --quiet.
  if (old_model) ReportChanges(*old_model, *model);
  WriteOutput(o.out, text, o.quiet);
}

}  // namespace

void RegisterFit(CLI::App& app) {
  auto o = std::make_shared<FitOptions>();
  CLI::App* cmd =
      app.add_subcommand("fit", "Fit a model to a data set and write it as a JSON model file");
  cmd->footer(
      "Fits the model to all samples of the data set and writes it as a versioned JSON model "
      "file (docs/model-format.md). The methods (docs/methods.md):\n" +
      MethodsHelp());
  cmd->add_option("--data", o->data_dir,
                  "Data set: folder with dataset.json, a manifest, or a bundled set's name")
      ->required();
  cmd->add_option("--exclude", o->exclude_text,
                  "Leave out the samples at these compositions (comma-separated; the manifest's "
                  "numbers or 75at%, 75wt%, 18k)");
  cmd->add_option("--method", o->method,
                  "auto (every method scored by leave-one-composition-out, the best kept, its "
                  "table in the model file), or one of " +
                      MethodNamesText() + " (below)")
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Model file to write (written atomically)")->required();
  cmd->add_option("--refit", o->refit,
                  "Start from this earlier model and report what changed (even with --quiet)");
  cmd->add_option("--from", o->from_old, "--refit's old name (accepted until version 0.3)")
      ->group("");
  AddMethodOptions(cmd, &o->method_options);
  cmd->add_option("--threads", o->threads,
                  "Threads for the leave-one-out folds of the fit (0: all the hardware's)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  CLI::Option* quiet = cmd->add_flag("--quiet", o->quiet, "No progress or warnings on stderr");
  cmd->add_flag("--verbose", o->verbose,
                "Also auto's leave-one-out table and the cross-validation of the smoothing")
      ->excludes(quiet);
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
