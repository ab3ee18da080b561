// A model of the permittivity eps(lambda, x) of a binary alloy, x the atomic fraction of
// element a. Every method (the paper's pointwise baseline, linear interpolation of eps,
// the smooth Ceres fit, the physical Drude + interband model) implements this interface,
// so all of them feed the same Fresnel-to-colour chain and the same JSON model file.
//
// Model file (JSON), format "alloycolor-model", version kModelFormatVersion:
//   {"format": "alloycolor-model", "version": 1, "method": "...",
//    "system": {"a": "Au", "b": "Ag"}, "composition": "atomic_fraction_a",
//    "x_range": [lo, hi], "lambda_range_nm": [lo, hi],
//    "training_samples": [{"x": ..., "x_given": ..., "file": ..., "checksum": ...}],
//    "in_sample": [{"x": ..., "file": ..., "delta_e00": ..., "reflectance_rms": ...}],
//    "parameters": {... method's own ...}, "fit": {... statistics ...},
//    "warnings": [...]}
// See docs/model-format.md.
#ifndef ALLOYCOLOR_MODEL_ALLOY_MODEL_H_
#define ALLOYCOLOR_MODEL_ALLOY_MODEL_H_

#include <complex>
#include <cstdint>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/core/composition.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/model/optics.h"

namespace alloycolor {

inline constexpr int kModelFormatVersion = 1;
inline constexpr const char* kModelFormatName = "alloycolor-model";

// How a fitted model was fitted, as recorded in the model file's "fit" block: the fields
// every fitted method has, typed, and the method's own further statistics in `details`
// (written beside them). Baselines built without a fit have none (present() is false).
// How `--method auto` chose the method of a model: every candidate's leave-one-
// composition-out score on the training data (the metric says which), lowest wins.
struct MethodScore {
  std::string method;
  double mean = 0;  // mean of the metric over the folds
  double max = 0;   // worst fold
  int folds = 0;
  // The model's own (in-sample) error at the end compositions, which no fold can hold
  // out, in the folds' metric: the larger of the two. Not in mean and max.
  double end_miss = 0;
  std::string error;  // non-empty: the candidate could not be scored (why)
};
struct MethodSelection {
  std::string metric;  // "delta_e00 (normal incidence, D65, 2 deg)" or "reflectance_rms"
  std::string reason;  // why the chosen one was chosen, one line
  std::vector<MethodScore> scores;
  bool present() const { return !reason.empty(); }
};

struct FitSummary {
  std::string solver;  // "method" in the file: the solver and its linear algebra
  int degree = -1;     // composition degree (the smooth model's, or each parameter's)
  double final_cost = 0;
  int iterations = 0;
  bool converged = false;
  std::string termination;
  double rms_relative_eps = 0;  // RMS of (eps_model - eps) / |eps| over the data
  nlohmann::json details = nlohmann::json::object();
  MethodSelection selection;  // set when the method was chosen by `auto`

