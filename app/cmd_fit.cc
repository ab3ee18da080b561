// alloycolor fit: fit a model to a data set and write it as a JSON model file; with
// --from, refit starting from an earlier model and report what changed.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "alloycolor/fit/physical_fit.h"
#include "alloycolor/fit/smooth_fit.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/model/smooth_model.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct FitOptions {
  std::string data_dir;
  std::string exclude_text;
  std::string method = "smooth";
  std::string terms = "auto";
  std::string out;
  std::string from;
  int degree = -1;
  int max_degree = 6;
  double smoothing = 1e-3;
  double lambda_from = 0, lambda_to = 0, lambda_step = 5;
  bool no_covariance = false;
  bool quiet = false;
};

// The largest change in n and k between two models over their common range, at
// compositions spread over the new model's range.
void ReportChanges(const AlloyModel& old_model, const AlloyModel& model) {
  std::map<std::string, const TrainingSample*> before, after;
  for (const auto& s : old_model.training_samples()) before[s.file] = &s;
  for (const auto& s : model.training_samples()) after[s.file] = &s;
  for (const auto& [file, s] : after) {
    auto it = before.find(file);
    if (it == before.end()) {
      std::fprintf(stderr, "alloycolor: refit: added sample %s (x = %g)\n", file.c_str(), s->x_atomic);
    } else if (it->second->checksum != s->checksum) {
      std::fprintf(stderr, "alloycolor: refit: sample %s changed (checksum %s -> %s)\n",
                   file.c_str(), it->second->checksum.c_str(), s->checksum.c_str());
    }
  }
  for (const auto& [file, s] : before) {
    if (!after.count(file)) {
      std::fprintf(stderr, "alloycolor: refit: removed sample %s (x = %g)\n", file.c_str(), s->x_atomic);
    }
  }
  const auto cost = [](const AlloyModel& m) {
    return m.fit_statistics().is_object() && m.fit_statistics().contains("final_cost")
               ? m.fit_statistics()["final_cost"].get<double>()
               : NAN;
  };
  std::fprintf(stderr, "alloycolor: refit: final cost %.6g -> %.6g\n", cost(old_model),
               cost(model));
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
  if (const auto* a = dynamic_cast<const SmoothModel*>(&old_model)) {
    const auto* b = dynamic_cast<const SmoothModel*>(&model);
    if (b && a->degree() == b->degree() && a->grid_nm() == b->grid_nm()) {
      double shift = 0;
      for (size_t j = 0; j < a->coeffs().size(); ++j) {
        for (size_t d = 0; d < a->coeffs()[j].size(); ++d) {
          shift = std::max(shift, std::abs(a->coeffs()[j][d] - b->coeffs()[j][d]));
        }
      }
      std::fprintf(stderr, "alloycolor: refit: largest coefficient shift %.3g\n", shift);
    }
  }
}

void Run(const FitOptions& o, CLI::App* cmd) {
  if (o.out.empty()) throw Error("--out: give the model file to write");
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!o.from.empty() && fs::equivalent(o.from, o.out, ec)) {
    throw Error("--out " + o.out + " is the --from model; write the refit elsewhere so the "
                "old model is kept");
  }
  Dataset dataset = LoadDatasetArg(o.data_dir);
  if (!o.quiet) {
    for (const auto& w : dataset.warnings) Warn(w);
  }
  if (!o.exclude_text.empty()) {
    const std::vector<double> exclude = ParseCompositions(o.exclude_text, dataset.system);
    for (double x : exclude) {
      bool found = false;
      for (const auto& s : dataset.samples) found |= std::abs(s.x_atomic - x) < 1e-9;
      if (!found) throw Error("--exclude: no sample at x = " + std::to_string(x));
    }
    dataset = WithoutSamples(dataset, exclude);
  }
  std::unique_ptr<AlloyModel> old_model;
  if (!o.from.empty()) old_model = ReadModelFile(o.from);
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<AlloyModel> model;
  if (o.method == "smooth") {
    fit::SmoothFitOptions options;
    options.degree = o.degree;
    options.max_degree = o.max_degree;
    options.smoothing = o.smoothing;
    options.covariance = !o.no_covariance;
    if (cmd->count("--lambda-from") || cmd->count("--lambda-to")) {
      if (!(o.lambda_to > o.lambda_from) || !(o.lambda_step > 0)) {
        throw Error("--lambda-from/--lambda-to/--lambda-step: need from < to, step > 0");
      }
      options.grid_nm = UniformGrid(o.lambda_from, o.lambda_to, o.lambda_step);
    }
    const auto* old_smooth = dynamic_cast<const SmoothModel*>(old_model.get());
    if (old_model && !old_smooth) {
      throw Error("--from " + o.from + " is a " + old_model->method() +
                  " model; a smooth refit needs a smooth model");
    }
    if (old_smooth) {
      options.start = old_smooth;
      if (o.degree < 0) options.degree = old_smooth->degree();
      if (options.grid_nm.empty()) options.grid_nm = old_smooth->grid_nm();
    }
    if (!o.quiet) {
      options.progress = [](const std::string& m) { std::cerr << "alloycolor: " << m << "\n"; };
    }
    model = std::move(fit::FitSmooth(dataset, options).model);
  } else if (o.method == "physical") {
    fit::PhysicalFitOptions options;
    if (o.degree >= 0) options.degree = o.degree;
    options.terms = o.terms;
    options.covariance = !o.no_covariance;
    if (cmd->count("--lambda-from") || cmd->count("--lambda-to")) {
      if (!(o.lambda_from > 0) || !(o.lambda_to > o.lambda_from)) {
        throw Error("--lambda-from/--lambda-to: need 0 < from < to");
      }
      options.lambda_from_nm = o.lambda_from;
      options.lambda_to_nm = o.lambda_to;
    }
    if (cmd->count("--lambda-step")) {
      if (!(o.lambda_step > 0)) throw Error("--lambda-step: need a positive step");
      options.lambda_step_nm = o.lambda_step;
    }
    if (!o.quiet) {
      options.progress = [](const std::string& m) { std::cerr << "alloycolor: " << m << "\n"; };
    }
    model = std::move(fit::FitPhysical(dataset, options).model);
  } else {
    model = BuildModel(o.method, dataset, o.quiet);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!o.quiet) {
    for (const auto& w : model->warnings()) Warn(w);
    const auto& stats = model->fit_statistics();
    if (stats.contains("final_cost")) {
      std::fprintf(stderr,
                   "alloycolor: %s fit: degree %d, final cost %.6g, %d iterations, %s, "
                   "RMS relative eps error %.3g, %.3f s\n",
                   model->method().c_str(), stats["degree"].get<int>(),
                   stats["final_cost"].get<double>(), stats["iterations"].get<int>(),
                   stats["converged"].get<bool>() ? "converged" : "NOT converged",
                   stats["rms_relative_eps"].get<double>(), seconds);
    }
    if (old_model) ReportChanges(*old_model, *model);
  }
  WriteOutput(o.out, ModelFileText(*model), o.quiet);
}

}  // namespace

