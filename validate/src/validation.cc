#include "alloycolor/validate/validation.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "alloycolor/color/match.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/color/sample_error.h"
#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/spectrum.h"
#include "alloycolor/core/text.h"
#include "alloycolor/core/units.h"
#include "alloycolor/model/optics.h"
#include "report_metrics.h"

namespace alloycolor::validate {
namespace {

// ---------------------------------------------------------------------------------------
// Computation.

struct Colour {
  std::vector<color::Lab> lab;
  std::vector<std::array<std::uint8_t, 3>> srgb8;
};

Colour ColourAtAngles(const color::Colorimeter& colorimeter,
                      const std::vector<std::complex<double>>& index,
                      const std::vector<double>& angles_deg) {
  Colour c;
  for (double angle : angles_deg) {
    const color::ColorResult r =
        color::ColorFromXYZ(colorimeter, color::MaterialXYZ(colorimeter, index, angle));
    c.lab.push_back(r.lab);
    c.srgb8.push_back(r.srgb8);
  }
  return c;
}

struct Spectra {
  std::vector<double> n, k, reflectance;
};

Spectra SpectraOf(const std::vector<std::complex<double>>& index) {
  Spectra s;
  s.reflectance = color::ReflectanceSpectrum(index, 0.0);
  for (const auto& v : index) {
    s.n.push_back(v.real());
    s.k.push_back(v.imag());
  }
  return s;
}

std::string Join(const std::vector<std::string>& parts) {
  std::string joined;
  for (const std::string& p : parts) joined += (joined.empty() ? "" : ", ") + p;
  return joined;
}

// The data set without the samples of `held` (indices).
Dataset WithoutSampleIndices(const Dataset& dataset, const SampleSplit& held) {
  Dataset training = dataset;
  training.samples.clear();
  for (size_t i = 0; i < dataset.samples.size(); ++i) {
    if (std::find(held.begin(), held.end(), i) == held.end()) {
      training.samples.push_back(dataset.samples[i]);
    }
  }
  return training;
}

void RequireThreeCompositions(const Dataset& dataset) {
  const size_t compositions = DistinctCompositions(dataset).size();
  if (compositions < 3) {
    throw Error(dataset.manifest_path + " has samples at " + std::to_string(compositions) +
                (compositions == 1 ? " composition" : " compositions") +
                "; validation needs at least one interior composition besides the two ends");
  }
}

// Wavelengths for the tau, m* curves: 450, 550, 650 nm when the training data cover them,
// otherwise a quarter, a half and three quarters of the common range (2 digits).
std::vector<double> DrudeWavelengths(double lo, double hi) {
  if (lo <= 450 && hi >= 650) return {450, 550, 650};
  std::vector<double> out;
  for (double f : {0.25, 0.5, 0.75}) {
    const double l = lo + f * (hi - lo);
    const double scale = std::pow(10.0, std::floor(std::log10(l)) - 1);
    out.push_back(std::clamp(std::round(l / scale) * scale, lo, hi));
  }
  return out;
}

// tau_fs, m*/m_e from Drude parameters at composition x.
void TauMass(const DrudePoint& p, double x, const AlloySystem& system, double* tau_fs,
             double* mass) {
  *tau_fs = TauFsFromGammaEv(p.gamma_ev);
  *mass = EffectiveMassRatio(FreeElectronDensityM3(x, system), p.wp2_ev2);
}

// tau_fs, m*/m_e of a measured spectrum at lambda by eq. 11, 12; NaN where undefined.
void MeasuredTauMass(const NkSpectrum& nk, double x, double lambda_nm, const AlloySystem& system,
                     double* tau_fs, double* mass) {
  *tau_fs = *mass = kNaN;
  if (lambda_nm < nk.lambda_min_nm() || lambda_nm > nk.lambda_max_nm()) return;
  const std::complex<double> i = NkAt(nk, lambda_nm);
  const std::complex<double> eps = i * i;
  if (!DrudeInvertible(eps.real(), eps.imag())) return;
  TauMass(InvertDrude(OmegaEvFromLambdaNm(lambda_nm), eps.real(), eps.imag()), x, system, tau_fs,
          mass);
}

void FillDrudeCurves(const AlloyModel& model, const std::string& method, const AlloySystem& system,
                     std::vector<DrudeCurve>* curves) {
  for (DrudeCurve& curve : *curves) {
    std::vector<double>& taus = curve.tau_fs[method];
    std::vector<double>& masses = curve.mass[method];
    for (double x : curve.x) {
      double tau = kNaN, mass = kNaN;
      DrudePoint p;
      if (model.DrudeAt(x, curve.lambda_nm, &p)) TauMass(p, x, system, &tau, &mass);
      taus.push_back(tau);
      masses.push_back(mass);
    }
  }
}

// The training set of a split: the data set without the held-out samples and without the
// samples set aside (every sample from index `in_use` on).
Dataset TrainingOf(const Dataset& dataset, SampleSplit held, size_t in_use) {
  for (size_t i = in_use; i < dataset.samples.size(); ++i) held.push_back(i);
  return WithoutSampleIndices(dataset, held);
}

SplitResult PrepareSplit(const Dataset& dataset, const SampleSplit& held, size_t in_use) {
  SplitResult split;
  std::vector<char> is_held(dataset.samples.size(), 0);
  for (size_t i : held) is_held.at(i) = 1;
  for (size_t i = 0; i < dataset.samples.size(); ++i) {
    if (i >= in_use && !is_held[i]) continue;  // set aside: in no split's training
    const Sample& s = dataset.samples[i];
    (is_held[i] ? split.holdout_x : split.train_x).push_back(s.x_atomic);
    (is_held[i] ? split.holdout_files : split.train_files).push_back(s.file);
  }
  const Dataset training = TrainingOf(dataset, held, in_use);
  WavelengthRange range;
  try {
    range = CommonRange(training);
  } catch (const Error&) {
    return split;  // the methods say why they cannot be built
  }
  const double lo = range.lo_nm, hi = range.hi_nm;
  const double x_lo = dataset.samples.front().x_atomic;
  const double x_hi = dataset.samples[in_use - 1].x_atomic;
  for (double lambda : DrudeWavelengths(lo, hi)) {
    DrudeCurve curve;
    curve.lambda_nm = lambda;
    for (int i = 0; i <= 100; ++i) curve.x.push_back(x_lo + (x_hi - x_lo) * i / 100.0);
    for (size_t i = 0; i < dataset.samples.size(); ++i) {
      if (i >= in_use && !is_held[i]) continue;
      const Sample& s = dataset.samples[i];
      double tau, mass;
      MeasuredTauMass(s.nk, s.x_atomic, lambda, dataset.system, &tau, &mass);
      (is_held[i] ? curve.holdout_x : curve.train_x).push_back(s.x_atomic);
      (is_held[i] ? curve.holdout_tau_fs : curve.train_tau_fs).push_back(tau);
      (is_held[i] ? curve.holdout_mass : curve.train_mass).push_back(mass);
    }
    split.drude.push_back(std::move(curve));
  }
  return split;
}

// Predicts one held-out sample with one model; fills the measured side of `holdout` the
// first time.
MethodResult Evaluate(const AlloyModel& model, const Sample& sample,
                      const color::Colorimeter& colorimeter, const ValidationOptions& options,
                      HoldoutResult* holdout) {
  MethodResult r;
  std::string description;
  r.lambda_nm = color::MetricGrid(model, sample.nk, &description);
  const Spectra predicted = SpectraOf(model.Index(sample.x_atomic, r.lambda_nm));
  const Spectra measured = SpectraOf(NkOn(sample.nk, r.lambda_nm));
  if (holdout->lambda_nm.empty()) {
    holdout->lambda_nm = r.lambda_nm;
    holdout->n = measured.n;
    holdout->k = measured.k;
    holdout->reflectance = measured.reflectance;
    holdout->metric_range = description;
  }
  double sum2 = 0;
  for (size_t i = 0; i < r.lambda_nm.size(); ++i) {
    const double dr = std::abs(predicted.reflectance[i] - measured.reflectance[i]);
    sum2 += dr * dr;
    r.reflectance_max = std::max(r.reflectance_max, dr);
    r.n_max_abs = std::max(r.n_max_abs, std::abs(predicted.n[i] - measured.n[i]));
    r.k_max_abs = std::max(r.k_max_abs, std::abs(predicted.k[i] - measured.k[i]));
  }
  r.reflectance_rms = std::sqrt(sum2 / r.lambda_nm.size());
  r.n = predicted.n;
  r.k = predicted.k;
  r.reflectance = predicted.reflectance;
  if (!holdout->lab.empty()) {
    std::vector<std::complex<double>> index;
    try {
      // On the colorimeter's grid as the measured colour is (held at the model's range
      // edges only where it stops short): `alloycolor color --model` gives the same.
      index = color::IndexOnGrid(colorimeter, model, sample.x_atomic);
    } catch (const Error& e) {
      r.error = std::string("no colour: ") + e.what();
      return r;
    }
    const Colour c = ColourAtAngles(colorimeter, index, options.angles_deg);
    r.lab = c.lab;
    r.srgb8 = c.srgb8;
    for (size_t a = 0; a < options.angles_deg.size(); ++a) {
      r.delta_e00.push_back(color::DeltaE00(holdout->lab[a], r.lab[a]));
      if (model.HasUncertainty()) {
        r.delta_e00_sigma.push_back(color::DeltaE00Sigma(
            colorimeter, model, sample.x_atomic, options.angles_deg[a], options.sigma_draws));
      }
    }
    // Back from colour to composition: the measured colour at normal incidence matched.
    const color::Lab measured_lab = color::LabFromXYZ(
        color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, sample.nk), 0.0),
        colorimeter.White());
    try {
      const color::Match best = color::MatchColour(colorimeter, model, measured_lab).front();
      r.x_recovered = best.x_atomic;
      r.x_recovered_sigma = best.x_sigma;
    } catch (const Error&) {
      // no composition recovered: the model gives no finite colour over its range
    }
  }
  return r;
}

}  // namespace

