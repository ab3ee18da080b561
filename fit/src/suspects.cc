#include "alloycolor/fit/suspects.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <string>

#include "alloycolor/color/material_color.h"
#include "alloycolor/color/sample_error.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/core/text.h"
#include "alloycolor/model/registry.h"
#include "folds.h"

namespace alloycolor::fit {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The visible range the metallic check prefers (the colour metrics' 380-780 nm).
constexpr double kVisibleLoNm = 380, kVisibleHiNm = 780;

const char* const kAdvice = "measure it again, or set it aside (\"exclude\": \"why\")";

std::string Percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f %%", 100 * fraction);
  return text;
}

std::string Short(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

std::string X(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", x);
  return text;
}

SampleNote NoteFor(const Sample& s, const std::string& check) {
  SampleNote n;
  n.x_atomic = s.x_atomic;
  n.x_given = s.x_given;
  n.file = s.file;
  n.check = check;
  return n;
}

// The samples at the distinct compositions of `xs` with these indices.
std::vector<const Sample*> SamplesOf(const Dataset& dataset, const std::vector<double>& xs,
                                     const std::vector<size_t>& indices) {
  std::vector<const Sample*> found;
  for (size_t i : indices) {
    for (const Sample& s : dataset.samples) {
      if (s.x_atomic == xs[i]) found.push_back(&s);
    }
  }
  return found;
}

// Samples not metallic where their neighbours are (suspects.h).
std::vector<SampleNote> MetallicSuspects(const Dataset& dataset) {
  const std::vector<double> xs = DistinctCompositions(dataset);
  std::vector<SampleNote> notes;
  if (xs.size() < 3) return notes;
  for (size_t i = 0; i < xs.size(); ++i) {
    const std::vector<size_t> next = i == 0               ? std::vector<size_t>{1, 2}
                                     : i + 1 == xs.size() ? std::vector<size_t>{i - 1, i - 2}
                                                          : std::vector<size_t>{i - 1, i + 1};
    const std::vector<const Sample*> neighbours = SamplesOf(dataset, xs, next);
    for (const Sample* s : SamplesOf(dataset, xs, {i})) {
      // The visible where every one covers it, else their common range.
      double lo = s->nk.lambda_min_nm(), hi = s->nk.lambda_max_nm();
      for (const Sample* t : neighbours) {
        lo = std::max(lo, t->nk.lambda_min_nm());
        hi = std::min(hi, t->nk.lambda_max_nm());
      }
      if (!(lo < hi)) continue;
      if (lo <= kVisibleLoNm && hi >= kVisibleHiNm) lo = kVisibleLoNm, hi = kVisibleHiNm;
      const double own = MetallicFraction(s->nk, lo, hi);
      if (!(own < 0.5)) continue;
      bool all_metallic = true;
      std::string theirs, where;
      for (size_t j : next) {
        double sum = 0;
        int count = 0;
        for (const Sample* t : SamplesOf(dataset, xs, {j})) {
          const double f = MetallicFraction(t->nk, lo, hi);
          if (std::isfinite(f)) sum += f, ++count;
        }
        const double f = count ? sum / count : kNaN;
        all_metallic = all_metallic && f >= 0.5;
        theirs += (theirs.empty() ? "" : ", ") + Percent(f);
        where += (where.empty() ? "" : ", ") + X(xs[j]);
      }
      if (!all_metallic) continue;
      SampleNote n = NoteFor(*s, "not metallic");
      n.figure_name = "fraction of the compared wavelengths where eps1 < 0 (n < k)";
      n.figure = own;
      n.reason = s->file + " (x = " + X(s->x_atomic) +
                 ") is not metallic where its neighbours are (n < k at " + Percent(own) + " of " +
                 FormatNumber(lo) + "-" + FormatNumber(hi) + " nm; " + theirs + " at x = " + where +
                 ")";
      notes.push_back(std::move(n));
    }
  }
  return notes;
}

// The data set without these samples (by file: a replicate stays).
Dataset Without(const Dataset& dataset, const std::vector<SampleNote>& notes) {
  Dataset rest = dataset;
  rest.samples.clear();
  for (const Sample& s : dataset.samples) {
    const bool out = std::any_of(notes.begin(), notes.end(), [&s](const SampleNote& n) {
      return n.file == s.file && n.x_atomic == s.x_atomic;
    });
    if (!out) rest.samples.push_back(s);
  }
  return rest;
}

// The one-line reason of a held-out suspect.
std::string HeldOutReason(const Sample& s, double error, double ratio, double p) {
  char tail[64];
  std::snprintf(tail, sizeof tail, "%.2g %%", 100 * p);
  return s.file + " (x = " + X(s.x_atomic) +
         ") is out of line with the series: held out, predicted off by ΔE00 " + Short(error) +
         ", " + Short(ratio) + " times the one-sigma the other folds give (a " + tail +
         " chance for a sample as good as the rest: mislabelled, oxidised, rough?); " + kAdvice;
}

const Sample* SampleByFile(const Dataset& dataset, double x, const std::string& file) {
  for (const Sample& s : dataset.samples) {
    if (s.x_atomic == x && s.file == file) return &s;
  }
  return nullptr;
}

// The held-out samples of the model's folds, each against the calibration of the others
// but its neighbours' (whose folds were predicted through it: a bad sample bends them too,
// and would mask itself).
std::vector<SampleNote> InteriorSuspects(const Dataset& dataset, const AlloyModel& model) {
  std::vector<SampleNote> notes;
  const auto& held = model.prediction_error().held_out;
  const std::vector<double> xs = DistinctCompositions(dataset);
  for (const PredictionError::HeldOut& h : held) {
    if (!(h.delta_e00 > kInSampleMissDe00) || !(h.sigma > 0)) continue;
    const size_t i = std::lower_bound(xs.begin(), xs.end(), h.x_atomic) - xs.begin();
    if (i == 0 || i + 1 >= xs.size()) continue;  // not an interior composition of this set
    double errors_sq = 0, sigmas_sq = 0;
    std::set<double> folds;
    for (const PredictionError::HeldOut& o : held) {
      if (o.x_atomic >= xs[i - 1] && o.x_atomic <= xs[i + 1]) continue;
      if (!std::isfinite(o.delta_e00) || !(o.sigma > 0)) continue;
      errors_sq += o.delta_e00 * o.delta_e00;
      sigmas_sq += o.sigma * o.sigma;
      folds.insert(o.x_atomic);
    }
    if (folds.empty()) continue;
    const double scale = std::sqrt(errors_sq / sigmas_sq);
    const double ratio = h.delta_e00 / (scale * h.sigma);  // infinite where the others are exact
    const double p = FTailTwo(ratio * ratio, static_cast<double>(folds.size()));
    const Sample* s = SampleByFile(dataset, h.x_atomic, h.file);
    if (s == nullptr || !(p < kSuspectTail)) continue;
    SampleNote n = NoteFor(*s, "held out");
    n.figure_name = "held-out dE00 over the one-sigma the other folds give there";
    n.figure = ratio;
    n.delta_e00 = h.delta_e00;
    n.sigma_de00 = scale * h.sigma;
    n.reason = HeldOutReason(*s, h.delta_e00, ratio, p);
    notes.push_back(std::move(n));
  }
  return notes;
}

// The two ends, each held out by fitting the method without it; its one-sigma from the
// model's error bars (calibrated on the interior folds, so without the end) moved onto the
// fold's compositions.
std::vector<SampleNote> EndSuspects(const Dataset& dataset, const AlloyModel& model,
                                    const FitSettings& settings) {
  std::vector<SampleNote> notes;
  const std::vector<double> xs = DistinctCompositions(dataset);
  const PredictionError& error = model.prediction_error();
  if (xs.size() < 4 || error.folds < 1) return notes;  // the rest must keep an interior fold
  const MethodInfo& method = RequireMethod(model.method());
  FitSettings at = settings;
  if (method.traits.chooses_degree) at.options.Set("degree", model.fit_summary().degree);
  const std::vector<Fold> folds = FitFolds(method, dataset, at, model, {{xs.front()}, {xs.back()}});
  for (const Fold& f : folds) {
    if (!f.model) continue;
    PredictionError moved = error;
    moved.compositions = f.compositions;
    moved.misfit.clear();  // the model's miss at its own compositions, not the fold's
    if (moved.scatter.empty()) moved.misfit_lambda_nm.clear();
    moved.held_out.clear();
    try {
      f.model->set_prediction_error(moved);
      const double sigma = color::DeltaE00Sigma(*settings.colorimeter, *f.model, f.x, 0.0);
      for (const Sample* s : f.held) {
        const color::SampleError e = color::ErrorAgainstSample(*settings.colorimeter, *f.model, *s);
        if (!(e.delta_e00 > kInSampleMissDe00) || !(sigma > 0)) continue;
        const double ratio = e.delta_e00 / sigma;
        const double p = FTailTwo(ratio * ratio, error.folds);
        if (!(p < kSuspectTail)) continue;
        SampleNote n = NoteFor(*s, "held out");
        n.figure_name = "held-out dE00 over the one-sigma there";
        n.figure = ratio;
        n.delta_e00 = e.delta_e00;
        n.sigma_de00 = sigma;
        n.reflectance_rms = e.reflectance_rms;
        n.reason = HeldOutReason(*s, e.delta_e00, ratio, p);
        notes.push_back(std::move(n));
      }
    } catch (const Error&) {
      // An end the fold cannot predict (its extrapolation unusable) is left unjudged.
    }
  }
  return notes;
}

// "1.63 (2 held out)": a model's mean leave-one-out error over its folds' held-out samples;
// empty where it has none.
std::string HeldOutMean(const AlloyModel& model) {
  double sum = 0;
  int count = 0;
  for (const auto& h : model.prediction_error().held_out) {
    if (std::isfinite(h.delta_e00)) sum += h.delta_e00, ++count;
  }
  if (count == 0) return "";
  return Short(sum / count);
}

}  // namespace

double MetallicFraction(const NkSpectrum& nk, double lo_nm, double hi_nm) {
  int metallic = 0, count = 0;
  for (size_t j = 0; j < nk.lambda_nm.size(); ++j) {
    if (nk.lambda_nm[j] < lo_nm || nk.lambda_nm[j] > hi_nm) continue;
    ++count;
    if (nk.n[j] < nk.k[j]) ++metallic;
  }
  return count ? static_cast<double>(metallic) / count : kNaN;
}

double FTailTwo(double f, double m) {
  if (!(f >= 0)) return 1;
  if (std::isinf(f)) return 0;
  return std::pow(1 + f / m, -m);
}

std::vector<SampleNote> CheckSamples(const Dataset& dataset, const AlloyModel& model,
                                     const FitSettings& settings) {
  std::vector<SampleNote> notes = MetallicSuspects(dataset);
  const bool colour = settings.colorimeter != nullptr;
  // One bad sample bends its neighbours' folds: the rest are judged without it.
  const AlloyModel* judged = &model;
  Dataset rest = dataset;
  std::unique_ptr<AlloyModel> without;
  if (!notes.empty()) {
    rest = Without(dataset, notes);
    if (DistinctCompositions(rest).size() >= 3) {
      Report(settings.progress, "checking the samples: the rest judged by " + model.method() +
                                    " fitted without " + std::to_string(notes.size()) +
                                    " suspect sample(s) (the model keeps them)");
      FitSettings quiet = settings;
      quiet.progress = {};
      quiet.details = {};
      quiet.start = nullptr;
      try {
        without = BuildModel(model.method(), rest, quiet);
        judged = without.get();
      } catch (const Error&) {
        judged = nullptr;  // the rest cannot be fitted alone: not judged further
      }
    } else {
      judged = nullptr;
    }
    const std::string mean_with = HeldOutMean(model);
    const std::string mean_without = without ? HeldOutMean(*without) : "";
    for (SampleNote& n : notes) {
      const Sample* s = SampleByFile(dataset, n.x_atomic, n.file);
      if (without && colour && s != nullptr) {
        try {
          n.delta_e00 = color::ErrorAgainstSample(*settings.colorimeter, *without, *s).delta_e00;
          n.sigma_de00 = color::DeltaE00Sigma(*settings.colorimeter, *without, s->x_atomic, 0.0);
          if (!(n.sigma_de00 > 0)) n.sigma_de00 = kNaN;
        } catch (const Error&) {
          n.delta_e00 = n.sigma_de00 = kNaN;
        }
      }
      if (!mean_with.empty() && !mean_without.empty()) {
        n.reason += "; the rest's leave-one-out ΔE00 " + mean_without + " without it, " +
                    mean_with + " with it";
      }
      n.reason += std::string("; ") + kAdvice;
    }
  }
  if (colour && judged != nullptr && judged->prediction_error().present()) {
    const std::vector<SampleNote> interior = InteriorSuspects(rest, *judged);
    const std::vector<SampleNote> ends = EndSuspects(rest, *judged, settings);
    notes.insert(notes.end(), interior.begin(), interior.end());
    notes.insert(notes.end(), ends.begin(), ends.end());
  }
  std::stable_sort(notes.begin(), notes.end(), [](const SampleNote& a, const SampleNote& b) {
    return a.x_atomic < b.x_atomic;
  });
  return notes;
}

}  // namespace alloycolor::fit
