#include "alloycolor/fit/methods.h"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/text.h"
#include "alloycolor/fit/physical_fit.h"
#include "alloycolor/fit/smooth_fit.h"
#include "alloycolor/model/registry.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/validate/validation.h"

namespace alloycolor::fit {

struct FitMemo {
  struct Remembered {
    nlohmann::json model;
    MethodScore score;
    std::vector<double> values;
    std::string metric;
  };
  std::mutex mutex;
  std::map<std::string, Remembered> degree_choices;
  std::shared_ptr<EndSampleFits> end_fits = MakeEndSampleFits();
};

std::shared_ptr<FitMemo> MakeFitMemo() { return std::make_shared<FitMemo>(); }

namespace {

template <SampleModel::Kind kind>
std::unique_ptr<AlloyModel> BuildSampleModel(const Dataset& dataset, const FitSettings&) {
  return std::make_unique<SampleModel>(kind, dataset);
}

std::unique_ptr<AlloyModel> BuildSmooth(const Dataset& dataset, const FitSettings& settings) {
  SmoothFitOptions options;
  if (settings.smoothing != -1) {
    if (!(std::isfinite(settings.smoothing) && settings.smoothing >= 0)) {
      throw Error("--smoothing: need a finite value >= 0");
    }
    options.smoothing = settings.smoothing;
  }
  if (settings.space == "eps") {
    options.space = SmoothSpace::kEps;
  } else if (settings.space == "log_eps") {
    options.space = SmoothSpace::kLogEps;
  } else if (!settings.space.empty()) {
    throw Error("--space: '" + settings.space + "' is none of eps, log_eps");
  }
  options.progress = settings.progress;
  if (settings.lambda_from_nm != 0 || settings.lambda_to_nm != 0) {
    const double step = settings.lambda_step_nm > 0 ? settings.lambda_step_nm : 5.0;
    if (!(settings.lambda_to_nm > settings.lambda_from_nm) || !(settings.lambda_step_nm >= 0)) {
      throw Error("--lambda-from/--lambda-to/--lambda-step: need from < to, step > 0");
    }
    options.grid_nm = UniformGrid(settings.lambda_from_nm, settings.lambda_to_nm, step);
  }
  std::unique_ptr<SmoothModel> start;
  if (settings.start) {
    if (settings.start->method() != "smooth") {
      throw Error("a smooth refit needs a smooth model to start from, not a " +
                  settings.start->method() + " model");
    }
    start = std::make_unique<SmoothModel>(settings.start->ToJson(), "the start model");
    options.start = start.get();
    if (options.grid_nm.empty()) options.grid_nm = start->grid_nm();
  }
  return std::move(FitSmooth(dataset, options).model);
}

std::unique_ptr<AlloyModel> BuildPhysical(const Dataset& dataset, const FitSettings& settings) {
  PhysicalFitOptions options;
  if (settings.degree >= 0) options.degree = settings.degree;
  options.terms = settings.terms;
  options.covariance = settings.covariance && !settings.fold;
  options.check_physics = !settings.fold;
  if (settings.memo) options.end_fits = settings.memo->end_fits.get();
  if (settings.max_iterations > 0) options.max_iterations = settings.max_iterations;
  // A fold starts at its parent's solution (warm): a fifth of the iterations is plenty
  // where the form fits, and where it does not (a degree too low) the fold's error is
  // plain long before.
  if (settings.fold) options.max_iterations = std::max(1, options.max_iterations / 5);
  options.progress = settings.progress;
  options.start = dynamic_cast<const PhysicalModel*>(settings.start);
  if (settings.lambda_from_nm != 0 || settings.lambda_to_nm != 0) {
    if (!(settings.lambda_from_nm > 0) || !(settings.lambda_to_nm > settings.lambda_from_nm)) {
      throw Error("--lambda-from/--lambda-to: need 0 < from < to");
    }
    options.lambda_from_nm = settings.lambda_from_nm;
    options.lambda_to_nm = settings.lambda_to_nm;
  }
  if (settings.lambda_step_nm != 0) {
    if (!(settings.lambda_step_nm > 0)) throw Error("--lambda-step: need a positive step");
    options.lambda_step_nm = settings.lambda_step_nm;
  }
  return std::move(FitPhysical(dataset, options).model);
}

}  // namespace

const std::vector<MethodBuilder>& Builders() {
  static const std::vector<MethodBuilder> kBuilders = {
      {"paper", &BuildSampleModel<SampleModel::Kind::kPaper>},
      {"eps-linear", &BuildSampleModel<SampleModel::Kind::kEpsLinear>},
      {"eps-pchip", &BuildSampleModel<SampleModel::Kind::kEpsPchip>},
      {"eps-spline", &BuildSampleModel<SampleModel::Kind::kEpsSpline>},
      {"smooth", &BuildSmooth},
      {"physical", &BuildPhysical},
  };
  return kBuilders;
}

namespace {

std::vector<double> DistinctCompositions(const Dataset& dataset) {
  std::vector<double> xs;
  for (const Sample& s : dataset.samples) xs.push_back(s.x_atomic);
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  return xs;
}

// The compositions held out to estimate the prediction error: the interior ones, 20 at
// most, spread by rank.
std::vector<double> ErrorFolds(const Dataset& dataset) {
  const std::vector<double> xs = DistinctCompositions(dataset);
  if (xs.size() < 3) return {};
  std::vector<double> interior(xs.begin() + 1, xs.end() - 1);
  constexpr size_t kMaxFolds = 20;
  if (interior.size() <= kMaxFolds) return interior;
  std::vector<double> folds;
  for (size_t f = 0; f < kMaxFolds; ++f) {
    folds.push_back(interior[f * (interior.size() - 1) / (kMaxFolds - 1)]);
  }
  return folds;
}

// One composition held out: the method built on the rest (null where it could not be),
// the held-out samples, and what the prediction error needs of the fold.
struct Fold {
  double x = 0;
  std::unique_ptr<AlloyModel> model;
  std::string error;                 // why model is null
  std::vector<const Sample*> held;
  std::vector<double> compositions;  // of the fold's training samples
};

// The method built without each of ErrorFolds in turn, in parallel. The physical fit of a
// fold starts from `model` (warm): the same ends, so the same interband terms, which its
// fits of the end samples chose, and coefficients near the fold's; it then converges on
// the fold's own data. (`validate` refits each of its splits from scratch.) A smooth fold
// with no interior composition (three compositions in all) cannot choose the space of its
// curves and takes the one `model` has, so that it scores the model delivered.
std::vector<Fold> FitFolds(const std::string& method, const Dataset& dataset,
                           const FitSettings& settings, const AlloyModel& model) {
  const std::vector<double> xs = ErrorFolds(dataset);
  FitSettings inner = settings;
  inner.calibrate = false;
  inner.fold = true;
  inner.progress = {};
  inner.start = method == "physical" ? &model : nullptr;
  std::vector<Fold> folds(xs.size());
  ParallelTasks(xs.size(), [&](size_t k) {
    Fold& f = folds[k];
    f.x = xs[k];
    const Dataset training = WithoutSamples(dataset, {f.x});
    FitSettings fold = inner;
    if (const auto* smooth = dynamic_cast<const SmoothModel*>(&model);
        smooth != nullptr && fold.space.empty() && DistinctCompositions(training).size() < 3) {
      fold.space = SmoothSpaceName(smooth->space());
    }
    try {
      f.model = BuildModel(method, training, fold);
    } catch (const Error& e) {
      f.error = e.what();
      return;
    }
    for (const Sample& s : dataset.samples) {
      if (s.x_atomic == f.x) f.held.push_back(&s);
    }
    f.compositions = DistinctCompositions(training);
  });
  return folds;
}

// The power of the gap in B: 2 for the methods that interpolate linearly between
// neighbouring samples (paper: tau and m*; eps-linear: eps), whose error on a smooth curve
// is t (1 - t) h^2 f'' / 2, and for every method on three compositions, whose one fold is
// that straight line between the ends; 1 for the others, between the h^3 or h^4 of a cubic
// on a smooth curve and the h^0 of sample-to-sample scatter.
double GapExponent(const std::string& method, const Dataset& dataset) {
  const bool line = method == "paper" || method == "eps-linear" ||
                    DistinctCompositions(dataset).size() == 3;
  return line ? 2.0 : 1.0;
}

// The prediction error (BuildModel) from the folds; sets each fold model's error too.
void EstimatePredictionError(const std::string& method, std::vector<Fold>& fitted,
                             const Dataset& dataset, const FitSettings& settings,
                             AlloyModel* model) {
  const double lo = model->lambda_min_nm(), hi = model->lambda_max_nm();
  std::vector<double> grid;
  for (int j = 0; j <= 80; ++j) grid.push_back(lo + (hi - lo) * j / 80.0);
  std::vector<Fold*> done;  // a fold the method cannot fit says nothing about the error
  double gap_sum = 0;
  for (Fold& f : fitted) {
    if (!f.model) continue;
    const size_t i = std::upper_bound(f.compositions.begin(), f.compositions.end(), f.x) -
                     f.compositions.begin();
    gap_sum += f.compositions[i] - f.compositions[i - 1];
    done.push_back(&f);
  }
  if (done.empty()) return;
  const double reference_gap = gap_sum / done.size();
  const double gap_exponent = GapExponent(method, dataset);
  // Each fold's relative eps errors per wavelength, over its B (reference gap, end factor 1).
  struct FoldErrors {
    Fold* fold = nullptr;
    std::vector<double> over_bump;  // per held-out sample and wavelength, flattened
    bool end = false;               // held out in an end interval of its training samples
    std::vector<double> sum_sq;     // per wavelength: its part of sum_sq below
    int count = 0;                  // its held-out samples
  };
  std::vector<FoldErrors> errors;
  for (Fold* fp : done) {
    const Fold& f = *fp;
    PredictionError shape;
    shape.compositions = f.compositions;
    shape.reference_gap = reference_gap;
    shape.gap_exponent = gap_exponent;
    const double bump = shape.Bump(f.x);
    if (!(bump > 0)) continue;
    FoldErrors fe;
    fe.fold = fp;
    const size_t n = f.compositions.size();
    const size_t hi = std::upper_bound(f.compositions.begin(), f.compositions.end(), f.x) -
                      f.compositions.begin();
    fe.end = n > 2 && (hi == 1 || hi == n - 1);
    const auto predicted = f.model->Permittivity(f.held.front()->x_atomic, grid);
    for (const Sample* s : f.held) {
      for (size_t j = 0; j < grid.size(); ++j) {
        const std::complex<double> nk = NkAt(s->nk, grid[j]), e = nk * nk;
        const double r = std::abs(predicted[j] - e) / std::abs(e);
        fe.over_bump.push_back(std::isfinite(r) ? r / bump : 0.0);
      }
    }
    errors.push_back(std::move(fe));
  }
  if (errors.empty()) return;
  // The end factor: how much larger the end folds' errors are than the interior ones'
  // (geometric means of their RMS), where the folds have both; at least 1.
  double end_factor = 1;
  {
    double log_sum[2] = {0, 0};
    int folds_of[2] = {0, 0};
    for (const FoldErrors& fe : errors) {
      double sq = 0;
      for (double v : fe.over_bump) sq += v * v;
      const double rms = std::sqrt(sq / std::max<size_t>(fe.over_bump.size(), 1));
      if (!(rms > 0)) continue;
      log_sum[fe.end] += std::log(rms);
      ++folds_of[fe.end];
    }
    if (folds_of[0] > 0 && folds_of[1] > 0) {
      // Shrunk towards 1 as few folds say little: weight k / (k + 2), k the smaller group.
      const double k = std::min(folds_of[0], folds_of[1]);
      end_factor = std::clamp(
          std::exp(k / (k + 2) * (log_sum[1] / folds_of[1] - log_sum[0] / folds_of[0])), 1.0,
          10.0);
    }
  }
  // scale[j]^2: mean over the held-out samples of (relative error / B)^2.
  std::vector<double> sum_sq(grid.size(), 0.0);
  int count = 0;
  for (FoldErrors& fe : errors) {
    const double factor = fe.end ? end_factor : 1.0;
    fe.sum_sq.assign(grid.size(), 0.0);
    for (size_t k = 0; k < fe.over_bump.size(); ++k) {
      fe.sum_sq[k % grid.size()] += std::pow(fe.over_bump[k] / factor, 2);
    }
    fe.count = static_cast<int>(fe.over_bump.size() / grid.size());
    for (size_t j = 0; j < grid.size(); ++j) sum_sq[j] += fe.sum_sq[j];
    count += fe.count;
  }
  if (count == 0) return;
  PredictionError error;
  error.end_factor = end_factor;
  error.lambda_nm = grid;
  for (double v : sum_sq) error.scale.push_back(std::min(std::sqrt(v / count), 100.0));
  error.compositions = DistinctCompositions(dataset);
  error.reference_gap = reference_gap;
  error.gap_exponent = gap_exponent;
  error.folds = static_cast<int>(done.size());
  // Calibration on colour: the folds' observed / predicted one-sigma CIEDE2000, each
  // fold's sigma from the scale of the other folds (cross-fitted: a fold's own error in
  // its scale would flatter the ratio, by half with two folds).
  if (settings.colorimeter != nullptr && CoversVisible(lo, hi)) {
    const color::Colorimeter& cm = *settings.colorimeter;
    std::vector<double> log_ratios;
    for (const FoldErrors& fe : errors) {
      Fold& f = *fe.fold;
      PredictionError fold_error = error;
      fold_error.compositions = f.compositions;
      if (errors.size() > 1) {
        for (size_t j = 0; j < grid.size(); ++j) {
          fold_error.scale[j] =
              std::min(std::sqrt((sum_sq[j] - fe.sum_sq[j]) / (count - fe.count)), 100.0);
        }
      }
      f.model->set_prediction_error(fold_error);
      const double x = f.held.front()->x_atomic;
      const double sigma = color::DeltaE00Sigma(cm, *f.model, x, 0.0);
      if (!(sigma > 0) || !std::isfinite(sigma)) continue;
      const color::Lab predicted = color::LabFromXYZ(
          color::MaterialXYZ(cm, color::IndexOnGrid(cm, *f.model, x), 0.0), cm.White());
      for (const Sample* s : f.held) {
        const color::Lab truth = color::LabFromXYZ(
            color::MaterialXYZ(cm, color::IndexOnGrid(cm, s->nk), 0.0), cm.White());
        const double ratio = color::DeltaE00(truth, predicted) / sigma;
        if (ratio > 0 && std::isfinite(ratio)) log_ratios.push_back(std::log(ratio));
      }
    }
    if (!log_ratios.empty()) error.calibration = SigmaCalibration(log_ratios);
  }
  model->set_prediction_error(std::move(error));
}

// `method` built on the data set, nothing more.
std::unique_ptr<AlloyModel> Build(const std::string& method, const Dataset& dataset,
                                  const FitSettings& settings) {
  RequireMethod(method);
  for (const MethodBuilder& b : Builders()) {
    if (b.name == method) return b.build(dataset, settings);
  }
  throw Error("method '" + method + "' cannot be fitted to data");
}

// `model` (`method` built on the data set) given its leave-one-out folds in *folds and,
// with settings.calibrate, its prediction error from them.
void AddFolds(const std::string& method, const Dataset& dataset, const FitSettings& settings,
              AlloyModel* model, std::vector<Fold>* folds) {
  *folds = FitFolds(method, dataset, settings, *model);
  if (settings.calibrate) EstimatePredictionError(method, *folds, dataset, settings, model);
}

// `method` built on the data set; with `folds` (or settings.calibrate) the leave-one-out
// folds too, and with settings.calibrate its prediction error from them.
std::unique_ptr<AlloyModel> BuildWithFolds(const std::string& method, const Dataset& dataset,
                                           const FitSettings& settings,
                                           std::vector<Fold>* folds) {
  std::unique_ptr<AlloyModel> model = Build(method, dataset, settings);
  std::vector<Fold> own;
  if (folds != nullptr || settings.calibrate) {
    AddFolds(method, dataset, settings, model.get(), folds != nullptr ? folds : &own);
  }
  return model;
}

// auto's score of a method: its folds' held-out samples scored as `validate` scores them
// (ComputeValidation, given the folds' models), mean over the folds; `values`: each
// held-out sample's score, in the folds' order.
MethodScore ScoreFolds(const std::string& method, const Dataset& dataset,
                       std::vector<Fold>& folds, const color::Colorimeter& colorimeter,
                       std::string* metric, std::vector<double>* values) {
  MethodScore score;
  score.method = method;
  *metric = "reflectance_rms at normal incidence";  // data without colour
  std::vector<std::vector<double>> splits;
  for (const Fold& f : folds) splits.push_back({f.x});
  validate::ValidationOptions options;
  options.build = [&folds](const std::string&, const Dataset& training) {
    for (Fold& f : folds) {
      const bool held = std::none_of(training.samples.begin(), training.samples.end(),
                                     [&](const Sample& s) { return s.x_atomic == f.x; });
      if (!held) continue;
      if (!f.model) throw Error(f.error);
      return std::move(f.model);
    }
    throw Error("no fold holds out this split");
  };
  options.methods = {method};
  options.angles_deg = {0.0};
  options.mode = "loo";
  options.sigma_draws = 0;
  const validate::ValidationReport report =
      validate::ComputeValidation(dataset, splits, colorimeter, options, {});
  double sum = 0;
  for (const auto& h : report.holdouts) {
    const auto it = h.results.find(method);
    if (it == h.results.end() || !it->second.error.empty()) continue;
    const validate::MethodResult& r = it->second;
    const double v = !r.delta_e00.empty() ? r.delta_e00[0] : r.reflectance_rms;
    if (!std::isfinite(v)) continue;
    sum += v;
    values->push_back(v);
    score.max = score.folds == 0 ? v : std::max(score.max, v);
    ++score.folds;
    if (!r.delta_e00.empty()) *metric = "delta_e00 at normal incidence";
  }
  if (score.folds < static_cast<int>(splits.size())) {
    score.error = "failed on " + std::to_string(splits.size() - score.folds) + " of " +
                  std::to_string(splits.size()) + " folds";
  } else {
    score.mean = sum / score.folds;
  }
  return score;
}

constexpr double kAutoTolerance = 1.10;
constexpr int kCandidateIterations = 100;  // a physical degree candidate's solver budget
// Nordheim's rule bows the damping quadratically in composition (the plasma frequency is
// nearly linear): the degree kept unless leave-one-out finds another clearly better.
constexpr int kPreferredDegree = 2;

// A candidate built on all samples with its folds (which also gave its prediction error),
// scored on them.
struct Scored {
  std::unique_ptr<AlloyModel> model;  // null where it could not be built or scored
  MethodScore score;
  std::vector<double> values;  // each held-out sample's score, in the folds' order
  std::string metric;
};

// `model` (`method` built on the data set) with its folds, scored on them.
Scored ScoreWithFolds(const std::string& method, const Dataset& dataset,
                      const FitSettings& settings, std::unique_ptr<AlloyModel> model) {
  Scored r;
  r.score.method = method;
  try {
    std::vector<Fold> folds;
    AddFolds(method, dataset, settings, model.get(), &folds);
    r.model = std::move(model);
    r.score = ScoreFolds(method, dataset, folds, *settings.colorimeter, &r.metric, &r.values);
  } catch (const Error& e) {
    r.score.error = e.what();
  }
  if (!r.score.error.empty()) r.model.reset();
  return r;
}

Scored BuildScored(const std::string& method, const Dataset& dataset,
                   const FitSettings& settings) {
  std::unique_ptr<AlloyModel> model;
  try {
    model = Build(method, dataset, settings);
  } catch (const Error& e) {
    Scored r;
    r.score.method = method;
    r.score.error = e.what();
    return r;
  }
  return ScoreWithFolds(method, dataset, settings, std::move(model));
}

double Rms(const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v * v;
  return std::sqrt(sum / std::max<size_t>(values.size(), 1));
}

// The one-standard-error choice among candidates listed in order of preference (auto:
// simplest first; the physical degree: Nordheim's first): the first whose
// mean lies within kAutoTolerance of the lowest, or above it by no more than the standard
// error of their fold-by-fold differences (paired folds, from two folds up):
// leave-one-out with few samples flatters the flexible candidates, and a lead within the
// folds' own scatter is no lead. `squared`: the same on the folds' squared scores (the
// tolerance on their RMS), so that one bad fold counts as it does in a squared loss.
// `chosen` and `best` are candidates.size() when none could be scored.
struct Choice {
  size_t chosen, best;
  std::string rule;  // why the chosen, if it is not the best: "10 %" or the standard error
};

Choice ChooseSimplest(const std::vector<Scored>& candidates, bool squared = false) {
  const size_t none = candidates.size();
  Choice c{none, none, ""};
  std::vector<std::vector<double>> loss(candidates.size());
  std::vector<double> mean(candidates.size(), 0.0);
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (!candidates[i].score.error.empty()) continue;
    for (double v : candidates[i].values) loss[i].push_back(squared ? v * v : v);
    for (double v : loss[i]) mean[i] += v / loss[i].size();
    if (!loss[i].empty() && (c.best == none || mean[i] < mean[c.best])) c.best = i;
  }
  if (c.best == none) return c;
  const auto within_scatter = [&](size_t i) {
    const std::vector<double>& a = loss[i];
    const std::vector<double>& b = loss[c.best];
    if (a.size() != b.size() || a.size() < 2) return false;
    double d = 0, sq = 0;
    for (size_t k = 0; k < a.size(); ++k) d += a[k] - b[k];
    d /= a.size();
    for (size_t k = 0; k < a.size(); ++k) sq += std::pow(a[k] - b[k] - d, 2);
    const double se = std::sqrt(sq / (a.size() - 1) / a.size());
    return d <= se;
  };
  const double tolerance = squared ? kAutoTolerance * kAutoTolerance : kAutoTolerance;
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (loss[i].empty()) continue;
    const bool close = mean[i] <= mean[c.best] * tolerance;
    if (close || within_scatter(i)) {
      c.chosen = i;
      if (i != c.best) c.rule = close ? "10 %" : "one standard error of the folds' differences";
      return c;
    }
  }
  return c;
}