std::vector<SampleSplit> LeaveOneOutSplits(const Dataset& dataset) {
  RequireThreeCompositions(dataset);
  const std::vector<double> xs = DistinctCompositions(dataset);
  std::vector<SampleSplit> splits;
  for (size_t c = 1; c + 1 < xs.size(); ++c)
    splits.push_back(SplitAtCompositions(dataset, {xs[c]}));
  return splits;
}

SampleSplit SplitAtCompositions(const Dataset& dataset, const std::vector<double>& x_atomic) {
  SampleSplit split;
  for (size_t i = 0; i < dataset.samples.size(); ++i) {
    if (AmongCompositions(dataset.samples[i].x_atomic, x_atomic)) split.push_back(i);
  }
  return split;
}

SampleSplit HoldoutSplit(const Dataset& dataset, const std::vector<std::string>& names) {
  RequireThreeCompositions(dataset);
  const auto list = [&dataset] {
    std::string s;
    for (const Sample& sample : dataset.samples) {
      s += (s.empty() ? "" : ", ") + Num(sample.x_given);
      // Replicates by their files, which tell them apart.
      if (SamplesAtComposition(dataset, sample.x_atomic).size() > 1) s += " (" + sample.file + ")";
    }
    return s;
  };
  SampleSplit split;
  const auto add = [&split](size_t i) {
    if (std::find(split.begin(), split.end(), i) == split.end()) split.push_back(i);
  };
  for (const std::string& name : names) {
    if (name.empty()) throw Error("empty sample or composition");
    if (const Sample* s = FindSampleByFile(dataset, name)) {
      add(static_cast<size_t>(s - dataset.samples.data()));
      continue;
    }
    const Sample* match = nullptr;
    try {
      match = FindSample(dataset, ParseComposition(name, dataset.system));
    } catch (const Error&) {
      // Neither a file of the data set nor a composition.
    }
    if (match == nullptr) {
      throw Error("no sample file or composition " + Quote(name, 60) + " in " +
                  dataset.manifest_path + " (samples at " + list() + ")");
    }
    for (size_t i : SplitAtCompositions(dataset, {match->x_atomic})) add(i);
  }
  if (split.empty()) throw Error("no sample or composition given");
  std::sort(split.begin(), split.end());
  const std::vector<double> xs = DistinctCompositions(dataset);
  for (double end : {xs.front(), xs.back()}) {
    const SampleSplit at_end = SplitAtCompositions(dataset, {end});
    if (std::all_of(at_end.begin(), at_end.end(), [&split](size_t i) {
          return std::find(split.begin(), split.end(), i) != split.end();
        })) {
      const Sample& s = dataset.samples[at_end.front()];
      throw Error(Num(s.x_given) + " is an end sample (" + s.file +
                  "); every method would have to extrapolate to predict it, so it is kept "
                  "for training: hold out interior samples (or one replicate of an end) only");
    }
  }
  return split;
}