  bool present() const { return !solver.empty(); }
};

// How far a model's predictions between its training compositions are off, estimated
// by leave-one-composition-out when it is fitted (fit/methods.h): at wavelength node j
// the relative eps error at composition x is scale[j] * B(x), with
//   B(x) = 4 t (1 - t) (h / reference_gap)^gap_exponent   (times end_factor in an end
// interval), t the position of x in its interval of width h between neighbouring training
// compositions (B = 0 at each of them; beyond the ends |t(1 - t)|, growing). The fit
// measures the exponent on the data (fit/src/prediction_error.cc, MeasuredGapExponent:
// pairs of neighbouring compositions held out together against each held out alone), at
// most the method's own (registry.h: 2 for a linear interpolation, whose error on a smooth
// curve grows as h^2, 1 for the others); under 1 where the samples scatter (the scatter
// does not shrink with the gap); on three compositions, where no pair can be held out, 2
// (the one fold is then a line). The calibration factor scales it so that held-out colour
// errors, in the folds, have the spread the one-sigma colour uncertainty claims. Draws of
// eps add
//   calibration * scale * B * |eps| (z1 + i z2) / sqrt(2),
// z1, z2 standard normal and the same at every wavelength of a draw (the error of an
// interpolation across composition is smooth in wavelength).
struct PredictionError {
  std::vector<double> lambda_nm, scale;  // wavelength nodes, increasing
  std::vector<double> compositions;      // training compositions, increasing
  double reference_gap = 1;
  // The power of h / reference_gap in B (0..4; 1 in files without it).
  double gap_exponent = 1;
  // B in an end interval (between the first two or the last two compositions, three or
  // more of them) is this many times an interior interval's: a curve there is pinned on
  // one side only. From the folds (1 where they cannot tell; docs/model-format.md).
  double end_factor = 1;
  double calibration = 1;
  int folds = 0;  // how many folds estimated it (0: scale is 0, the terms below remain)
  // What the model misses at its own training compositions, and what one measurement can
  // resolve, added to each draw of eps so that no prediction claims more than the data
  // allow (docs/model-format.md):
  //  - misfit[i][j]: (measured eps - model eps) / |model eps| at compositions[i] (the mean
  //    of the samples there) and misfit_lambda_nm[j]; between compositions interpolated
  //    linearly and added to every draw, so that at a training composition the draws land
  //    on the measurement the model misses (the colour sigma there is at least the miss);
  //  - scatter[r][j]: a replicate sample's relative deviation from its composition's mean
  //    (times sqrt(n / (n - 1))), taken in turn by the draws with a sign of their own;
  //  - precision: a measurement's relative eps error (the resolution of the data's
  //    printed digits), a complex normal term at every composition.
  std::vector<double> misfit_lambda_nm;  // increasing; empty: no misfit nor scatter
  std::vector<std::vector<std::complex<double>>> misfit, scatter;
  double precision = 0;
  // The folds' held-out samples as the calibration saw them (kept in memory, not in the
  // model file): each one's CIEDE2000 error and its one-sigma before calibration, from
  // the other folds' scale (fit/suspects.h weighs each against the others).
  struct HeldOut {
    double x_atomic;
    std::string file;
    double delta_e00;
    double sigma;
  };
  std::vector<HeldOut> held_out;
  bool present() const { return !lambda_nm.empty(); }
  // B(x) above.
  double Bump(double x_atomic) const;
  // scale interpolated linearly in wavelength (held at the ends).
  double ScaleAt(double lambda_nm) const;
  // The misfit at composition x, interpolated in wavelength (zero without one).
  std::complex<double> MisfitAt(double x_atomic, double lambda_nm) const;
  // Scatter spectrum r at a wavelength.
  std::complex<double> ScatterAt(size_t r, double lambda_nm) const;
};

// A model against one of its own training samples (color/sample_error.h metrics): what
// `fit` measured when it built the model, kept in the model file.
struct InSampleError {
  double x_atomic = 0;
  std::string file;
  double delta_e00 = 0;  // NaN for data without colour (null in the file)
  double reflectance_rms = 0;
};

// What a model keeps of each training sample (not its data, unless the method needs it).
struct TrainingSample {
  double x_atomic;
  double x_given;
  std::string file;
  std::string checksum;
};

// A sample of the data set that a fit questions (fit/suspects.h: out of line with the
// rest of the series) or that the manifest sets aside ("exclude"), as the model file keeps
// it: fit.suspect_samples and excluded_samples (docs/model-format.md).
struct SampleNote {
  double x_atomic = 0, x_given = 0;
  std::string file;
  std::string check;   // suspects: "not metallic" or "held out"; set aside: "excluded"
  std::string reason;  // one line: why it is suspect, or the manifest's reason
  // The check's figure and what it is ("held-out dE00 / one-sigma", "fraction metallic");
  // NaN where none.
  std::string figure_name;
  double figure = std::numeric_limits<double>::quiet_NaN();
  // The model built without the sample against it (color/sample_error.h) and the model's
  // one-sigma there; NaN where not computed or not available.
  double delta_e00 = std::numeric_limits<double>::quiet_NaN();
  double sigma_de00 = std::numeric_limits<double>::quiet_NaN();
  double reflectance_rms = std::numeric_limits<double>::quiet_NaN();
};

// One fit in a model's lineage (the model file's "history", oldest first): `fit` adds one
// entry, a refit (`fit --refit OLD`) adds its own to OLD's. For each sample added since the
// previous model, that model's prediction there: its error (delta_e00 at normal incidence,
// D65, 2 deg; reflectance_rms) and its one-sigma, and the verdict (SigmaVerdict).
struct AddedSample {
  double x_atomic = 0, x_given = 0;
  std::string file, checksum;
  double delta_e00 = std::numeric_limits<double>::quiet_NaN();
  double sigma_de00 = std::numeric_limits<double>::quiet_NaN();
  double reflectance_rms = std::numeric_limits<double>::quiet_NaN();
  std::string verdict;  // empty for a first fit (no earlier model predicted it)
};
struct HistoryEntry {
  std::string date;  // ISO 8601, UTC ("2026-12-06T10:00:00Z"); empty where unknown
  std::string method;
  std::string previous_method;  // a refit's: the method of the model it refitted
  int samples = 0;              // the samples it was fitted to
  std::vector<AddedSample> added;
  std::vector<TrainingSample> removed, changed;  // changed: the same file, another checksum
};

// The verdict on an error against a one-sigma: "within one sigma", "within two sigma",
// "beyond two sigma", or "no error bar" where sigma is not a positive number.
std::string SigmaVerdict(double error, double sigma);

// Uncertainty is propagated by draws of eps: this many, from this seed, wherever the
// program reports a sigma, so reports repeat exactly.
inline constexpr int kUncertaintyDraws = 64;
inline constexpr std::uint32_t kUncertaintySeed = 20261122u;

// A model's physical parameters against composition (the `params` read-out): one column a
// quantity, named with its unit ("tau_fs@550nm", "wp_eV", "t1:E0_nm"), one row a
// composition; sigma is 0 where the model has no uncertainty, NaN where the quantity is
// undefined (value NaN too).
struct ParameterTable {
  struct Quantity {
    double value;
    double sigma;
  };
  std::vector<std::string> notes;    // lines explaining the columns
  std::vector<std::string> columns;  // besides x
  std::vector<double> x_atomic;
  std::vector<std::vector<Quantity>> rows;  // rows[i][column]
};

// A model bound to one wavelength grid: eps at any composition on that grid, with all that
// does not depend on the composition done once when binding (AlloyModel::Bind), so that
// sweeps over composition, colour tables and renderers evaluate many compositions fast and
// without knowing the method. Equal to AlloyModel::Permittivity on the grid to rounding.
class BoundModel {
 public:
  explicit BoundModel(std::vector<double> lambda_nm) : lambda_nm_(std::move(lambda_nm)) {}
  virtual ~BoundModel() = default;
  const std::vector<double>& lambda_nm() const { return lambda_nm_; }
  // eps1 and eps2 at x_atomic on lambda_nm(), each array holding lambda_nm().size()
  // values: two arrays rather than one of complex numbers, so that the colour chain
  // reads a run of wavelengths into each SIMD register. A method whose eps can be
  // unusable there throws Error naming the model's source, as AlloyModel::Index does.
  virtual void Permittivity(double x_atomic, double* eps1, double* eps2) const = 0;
  // The same as complex numbers (allocates).
  std::vector<Complex<double>> Permittivity(double x_atomic) const;