// RMS of a model's error on the samples it was fitted to, over those its folds hold out
// (ErrorFolds), in the metric ScoreFolds uses: CIEDE2000 at normal incidence, or for data
// without colour the reflectance RMS over the sample's wavelengths inside the model's range.
double OwnErrorRms(const AlloyModel& model, const Dataset& dataset,
                   const color::Colorimeter& cm) {
  const bool colour = CoversVisible(model.lambda_min_nm(), model.lambda_max_nm());
  const std::vector<double> held = ErrorFolds(dataset);
  double sum = 0;
  int count = 0;
  for (const Sample& s : dataset.samples) {
    if (std::find(held.begin(), held.end(), s.x_atomic) == held.end()) continue;
    ++count;
    double e = 0;
    if (colour) {
      const color::Lab a = color::LabFromXYZ(
          color::MaterialXYZ(cm, color::IndexOnGrid(cm, model, s.x_atomic), 0.0), cm.White());
      const color::Lab b = color::LabFromXYZ(
          color::MaterialXYZ(cm, color::IndexOnGrid(cm, s.nk), 0.0), cm.White());
      e = color::DeltaE00(a, b);
    } else {
      std::vector<double> grid;
      for (double l : s.nk.lambda_nm) {
        if (l >= model.lambda_min_nm() && l <= model.lambda_max_nm()) grid.push_back(l);
      }
      if (grid.empty()) continue;
      std::vector<std::complex<double>> measured;
      for (double l : grid) measured.push_back(NkAt(s.nk, l));
      const auto r_model = color::ReflectanceSpectrum(model.Index(s.x_atomic, grid), 0.0);
      const auto r_data = color::ReflectanceSpectrum(measured, 0.0);
      for (size_t j = 0; j < grid.size(); ++j) e += std::pow(r_model[j] - r_data[j], 2);
      e = std::sqrt(e / grid.size());
    }
    sum += e * e;
  }
  return std::sqrt(sum / std::max(count, 1));
}

