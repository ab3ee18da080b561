// Building a model from a data set, for every method of the registry (model/registry.h):
// fitting is the only place that builds a model from data, so the built-in methods'
// builders sit here (fit/src/builders.cc) and are attached to their registry entries before
// the first build. Baselines that keep the samples (paper, eps-linear) need no solver; the
// fitted methods run their Ceres fits (smooth_fit.h, physical_fit.h).
//
// The layout of the library: builders.cc (one builder per method), folds.cc (the
// leave-one-composition-out folds and their held-out errors), prediction_error.cc (the
// error bars from the folds and the in-sample misfit), selection.cc (`auto` and the
// physical degree), methods.cc (BuildModel, which ties them together).
//
// FitSettings are the options a user can give any method; a method uses those that apply
// to it and refuses values that make no sense for it, naming the option.
#ifndef ALLOYCOLOR_FIT_METHODS_H_
#define ALLOYCOLOR_FIT_METHODS_H_

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::fit {

// What fits within one job may reuse, keyed by the samples and settings: the physical
// degree choice (`validate` builds physical and auto's physical candidate on the same
// training samples) and the physical fits of the end samples (every fold and candidate
// keeps the ends). Thread-safe; made by MakeFitMemo, shared through FitSettings::memo;
// BuildModel makes one for itself when none is given.
struct FitMemo;
std::shared_ptr<FitMemo> MakeFitMemo();

struct FitSettings {
  ThreadBudget* threads = nullptr;  // the threads its folds may share; none: one at a time
  int degree = -1;                  // physical: composition degree; < 0: the method's default
  double smoothing = -1;  // smooth: roughness penalty across composition; -1: cross-validated
  // smooth: the space of its curves, "eps" or "log_eps"; empty: chosen by its leave-one-out
  // (a fold of the prediction error or of auto that has no interior composition to choose
  // by takes the space of the model it scores).
  std::string space;
  std::string terms = "auto";  // physical: interband terms
  // Fit grid: both 0 for the method's default range; step 0 for its default step.
  double lambda_from_nm = 0, lambda_to_nm = 0, lambda_step_nm = 0;
  bool covariance = true;
  // Estimate the model's prediction error (PredictionError) by leave-one-composition-out:
  // one more fit per interior composition (at most 20).
  bool calibrate = true;
  // The model of a leave-one-out fold (set by the folds themselves): it only predicts its
  // held-out samples, so the physical fit skips its covariance and its check for leaving
  // physics.
  bool fold = false;
  // A fold's: the model fitted to all samples, whose folds these are (a builder may take
  // from it what its fold cannot choose, such as the smooth model's space).
  const AlloyModel* parent = nullptr;
  const AlloyModel* start = nullptr;  // refit: start from this model (same method)
  int max_iterations = 0;             // physical: the solver's iterations, 0 for the fit's default
  std::shared_ptr<FitMemo> memo;      // null: BuildModel makes one for this fit alone
  ProgressCallback progress;          // may be empty: a line per step of the work
  ProgressCallback details;           // may be empty: cross-validation tables and the like
  // auto (required there): the colorimeter its leave-one-out scores colour with, at normal
  // incidence; data without colour (infrared) are scored by reflectance.
  const color::Colorimeter* colorimeter = nullptr;
};

// "auto", the default of `alloycolor fit`: every other method is built on all samples with
// its leave-one-composition-out folds (those of its prediction error, see BuildModel: each
// interior composition held out in turn, 20 at most), and scored on the folds' held-out
// samples as `validate` scores them (mean CIEDE2000 at normal incidence, or reflectance RMS
// for data without colour); the first method in the registry's order of preference
// (MethodTraits::auto_rank: smooth, eps-pchip, eps-linear, eps-spline, paper, physical)
// whose mean lies within 10 % of the lowest, or whose best fold is no worse than the
// lowest's worst, wins: a rival displaces the default regression only on evidence the folds
// can give, a lead on every fold that no reshuffling of them could undo. The folds cannot
// hold out the two end samples: among the methods the rule accepts, one that misses an end
// sample by more than ΔE00 1 (reflectance RMS 0.01) and by more than its mean fold error
// gives way to one that does not. The physical model is not scored where its folds cannot
// fit its composition degree (three compositions: degree 2, its folds' two samples only a
// line). With three compositions
// the one fold predicts the middle from the ends, where every interpolation is a straight
// line, so it cannot compare the curves delivered: smooth is chosen (unless it failed).
// With fewer, nothing can be held out and the first in order is chosen (with two samples every
// interpolation is the line). The chosen model carries the table (FitSummary::selection).
inline constexpr const char* kAutoMethod = "auto";
std::unique_ptr<AlloyModel> BuildAuto(const Dataset& dataset, const FitSettings& settings);

// The calibration of a prediction error's one-sigma colour uncertainty from its folds'
// observed CIEDE2000 errors and uncalibrated predicted one-sigmas (docs/model-format.md):
// sqrt(sum of squared errors / sum of squared sigmas), as the one-sigma is the draws' RMS
// colour difference, times 1 + 1 / (2 k) + 1 / (4 k^2) from k = `folds` of two or more
// (Student's t with k degrees of freedom at its one-sigma point: the scale is estimated
// from k errors); pairs whose sigma is not positive are left out. 1 for none; clamped to
// 1e-3..1e3.
double SigmaCalibration(const std::vector<double>& errors, const std::vector<double>& sigmas,
                        int folds);

// Attaches the built-in methods' builders to their registry entries (once; BuildModel does
// it before building).
void AttachBuiltInBuilders();

// Builds `method` on the data set and, with settings.calibrate and three compositions or
// more, estimates its prediction error: each interior composition (20 at most, spread by
// rank) is held out in turn, the method built on the rest predicts it, and the relative
// eps errors give scale[j] = RMS over folds of error / B (PredictionError), B's gap
// exponent measured by holding out each of those compositions again together with its
// neighbour (four compositions or more; docs/model-format.md); the
// calibration (SigmaCalibration) then scales the one-sigma colour uncertainty to the
// folds' held-out CIEDE2000 errors, each fold's sigma from the other folds' scale
// (colorimeter and visible data needed; 1 otherwise). Throws Error for an unknown method
// (listing the known ones), a bad setting (naming the option) or data the method cannot
// use.
std::unique_ptr<AlloyModel> BuildModel(const std::string& method, const Dataset& dataset,
                                       const FitSettings& settings = {});

// BuildModel for many fits of one job (the splits and methods of a validation report, as
// validate::ModelBuilder): colours scored with `colorimeter`, which must outlive it, one
// FitMemo shared by every fit it makes, and the folds' threads from `threads` (if given,
// it must outlive the builder).
std::function<std::unique_ptr<AlloyModel>(const std::string& method, const Dataset& training)>
SharedFitBuilder(const color::Colorimeter& colorimeter, ThreadBudget* threads = nullptr);

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_METHODS_H_
