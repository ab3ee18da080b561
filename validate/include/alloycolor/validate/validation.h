// Held-out validation as a library: for each split of a data set into training and
// held-out samples, every method is built on the training samples only and predicts each
// held-out sample (one result row per sample: replicates, several samples at one
// composition, each have their own); plain structs in, plain structs out, so the command line, the
// report writers and the Python module all see the same numbers. The builder is passed in
// (ValidationOptions::build, normally fit::SharedFitBuilder), so this library needs no solver.
//
// Metrics per method and held-out sample:
//  - delta_e00[angle]: CIEDE2000 between the measured and the predicted colour of the
//    polished metal (Fresnel reflectance, eq. 2-4, integrated against the illuminant and
//    observer, eq. 5; CIELAB relative to the illuminant's white). Both spectra are held at
//    their nearest measured or predicted wavelength where the colorimeter's grid
//    (360-830 nm for D65) reaches beyond 380-780 nm; the prediction is evaluated on
//    380-780 nm, exactly as `alloycolor predict` writes it by default, so the numbers can be
//    recomputed from its output. Not available when the data do not cover 380-780 nm.
//  - delta_e00_sigma[angle]: the model's own one-sigma colour uncertainty
//    (color::DeltaE00Sigma) where AlloyModel::HasUncertainty().
//  - reflectance_rms, reflectance_max: normal-incidence reflectance error over 380-780 nm
//    on a 5 nm grid (measured n, k interpolated linearly); for data that do not cover the
//    visible (infrared sets), over the held-out sample's own wavelengths inside the model's
//    range. n_max_abs, k_max_abs: largest |dn|, |dk| on the same wavelengths.
// Drude curves: tau_fs(x) = hbar / gamma and m*/m_e = kPlasmaEv2M3 N_e(x) / wp^2 at a few
// wavelengths, from AlloyModel::DrudeAt (the paper method's own interpolated tau and m*,
// the other methods' eps inverted with eq. 11, 12 where it is invertible).

#ifndef ALLOYCOLOR_VALIDATE_VALIDATION_H_
#define ALLOYCOLOR_VALIDATE_VALIDATION_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/suggest.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::validate {

// Builds a method's model on a training set (fit::BuildModel with default settings).
using ModelBuilder =
    std::function<std::unique_ptr<AlloyModel>(const std::string& method, const Dataset& training)>;

struct ValidationOptions {
  ModelBuilder build;                // required
  std::vector<std::string> methods;  // names of the registry (model/registry.h)
  std::vector<double> angles_deg;    // incidence angles for delta_e00
  std::string mode;                  // "loo" or "holdout", recorded in the report
  int sigma_draws = 64;              // draws for delta_e00_sigma
  ThreadBudget* threads = nullptr;   // the threads its splits may share; none: in turn
  // A line per split done (may be empty); the progress callback gets a line per method
  // and the splits that failed.
  ProgressCallback details;
  // The model of the whole data set the report opens with (ValidationReport::whole,
  // DescribeWholeDataSet): the face's fit::WholeDataSetFitter; empty: not described. Its
  // method: the one validated, where one is; else auto, as `fit` chooses.
  ModelBuilder fit_whole;
  // Called before each split's fit and each held-out sample's scores (core/progress.h);
  // the builders check it within their fits when the face gave it to them too.
  CancelCheck cancel;
};

// What one method predicts for one held-out sample.
struct MethodResult {
  std::string error;  // non-empty: the method could not be built or evaluated
  // Colour (empty when not available): one entry per angle.
  std::vector<double> delta_e00;
  std::vector<double> delta_e00_sigma;  // empty without uncertainty
  std::vector<std::array<std::uint8_t, 3>> srgb8;
  std::vector<color::Lab> lab;
  // Spectral errors on lambda_nm (see above).
  double reflectance_rms = 0, reflectance_max = 0, n_max_abs = 0, k_max_abs = 0;
  std::vector<double> lambda_nm, n, k, reflectance;  // predicted, for plots
  // The composition recovered from the sample's measured colour at normal incidence
  // (color::MatchColour: the best match within the model's range) and its one-sigma
  // (NaN without colour or uncertainty).
  double x_recovered = std::numeric_limits<double>::quiet_NaN();
  double x_recovered_sigma = std::numeric_limits<double>::quiet_NaN();
};

struct HoldoutResult {
  double x_atomic = 0, x_given = 0;
  std::string file, path;
  // Index in the data set's samples followed by its set-aside ones (Dataset::excluded).
  int sample = 0;
  bool replicate = false;  // another sample of the data set shares its composition
  // Why the manifest sets it aside ("exclude"), empty for a sample in use: such a sample is
  // held out of every split (its own split trains on all the samples in use) and left out
  // of the summaries (Coverage, Recovery and the report's means).
  std::string excluded;
  int split = 0;
  // Measured, on the metric wavelengths (those of the first method that could be
  // evaluated; every method trained on a split shares them).
  std::vector<double> lambda_nm, n, k, reflectance;
  std::string metric_range;                        // how lambda_nm was chosen, for the report
  std::vector<std::array<std::uint8_t, 3>> srgb8;  // per angle; empty without colour
  std::vector<color::Lab> lab;
  std::string colour_note;  // why there is no colour, when there is none
  std::map<std::string, MethodResult> results;
};