// A physical candidate scored on its folds unless its own error on the samples (converged:
// an unfinished fit is continued first) already exceeds what it would have to beat,
// `preferred`'s leave-one-out RMS over kAutoTolerance: a held-out sample is no nearer than
// the fitted ones, so its folds could not make it win (Au-Ag at degree 1: own error 1.0
// against 4e-5), and they are not fitted.
Scored BuildUnlessOutdone(const Dataset& dataset, const FitSettings& settings,
                          const Scored& preferred) {
  if (!preferred.score.error.empty()) return BuildScored("physical", dataset, settings);
  const double must_beat = Rms(preferred.values) / kAutoTolerance;
  Scored r;
  r.score.method = "physical";
  std::unique_ptr<AlloyModel> model;
  double own = 0;
  try {
    model = Build("physical", dataset, settings);
    own = OwnErrorRms(*model, dataset, *settings.colorimeter);
    if (own >= must_beat && !model->fit_summary().converged) {
      FitSettings full = settings;
      full.start = model.get();
      full.max_iterations = 0;
      model = Build("physical", dataset, full);
      own = OwnErrorRms(*model, dataset, *settings.colorimeter);
    }
  } catch (const Error& e) {
    r.score.error = e.what();
    return r;
  }
  if (own >= must_beat) {
    char why[160];
    std::snprintf(why, sizeof why,
                  "its own RMS error on the samples, %.4g, already exceeds what it would have "
                  "to beat, %.4g",
                  own, must_beat);
    r.score.error = why;
    return r;
  }
  return ScoreWithFolds("physical", dataset, settings, std::move(model));
}