namespace {

// The report's account of what was validated: the data, the methods, the colour settings.
ValidationReport DescribeValidation(const Dataset& dataset, const color::Colorimeter& colorimeter,
                                    const ValidationOptions& options) {
  ValidationReport report;
  report.data = dataset.manifest_path;
  report.name = dataset.name;
  report.system = dataset.system.Name();
  report.composition = dataset.composition;
  report.element_a = dataset.system.a.symbol;
  report.element_b = dataset.system.b.symbol;
  report.mode = options.mode;
  report.methods = options.methods;
  report.angles_deg = options.angles_deg;
  report.illuminant = colorimeter.illuminant();
  report.observer_deg = colorimeter.observer_deg();
  report.colour_nm = {colorimeter.lambda_nm().front(), colorimeter.lambda_nm().back()};
  report.dataset_warnings = dataset.warnings;
  return report;
}

// Held-out sample i of split s, with its measured colour (or why it has none).
HoldoutResult MeasuredHoldout(const Dataset& dataset, size_t i, size_t s,
                              const color::Colorimeter& colorimeter,
                              const ValidationOptions& options) {
  const Sample& sample = dataset.samples[i];
  HoldoutResult h;
  h.x_atomic = sample.x_atomic;
  h.x_given = sample.x_given;
  h.file = sample.file;
  h.path = sample.path;
  h.sample = static_cast<int>(i);
  h.replicate = SamplesAtComposition(dataset, sample.x_atomic).size() > 1;
  h.excluded = sample.excluded;
  h.split = static_cast<int>(s);
  try {
    const Colour c =
        ColourAtAngles(colorimeter, color::IndexOnGrid(colorimeter, sample.nk), options.angles_deg);
    h.lab = c.lab;
    h.srgb8 = c.srgb8;
  } catch (const Error& e) {
    h.colour_note = e.what();
  }
  return h;
}

// Adds every split and its held-out samples, with their measured colour, to the report.
void AddSplits(const Dataset& dataset, const std::vector<SampleSplit>& splits, size_t in_use,
               const color::Colorimeter& colorimeter, const ValidationOptions& options,
               ValidationReport* report) {
  for (size_t s = 0; s < splits.size(); ++s) {
    for (size_t i : splits[s]) {
      if (i >= dataset.samples.size()) {
        throw Error("split " + std::to_string(s) + ": no sample " + std::to_string(i) + " in " +
                    dataset.manifest_path);
      }
    }
    if (splits[s].empty()) throw Error("split " + std::to_string(s) + " holds out no sample");
    report->splits.push_back(PrepareSplit(dataset, splits[s], in_use));
    SampleSplit held = splits[s];
    std::sort(held.begin(), held.end());
    held.erase(std::unique(held.begin(), held.end()), held.end());
    for (size_t i : held) {
      report->holdouts.push_back(MeasuredHoldout(dataset, i, s, colorimeter, options));
    }
  }
}

}  // namespace