// tau and m* against composition at one wavelength, for one split.
struct DrudeCurve {
  double lambda_nm = 0;
  std::vector<double> x;                              // composition grid
  std::map<std::string, std::vector<double>> tau_fs;  // per method; NaN where undefined
  std::map<std::string, std::vector<double>> mass;    // m*/m_e
  // Measured samples' own inversion (NaN where eq. 11, 12 are undefined).
  std::vector<double> train_x, train_tau_fs, train_mass;
  std::vector<double> holdout_x, holdout_tau_fs, holdout_mass;
};

struct SplitResult {
  // Per sample, in the data set's order (a composition repeats with its replicates).
  std::vector<double> train_x, holdout_x;
  std::vector<std::string> train_files, holdout_files;
  std::map<std::string, std::string> errors;                 // method -> why it could not be built
  std::map<std::string, std::vector<std::string>> warnings;  // method -> its warnings
  // method -> its model against its own training samples (AlloyModel::in_sample)
  std::map<std::string, std::vector<InSampleError>> in_sample;
  // method -> what it chose on this split's training samples (auto: the method and why)
  std::map<std::string, std::string> choices;
  std::vector<DrudeCurve> drude;
};

// What the report says first, of the data set as a whole (DescribeWholeDataSet): the model
// a user would fit to every sample, its checks of the samples (fit/suspects.h), the samples
// the manifest sets aside as it predicts them, its one-sigma across composition, and
// where to measure next (color/suggest.h).
struct WholeDataSet {
  std::string method;        // empty: not described
  std::string choice;        // why auto chose it, where it did
  std::string error;         // why the model could not be built
  std::string no_error_bar;  // AlloyModel::NoErrorBarReason, empty where it has error bars
  bool samples_checked = false;
  std::vector<SampleNote> suspects, excluded;
  std::vector<double> sample_x;  // its training compositions
  // The scan across composition (normal incidence): x, sRGB and one-sigma CIEDE2000 (empty
  // without error bars).
  std::vector<double> x, sigma;
  std::vector<std::array<std::uint8_t, 3>> srgb8;
  std::vector<color::Suggestion> suggestions;
  std::string suggest_rule;
  bool present() const { return !method.empty() || !error.empty(); }
};

struct ValidationReport {
  std::string data;  // the manifest
  std::string name;  // the data set's name
  std::string system;
  std::string composition;  // of the manifest; report x values are atomic fractions
  std::string element_a, element_b;
  std::string mode;
  std::vector<std::string> methods;
  std::vector<double> angles_deg;
  std::string illuminant;
  int observer_deg = 2;
  std::vector<double> colour_nm;  // the colorimeter's grid ends
  std::vector<std::string> dataset_warnings;
  std::vector<SplitResult> splits;
  std::vector<HoldoutResult> holdouts;
  WholeDataSet whole;  // described where ValidationOptions::fit_whole is given
};

// Builds the model of the whole data set with `fit_whole` (the face's: fit::FitDataSet, so
// that its samples are checked) and `method`, and describes it (WholeDataSet), with `count`
// suggestions of where to measure next. A model that cannot be built is described by its
// error. Colour at normal incidence under `colorimeter`.
WholeDataSet DescribeWholeDataSet(const Dataset& dataset, const color::Colorimeter& colorimeter,
                                  const ModelBuilder& fit_whole, const std::string& method,
                                  int count = 3);

// One split: the held-out samples, as indices into dataset.samples.
using SampleSplit = std::vector<size_t>;

// Leave one composition out: each interior composition in turn, all of its replicates
// held out together (a replicate left in would predict its twin). Throws Error when the
// data set has fewer than three compositions.
std::vector<SampleSplit> LeaveOneOutSplits(const Dataset& dataset);

// One split from names: each the file of a sample (FindSampleByFile: that replicate alone)
// or a composition as ParseComposition reads it, or the manifest's number for it (every
// replicate there). Throws Error naming what matches no sample, and when the split would
// leave an end composition without a sample (every method would have to extrapolate).
SampleSplit HoldoutSplit(const Dataset& dataset, const std::vector<std::string>& names);

// The samples at these compositions (atomic fractions, within 1e-9), every replicate.
SampleSplit SplitAtCompositions(const Dataset& dataset, const std::vector<double>& x_atomic);

// Runs every method on every split. A method that fails on a split is recorded
// there; a method that fails on every split (an unknown name) throws its first error
// before the other methods' long work. Progress goes to `progress` (may be empty). The
// samples the manifest sets aside (Dataset::excluded) are held out of every split and
// scored in one more split, trained on every sample in use.

ValidationReport ComputeValidation(const Dataset& dataset, const std::vector<SampleSplit>& splits,
                                   const color::Colorimeter& colorimeter,
                                   const ValidationOptions& options,
                                   const ProgressCallback& progress);

// How the observed delta_e00 compares with the model's own one-sigma, for one method at one
// angle, pooled over every held-out sample: the fractions within 1 and 2 sigma (about 68 %
// and 95 % for honest error bars) and the median observed / sigma.
struct SigmaCoverage {
  int count = 0, within_1 = 0, within_2 = 0;
  double median_ratio = 0;  // NaN when count is 0
};
SigmaCoverage Coverage(const ValidationReport& report, const std::string& method, int angle);

// The compositions recovered from held-out colours, for one method, pooled: mean |error|
// in at% and the number whose true composition lies within two sigma.
struct RecoverySummary {
  int count = 0, with_sigma = 0, within_2 = 0;
  double mean_abs_at_percent = 0;  // NaN when count is 0
};
RecoverySummary Recovery(const ValidationReport& report, const std::string& method);

}  // namespace alloycolor::validate

#endif  // ALLOYCOLOR_VALIDATE_VALIDATION_H_