// The physical fit's composition degree chosen by the data: degrees 2 and 1 (2 needs four
// compositions, so that every fold fits it too), each built with its folds and scored on
// them by the RMS of the folds' errors. Degree 2 (kPreferredDegree) stays unless degree 1
// is lower by more than 10 % and by more than one standard error of the folds' paired
// differences (ChooseSimplest with 2 first, squared: a degree that misses one fold badly
// is not saved by the others): leave-one-out over a few folds is too noisy to overrule
// the physics on less. Degree 3 is not offered: on Nb-Sn the folds chose it where a
// held-out end sample left a wide gap, and it bent across that gap (reflectance RMS 0.42
// against 0.13); --degree asks for it. Fewer than four compositions cannot tell degrees
// apart: the default degree then. The table and the reason go into the fit summary.
Scored BuildPhysicalChoosingDegree(const Dataset& dataset, const FitSettings& settings) {
  const int compositions = static_cast<int>(DistinctCompositions(dataset).size());
  const int top = std::min(kPreferredDegree, compositions - 2);
  if (settings.colorimeter == nullptr || ErrorFolds(dataset).size() < 2 || top < 2) {
    return BuildScored("physical", dataset, settings);
  }
  // Candidates on a fifth of the iterations and without covariance: a degree that does
  // not fit the data shows it long before, and the chosen one is finished below.
  std::vector<Scored> candidates;
  std::vector<int> degrees;
  for (int degree : {kPreferredDegree, 1}) {
    if (degree <= top) degrees.push_back(degree);
  }
  for (int degree : degrees) {
    Report(settings.progress, "physical: degree " + std::to_string(degree) +
                                  ", leave-one-out over " +
                                  std::to_string(ErrorFolds(dataset).size()) + " compositions");
    FitSettings at = settings;
    at.degree = degree;
    at.progress = {};
    at.covariance = false;
    at.max_iterations = kCandidateIterations;
    Scored r = candidates.empty() ? BuildScored("physical", dataset, at)
                                  : BuildUnlessOutdone(dataset, at, candidates.front());
    if (r.model && r.model->fit_summary().degree != degree) {
      r.score.error = "lowered to degree " + std::to_string(r.model->fit_summary().degree) +
                      " (it left physics or did not converge)";
      r.model.reset();
    }
    candidates.push_back(std::move(r));
  }
  const Choice c = ChooseSimplest(candidates, /*squared=*/true);
  if (c.chosen == candidates.size()) {
    // No degree could be scored: the default fit says why (or succeeds on its own).
    return BuildScored("physical", dataset, settings);
  }
  Scored chosen = std::move(candidates[c.chosen]);
  const int degree = chosen.model->fit_summary().degree;
  {
    // Finished from where the candidate stopped, with the covariance; its folds' prediction
    // error carries over (the folds started from the candidate). The finished fit may still
    // leave physics where the candidate had not (on Au-Ag with 2 % scatter added, eps2 < 0
    // at the silver end at degree 1): then the physical model is refused, as any fit that
    // leaves physics is, and auto goes on without it.
    FitSettings full = settings;
    full.degree = degree;
    full.start = chosen.model.get();
    std::unique_ptr<AlloyModel> finished;
    try {
      finished = Build("physical", dataset, full);
    } catch (const Error& e) {
      Scored refused;
      refused.score.method = "physical";
      refused.score.error = e.what();
      return refused;
    }
    if (chosen.model->prediction_error().present()) {
      finished->set_prediction_error(chosen.model->prediction_error());
    }
    chosen.model = std::move(finished);
  }
  char reason[200];
  std::snprintf(reason, sizeof reason, "leave-one-out RMS %s %.4g over %d folds%s%s",
                chosen.metric.c_str(), Rms(chosen.values), chosen.score.folds,
                c.rule.empty() ? ", the lowest" : ", Nordheim's degree 2 within ",
                c.rule.c_str());
  FitSummary summary = chosen.model->fit_summary();
  nlohmann::json table = nlohmann::json::array();
  for (size_t i = 0; i < candidates.size(); ++i) {
    const Scored& r = i == c.chosen ? chosen : candidates[i];
    const MethodScore& s = r.score;
    nlohmann::json row = {{"degree", degrees[i]}};
    if (s.error.empty()) {
      row["rms"] = Rms(r.values);
      row["mean"] = s.mean;
      row["max"] = s.max;
      row["folds"] = s.folds;
    } else {
      row["error"] = s.error;
    }
    table.push_back(row);
  }
  summary.details["degree_chosen_by"] = reason;
  summary.details["degree_selection"] = table;
  chosen.model->set_fit_summary(std::move(summary));
  Report(settings.progress, "physical: degree " + std::to_string(degree) + ": " + reason);
  return chosen;
}