 private:
  std::vector<double> lambda_nm_;
};

class AlloyModel {
 public:
  virtual ~AlloyModel() = default;

  virtual std::string method() const = 0;

  // eps at composition x_atomic for each wavelength (nm). Throws Error for a wavelength
  // outside [lambda_min_nm(), lambda_max_nm()]. Never returns NaN (a method may return 0
  // where it cannot compute eps: Index and the bound models refuse that).
  virtual std::vector<std::complex<double>> Permittivity(
      double x_atomic, const std::vector<double>& lambda_nm) const = 0;

  // The model bound to a grid inside its range (throws Error as Permittivity for one
  // outside). The model must outlive the bound model.
  virtual std::unique_ptr<BoundModel> Bind(const std::vector<double>& lambda_nm) const;

  // n + i k (eq. 13, 14 applied to Permittivity). Throws Error naming source() where eps
  // is not usable (UsablePermittivity), so that no output shows a made-up colour.
  std::vector<std::complex<double>> Index(double x_atomic,
                                          const std::vector<double>& lambda_nm) const;

  // Drude parameters of the model at (x, lambda): gamma = hbar / tau and wp^2, the
  // pointwise inversion (eq. 11, 12) of Permittivity; false where it is undefined
  // (eps1 >= 1 or eps2 <= 0) or lambda lies outside the model's range. A method that
  // interpolates Drude parameters itself (the paper's) gives its own.
  virtual bool DrudeAt(double x_atomic, double lambda_nm, DrudePoint* out) const;

