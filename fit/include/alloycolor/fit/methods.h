// Building a model from a data set, for every method of the registry (model/registry.h):
// fitting is the only place that builds a model from data, so the built-in methods'
// builders sit here (fit/src/builders.cc), attached to their registry entries by a static
// initializer there, before `main`. Baselines that keep the samples (paper, eps-linear) need no
// solver; the fitted methods run their Ceres fits (smooth_fit.h, physical_fit.h).
//
// The layout of the library: builders.cc (one builder per method), folds.cc (the
// leave-one-composition-out folds and their held-out errors), prediction_error.cc (the
// error bars from the folds and the in-sample misfit), selection.cc (`auto` and the
// physical degree), methods.cc (BuildModel, which ties them together).
//
// FitSettings carry the options a user gave (OptionValues, checked once by BuildModel
// against the method's declarations in the registry) and how the fit runs (threads,
// progress, the colorimeter that scores colour, what folds and refits pass down).
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
#include "alloycolor/core/setting.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/registry.h"

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
  // The method's options as given, by name (model/registry.h declares each method's:
  // smooth's smoothing and space, physical's degree, terms and covariance, the fit grid's
  // lambda_from_nm, lambda_to_nm, lambda_step_nm; docs/methods.md lists them). BuildModel
  // checks them against the declarations (CheckFitOptions) and fills in the declared
  // defaults; an option not given is the method's to choose (a fold of the prediction
  // error or of auto that has no interior composition to choose smooth's space by takes
  // the space of the model it scores).
  OptionValues options;
  // Set by BuildModel once `options` are checked: the candidates, folds and refits it
  // builds with them take them as they are.
  bool options_checked = false;
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
  // May be empty: called before every fit the job makes (candidates, degrees, folds, the
  // samples' checks) and between the solver's iterations (core/progress.h); its exception
  // stops them all. Unlike progress, the folds keep it.
  CancelCheck cancel;
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
inline constexpr const char* kAutoMethod = kAutoMethodName;
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

// Whether the built-in methods' builders are in the registry (they are attached by a
// static initializer of the fit library; BuildModel refers to this so that the linker
// keeps it).
bool BuiltInBuildersAttached();

// The fit grid's options checked together against the data set: lambda_from_nm and
// lambda_to_nm given together, from below to, and at most kMaxFitGridNodes nodes
// ((to - from) / lambda_step_nm, from and to the samples' common range where not given).
// Throws Error naming the options as `spelling` spells them.
void CheckFitGrid(const OptionValues& options, const Dataset& dataset, OptionSpelling spelling);

// What BuildModel checks before any work, for a face that names options its own way (the
// program: by flag) and checks before it reads or writes anything else: `given` against
// the method's declarations (model/registry.h CheckMethodOptions) and the fit grid
// (CheckFitGrid). Returns the options with the declared defaults.
OptionValues CheckFitOptions(const std::string& method, const OptionValues& given,
                             const Dataset& dataset,
                             OptionSpelling spelling = OptionSpelling::kName);

// Builds `method` on the data set and, with settings.calibrate and three compositions or
// more, estimates its prediction error: each interior composition (20 at most, spread by
// rank) is held out in turn, the method built on the rest predicts it, and the relative
// eps errors give scale[j] = RMS over folds of error / B (PredictionError), B's gap
// exponent measured by holding out each of those compositions again together with its
// neighbour (four compositions or more; docs/model-format.md); the
// calibration (SigmaCalibration) then scales the one-sigma colour uncertainty to the
// folds' held-out CIEDE2000 errors, each fold's sigma from the other folds' scale
// (colorimeter and visible data needed; 1 otherwise). Throws Error for an unknown method
// (listing the known ones), an option the method does not take or a value its declaration
// refuses (naming the option: CheckFitOptions), or data the method cannot use.
std::unique_ptr<AlloyModel> BuildModel(const std::string& method, const Dataset& dataset,
                                       const FitSettings& settings = {});

// BuildModel for many fits of one job (the splits and methods of a validation report, as
// validate::ModelBuilder): colours scored with `colorimeter`, which must outlive it, one
// FitMemo shared by every fit it makes, the folds' threads from `threads` (if given, it must
// outlive the builder), and `cancel` checked in every fit (FitSettings::cancel).
std::function<std::unique_ptr<AlloyModel>(const std::string& method, const Dataset& training)>
SharedFitBuilder(const color::Colorimeter& colorimeter, ThreadBudget* threads = nullptr,
                 CancelCheck cancel = {});

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_METHODS_H_