// BuildPhysicalChoosingDegree through settings.memo: the choice is deterministic, so the
// remembered result (a copy through the model file) is what a new one would give. Keyed by
// the samples (composition, wavelengths, n, k) and every setting the fit reads; a refit
// (settings.start) is not remembered.
Scored RememberedDegreeChoice(const Dataset& dataset, const FitSettings& settings) {
  if (!settings.memo || settings.start != nullptr) {
    return BuildPhysicalChoosingDegree(dataset, settings);
  }
  std::string key = settings.terms;
  const auto add = [&key](const void* bytes, size_t size) {
    key.append(static_cast<const char*>(bytes), size);
  };
  const double numbers[] = {settings.lambda_from_nm, settings.lambda_to_nm,
                            settings.lambda_step_nm};
  add(numbers, sizeof numbers);
  const int flags[] = {settings.covariance, settings.calibrate, settings.max_iterations};
  add(flags, sizeof flags);
  add(&settings.colorimeter, sizeof settings.colorimeter);
  for (const Sample& s : dataset.samples) {
    add(&s.x_atomic, sizeof s.x_atomic);
    for (const auto* v : {&s.nk.lambda_nm, &s.nk.n, &s.nk.k}) {
      const size_t size = v->size();
      add(&size, sizeof size);
      add(v->data(), size * sizeof(double));
    }
  }
  FitMemo& memo = *settings.memo;
  const auto copy = [](const FitMemo::Remembered& m) {
    Scored r;
    r.model = RequireMethod("physical").read(m.model, "the remembered physical fit");
    r.score = m.score;
    r.values = m.values;
    r.metric = m.metric;
    return r;
  };
  {
    const std::lock_guard<std::mutex> lock(memo.mutex);
    const auto it = memo.degree_choices.find(key);
    if (it != memo.degree_choices.end()) return copy(it->second);
  }
  Scored r = BuildPhysicalChoosingDegree(dataset, settings);
  if (!r.model) return r;
  FitMemo::Remembered m{r.model->ToJson(), r.score, r.values, r.metric};
  const std::lock_guard<std::mutex> lock(memo.mutex);
  memo.degree_choices.emplace(std::move(key), std::move(m));
  return r;
}