  // Whether the model gives an error bar: draws of eps (CheckedDraws) from the
  // cross-validated prediction error (or, for a model that has one and no prediction
  // error, from its parameters' covariance: HasUncertaintyTerms), for propagating
  // uncertainty to reflectance and colour, and only for a model fitted to three
  // compositions or more: with two, nothing could be held out to measure its error, and
  // no face claims one (NoErrorBarReason says so instead).
  bool HasUncertainty() const;
  virtual bool HasUncertaintyTerms() const { return prediction_error_.present(); }
  // Why there is no error bar, one phrase for every face ("no error bar: 2 compositions
  // ..."); empty when HasUncertainty().
  std::string NoErrorBarReason() const;
  // The number of distinct training compositions.
  int TrainingCompositions() const;
  virtual std::vector<std::vector<std::complex<double>>> PermittivityDraws(
      double x_atomic, const std::vector<double>& lambda_nm, int count = kUncertaintyDraws,
      std::uint32_t seed = kUncertaintySeed) const;
  // PermittivityDraws with every value checked (none without HasUncertainty()): throws
  // Error naming source() and the uncertainty when a draw is not usable (an uncertainty
  // too wide to propagate).
  std::vector<std::vector<std::complex<double>>> CheckedDraws(
      double x_atomic, const std::vector<double>& lambda_nm, int count = kUncertaintyDraws,
      std::uint32_t seed = kUncertaintySeed) const;

  // The model's physical parameters at each composition. Every model gives the free-carrier
  // density N_e(x) and the Drude tau and m*/m_e (DrudeAt) at 450, 550 and 650 nm (three
  // wavelengths across the range for infrared models), sigma from 256 draws; a model with
  // fitted physical parameters gives those instead.
  virtual ParameterTable Parameters(const std::vector<double>& x_atomic) const;

  // The wavelengths the model is defined on, where it has its own grid (nodes between
  // which it interpolates); empty for a model defined at every wavelength of its range.
  virtual std::vector<double> native_grid_nm() const { return {}; }

  // The fitted coefficients in the model file's order (empty for a model that keeps its
  // samples instead): refits compare them.
  virtual std::vector<double> FittedCoefficients() const { return {}; }

  // The complete model file (see above), deterministic for the same model.
  nlohmann::json ToJson() const;

  const AlloySystem& system() const { return system_; }
  const std::string& composition() const { return composition_; }
  double x_min() const { return x_min_; }
  double x_max() const { return x_max_; }
  double lambda_min_nm() const { return lambda_min_nm_; }
  double lambda_max_nm() const { return lambda_max_nm_; }
  const std::vector<TrainingSample>& training_samples() const { return training_; }
  const std::vector<std::string>& warnings() const { return warnings_; }
  void AddWarning(std::string warning) { warnings_.push_back(std::move(warning)); }
  const FitSummary& fit_summary() const { return fit_summary_; }
  void set_fit_summary(FitSummary summary) { fit_summary_ = std::move(summary); }
  const std::vector<InSampleError>& in_sample() const { return in_sample_; }
  void set_in_sample(std::vector<InSampleError> rows) { in_sample_ = std::move(rows); }
  // What the fit found of the data set's samples (fit/suspects.h), and the samples the
  // manifest set aside, each scored as held out.
  const std::vector<SampleNote>& suspect_samples() const { return suspects_; }
  // Whether the samples were checked (a model built for a fold or a split is not).
  bool samples_checked() const { return samples_checked_; }
  void set_suspect_samples(std::vector<SampleNote> notes) {
    suspects_ = std::move(notes);
    samples_checked_ = true;
  }
  const std::vector<SampleNote>& excluded_samples() const { return excluded_; }
  void set_excluded_samples(std::vector<SampleNote> notes) { excluded_ = std::move(notes); }
  // The model's lineage, oldest first (HistoryEntry); empty for a model built in memory
  // and not yet recorded.
  const std::vector<HistoryEntry>& history() const { return history_; }
  void set_history(std::vector<HistoryEntry> history) { history_ = std::move(history); }
  // The design's parameters over the composition range (ParameterCurvesJson), kept in the
  // model file as parameters.curves; null where not computed.
  const nlohmann::json& parameter_curves() const { return parameter_curves_; }
  void set_parameter_curves(nlohmann::json curves) { parameter_curves_ = std::move(curves); }
  const PredictionError& prediction_error() const { return prediction_error_; }
  // Throws Error naming the field when the values are not usable.
  void set_prediction_error(PredictionError error);