void RegisterFit(CLI::App& app) {
  auto o = std::make_shared<FitOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fit",
      "Fit a model to all samples of a data set and write it as a versioned JSON model "
      "file (docs/model-format.md). smooth: Ceres fit of tau and m* as smooth functions of "
      "composition at every wavelength, degree by leave-one-out cross-validation, with "
      "covariance. physical: Ceres fit of a Drude + interband model (eps_inf, wp, gamma, "
      "Lorentz / critical-point / Rioux terms) whose parameters are polynomials in "
      "composition, to all samples at once, with covariance. paper, eps-linear: the "
      "baselines (they keep the samples' data).");
  cmd->add_option("--data", o->data_dir,
                  "Data set: folder with dataset.json, a manifest, or a bundled set's name")
      ->required();
  cmd->add_option("--exclude", o->exclude_text,
                  "Leave out the samples at these compositions (comma-separated)");
  cmd->add_option("--method", o->method, "smooth, physical, paper or eps-linear")
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Model file to write (written atomically)")->required();
  cmd->add_option("--from", o->from,
                  "Refit: start from this earlier model and report what changed");
  cmd->add_option("--degree", o->degree,
                  "smooth: polynomial degree in composition (default: cross-validated); "
                  "physical: degree of every parameter's polynomial (default 2)");
  cmd->add_option("--terms", o->terms,
                  "physical: interband terms, comma-separated: lorentz, cp (Etchegoin 2006 "
                  "critical point), rioux-gap, rioux-edge (Rioux 2014); none for the Drude "
                  "term alone; auto: none for infrared data, else the best of "
                  "rioux-gap,rioux-edge / cp,cp / lorentz,lorentz,lorentz on the end samples")
      ->capture_default_str();
  cmd->add_option("--max-degree", o->max_degree, "smooth: largest degree cross-validation tries")
      ->capture_default_str();
  cmd->add_option("--smoothing", o->smoothing,
                  "smooth: weight of the curvature penalty across wavelength")
      ->capture_default_str();
  cmd->add_option("--lambda-from", o->lambda_from,
                  "smooth, physical: first wavelength of the fit grid, nm (physical default: "
                  "the common range within 300-1000 nm, or all of it for infrared data)");
  cmd->add_option("--lambda-to", o->lambda_to,
                  "smooth, physical: last wavelength of the fit grid, nm");
  cmd->add_option("--lambda-step", o->lambda_step,
                  "smooth, physical: grid step, nm (physical default: 5, or range/200 in the "
                  "infrared)")
      ->capture_default_str();
  cmd->add_flag("--no-covariance", o->no_covariance, "smooth, physical: skip the covariance");
  cmd->add_flag("--quiet", o->quiet, "No progress or warnings on stderr");
  cmd->callback([o, cmd]() { Run(*o, cmd); });
}

}  // namespace alloycolor::app