bool ChoosesDegree(const std::string& method, const FitSettings& settings) {
  return method == "physical" && settings.degree < 0 && !settings.fold;
}

}  // namespace

double SigmaCalibration(const std::vector<double>& log_ratios) {
  if (log_ratios.empty()) return 1;
  constexpr double kPriorLogSpread = 0.6, kPriorFolds = 2;
  const double f = static_cast<double>(log_ratios.size());
  double mu = 0, sq = 0;
  for (double v : log_ratios) mu += v;
  mu /= f;
  for (double v : log_ratios) sq += (v - mu) * (v - mu);
  const double s2 = (kPriorFolds * kPriorLogSpread * kPriorLogSpread + sq) / (kPriorFolds + f - 1);
  const double spread = std::sqrt(s2 * (1 + 1 / f));
  // A new log ratio's predictive law: Student's t with the pooled variance's degrees of
  // freedom (normal-inverse-chi-squared prior), its quantiles wider than the normal's
  // while the folds are few.
  const boost::math::students_t law(kPriorFolds + f - 1);
  const double q68 = boost::math::quantile(law, 0.68), q95 = boost::math::quantile(law, 0.95);
  const double c68 = std::exp(mu + q68 * spread), c95 = std::exp(mu + q95 * spread) / 2;
  // Both aims hold where the ratio's 95 % quantile is at most twice its 68 % one (c95 <= c68,
  // as for a half-normal error). Where it is more they cannot: the factor for 95 % inside
  // two sigma would put far more than 68 % inside one (84 % in the bundled sets' pooled
  // leave-one-out folds). There the factor splits the difference: the geometric mean.
  return std::clamp(std::max(c68, std::sqrt(c68 * c95)), 1e-3, 1e3);
}

