// Validation reports and composition charts: the computation (which models predict the
// held-out samples how well) and its presentation (JSON, a self-contained HTML page with
// inline SVG plots, an SVG chart) are kept apart: Compute* functions fill plain structs,
// the *Json / *Html / *Svg functions only format them.
//
// Validation: for each split of the data set into training and held-out samples, every
// method is built on the training samples only (app BuildModel, default options) and
// predicts each held-out composition. Metrics per method and held-out sample:
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
// wavelengths; for "paper" from SampleModel::PaperTauMass, for other methods by inverting
// the model's eps with eq. 11, 12 (InvertDrude) where it is invertible.
#ifndef ALLOYCOLOR_APP_REPORT_H_
#define ALLOYCOLOR_APP_REPORT_H_

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/model/alloy_model.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/color/colorimetry.h"
#include "alloycolor/render/image.h"

namespace alloycolor::app {

using ProgressFunction = std::function<void(const std::string& message)>;

// ---------------------------------------------------------------------------------------
// Validation: computation.

struct ValidationOptions {
  std::vector<std::string> methods;  // as BuildModel knows them
  std::vector<double> angles_deg;    // incidence angles for delta_e00
  std::string mode;                  // "loo" or "holdout", recorded in the report
  int sigma_draws = 64;              // draws for delta_e00_sigma
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
};

struct HoldoutResult {
  double x_atomic = 0, x_given = 0;
  std::string file, path;
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
  std::vector<double> train_x, holdout_x;
  std::map<std::string, std::string> errors;                 // method -> why it could not be built
  std::map<std::string, std::vector<std::string>> warnings;  // method -> its warnings
  std::vector<DrudeCurve> drude;
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
};

// Runs every method on every split (each split: the compositions held out, atomic
// fractions of samples of the data set). A method that fails on a split is recorded
// there; a method that fails on every split (an unknown name) throws its first error
// before the other methods' long work. Progress goes to `progress` (may be empty).
ValidationReport ComputeValidation(const Dataset& dataset,
                                   const std::vector<std::vector<double>>& splits,
                                   const color::Colorimeter& colorimeter,
                                   const ValidationOptions& options,
                                   const ProgressFunction& progress);

// ---------------------------------------------------------------------------------------
// Validation: presentation.

// {"format": "alloycolor-validation", "version": 1, "data": ..., "methods": [...],
//  "holdouts": [{"x": ..., "results": {METHOD: {"delta_e00": {"0": ...}, ...}}}], ...}
nlohmann::json ValidationJson(const ValidationReport& report);

// A self-contained HTML page (inline CSS and SVG; no scripts, no external files).
std::string ValidationHtml(const ValidationReport& report);

// ---------------------------------------------------------------------------------------
// Composition chart.

struct ChartSwatch {
  double x_atomic;
  double x_weight;
  std::array<std::uint8_t, 3> srgb8;
  bool clipped;  // linear sRGB outside [0, 1] before clamping
};

struct CompositionChart {
  std::string system, element_a, element_b, method, illuminant;
  int observer_deg = 2;
  double angle_deg = 0;
  bool weight_labels = false;  // label compositions in wt% rather than at%
  std::vector<ChartSwatch> swatches;
};

// Colours of the model at `steps` compositions from x_from to x_to (atomic fractions),
// evenly spaced in weight fraction when labelled in wt%, else in atomic fraction; throws
// Error when the model does not cover 380-780 nm.
CompositionChart ComputeChart(const AlloyModel& model, const color::Colorimeter& colorimeter,
                              double x_from, double x_to, int steps, double angle_deg,
                              bool weight_labels);

// SVG with the swatches, the composition under each and the elements at the ends.
std::string ChartSvg(const CompositionChart& chart);

// The chart without text, for a PNG: swatches of swatch_px squared on white, gap_px between
// them and around them.
render::ImageRGBA8 ChartImage(const CompositionChart& chart, int swatch_px, int gap_px);

}  // namespace alloycolor::app

#endif  // ALLOYCOLOR_APP_REPORT_H_
