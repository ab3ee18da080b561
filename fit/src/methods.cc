#include "alloycolor/fit/methods.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "alloycolor/core/error.h"
#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/core/text.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/fit/physical_fit.h"
#include "alloycolor/fit/smooth_fit.h"
#include "alloycolor/model/registry.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/validate/validation.h"

namespace alloycolor::fit {
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
  options.covariance = settings.covariance;
  options.progress = settings.progress;
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

void EstimatePredictionError(const std::string& method, const Dataset& dataset,
                             const FitSettings& settings, AlloyModel* model) {
  const std::vector<double> folds = ErrorFolds(dataset);
  if (folds.empty()) return;
  FitSettings inner = settings;
  inner.calibrate = false;
  inner.progress = {};
  inner.start = nullptr;
  const double lo = model->lambda_min_nm(), hi = model->lambda_max_nm();
  std::vector<double> grid;
  for (int j = 0; j <= 80; ++j) grid.push_back(lo + (hi - lo) * j / 80.0);
  struct Fold {
    std::unique_ptr<AlloyModel> model;
    std::vector<const Sample*> held;
    std::vector<double> compositions;  // of the fold's training samples
    double bump = 0;                   // B(x) of the held-out composition, reference gap 1
  };
  std::vector<Fold> done;
  double gap_sum = 0;
  for (double x : folds) {
    Fold f;
    const Dataset training = WithoutSamples(dataset, {x});
    try {
      f.model = BuildModel(method, training, inner);
    } catch (const Error&) {
      continue;  // a fold the method cannot fit says nothing about the error
    }
    for (const Sample& s : dataset.samples) {
      if (s.x_atomic == x) f.held.push_back(&s);
    }
    f.compositions = DistinctCompositions(training);
    PredictionError unit;
    unit.compositions = f.compositions;
    f.bump = unit.Bump(x);
    const size_t i = std::upper_bound(f.compositions.begin(), f.compositions.end(), x) -
                     f.compositions.begin();
    gap_sum += f.compositions[i] - f.compositions[i - 1];
    done.push_back(std::move(f));
  }
  if (done.empty()) return;
  const double reference_gap = gap_sum / done.size();
  // scale[j]^2: mean over folds of (relative error / B)^2, B with the reference gap.
  std::vector<double> sum_sq(grid.size(), 0.0);
  int count = 0;
  for (const Fold& f : done) {
    const double bump = f.bump / reference_gap;
    if (!(bump > 0)) continue;
    const auto predicted = f.model->Permittivity(f.held.front()->x_atomic, grid);
    for (const Sample* s : f.held) {
      for (size_t j = 0; j < grid.size(); ++j) {
        const std::complex<double> nk = NkAt(s->nk, grid[j]), e = nk * nk;
        const double r = std::abs(predicted[j] - e) / std::abs(e);
        if (std::isfinite(r)) sum_sq[j] += std::pow(r / bump, 2);
      }
      ++count;
    }
  }
  if (count == 0) return;
  PredictionError error;
  error.lambda_nm = grid;
  for (double v : sum_sq) error.scale.push_back(std::min(std::sqrt(v / count), 100.0));
  error.compositions = DistinctCompositions(dataset);
  error.reference_gap = reference_gap;
  error.folds = static_cast<int>(done.size());
  // Calibration on colour: RMS over folds of observed / predicted one-sigma CIEDE2000.
  if (settings.colorimeter != nullptr && CoversVisible(lo, hi)) {
    const color::Colorimeter& cm = *settings.colorimeter;
    double ratio_sq = 0;
    int ratios = 0;
    for (Fold& f : done) {
      PredictionError fold_error = error;
      fold_error.compositions = f.compositions;
      f.model->set_prediction_error(fold_error);
      const double x = f.held.front()->x_atomic;
      const double sigma = color::DeltaE00Sigma(cm, *f.model, x, 0.0);
      if (!(sigma > 0) || !std::isfinite(sigma)) continue;
      const color::Lab predicted = color::LabFromXYZ(
          color::MaterialXYZ(cm, color::IndexOnGrid(cm, *f.model, x), 0.0), cm.White());
      for (const Sample* s : f.held) {
        const color::Lab truth = color::LabFromXYZ(
            color::MaterialXYZ(cm, color::IndexOnGrid(cm, s->nk), 0.0), cm.White());
        ratio_sq += std::pow(color::DeltaE00(truth, predicted) / sigma, 2);
        ++ratios;
      }
    }
    if (ratios > 0 && ratio_sq > 0) {
      // The RMS ratio from f folds, widened by sqrt(1 + 1/f) as a prediction interval is
      // for the spread estimated from f values.
      error.calibration =
          std::clamp(std::sqrt(ratio_sq / ratios * (1.0 + 1.0 / ratios)), 1e-3, 1e3);
    }
  }
  model->set_prediction_error(std::move(error));
}

}  // namespace