std::unique_ptr<AlloyModel> BuildModel(const std::string& method, const Dataset& dataset,
                                       const FitSettings& settings) {
  if (!settings.memo) {
    // One memo for this fit, its candidates and its folds.
    FitSettings with_memo = settings;
    with_memo.memo = MakeFitMemo();
    return BuildModel(method, dataset, with_memo);
  }
  if (method == kAutoMethod) return BuildAuto(dataset, settings);
  if (ChoosesDegree(method, settings)) {
    if (settings.colorimeter == nullptr) {
      throw Error(
          "physical: the composition degree is chosen by the colour error of leave-one-out "
          "folds, which needs a colorimeter (FitSettings::colorimeter); or give the degree");
    }
    Scored r = RememberedDegreeChoice(dataset, settings);
    if (!r.model) throw Error(r.score.error);
    return std::move(r.model);
  }
  return BuildWithFolds(method, dataset, settings, nullptr);
}

std::function<std::unique_ptr<AlloyModel>(const std::string& method, const Dataset& training)>
SharedFitBuilder(const color::Colorimeter& colorimeter) {
  FitSettings settings;
  settings.colorimeter = &colorimeter;
  settings.memo = MakeFitMemo();
  return [settings](const std::string& method, const Dataset& training) {
    return BuildModel(method, training, settings);
  };
}

