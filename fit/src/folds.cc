#include "folds.h"

#include <algorithm>
#include <cmath>

#include "alloycolor/color/sample_error.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/parallel.h"

namespace alloycolor::fit {

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

namespace {

// The samples a fold that holds out the compositions `held` is fitted to: all the others
// (`rest`, increasing), or for a method of MethodTraits::fold_reach >= 0 those from
// `reach` + 1 compositions below each held-out one to as many above it, where they span
// the wavelengths all the others share (the model's range, CommonRange): its model there
// is the one all the others give.
Dataset FoldTraining(const Dataset& dataset, const std::vector<double>& held,
                     const std::vector<double>& rest, int reach) {
  if (reach < 0) return WithoutSamples(dataset, held);
  std::vector<std::pair<double, double>> spans;  // of compositions kept
  for (double x : held) {
    const size_t above = std::upper_bound(rest.begin(), rest.end(), x) - rest.begin();
    if (above == 0 || above == rest.size()) return WithoutSamples(dataset, held);
    const size_t r = static_cast<size_t>(reach);
    spans.push_back(
        {rest[above - 1 - std::min(r, above - 1)], rest[std::min(above + r, rest.size() - 1)]});
  }
  const auto is_held = [&held](const Sample& s) { return AmongCompositions(s.x_atomic, held); };
  Dataset window = KeepSamples(dataset, [&](const Sample& s) {
    return !is_held(s) && std::any_of(spans.begin(), spans.end(), [&s](const auto& span) {
      return s.x_atomic >= span.first && s.x_atomic <= span.second;
    });
  });
  double lo = -1e300, hi = 1e300;
  for (const Sample& s : dataset.samples) {
    if (is_held(s)) continue;
    lo = std::max(lo, s.nk.lambda_min_nm());
    hi = std::min(hi, s.nk.lambda_max_nm());
  }
  const WavelengthRange own = CommonRange(window);
  if (own.lo_nm != lo || own.hi_nm != hi) return WithoutSamples(dataset, held);
  return window;
}

}  // namespace

std::vector<Fold> FitFolds(const MethodInfo& method, const Dataset& dataset,
                           const FitSettings& settings, const AlloyModel& model) {
  std::vector<std::vector<double>> held;
  for (double x : ErrorFolds(dataset)) held.push_back({x});
  return FitFolds(method, dataset, settings, model, held);
}

std::vector<Fold> FitFolds(const MethodInfo& method, const Dataset& dataset,
                           const FitSettings& settings, const AlloyModel& model,
                           const std::vector<std::vector<double>>& held) {
  FitSettings inner = settings;
  inner.calibrate = false;
  inner.fold = true;
  inner.progress = {};
  inner.details = {};
  inner.parent = &model;
  inner.start = method.traits.warm_start_folds ? &model : nullptr;
  std::vector<Fold> folds(held.size());
  const std::vector<double> xs = DistinctCompositions(dataset);
  ParallelTasks(
      held.size(),
      [&](size_t k) {
        Fold& f = folds[k];
        f.x = held[k].front();
        std::vector<double> rest;
        for (double x : xs) {  // as WithoutSamples leaves them
          if (!AmongCompositions(x, held[k])) rest.push_back(x);
        }
        const Dataset training = FoldTraining(dataset, held[k], rest, method.traits.fold_reach);
        try {
          f.model = BuildWithFolds(method, training, inner, nullptr);
        } catch (const Error& e) {
          f.error = e.what();
          return;
        }
        for (const Sample& s : dataset.samples) {
          if (std::find(held[k].begin(), held[k].end(), s.x_atomic) != held[k].end()) {
            f.held.push_back(&s);
          }
        }
        f.compositions = std::move(rest);
      },
      settings.threads);
  return folds;
}

void ScoreFolds(const std::string& method, const std::vector<Fold>& folds,
                const color::Colorimeter& colorimeter, Scored* r) {
  MethodScore& score = r->score;
  score = MethodScore{};
  score.method = method;
  r->metric = "reflectance_rms at normal incidence";  // data without colour
  double sum = 0;
  int failed = 0;
  for (const Fold& f : folds) {
    if (!f.model) {
      ++failed;
      continue;
    }
    bool fold_failed = false;
    for (const Sample* s : f.held) {
      double v = 0;
      try {
        const color::SampleError e = color::ErrorAgainstSample(colorimeter, *f.model, *s);
        if (e.has_colour()) r->metric = "delta_e00 at normal incidence";
        v = e.score();
      } catch (const Error&) {
        fold_failed = true;
        continue;
      }
      if (!std::isfinite(v)) {
        fold_failed = true;
        continue;
      }
      sum += v;
      r->values.push_back(v);
      r->held_x.push_back(f.x);
      score.max = score.folds == 0 ? v : std::max(score.max, v);
      ++score.folds;
    }
    failed += fold_failed;
  }
  if (failed > 0) {
    score.error =
        "failed on " + std::to_string(failed) + " of " + std::to_string(folds.size()) + " folds";
  } else {
    score.mean = score.folds > 0 ? sum / score.folds : 0;
  }
}

std::unique_ptr<AlloyModel> Build(const MethodInfo& method, const Dataset& dataset,
                                  const FitSettings& settings) {
  if (method.build == nullptr) {
    throw Error("method '" + method.name + "' cannot be fitted to data");
  }
  CheckCancel(settings.cancel);  // every fit of the job starts here
  return method.build(dataset, settings);
}

void AddFolds(const MethodInfo& method, const Dataset& dataset, const FitSettings& settings,
              AlloyModel* model, std::vector<Fold>* folds) {
  *folds = FitFolds(method, dataset, settings, *model);
  if (settings.calibrate) EstimatePredictionError(method, *folds, dataset, settings, model);
}

std::unique_ptr<AlloyModel> BuildWithFolds(const MethodInfo& method, const Dataset& dataset,
                                           const FitSettings& settings, std::vector<Fold>* folds) {
  std::unique_ptr<AlloyModel> model = Build(method, dataset, settings);
  if (!settings.fold) RecordInSampleError(dataset, settings, model.get());
  std::vector<Fold> own;
  if (folds != nullptr || settings.calibrate) {
    AddFolds(method, dataset, settings, model.get(), folds != nullptr ? folds : &own);
  }
  return model;
}

std::string FitMemoKey(const MethodInfo& method, const Dataset& dataset,
                       const FitSettings& settings) {
  std::string key = method.name + '\n' + settings.options.Key();
  const auto add = [&key](const void* bytes, size_t size) {
    key.append(static_cast<const char*>(bytes), size);
  };
  const int flags[] = {settings.calibrate, settings.max_iterations};
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
  return key;
}

namespace {

Scored BuildAndScore(const MethodInfo& method, const Dataset& dataset,
                     const FitSettings& settings) {
  Scored r;
  r.score.method = method.name;
  std::vector<Fold> folds;
  try {
    r.model = Build(method, dataset, settings);
    RecordInSampleError(dataset, settings, r.model.get());
    AddFolds(method, dataset, settings, r.model.get(), &folds);
  } catch (const Error& e) {
    r.model.reset();
    r.score.error = e.what();
    return r;
  }
  ScoreFolds(method.name, folds, *settings.colorimeter, &r);
  return r;
}

}  // namespace

Scored ThroughMemo(const MethodInfo& method, const FitSettings& settings, const std::string& key,
                   std::map<std::string, FitMemo::Remembered> FitMemo::*table,
                   const std::function<Scored()>& build,
                   const std::function<bool(const Scored&)>& keep) {
  FitMemo& memo = *settings.memo;
  {
    const std::lock_guard<std::mutex> lock(memo.mutex);
    const auto it = (memo.*table).find(key);
    if (it != (memo.*table).end()) {
      const FitMemo::Remembered& m = it->second;
      Scored r;
      if (!m.model.is_null())
        r.model = method.read(m.model, "the remembered " + method.name + " fit");
      r.score = m.score;
      r.values = m.values;
      r.held_x = m.held_x;
      r.metric = m.metric;
      return r;
    }
  }
  Scored r = build();
  if (!keep(r)) return r;
  FitMemo::Remembered m{r.model ? r.model->ToJson() : nlohmann::json(), r.score, r.values, r.held_x,
                        r.metric};
  const std::lock_guard<std::mutex> lock(memo.mutex);
  (memo.*table).emplace(key, std::move(m));
  return r;
}

Scored RememberedBuild(const MethodInfo& method, const Dataset& dataset,
                       const FitSettings& settings) {
  if (!settings.memo || settings.start != nullptr || settings.fold) {
    return BuildAndScore(method, dataset, settings);
  }
  // A model that keeps its samples (no fitted coefficients: paper, eps-*) is built again
  // rather than copied: its copy through the model file, every sample's spectrum, costs
  // what building it does.
  return ThroughMemo(
      method, settings, FitMemoKey(method, dataset, settings), &FitMemo::builds,
      [&] { return BuildAndScore(method, dataset, settings); },
      [](const Scored& r) { return !r.model || !r.model->FittedCoefficients().empty(); });
}

}  // namespace alloycolor::fit