std::unique_ptr<AlloyModel> BuildModel(const std::string& method, const Dataset& dataset,
                                       const FitSettings& settings) {
  if (method == kAutoMethod) return BuildAuto(dataset, settings);
  RequireMethod(method);
  for (const MethodBuilder& b : Builders()) {
    if (b.name != method) continue;
    std::unique_ptr<AlloyModel> model = b.build(dataset, settings);
    if (settings.calibrate) EstimatePredictionError(method, dataset, settings, model.get());
    return model;
  }
  throw Error("method '" + method + "' cannot be fitted to data");
}

constexpr double kAutoTolerance = 1.10;

std::unique_ptr<AlloyModel> BuildAuto(const Dataset& dataset, const FitSettings& settings) {
  // Simplest first: ties go to the earlier.
  const std::vector<std::string> order = {"eps-pchip", "eps-linear", "eps-spline",
                                          "paper",     "smooth",     "physical"};
  MethodSelection selection;
  std::vector<std::vector<double>> splits;
  for (size_t i = 1; i + 1 < dataset.samples.size(); ++i) {
    splits.push_back({dataset.samples[i].x_atomic});
  }
  std::string chosen = "eps-pchip";
  if (settings.colorimeter == nullptr) throw Error("auto: no colorimeter to score colours with");
  if (splits.empty()) {
    selection.metric = "none";
    selection.reason = "eps-pchip: " + std::to_string(dataset.samples.size()) +
                       " compositions leave none to hold out (every interpolation is then the "
                       "straight line between the samples)";
  } else {
    FitSettings inner = settings;
    inner.progress = {};
    inner.start = nullptr;
    inner.calibrate = false;
    validate::ValidationOptions options;
    options.build = [&inner](const std::string& method, const Dataset& training) {
      return BuildModel(method, training, inner);
    };
    options.angles_deg = {0.0};
    options.mode = "loo";
    options.sigma_draws = 0;
    double best = 1e300;
    const MethodScore* best_score = nullptr;
    for (const std::string& method : order) {
      Report(settings.progress, "auto: scoring " + method + " by leave-one-out over " +
                                    std::to_string(splits.size()) + " interior samples");
      options.methods = {method};
      MethodScore score;
      score.method = method;
      try {
        const validate::ValidationReport report =
            validate::ComputeValidation(dataset, splits, *settings.colorimeter, options, {});
        double sum = 0;
        for (const auto& h : report.holdouts) {
          const auto it = h.results.find(method);
          if (it == h.results.end() || !it->second.error.empty()) continue;
          const validate::MethodResult& r = it->second;
          const double v = !r.delta_e00.empty() ? r.delta_e00[0] : r.reflectance_rms;
          if (!std::isfinite(v)) continue;
          sum += v;
          score.max = score.folds == 0 ? v : std::max(score.max, v);
          ++score.folds;
          if (!r.delta_e00.empty()) selection.metric = "delta_e00 at normal incidence";
        }
        if (score.folds < static_cast<int>(splits.size())) {
          score.error = "failed on " + std::to_string(splits.size() - score.folds) + " of " +
                        std::to_string(splits.size()) + " folds";
        } else {
          score.mean = sum / score.folds;
        }
      } catch (const Error& e) {
        score.error = e.what();
      }
      selection.scores.push_back(score);
    }
    if (selection.metric.empty()) selection.metric = "reflectance_rms at normal incidence";
    // The simplest method within kAutoTolerance of the lowest score: leave-one-out with few
    // samples flatters the flexible methods.
    for (const MethodScore& s : selection.scores) {
      if (s.error.empty()) best = std::min(best, s.mean);
    }
    for (const MethodScore& s : selection.scores) {
      if (s.error.empty() && s.mean <= best * kAutoTolerance) {
        best_score = &s;
        break;
      }
    }
    if (best_score == nullptr) throw Error(dataset.manifest_path + ": auto: no method could be scored");
    chosen = best_score->method;
    char reason[160];
    std::snprintf(reason, sizeof reason, "%s: lowest leave-one-out mean %s, %.4g over %d folds",
                  chosen.c_str(), selection.metric.c_str(), best_score->mean, best_score->folds);
    selection.reason = reason;
  }
  Report(settings.progress, "auto: " + selection.reason);
  std::unique_ptr<AlloyModel> model = BuildModel(chosen, dataset, settings);
  FitSummary summary = model->fit_summary();
  summary.selection = selection;
  model->set_fit_summary(std::move(summary));
  return model;
}

}  // namespace alloycolor::fit