std::unique_ptr<AlloyModel> BuildAuto(const Dataset& dataset, const FitSettings& settings) {
  // Simplest first: ties go to the earlier.
  const std::vector<std::string> order = {"eps-pchip", "eps-linear", "eps-spline",
                                          "paper",     "smooth",     "physical"};
  if (settings.colorimeter == nullptr) throw Error("auto: no colorimeter to score colours with");
  MethodSelection selection;
  const size_t held_out = ErrorFolds(dataset).size();
  if (held_out == 0) {
    selection.metric = "none";
    selection.reason = "eps-pchip: " + std::to_string(DistinctCompositions(dataset).size()) +
                       " compositions leave none to hold out (every interpolation is then the "
                       "straight line between the samples)";
    Report(settings.progress, "auto: " + selection.reason);
    std::unique_ptr<AlloyModel> model = BuildModel("eps-pchip", dataset, settings);
    FitSummary summary = model->fit_summary();
    summary.selection = selection;
    model->set_fit_summary(std::move(summary));
    return model;
  }
  // Every candidate built on all samples with its folds (which also give its prediction
  // error): the folds score it, and the chosen one is already built.
  FitSettings inner = settings;
  inner.progress = {};
  inner.start = nullptr;
  std::vector<Scored> candidates;
  const int compositions = static_cast<int>(DistinctCompositions(dataset).size());
  for (const std::string& method : order) {
    Report(settings.progress, "auto: scoring " + method + " by leave-one-out over " +
                                  std::to_string(held_out) + " interior compositions");
    candidates.push_back(ChoosesDegree(method, inner)
                             ? RememberedDegreeChoice(dataset, inner)
                             : BuildScored(method, dataset, inner));
    Scored& r = candidates.back();
    // The folds must score the model delivered: a fold holds compositions - 1, enough
    // for degree compositions - 2 at most (three compositions: the physical model is
    // delivered at degree 2 and its folds are degree-1 fits to two samples).
    if (method == "physical" && r.model && r.model->fit_summary().degree > compositions - 2) {
      r.score.error = "its folds (" + std::to_string(compositions - 1) +
                      " compositions each) cannot fit its degree " +
                      std::to_string(r.model->fit_summary().degree);
      r.model.reset();
    }
    selection.scores.push_back(r.score);
    if (selection.metric.empty()) selection.metric = candidates.back().metric;
  }
  Choice c = ChooseSimplest(candidates);
  // One fold (three compositions): it holds out the middle sample and predicts it from the
  // ends, where every interpolation is a straight line in its own space, so the fold
  // compares spaces, not the curves delivered through three samples, and one score has no
  // scatter to weigh a lead by (on Au-Ag's 0, 0.1, 1 it preferred paper's line, whose curve
  // then erred 11 on the held-out samples against smooth's 1.3). Smooth asks of that fold
  // only what it can tell, its space, and chooses its smoothing by the marginal likelihood.
  const size_t smooth = std::find(order.begin(), order.end(), "smooth") - order.begin();
  if (held_out == 1 && candidates[smooth].score.error.empty() && c.chosen != smooth) {
    c.rule = "one fold";
    c.chosen = smooth;
  }
  if (c.chosen == order.size()) {
    throw Error(dataset.manifest_path + ": auto: no method could be scored");
  }
  const MethodScore& chosen_score = selection.scores[c.chosen];
  const MethodScore& best_score = selection.scores[c.best];
  char reason[240];
  if (c.rule.empty()) {
    std::snprintf(reason, sizeof reason, "%s: lowest leave-one-out mean %s, %.4g over %d folds",
                  order[c.chosen].c_str(), selection.metric.c_str(), chosen_score.mean,
                  chosen_score.folds);
  } else if (c.rule == "one fold") {
    std::snprintf(reason, sizeof reason,
                  "%s: one fold (three compositions) compares the straight lines between the "
                  "ends, not the curves through three samples; %s scored %.4g, %s %.4g",
                  order[c.chosen].c_str(), order[c.chosen].c_str(), chosen_score.mean,
                  order[c.best].c_str(), best_score.mean);
  } else {
    std::snprintf(reason, sizeof reason,
                  "%s: leave-one-out mean %s %.4g over %d folds, the simplest within %s of the "
                  "lowest (%s, %.4g)",
                  order[c.chosen].c_str(), selection.metric.c_str(), chosen_score.mean,
                  chosen_score.folds, c.rule.c_str(), order[c.best].c_str(), best_score.mean);
  }
  selection.reason = reason;
  std::unique_ptr<AlloyModel> model = std::move(candidates[c.chosen].model);
  Report(settings.progress, "auto: " + selection.reason);
  FitSummary summary = model->fit_summary();
  summary.selection = selection;
  model->set_fit_summary(std::move(summary));
  return model;
}

}  // namespace alloycolor::fit
