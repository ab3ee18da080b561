// Inside the fit library: the leave-one-composition-out folds every fitted model carries
// (its prediction error comes from them, `auto` scores methods by them), and the memo that
// the fits of one job share.
#ifndef ALLOYCOLOR_FIT_SRC_FOLDS_H_
#define ALLOYCOLOR_FIT_SRC_FOLDS_H_

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/fit/physical_fit.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/registry.h"

namespace alloycolor::fit {

// A candidate built on all samples with its folds, scored on them (selection.cc).
struct Scored {
  std::unique_ptr<AlloyModel> model;  // null where it could not be built or scored
  MethodScore score;
  // Each held-out sample's score, in the folds' order, and beside it its composition.
  std::vector<double> values, held_x;
  std::string metric;
};

struct FitMemo {
  struct Remembered {
    nlohmann::json model;
    MethodScore score;
    std::vector<double> values, held_x;
    std::string metric;
  };
  std::mutex mutex;
  std::map<std::string, Remembered> degree_choices;
  std::map<std::string, Remembered> builds;  // RememberedBuild's
  std::shared_ptr<EndSampleFits> end_fits = MakeEndSampleFits();
};

inline EndSampleFits* FitMemoEndFits(FitMemo& memo) { return memo.end_fits.get(); }

// The compositions held out to estimate the prediction error: the interior ones, 20 at
// most, spread by rank.
std::vector<double> ErrorFolds(const Dataset& dataset);

// One composition held out with all its replicates (one left in would predict its twin):
// the method built on the rest (null where it could not be), the held-out samples, and
// what the prediction error needs of the fold.
struct Fold {
  double x = 0;
  std::unique_ptr<AlloyModel> model;
  std::string error;  // why model is null
  std::vector<const Sample*> held;
  std::vector<double> compositions;  // of the fold's training samples
};

// The method built without each of ErrorFolds in turn, in parallel; `model` is the one
// built on all samples (the folds' parent: a method with warm-started folds starts there).
std::vector<Fold> FitFolds(const MethodInfo& method, const Dataset& dataset,
                           const FitSettings& settings, const AlloyModel& model);
// The same for other sets of compositions held out together (x: the first of each).
std::vector<Fold> FitFolds(const MethodInfo& method, const Dataset& dataset,
                           const FitSettings& settings, const AlloyModel& model,
                           const std::vector<std::vector<double>>& held);

// The folds' held-out samples scored as `validate` scores them (color/sample_error.h):
// CIEDE2000 at normal incidence, or the reflectance RMS for data without colour; the mean
// over them in r->score, each one in r->values (with held_x), r->metric which.
void ScoreFolds(const std::string& method, const std::vector<Fold>& folds,
                const color::Colorimeter& colorimeter, Scored* r);

// `method` built on the data set, nothing more (its registry builder).
std::unique_ptr<AlloyModel> Build(const MethodInfo& method, const Dataset& dataset,
                                  const FitSettings& settings);

// The model's folds and, with settings.calibrate, its prediction error from them and its
// in-sample misfit (prediction_error.h).
void AddFolds(const MethodInfo& method, const Dataset& dataset, const FitSettings& settings,
              AlloyModel* model, std::vector<Fold>* folds);

// `method` built on the data set; with `folds` (or settings.calibrate) the leave-one-out
// folds too, and with settings.calibrate its prediction error from them.
std::unique_ptr<AlloyModel> BuildWithFolds(const MethodInfo& method, const Dataset& dataset,
                                           const FitSettings& settings, std::vector<Fold>* folds);

// The model's prediction error (alloy_model.h PredictionError) from its folds, its
// in-sample misfit and the data's precision (prediction_error.cc); sets each fold model's
// error too.
void EstimatePredictionError(const MethodInfo& method, std::vector<Fold>& folds,
                             const Dataset& dataset, const FitSettings& settings,
                             AlloyModel* model);

// The prediction error `error` (another fit's, whose folds stand for this one's) given to
// `model` with the misfit and replicate scatter measured on `model` itself.
void CarryPredictionError(const Dataset& dataset, PredictionError error, AlloyModel* model);

// The model against each of its own training samples (color/sample_error.h), kept in the
// model (AlloyModel::in_sample) with a warning for each sample it misses by more than
// kInSampleMissDe00 (or kInSampleMissReflectance for data without colour).
void RecordInSampleError(const Dataset& dataset, const FitSettings& settings, AlloyModel* model);
inline constexpr double kInSampleMissDe00 = 1.0;
inline constexpr double kInSampleMissReflectance = 0.01;

// auto's one-sigma calibrated on the errors of its choice, not only of the method chosen
// (selection.cc): the method that wins on the folds is the one whose folds happened to go
// well, so the calibration on its own folds is optimistic. Each fold's held-out error is
// taken from the candidate that auto's rule chooses without that fold; as the calibration is
// the folds' squared errors over their squared sigmas, summed (SigmaCalibration), the one
// from those errors over the chosen candidate's own is sqrt(sum of the choices' squared
// errors / sum of its own), the factor, at least 1. 1 with fewer than two folds or where
// every fold leads to the chosen one.
// `misses_end`: per candidate, whether it contradicts an end sample (BuildAuto).
double ChoiceCalibrationFactor(const std::vector<Scored>& candidates,
                               const std::vector<bool>& misses_end, size_t chosen);

// The memo's key of a build of `method` on the data set: the method, its options and every
// setting a build reads, and the samples (composition, wavelengths, n, k).
std::string FitMemoKey(const MethodInfo& method, const Dataset& dataset,
                       const FitSettings& settings);

// What `build` gives for `key` in settings.memo's `table`: a copy of the remembered result
// (its model through the model file) where there is one, else built, and kept there where
// `keep` accepts it. settings.memo must be set.
Scored ThroughMemo(const MethodInfo& method, const FitSettings& settings, const std::string& key,
                   std::map<std::string, FitMemo::Remembered> FitMemo::*table,
                   const std::function<Scored()>& build,
                   const std::function<bool(const Scored&)>& keep);

// `method` built on the data set with its folds (with settings.calibrate, its prediction
// error from them) and the folds' held-out samples scored (ScoreFolds): what `auto` scores a
// candidate by and what `validate` builds a method as, done once per job through
// settings.memo (the remembered model a copy through the model file; FitMemoKey). A method that
// cannot be built gives no model and score.error says why; one whose folds cannot be scored keeps
// its model, score.error saying why. settings.colorimeter is needed; a refit (settings.start) or a
// fold is not remembered.
Scored RememberedBuild(const MethodInfo& method, const Dataset& dataset,
                       const FitSettings& settings);

// `auto` and the physical degree choice (selection.cc).
bool ChoosesDegree(const MethodInfo& method, const FitSettings& settings);
Scored RememberedDegreeChoice(const MethodInfo& method, const Dataset& dataset,
                              const FitSettings& settings);

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_SRC_FOLDS_H_