ValidationReport ComputeValidation(const Dataset& dataset, const std::vector<SampleSplit>& splits,
                                   const color::Colorimeter& colorimeter,
                                   const ValidationOptions& options,
                                   const ProgressCallback& progress) {
  ValidationReport report = DescribeValidation(dataset, colorimeter, options);
  // The samples set aside follow those in use, held out together in a split of their own.
  const size_t in_use = dataset.samples.size();
  Dataset all = dataset;
  all.samples.insert(all.samples.end(), dataset.excluded.begin(), dataset.excluded.end());
  std::vector<SampleSplit> all_splits = splits;
  SampleSplit aside;
  for (size_t i = in_use; i < all.samples.size(); ++i) aside.push_back(i);
  if (!aside.empty()) all_splits.push_back(aside);
  // Held-out samples and their measured colour.
  AddSplits(all, all_splits, in_use, colorimeter, options, &report);

  // Every method on every split; a method's splits run in parallel (ParallelTasks), each
  // task building its model and scoring its own held-out samples, so nothing is shared.
  std::vector<std::vector<size_t>> holdouts_of(report.splits.size());
  for (size_t h = 0; h < report.holdouts.size(); ++h) {
    holdouts_of[report.holdouts[h].split].push_back(h);
  }
  const size_t total = options.methods.size() * report.splits.size();
  size_t done = 0;
  std::mutex progress_mutex;
  bool any_method = false;
  std::string first_error;
  for (const std::string& method : options.methods) {
    Report(progress, "validate: " + method + " on " + std::to_string(report.splits.size()) +
                         (report.splits.size() == 1 ? " split" : " splits"));
    std::vector<std::string> errors(report.splits.size());
    ParallelTasks(
        report.splits.size(),
        [&](size_t s) {
          SplitResult& split = report.splits[s];
          CheckCancel(options.cancel);
          std::unique_ptr<AlloyModel> model;
          try {
            model = options.build(method, TrainingOf(all, all_splits[s], in_use));
          } catch (const Error& e) {
            errors[s] = e.what();
          }
          if (model) {
            split.warnings[method] = model->warnings();
            split.in_sample[method] = model->in_sample();
            if (model->fit_summary().selection.present()) {
              split.choices[method] = model->fit_summary().selection.reason;
            }
            FillDrudeCurves(*model, method, dataset.system, &split.drude);
            for (size_t h : holdouts_of[s]) {
              HoldoutResult& holdout = report.holdouts[h];
              const Sample& sample = all.samples[holdout.sample];
              CheckCancel(options.cancel);
              try {
                holdout.results[method] = Evaluate(*model, sample, colorimeter, options, &holdout);
              } catch (const Error& e) {
                holdout.results[method].error = e.what();
              }
            }
          }
          const ProgressCallback& report_split = errors[s].empty() ? options.details : progress;
          const std::lock_guard<std::mutex> lock(progress_mutex);
          ++done;
          if (report_split) {
            report_split("validate [" + std::to_string(done) + "/" + std::to_string(total) + "] " +
                         method + ", trained on " + std::to_string(split.train_x.size()) +
                         " samples, held out x = " + XList(split.holdout_x) +
                         (std::any_of(holdouts_of[s].begin(), holdouts_of[s].end(),
                                      [&](size_t h) { return report.holdouts[h].replicate; })
                              ? " (" + Join(split.holdout_files) + ")"
                              : std::string()) +
                         (errors[s].empty() ? "" : ": failed: " + errors[s]));
          }
        },
        options.threads);
    // A method that fails everywhere beside others that work is reported as failed in
    // each split (the physical fit refusing unphysical data, say); when no method builds
    // on any split, the first method's first error is the answer.
    for (size_t s = 0; s < report.splits.size(); ++s) {
      if (errors[s].empty()) {
        any_method = true;
      } else {
        report.splits[s].errors[method] = errors[s];
        if (first_error.empty()) first_error = errors[s];
      }
    }
  }
  if (!any_method) throw Error(first_error);
  if (options.fit_whole) {
    CheckCancel(options.cancel);
    const std::string method = options.methods.size() == 1 ? options.methods[0] : "auto";
    Report(progress, "validate: the whole data set with " + method +
                         " (its samples checked, where to measure next)");
    report.whole = DescribeWholeDataSet(dataset, colorimeter, options.fit_whole, method);
  }
  return report;
}