  // Throws Error naming x when it lies outside [x_min, x_max] (beyond 1e-9).
  void CheckInRange(double x_atomic) const;

  // Where the model comes from: its file (ModelFromJson), or the manifest of the data set
  // it was built from. Errors about using the model name it.
  const std::string& source() const { return source_; }
  void set_source(std::string source) { source_ = std::move(source); }

  // Throws Error naming source(), the composition and the wavelength: eps there is not
  // usable (`draw`: in a draw of the uncertainty).
  [[noreturn]] void FailUnusable(double x_atomic, double lambda_nm, std::complex<double> eps,
                                 bool draw) const;

 protected:
  // The method's own "parameters" block.
  virtual nlohmann::json ParametersJson() const = 0;
  // Sets the common fields from a data set (training samples, x range).
  void SetCommon(const Dataset& dataset, double lambda_min_nm, double lambda_max_nm);
  // Reads the common fields back from a model file.
  void ReadCommon(const nlohmann::json& doc);
  void CheckLambda(const std::vector<double>& lambda_nm) const;

 private:
  AlloySystem system_{};
  std::string composition_ = "atomic_fraction_a";
  double x_min_ = 0.0, x_max_ = 1.0;
  double lambda_min_nm_ = 0.0, lambda_max_nm_ = 0.0;
  std::vector<TrainingSample> training_;
  std::vector<std::string> warnings_;
  FitSummary fit_summary_;
  PredictionError prediction_error_;
  std::vector<InSampleError> in_sample_;
  std::vector<SampleNote> suspects_, excluded_;
  bool samples_checked_ = false;
  std::vector<HistoryEntry> history_;
  nlohmann::json parameter_curves_;
  std::string source_;
};

// The model's parameters against composition (Parameters) as the model file and
// `alloycolor params --format json` write them: {"system", "method", "uncertainty",
// "notes", "rows": [{"x", "x_weight", column: {"value", "sigma"} or null, ...}]}, at
// `steps` compositions evenly over [from, to].
nlohmann::json ParameterCurvesJson(const AlloyModel& model, double from, double to, int steps);
// The same over the model's composition range, 11 compositions (`params`' default).
nlohmann::json ParameterCurvesJson(const AlloyModel& model);
// The line on N_e that every parameter table carries (the elements' valence, density and
// atomic mass).
std::string FreeElectronDensityNote(const AlloySystem& system);

// The end of the message for a model whose uncertainty draws cannot be used.
extern const char* const kUncertaintyTooWide;

// The largest |eps1|, |eps2| the optics take: metals reach about 1e8 at 1 mm; beyond 1e30
// the Fresnel terms (|eps|^2) would overflow.
inline constexpr double kMaxUsablePermittivity = 1e30;

// Whether eps can feed the Fresnel chain: finite, not exactly 0 (no material has
// n = k = 0; the physical model returns 0 where its terms are not finite), and no larger
// than kMaxUsablePermittivity.
bool UsablePermittivity(double eps1, double eps2);

// Throws Error naming model.source() unless the model can be used over its whole stated
// range: a native grid (native_grid_nm) runs from lambda_range_nm[0] to [1]; eps is
// usable at the ends of the x range and at the training compositions, at the colour
// tables' 5 nm steps and the native grid; every uncertainty draw is usable at the ends and
// the middle of the x range. ModelFromJson calls it on every file; `fit` before writing.
void CheckModelUsable(const AlloyModel& model);

// Reads a model file of any method; throws Error naming the file and the field for a
// damaged file, another format, or an unknown version or method.
std::unique_ptr<AlloyModel> ReadModelFile(const std::string& path);
std::unique_ptr<AlloyModel> ModelFromJson(const nlohmann::json& doc, const std::string& source);

// The model file as text: pretty JSON with a final newline; the same model gives the
// same bytes.
std::string ModelFileText(const AlloyModel& model);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_ALLOY_MODEL_H_