// ---------------------------------------------------------------------------------------

RecoverySummary Recovery(const ValidationReport& report, const std::string& method) {
  RecoverySummary s;
  double sum = 0;
  for (const HoldoutResult& h : report.holdouts) {
    const auto it = h.results.find(method);
    if (!h.excluded.empty()) continue;
    if (it == h.results.end() || !std::isfinite(it->second.x_recovered)) continue;
    const double error = std::abs(it->second.x_recovered - h.x_atomic);
    sum += 100 * error;
    ++s.count;
    if (std::isfinite(it->second.x_recovered_sigma)) {
      ++s.with_sigma;
      s.within_2 += error <= 2 * it->second.x_recovered_sigma;
    }
  }
  s.mean_abs_at_percent = s.count > 0 ? sum / s.count : std::numeric_limits<double>::quiet_NaN();
  return s;
}

SigmaCoverage Coverage(const ValidationReport& report, const std::string& method, int angle) {
  SigmaCoverage s;
  s.median_ratio = kNaN;
  std::vector<double> ratios;
  for (const HoldoutResult& h : report.holdouts) {
    const auto it = h.results.find(method);
    if (it == h.results.end() || !h.excluded.empty()) continue;
    const MethodResult& r = it->second;
    if (angle >= static_cast<int>(r.delta_e00_sigma.size())) continue;
    const double sigma = r.delta_e00_sigma[angle];
    const double observed = r.delta_e00[angle];
    if (!(sigma >= 0)) continue;
    ++s.count;
    s.within_1 += observed <= sigma;
    s.within_2 += observed <= 2 * sigma;
    ratios.push_back(sigma > 0 ? observed / sigma : std::numeric_limits<double>::infinity());
  }
  if (!ratios.empty()) {
    std::sort(ratios.begin(), ratios.end());
    const size_t n = ratios.size();
    s.median_ratio = n % 2 ? ratios[n / 2] : 0.5 * (ratios[n / 2 - 1] + ratios[n / 2]);
  }
  return s;
}

}  // namespace alloycolor::validate
