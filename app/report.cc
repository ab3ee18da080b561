#include "report.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <utility>

#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/model/optics.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/core/spectrum.h"
#include "alloycolor/core/units.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/fit/methods.h"
#include "common.h"

namespace alloycolor::app {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kVisibleLoNm = 380.0;
constexpr double kVisibleHiNm = 780.0;
constexpr double kMetricStepNm = 5.0;
constexpr double kSameX = 1e-9;

std::string Num(double v, const char* format = "%g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::string XList(const std::vector<double>& xs) {
  std::string s;
  for (double x : xs) s += (s.empty() ? "" : ", ") + Num(x, "%.4g");
  return s;
}

// ---------------------------------------------------------------------------------------
// Computation.

// The wavelengths on which n, k and reflectance errors are taken (see report.h).
std::vector<double> MetricGrid(const AlloyModel& model, const NkSpectrum& measured,
                               std::string* description) {
  const double lo = std::max(model.lambda_min_nm(), measured.lambda_min_nm());
  const double hi = std::min(model.lambda_max_nm(), measured.lambda_max_nm());
  if (lo <= kVisibleLoNm + 1e-9 && hi >= kVisibleHiNm - 1e-9) {
    *description = "380-780 nm, 5 nm step";
    return UniformGrid(kVisibleLoNm, kVisibleHiNm, kMetricStepNm);
  }
  std::vector<double> grid;
  for (double l : measured.lambda_nm) {
    if (l >= lo - 1e-9 && l <= hi + 1e-9) grid.push_back(std::clamp(l, lo, hi));
  }
  if (grid.size() < 2) {
    throw Error(measured.source + " and the " + model.method() + " model share under two " +
                "wavelengths (" + Num(lo) + "-" + Num(hi) + " nm)");
  }
  *description = "the measured sample's " + std::to_string(grid.size()) + " wavelengths in " +
                 Num(grid.front()) + "-" + Num(grid.back()) +
                 " nm (the data do not cover 380-780 nm)";
  return grid;
}

std::vector<std::complex<double>> MeasuredIndex(const NkSpectrum& nk,
                                                const std::vector<double>& grid) {
  std::vector<std::complex<double>> index(grid.size());
  for (size_t i = 0; i < grid.size(); ++i) index[i] = NkAt(nk, grid[i]);
  return index;
}

// The predicted index on the colorimeter's grid held inside 380-780 nm: the spectrum
// `alloycolor predict` writes by default, integrated as `alloycolor color --nk` would.
std::vector<std::complex<double>> PredictedColourIndex(const color::Colorimeter& colorimeter,
                                                       const AlloyModel& model, double x) {
  if (model.lambda_min_nm() > kVisibleLoNm + 1e-9 || model.lambda_max_nm() < kVisibleHiNm - 1e-9) {
    // Throws the standard message naming the model's range.
    color::EvaluationGrid(colorimeter, model.lambda_min_nm(), model.lambda_max_nm(),
                           "the " + model.method() + " model");
  }
  const std::vector<double> grid =
      color::EvaluationGrid(colorimeter, kVisibleLoNm, kVisibleHiNm, model.method());
  return model.Index(x, grid);
}

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

// The composition with atomic fraction x as a sample of the data set.
const Sample& SampleAt(const Dataset& dataset, double x) {
  for (const Sample& s : dataset.samples) {
    if (std::abs(s.x_atomic - x) <= kSameX) return s;
  }
  throw Error("no sample at x = " + Num(x));
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

// tau_fs, m*/m_e of a measured spectrum at lambda by eq. 11, 12; NaN where undefined.
void MeasuredTauMass(const NkSpectrum& nk, double x, double lambda_nm, const AlloySystem& system,
                     double* tau_fs, double* mass) {
  *tau_fs = *mass = kNaN;
  if (lambda_nm < nk.lambda_min_nm() || lambda_nm > nk.lambda_max_nm()) return;
  const std::complex<double> i = NkAt(nk, lambda_nm);
  const std::complex<double> eps = i * i;
  if (!DrudeInvertible(eps.real(), eps.imag())) return;
  const DrudePoint p = InvertDrude(OmegaEvFromLambdaNm(lambda_nm), eps.real(), eps.imag());
  *tau_fs = TauFsFromGammaEv(p.gamma_ev);
  *mass = kPlasmaEv2M3 * FreeElectronDensityM3(x, system) / p.wp2_ev2;
}

void FillDrudeCurves(const AlloyModel& model, const std::string& method, const AlloySystem& system,
                     std::vector<DrudeCurve>* curves) {
  const auto* sample_model = dynamic_cast<const SampleModel*>(&model);
  const bool paper = sample_model != nullptr && model.method() == "paper";
  for (DrudeCurve& curve : *curves) {
    std::vector<double>& taus = curve.tau_fs[method];
    std::vector<double>& masses = curve.mass[method];
    const bool in_range = curve.lambda_nm >= model.lambda_min_nm() - 1e-9 &&
                          curve.lambda_nm <= model.lambda_max_nm() + 1e-9;
    for (double x : curve.x) {
      double tau = kNaN, mass = kNaN;
      if (paper) {
        SampleModel::TauMass tm;
        if (in_range && sample_model->PaperTauMass(x, curve.lambda_nm, &tm)) {
          tau = tm.tau_fs;
          mass = tm.mass_ratio;
        }
      } else if (in_range) {
        const std::complex<double> eps = model.Permittivity(x, {curve.lambda_nm})[0];
        if (DrudeInvertible(eps.real(), eps.imag())) {
          const DrudePoint p =
              InvertDrude(OmegaEvFromLambdaNm(curve.lambda_nm), eps.real(), eps.imag());
          tau = TauFsFromGammaEv(p.gamma_ev);
          mass = kPlasmaEv2M3 * FreeElectronDensityM3(x, system) / p.wp2_ev2;
        }
      }
      taus.push_back(tau);
      masses.push_back(mass);
    }
  }
}

SplitResult PrepareSplit(const Dataset& dataset, const std::vector<double>& holdout_x) {
  SplitResult split;
  split.holdout_x = holdout_x;
  std::sort(split.holdout_x.begin(), split.holdout_x.end());
  double lo = -1e300, hi = 1e300;
  for (const Sample& s : dataset.samples) {
    const bool held = std::any_of(holdout_x.begin(), holdout_x.end(),
                                  [&](double x) { return std::abs(x - s.x_atomic) <= kSameX; });
    if (held) continue;
    split.train_x.push_back(s.x_atomic);
    lo = std::max(lo, s.nk.lambda_min_nm());
    hi = std::min(hi, s.nk.lambda_max_nm());
  }
  if (!(lo < hi)) return split;
  const double x_lo = dataset.samples.front().x_atomic;
  const double x_hi = dataset.samples.back().x_atomic;
  for (double lambda : DrudeWavelengths(lo, hi)) {
    DrudeCurve curve;
    curve.lambda_nm = lambda;
    for (int i = 0; i <= 100; ++i) curve.x.push_back(x_lo + (x_hi - x_lo) * i / 100.0);
    for (const Sample& s : dataset.samples) {
      double tau, mass;
      MeasuredTauMass(s.nk, s.x_atomic, lambda, dataset.system, &tau, &mass);
      const bool held = std::any_of(split.holdout_x.begin(), split.holdout_x.end(),
                                    [&](double x) { return std::abs(x - s.x_atomic) <= kSameX; });
      (held ? curve.holdout_x : curve.train_x).push_back(s.x_atomic);
      (held ? curve.holdout_tau_fs : curve.train_tau_fs).push_back(tau);
      (held ? curve.holdout_mass : curve.train_mass).push_back(mass);
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
  r.lambda_nm = MetricGrid(model, sample.nk, &description);
  const Spectra predicted = SpectraOf(model.Index(sample.x_atomic, r.lambda_nm));
  const Spectra measured = SpectraOf(MeasuredIndex(sample.nk, r.lambda_nm));
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
      index = PredictedColourIndex(colorimeter, model, sample.x_atomic);
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
  }
  return r;
}

}  // namespace

ValidationReport ComputeValidation(const Dataset& dataset,
                                   const std::vector<std::vector<double>>& splits,
                                   const color::Colorimeter& colorimeter,
                                   const ValidationOptions& options,
                                   const ProgressFunction& progress) {
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

  // Held-out samples and their measured colour.
  for (size_t s = 0; s < splits.size(); ++s) {
    report.splits.push_back(PrepareSplit(dataset, splits[s]));
    for (double x : report.splits.back().holdout_x) {
      const Sample& sample = SampleAt(dataset, x);
      HoldoutResult h;
      h.x_atomic = sample.x_atomic;
      h.x_given = sample.x_given;
      h.file = sample.file;
      h.path = sample.path;
      h.split = static_cast<int>(s);
      try {
        const Colour c = ColourAtAngles(colorimeter, color::IndexOnGrid(colorimeter, sample.nk),
                                        options.angles_deg);
        h.lab = c.lab;
        h.srgb8 = c.srgb8;
      } catch (const Error& e) {
        h.colour_note = e.what();
      }
      report.holdouts.push_back(std::move(h));
    }
  }

  const int total = static_cast<int>(options.methods.size() * splits.size());
  int step = 0;
  using Key = std::pair<std::string, size_t>;  // method, split
  std::map<Key, std::unique_ptr<AlloyModel>> built;
  std::map<Key, std::string> failed;
  const auto build = [&](const std::string& method, size_t s) -> const AlloyModel* {
    const Key key{method, s};
    if (built.count(key)) return built[key].get();
    if (failed.count(key)) return nullptr;
    const SplitResult& split = report.splits[s];
    ++step;
    if (progress) {
      progress("validate [" + std::to_string(step) + "/" + std::to_string(total) + "] " + method +
               ": training on " + std::to_string(split.train_x.size()) +
               " samples, holding out x = " + XList(split.holdout_x));
    }
    try {
      built[key] = fit::BuildModel(method, WithoutSamples(dataset, split.holdout_x));
      return built[key].get();
    } catch (const Error& e) {
      failed[key] = e.what();
      if (progress) progress("validate: " + method + " failed: " + e.what());
      return nullptr;
    }
  };
  // First, every method until it builds on some split: a method that builds on none (an
  // unknown name, say) is refused before the long work.
  for (const std::string& method : options.methods) {
    bool any = false;
    for (size_t s = 0; s < report.splits.size() && !any; ++s) any = build(method, s) != nullptr;
    if (!any) throw Error(failed[{method, 0}]);
  }
  for (const std::string& method : options.methods) {
    for (size_t s = 0; s < report.splits.size(); ++s) {
      SplitResult& split = report.splits[s];
      const AlloyModel* model = build(method, s);
      if (model == nullptr) {
        split.errors[method] = failed[{method, s}];
        continue;
      }
      split.warnings[method] = model->warnings();
      FillDrudeCurves(*model, method, dataset.system, &split.drude);
      for (HoldoutResult& h : report.holdouts) {
        if (h.split != static_cast<int>(s)) continue;
        const Sample& sample = SampleAt(dataset, h.x_atomic);
        try {
          h.results[method] = Evaluate(*model, sample, colorimeter, options, &h);
        } catch (const Error& e) {
          h.results[method].error = e.what();
        }
      }
      built.erase({method, s});
    }
  }
  return report;
}

// ---------------------------------------------------------------------------------------
// Presentation: the metrics as columns of a table.

namespace {

struct Metric {
  std::string key;    // JSON summary key
  std::string label;  // HTML
  int angle = -1;     // index into angles_deg for delta_e00
  const char* format;
  double (*value)(const MethodResult&, int angle);
};

double DeltaE00Value(const MethodResult& r, int angle) {
  return angle < static_cast<int>(r.delta_e00.size()) ? r.delta_e00[angle] : kNaN;
}

bool AnyColour(const ValidationReport& report) {
  for (const HoldoutResult& h : report.holdouts) {
    for (const auto& [method, r] : h.results) {
      if (!r.delta_e00.empty()) return true;
    }
  }
  return false;
}

std::vector<Metric> Metrics(const ValidationReport& report) {
  std::vector<Metric> metrics;
  if (AnyColour(report)) {
    for (size_t a = 0; a < report.angles_deg.size(); ++a) {
      metrics.push_back({"delta_e00_" + Num(report.angles_deg[a]),
                         "&Delta;E<sub>00</sub> at " + Num(report.angles_deg[a]) + "&deg;",
                         static_cast<int>(a), "%.2f", DeltaE00Value});
    }
  }
  metrics.push_back({"reflectance_rms", "R RMS error", -1, "%.4f",
                     [](const MethodResult& r, int) { return r.reflectance_rms; }});
  metrics.push_back({"reflectance_max", "R max error", -1, "%.4f",
                     [](const MethodResult& r, int) { return r.reflectance_max; }});
  metrics.push_back({"n_max_abs", "max |&Delta;n|", -1, "%.3f",
                     [](const MethodResult& r, int) { return r.n_max_abs; }});
  metrics.push_back({"k_max_abs", "max |&Delta;k|", -1, "%.3f",
                     [](const MethodResult& r, int) { return r.k_max_abs; }});
  return metrics;
}

// A metric's value for one method and held-out sample; NaN where there is none.
double ValueOf(const HoldoutResult& h, const std::string& method, const Metric& metric) {
  const auto it = h.results.find(method);
  if (it == h.results.end() || it->second.lambda_nm.empty()) return kNaN;
  return metric.value(it->second, metric.angle);
}

// The methods with the lowest value in a row (ties within 1e-12 relative all win).
std::set<std::string> Best(const ValidationReport& report, const HoldoutResult& h,
                           const Metric& metric) {
  double best = kNaN;
  for (const std::string& m : report.methods) {
    const double v = ValueOf(h, m, metric);
    if (std::isfinite(v) && !(v >= best)) best = v;
  }
  std::set<std::string> winners;
  if (!std::isfinite(best)) return winners;
  for (const std::string& m : report.methods) {
    const double v = ValueOf(h, m, metric);
    if (std::isfinite(v) && v <= best + 1e-12 * std::max(1.0, std::abs(best))) {
      winners.insert(m);
    }
  }
  return winners;
}

struct MetricSummary {
  int count = 0, wins = 0;
  double mean = kNaN, max = kNaN;
};

MetricSummary Summarise(const ValidationReport& report, const std::string& method,
                        const Metric& metric) {
  MetricSummary s;
  double sum = 0;
  for (const HoldoutResult& h : report.holdouts) {
    const double v = ValueOf(h, method, metric);
    if (!std::isfinite(v)) continue;
    ++s.count;
    sum += v;
    s.max = s.count == 1 ? v : std::max(s.max, v);
    if (Best(report, h, metric).count(method)) ++s.wins;
  }
  if (s.count > 0) s.mean = sum / s.count;
  return s;
}

// How the observed delta_e00 compares with the predicted one-sigma, per method and angle.
struct SigmaSummary {
  int count = 0, within_1 = 0, within_2 = 0;
  double median_ratio = kNaN;
};

SigmaSummary SummariseSigma(const ValidationReport& report, const std::string& method, int angle) {
  SigmaSummary s;
  std::vector<double> ratios;
  for (const HoldoutResult& h : report.holdouts) {
    const auto it = h.results.find(method);
    if (it == h.results.end()) continue;
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

nlohmann::json OrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nullptr; }

nlohmann::json ByAngle(const std::vector<double>& angles, const std::vector<double>& values) {
  if (values.empty()) return nullptr;
  nlohmann::json out = nlohmann::json::object();
  for (size_t a = 0; a < angles.size() && a < values.size(); ++a) {
    out[Num(angles[a])] = OrNull(values[a]);
  }
  return out;
}

nlohmann::json HexByAngle(const std::vector<double>& angles,
                          const std::vector<std::array<std::uint8_t, 3>>& srgb8) {
  if (srgb8.empty()) return nullptr;
  nlohmann::json out = nlohmann::json::object();
  for (size_t a = 0; a < angles.size() && a < srgb8.size(); ++a) {
    out[Num(angles[a])] = color::HexColor(srgb8[a]);
  }
  return out;
}

nlohmann::json LabByAngle(const std::vector<double>& angles, const std::vector<color::Lab>& labs) {
  if (labs.empty()) return nullptr;
  nlohmann::json out = nlohmann::json::object();
  for (size_t a = 0; a < angles.size() && a < labs.size(); ++a) {
    out[Num(angles[a])] = {labs[a].L, labs[a].a, labs[a].b};
  }
  return out;
}

std::string ColourRangeText(const ValidationReport& report) {
  return "the colorimeter's grid " + Num(report.colour_nm[0]) + "-" + Num(report.colour_nm[1]) +
         " nm (" + report.illuminant + ", " + std::to_string(report.observer_deg) +
         "-degree observer); the prediction evaluated on 380-780 nm as `alloycolor predict` "
         "writes it, the measured file on its own range, each held at its ends";
}

}  // namespace

nlohmann::json ValidationJson(const ValidationReport& report) {
  const bool colour = AnyColour(report);
  nlohmann::json doc = {{"format", "alloycolor-validation"},
                        {"version", 1},
                        {"generator", "alloycolor " ALLOYCOLOR_VERSION},
                        {"data", report.data},
                        {"name", report.name},
                        {"system", report.system},
                        {"composition", "atomic_fraction_a"},
                        {"manifest_composition", report.composition},
                        {"mode", report.mode},
                        {"methods", report.methods},
                        {"angles_deg", report.angles_deg},
                        {"illuminant", report.illuminant},
                        {"observer", report.observer_deg}};
  std::string no_colour;
  for (const HoldoutResult& h : report.holdouts) {
    if (no_colour.empty() && !h.colour_note.empty()) no_colour = h.colour_note;
  }
  doc["metric_ranges"] = {
      {"delta_e00", colour ? nlohmann::json(ColourRangeText(report))
                           : nlohmann::json("not available: " + no_colour)},
      {"reflectance", "normal incidence; per held-out sample, see holdouts[].metric_range"},
      {"n_k", "the same wavelengths as the reflectance"}};
  doc["delta_e00_available"] = colour;
  nlohmann::json splits = nlohmann::json::array();
  for (const SplitResult& s : report.splits) {
    nlohmann::json split = {{"train_x", s.train_x}, {"holdout_x", s.holdout_x}};
    if (!s.errors.empty()) split["errors"] = s.errors;
    split["warnings"] = s.warnings;
    nlohmann::json drude = nlohmann::json::array();
    for (const DrudeCurve& c : s.drude) {
      nlohmann::json curve = {{"lambda_nm", c.lambda_nm}};
      const auto nulls = [](const std::vector<double>& v) {
        nlohmann::json a = nlohmann::json::array();
        for (double x : v) a.push_back(OrNull(x));
        return a;
      };
      curve["train"] = {
          {"x", c.train_x}, {"tau_fs", nulls(c.train_tau_fs)}, {"mass_ratio", nulls(c.train_mass)}};
      curve["holdout"] = {{"x", c.holdout_x},
                          {"tau_fs", nulls(c.holdout_tau_fs)},
                          {"mass_ratio", nulls(c.holdout_mass)}};
      drude.push_back(curve);
    }
    split["drude_measured"] = drude;
    splits.push_back(split);
  }
  doc["splits"] = splits;
  nlohmann::json holdouts = nlohmann::json::array();
  for (const HoldoutResult& h : report.holdouts) {
    nlohmann::json item = {{"x", h.x_atomic},
                           {"x_given", h.x_given},
                           {"file", h.file},
                           {"path", h.path},
                           {"split", h.split},
                           {"train_x", report.splits[h.split].train_x},
                           {"metric_range", h.metric_range},
                           {"measured",
                            {{"srgb_hex", HexByAngle(report.angles_deg, h.srgb8)},
                             {"Lab", LabByAngle(report.angles_deg, h.lab)}}}};
    if (!h.colour_note.empty()) item["delta_e00_note"] = "not available: " + h.colour_note;
    nlohmann::json results = nlohmann::json::object();
    for (const std::string& method : report.methods) {
      const auto it = h.results.find(method);
      if (it == h.results.end()) {
        const auto& errors = report.splits[h.split].errors;
        const auto e = errors.find(method);
        results[method] = {{"error", e != errors.end() ? e->second : "not evaluated"}};
        continue;
      }
      const MethodResult& r = it->second;
      if (r.lambda_nm.empty()) {
        results[method] = {{"error", r.error}};
        continue;
      }
      nlohmann::json m = {{"delta_e00", ByAngle(report.angles_deg, r.delta_e00)},
                          {"reflectance_rms", r.reflectance_rms},
                          {"reflectance_max", r.reflectance_max},
                          {"n_max_abs", r.n_max_abs},
                          {"k_max_abs", r.k_max_abs},
                          {"delta_e00_sigma", ByAngle(report.angles_deg, r.delta_e00_sigma)},
                          {"srgb_hex", HexByAngle(report.angles_deg, r.srgb8)},
                          {"Lab", LabByAngle(report.angles_deg, r.lab)}};
      if (!r.error.empty()) m["note"] = r.error;
      results[method] = m;
    }
    item["results"] = results;
    holdouts.push_back(item);
  }
  doc["holdouts"] = holdouts;
  nlohmann::json summary = nlohmann::json::object();
  for (const Metric& metric : Metrics(report)) {
    nlohmann::json row = nlohmann::json::object();
    for (const std::string& method : report.methods) {
      const MetricSummary s = Summarise(report, method, metric);
      row[method] = {
          {"count", s.count}, {"mean", OrNull(s.mean)}, {"max", OrNull(s.max)}, {"wins", s.wins}};
    }
    summary[metric.key] = row;
  }
  doc["summary"] = summary;
  nlohmann::json honesty = nlohmann::json::object();
  for (const std::string& method : report.methods) {
    for (size_t a = 0; a < report.angles_deg.size(); ++a) {
      const SigmaSummary s = SummariseSigma(report, method, static_cast<int>(a));
      if (s.count == 0) continue;
      honesty[method][Num(report.angles_deg[a])] = {
          {"count", s.count},
          {"within_1_sigma", s.within_1},
          {"within_2_sigma", s.within_2},
          {"median_observed_over_sigma", OrNull(s.median_ratio)}};
    }
  }
  doc["sigma_honesty"] = honesty;
  doc["dataset_warnings"] = report.dataset_warnings;
  return doc;
}

// ---------------------------------------------------------------------------------------
// Presentation: HTML and SVG.

namespace {

std::string Escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

const char* const kPalette[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd",
                                "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

std::string MethodColour(const ValidationReport& report, const std::string& method) {
  const auto it = std::find(report.methods.begin(), report.methods.end(), method);
  const size_t i = it - report.methods.begin();
  return kPalette[i % (sizeof kPalette / sizeof kPalette[0])];
}

struct PlotSeries {
  std::string label, colour;
  std::vector<double> x, y;
  bool line = true;
  bool markers = false;
  bool hollow = false;
  double width = 1.6;
  std::string dash;
};

struct PlotSpec {
  std::string id, title, x_label, y_label;
  int width = 370, height = 250;
  std::vector<PlotSeries> series;
};

// About `count` round tick values (1, 2, 5 times a power of ten) spanning [lo, hi].
std::vector<double> NiceTicks(double lo, double hi, int count) {
  const double raw = (hi - lo) / std::max(count, 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double f : {1.0, 2.0, 5.0, 10.0}) {
    step = f * mag;
    if (step >= raw) break;
  }
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step) {
    ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
  }
  return ticks;
}

std::string SvgPlot(const PlotSpec& spec) {
  const double left = 58, right = 20, top = 26, bottom = 40;
  const double pw = spec.width - left - right, ph = spec.height - top - bottom;
  double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
  for (const PlotSeries& s : spec.series) {
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x_lo = std::min(x_lo, s.x[i]);
      x_hi = std::max(x_hi, s.x[i]);
      y_lo = std::min(y_lo, s.y[i]);
      y_hi = std::max(y_hi, s.y[i]);
    }
  }
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" width=\"" << spec.width
      << "\" height=\"" << spec.height << "\" viewBox=\"0 0 " << spec.width << " " << spec.height
      << "\" role=\"img\" aria-label=\"" << Escape(spec.title) << "\">";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>";
  svg << "<text x=\"" << left + pw / 2 << "\" y=\"16\" text-anchor=\"middle\" "
      << "class=\"pt\">" << Escape(spec.title) << "</text>";
  if (!(x_lo <= x_hi) || !(y_lo <= y_hi)) {
    svg << "<text x=\"" << left + pw / 2 << "\" y=\"" << top + ph / 2
        << "\" text-anchor=\"middle\" class=\"pl\">no data</text></svg>";
    return svg.str();
  }
  if (x_hi - x_lo < 1e-12) {
    x_lo -= 0.5;
    x_hi += 0.5;
  }
  const double pad =
      y_hi - y_lo < 1e-12 ? std::max(std::abs(y_hi) * 0.05, 1e-3) : (y_hi - y_lo) * 0.06;
  y_lo -= pad;
  y_hi += pad;
  const auto px = [&](double x) { return left + (x - x_lo) / (x_hi - x_lo) * pw; };
  const auto py = [&](double y) { return top + (y_hi - y) / (y_hi - y_lo) * ph; };
  svg << "<defs><clipPath id=\"" << spec.id << "\"><rect x=\"" << left << "\" y=\"" << top
      << "\" width=\"" << pw << "\" height=\"" << ph << "\"/></clipPath></defs>";
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"none\" stroke=\"#999\"/>";
  char buf[64];
  for (double t : NiceTicks(x_lo, x_hi, 5)) {
    std::snprintf(buf, sizeof buf, "%.1f", px(t));
    svg << "<line x1=\"" << buf << "\" x2=\"" << buf << "\" y1=\"" << top << "\" y2=\"" << top + ph
        << "\" class=\"grid\"/><text x=\"" << buf << "\" y=\"" << top + ph + 14
        << "\" text-anchor=\"middle\" class=\"pl\">" << Num(t, "%.6g") << "</text>";
  }
  for (double t : NiceTicks(y_lo, y_hi, 5)) {
    std::snprintf(buf, sizeof buf, "%.1f", py(t));
    svg << "<line x1=\"" << left << "\" x2=\"" << left + pw << "\" y1=\"" << buf << "\" y2=\""
        << buf << "\" class=\"grid\"/><text x=\"" << left - 4 << "\" y=\"" << buf
        << "\" dy=\"3\" text-anchor=\"end\" class=\"pl\">" << Num(t, "%.4g") << "</text>";
  }
  svg << "<text x=\"" << left + pw / 2 << "\" y=\"" << spec.height - 6
      << "\" text-anchor=\"middle\" class=\"pl\">" << Escape(spec.x_label) << "</text>";
  svg << "<text transform=\"translate(12," << top + ph / 2 << ") rotate(-90)\" "
      << "text-anchor=\"middle\" class=\"pl\">" << Escape(spec.y_label) << "</text>";
  svg << "<g clip-path=\"url(#" << spec.id << ")\">";
  for (const PlotSeries& s : spec.series) {
    if (s.line) {
      std::string points;
      const auto flush = [&]() {
        if (points.find(' ') != std::string::npos) {
          svg << "<polyline fill=\"none\" stroke=\"" << s.colour << "\" stroke-width=\"" << s.width
              << "\"" << (s.dash.empty() ? "" : " stroke-dasharray=\"" + s.dash + "\"")
              << " points=\"" << points << "\"><title>" << Escape(s.label) << "</title></polyline>";
        }
        points.clear();
      };
      for (size_t i = 0; i < s.x.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
          flush();
          continue;
        }
        std::snprintf(buf, sizeof buf, "%s%.1f,%.1f", points.empty() ? "" : " ", px(s.x[i]),
                      py(s.y[i]));
        points += buf;
      }
      flush();
    }
    if (s.markers) {
      for (size_t i = 0; i < s.x.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
        std::snprintf(buf, sizeof buf, "cx=\"%.1f\" cy=\"%.1f\"", px(s.x[i]), py(s.y[i]));
        svg << "<circle " << buf << " r=\"3.5\" fill=\"" << (s.hollow ? "#fff" : s.colour)
            << "\" stroke=\"" << s.colour << "\" stroke-width=\"1.5\"><title>" << Escape(s.label)
            << ": " << Num(s.x[i], "%.4g") << ", " << Num(s.y[i], "%.4g") << "</title></circle>";
      }
    }
  }
  svg << "</g></svg>";
  return svg.str();
}

std::string Swatch(const std::array<std::uint8_t, 3>& srgb8, const std::string& caption) {
  return "<div class=\"sw\"><div class=\"chip\" style=\"background:" + color::HexColor(srgb8) +
         "\"></div><div class=\"cap\">" + caption + "</div></div>";
}

std::string Legend(const ValidationReport& report, bool drude) {
  std::string html = "<div class=\"legend\"><span><i style=\"background:#000\"></i>measured";
  html += drude ? " (training: filled; held out: open)" : "";
  html += "</span>";
  for (const std::string& m : report.methods) {
    html += "<span><i style=\"background:" + MethodColour(report, m) + "\"></i>" + Escape(m) +
            "</span>";
  }
  return html + "</div>";
}

const char kStyle[] = R"css(
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,Helvetica,Arial,sans-serif;
 margin:24px;color:#222;max-width:1180px;line-height:1.4}
h1{font-size:24px;margin:0 0 8px} h2{font-size:19px;margin:28px 0 8px;border-bottom:1px solid #ccc}
h3{font-size:16px;margin:22px 0 6px} h4{font-size:15px;margin:16px 0 6px}
table{border-collapse:collapse;margin:6px 0 14px;font-size:13px}
th,td{border:1px solid #ccc;padding:3px 8px;text-align:right} th{background:#f2f2f2}
td.l,th.l{text-align:left} td.best{background:#dff0d8;font-weight:bold}
td.best::after{content:" \2605";color:#3c763d}
.meta{color:#555;font-size:13px} .note{color:#8a6d3b;background:#fcf8e3;padding:6px 10px;
 border:1px solid #faebcc;font-size:13px} .bad{color:#a94442}
.swrow{display:flex;flex-wrap:wrap;gap:10px;align-items:flex-start;margin:4px 0 10px}
.swlabel{width:70px;font-size:13px;padding-top:22px}
.sw{width:104px;text-align:center;font-size:12px}
.chip{width:96px;height:64px;margin:0 auto 3px;border:1px solid #888;border-radius:4px}
.plots{display:flex;flex-wrap:wrap;gap:8px}
.plot text{font-size:11px;fill:#333} .plot .pt{font-size:12px;font-weight:bold}
.plot line.grid{stroke:#eee}
.legend{font-size:13px;margin:4px 0} .legend span{margin-right:16px;white-space:nowrap}
.legend i{display:inline-block;width:14px;height:4px;margin:0 5px 3px 0;vertical-align:middle}
)css";

std::string MetricCell(double v, const char* format, bool best) {
  if (!std::isfinite(v)) return "<td>&ndash;</td>";
  return std::string("<td") + (best ? " class=\"best\"" : "") + ">" + Num(v, format) + "</td>";
}

bool WeightManifest(const ValidationReport& report) {
  return report.composition == "weight_fraction_a";
}

std::string XLabel(const ValidationReport& report, const HoldoutResult& h) {
  return "x = " + Num(h.x_atomic, "%.4g") + " (" + Num(100 * h.x_atomic, "%.4g") + " at%" +
         (WeightManifest(report) ? ", " + Num(100 * h.x_given, "%.4g") + " wt%" : "") + " " +
         report.element_a + ")";
}

// The held-out composition in a table row: x, and the manifest's weight fraction if given.
std::string RowLabel(const ValidationReport& report, const HoldoutResult& h) {
  return Num(h.x_atomic, "%.4g") +
         (WeightManifest(report) ? " <small>(" + Num(h.x_given, "%.4g") + " wt)</small>" : "");
}

void WriteVerdict(const ValidationReport& report, std::ostringstream& html) {
  html << "<h2>Verdict</h2><ul>";
  for (const Metric& metric : Metrics(report)) {
    std::vector<std::pair<double, std::string>> ranked;
    std::map<std::string, MetricSummary> sums;
    for (const std::string& m : report.methods) {
      sums[m] = Summarise(report, m, metric);
      if (sums[m].count > 0) ranked.push_back({sums[m].mean, m});
    }
    if (ranked.empty()) continue;
    std::sort(ranked.begin(), ranked.end());
    html << "<li><b>" << metric.label << "</b>: lowest mean <b>" << Escape(ranked[0].second)
         << "</b>";
    for (size_t i = 0; i < ranked.size(); ++i) {
      const MetricSummary& s = sums[ranked[i].second];
      html << (i == 0 ? " (" : "; ") << (i == 0 ? "" : Escape(ranked[i].second) + " ") << "mean "
           << Num(s.mean, metric.format) << ", max " << Num(s.max, metric.format) << ", best on "
           << s.wins << " of " << s.count;
    }
    html << ")</li>";
  }
  html << "</ul>";
}

void WriteSummaryTables(const ValidationReport& report, std::ostringstream& html) {
  html << "<h2>Summary</h2><p class=\"meta\">Error of each method on each held-out "
          "composition; the best method in each row is marked &#9733;. Lower is better.</p>";
  html << "<div class=\"plots\">";
  for (const Metric& metric : Metrics(report)) {
    html << "<table class=\"summary\"><caption>" << metric.label
         << "</caption><tr><th class=\"l\">held out</th>";
    for (const std::string& m : report.methods) html << "<th>" << Escape(m) << "</th>";
    html << "</tr>";
    for (const HoldoutResult& h : report.holdouts) {
      const std::set<std::string> best = Best(report, h, metric);
      html << "<tr><td class=\"l\">" << RowLabel(report, h) << "</td>";
      for (const std::string& m : report.methods) {
        html << MetricCell(ValueOf(h, m, metric), metric.format, best.count(m) > 0);
      }
      html << "</tr>";
    }
    html << "<tr><th class=\"l\">mean</th>";
    for (const std::string& m : report.methods) {
      html << "<th>" << Num(Summarise(report, m, metric).mean, metric.format) << "</th>";
    }
    html << "</tr><tr><th class=\"l\">wins</th>";
    for (const std::string& m : report.methods) {
      html << "<th>" << Summarise(report, m, metric).wins << "</th>";
    }
    html << "</tr></table>";
  }
  html << "</div>";
}

void WriteHonesty(const ValidationReport& report, std::ostringstream& html) {
  std::ostringstream rows;
  for (const std::string& m : report.methods) {
    for (size_t a = 0; a < report.angles_deg.size(); ++a) {
      const SigmaSummary s = SummariseSigma(report, m, static_cast<int>(a));
      if (s.count == 0) continue;
      const double frac1 = double(s.within_1) / s.count;
      std::string verdict;
      if (s.median_ratio > 2) {
        verdict = "<span class=\"bad\">too small: errors are typically " +
                  Num(s.median_ratio, "%.1f") + "&times; the predicted sigma</span>";
      } else if (s.median_ratio < 0.3) {
        verdict = "too large (over-cautious): errors are typically " + Num(s.median_ratio, "%.2g") +
                  "&times; the predicted sigma";
      } else {
        verdict = "about right";
      }
      rows << "<tr><td class=\"l\">" << Escape(m) << "</td><td>" << Num(report.angles_deg[a])
           << "&deg;</td><td>" << s.within_1 << " of " << s.count << " ("
           << Num(100 * frac1, "%.0f") << "%)</td><td>" << s.within_2 << " of " << s.count
           << "</td><td>" << Num(s.median_ratio, "%.2f") << "</td><td class=\"l\">" << verdict
           << "</td></tr>";
    }
  }
  html << "<h2>Are the error bars honest?</h2>";
  if (rows.str().empty()) {
    html << "<p class=\"meta\">No method in this report carries an uncertainty (or no colour "
            "could be computed).</p>";
    return;
  }
  html << "<p class=\"meta\">For methods with an uncertainty, the observed &Delta;E<sub>00</sub> "
          "against the model's own one-sigma &Delta;E<sub>00</sub> (RMS over draws from the "
          "fit covariance). Honest error bars hold about 68% of the errors within one sigma "
          "and 95% within two.</p>"
       << "<table><tr><th class=\"l\">method</th><th>angle</th><th>&Delta;E &le; "
          "1&sigma;</th><th>&Delta;E &le; 2&sigma;</th><th>median &Delta;E/&sigma;</th><th "
          "class=\"l\">verdict</th></tr>"
       << rows.str() << "</table>";
}

void WriteDrude(const ValidationReport& report, const SplitResult& split, int split_index,
                std::ostringstream& html) {
  if (split.drude.empty()) return;
  html << "<h4>Drude parameters against composition</h4><p class=\"meta\">&tau; = "
          "&hbar;/&gamma; and m*/m<sub>e</sub> = e&sup2;&hbar;&sup2;N<sub>e</sub>(x)/"
          "(&epsilon;<sub>0</sub>m<sub>e</sub>&omega;<sub>p</sub>&sup2;) from each model "
          "(paper: its interpolated inversion; others: eq. 11, 12 applied to the predicted "
          "&epsilon;), and from the measured samples (dots; held out: open).</p>"
       << Legend(report, true);
  for (int quantity = 0; quantity < 2; ++quantity) {
    html << "<div class=\"plots\">";
    for (size_t c = 0; c < split.drude.size(); ++c) {
      const DrudeCurve& curve = split.drude[c];
      PlotSpec spec;
      spec.id = "d" + std::to_string(split_index) + "_" + std::to_string(quantity) + "_" +
                std::to_string(c);
      spec.title = std::string(quantity == 0 ? "\u03c4" : "m*/m\u2091") + " at " +
                   Num(curve.lambda_nm) + " nm";
      spec.x_label = "x (atomic fraction " + report.element_a + ")";
      spec.y_label = quantity == 0 ? "\u03c4 (fs)" : "m*/m\u2091";
      for (const std::string& m : report.methods) {
        const auto& values = quantity == 0 ? curve.tau_fs : curve.mass;
        const auto it = values.find(m);
        if (it == values.end()) continue;
        PlotSeries s;
        s.label = m;
        s.colour = MethodColour(report, m);
        s.x = curve.x;
        s.y = it->second;
        spec.series.push_back(s);
      }
      PlotSeries train;
      train.label = "measured (training)";
      train.colour = "#000";
      train.line = false;
      train.markers = true;
      train.x = curve.train_x;
      train.y = quantity == 0 ? curve.train_tau_fs : curve.train_mass;
      spec.series.push_back(train);
      PlotSeries held = train;
      held.label = "measured (held out)";
      held.hollow = true;
      held.x = curve.holdout_x;
      held.y = quantity == 0 ? curve.holdout_tau_fs : curve.holdout_mass;
      spec.series.push_back(held);
      html << SvgPlot(spec);
    }
    html << "</div>";
  }
}

void WriteHoldout(const ValidationReport& report, const HoldoutResult& h, int index,
                  std::ostringstream& html) {
  html << "<h4>Held out: " << XLabel(report, h) << " &mdash; " << Escape(h.file) << "</h4>";
  // Swatches.
  if (!h.srgb8.empty()) {
    for (size_t a = 0; a < report.angles_deg.size(); ++a) {
      html << "<div class=\"swrow\"><div class=\"swlabel\">" << Num(report.angles_deg[a])
           << "&deg; incidence</div>"
           << Swatch(h.srgb8[a], "<b>measured</b><br>" + color::HexColor(h.srgb8[a]));
      for (const std::string& m : report.methods) {
        const auto it = h.results.find(m);
        if (it == h.results.end() || a >= it->second.srgb8.size()) continue;
        const MethodResult& r = it->second;
        std::string cap = "<b>" + Escape(m) + "</b><br>" + color::HexColor(r.srgb8[a]) +
                          "<br>&Delta;E " + Num(r.delta_e00[a], "%.2f");
        if (a < r.delta_e00_sigma.size()) {
          cap += " (&sigma; " + Num(r.delta_e00_sigma[a], "%.2f") + ")";
        }
        html << Swatch(r.srgb8[a], cap);
      }
      html << "</div>";
    }
  } else {
    html << "<p class=\"note\">No colour: " << Escape(h.colour_note)
         << ". &Delta;E<sub>00</sub> is not available; n, k and reflectance are compared "
            "over "
         << Escape(h.metric_range.empty() ? "the data's range" : h.metric_range) << ".</p>";
  }
  // Metrics of this composition.
  html << "<table><tr><th class=\"l\">method</th>";
  for (double angle : report.angles_deg) {
    if (!h.srgb8.empty()) html << "<th>&Delta;E<sub>00</sub> " << Num(angle) << "&deg;</th>";
  }
  if (!h.srgb8.empty()) html << "<th>&sigma; (&Delta;E<sub>00</sub>)</th>";
  html << "<th>R RMS</th><th>R max</th><th>max |&Delta;n|</th><th>max |&Delta;k|</th>"
          "<th class=\"l\">notes</th></tr>";
  for (const std::string& m : report.methods) {
    html << "<tr><td class=\"l\">" << Escape(m) << "</td>";
    const auto it = h.results.find(m);
    std::string note;
    if (it == h.results.end()) {
      const auto& errors = report.splits[h.split].errors;
      const auto e = errors.find(m);
      note = e != errors.end() ? e->second : "not evaluated";
    }
    const MethodResult* r = it == h.results.end() ? nullptr : &it->second;
    const bool spectral = r && !r->lambda_nm.empty();
    if (r && !r->error.empty()) note = r->error;
    if (!h.srgb8.empty()) {
      for (size_t a = 0; a < report.angles_deg.size(); ++a) {
        html << MetricCell(r && a < r->delta_e00.size() ? r->delta_e00[a] : kNaN, "%.2f", false);
      }
      std::string sigmas;
      for (size_t a = 0; r && a < r->delta_e00_sigma.size(); ++a) {
        sigmas += (a ? " / " : "") + Num(r->delta_e00_sigma[a], "%.2f");
      }
      html << "<td>" << (sigmas.empty() ? "&ndash;" : sigmas) << "</td>";
    }
    html << MetricCell(spectral ? r->reflectance_rms : kNaN, "%.4f", false)
         << MetricCell(spectral ? r->reflectance_max : kNaN, "%.4f", false)
         << MetricCell(spectral ? r->n_max_abs : kNaN, "%.3f", false)
         << MetricCell(spectral ? r->k_max_abs : kNaN, "%.3f", false) << "<td class=\"l\">"
         << Escape(note) << "</td></tr>";
  }
  html << "</table>";
  if (h.lambda_nm.empty()) return;
  // Spectra.
  html << "<p class=\"meta\">Spectra over " << Escape(h.metric_range)
       << "; R at normal incidence.</p>" << Legend(report, false) << "<div class=\"plots\">";
  const bool few = h.lambda_nm.size() <= 60;
  for (int q = 0; q < 3; ++q) {
    PlotSpec spec;
    spec.id = "s" + std::to_string(index) + "_" + std::to_string(q);
    spec.title = q == 0 ? "n" : q == 1 ? "k" : "R (normal incidence)";
    spec.x_label = "wavelength (nm)";
    spec.y_label = q == 0 ? "n" : q == 1 ? "k" : "R";
    PlotSeries measured;
    measured.label = "measured";
    measured.colour = "#000";
    measured.width = 2.6;
    measured.markers = few;
    measured.x = h.lambda_nm;
    measured.y = q == 0 ? h.n : q == 1 ? h.k : h.reflectance;
    spec.series.push_back(measured);
    for (const std::string& m : report.methods) {
      const auto it = h.results.find(m);
      if (it == h.results.end() || it->second.lambda_nm.empty()) continue;
      const MethodResult& r = it->second;
      PlotSeries s;
      s.label = m;
      s.colour = MethodColour(report, m);
      s.x = r.lambda_nm;
      s.y = q == 0 ? r.n : q == 1 ? r.k : r.reflectance;
      s.dash = "6 3";
      spec.series.push_back(s);
    }
    html << SvgPlot(spec);
  }
  html << "</div>";
}

}  // namespace

std::string ValidationHtml(const ValidationReport& report) {
  std::ostringstream html;
  const std::string title = "alloycolor validation: " + report.system;
  html << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>"
       << Escape(title) << "</title><style>" << kStyle << "</style></head><body>\n";
  html << "<h1>" << Escape(title) << "</h1>";
  html << "<p class=\"meta\">Data: " << Escape(report.name) << " &mdash; <code>"
       << Escape(report.data) << "</code><br>Methods: ";
  for (size_t i = 0; i < report.methods.size(); ++i) {
    html << (i ? ", " : "") << Escape(report.methods[i]);
  }
  html << ". "
       << (report.mode == "loo" ? "Leave-one-out: each interior sample held out in "
                                  "turn, every method refitted without it."
                                : "Held out: the given compositions, every method "
                                  "refitted without them.")
       << "<br>Colour: illuminant " << Escape(report.illuminant) << ", " << report.observer_deg
       << "&deg; observer, incidence ";
  for (size_t a = 0; a < report.angles_deg.size(); ++a) {
    html << (a ? ", " : "") << Num(report.angles_deg[a]) << "&deg;";
  }
  html << ". Compositions x are atomic fractions of " << Escape(report.element_a)
       << (report.composition == "weight_fraction_a" ? " (the manifest gives weight fractions)"
                                                     : "")
       << ".<br>Generated by alloycolor " ALLOYCOLOR_VERSION ".</p>";

  // What each metric covers.
  html << "<h2>What is compared</h2><ul class=\"meta\">";
  if (AnyColour(report)) {
    html << "<li>&Delta;E<sub>00</sub> (CIEDE2000) between measured and predicted colour of "
            "the polished metal, over "
         << Escape(ColourRangeText(report)) << ".</li>";
  } else {
    std::string why;
    for (const HoldoutResult& h : report.holdouts) {
      if (why.empty()) why = h.colour_note;
    }
    html << "<li class=\"note\">&Delta;E<sub>00</sub> is <b>not available</b>: " << Escape(why)
         << ". The data carry no colour; n, k and reflectance are compared over "
            "the data's own wavelengths.</li>";
  }
  std::set<std::string> ranges;
  for (const HoldoutResult& h : report.holdouts) {
    if (!h.metric_range.empty()) ranges.insert(h.metric_range);
  }
  html << "<li>Reflectance RMS and maximum error (normal incidence), max |&Delta;n| and "
          "max |&Delta;k| over: ";
  size_t i = 0;
  for (const std::string& r : ranges) html << (i++ ? "; " : "") << Escape(r);
  html << ".</li></ul>";
  if (!report.dataset_warnings.empty()) {
    html << "<details><summary class=\"meta\">Data set warnings (" << report.dataset_warnings.size()
         << ")</summary><ul class=\"meta\">";
    for (const std::string& w : report.dataset_warnings) html << "<li>" << Escape(w) << "</li>";
    html << "</ul></details>";
  }

  WriteVerdict(report, html);
  WriteSummaryTables(report, html);
  WriteHonesty(report, html);

  html << "<h2>Held-out compositions</h2>";
  int holdout_index = 0;
  for (size_t s = 0; s < report.splits.size(); ++s) {
    const SplitResult& split = report.splits[s];
    html << "<h3>Trained on x = " << XList(split.train_x)
         << "; held out x = " << XList(split.holdout_x) << "</h3>";
    for (const auto& [method, error] : split.errors) {
      html << "<p class=\"note\">" << Escape(method) << " could not be built: " << Escape(error)
           << "</p>";
    }
    for (const auto& [method, warnings] : split.warnings) {
      if (warnings.empty()) continue;
      html << "<details><summary class=\"meta\">" << Escape(method) << ": " << warnings.size()
           << " warning(s)</summary><ul class=\"meta\">";
      for (const std::string& w : warnings) html << "<li>" << Escape(w) << "</li>";
      html << "</ul></details>";
    }
    for (const HoldoutResult& h : report.holdouts) {
      if (h.split == static_cast<int>(s)) WriteHoldout(report, h, holdout_index++, html);
    }
    WriteDrude(report, split, static_cast<int>(s), html);
  }
  html << "\n</body></html>\n";
  return html.str();
}

// ---------------------------------------------------------------------------------------
// Composition chart.

CompositionChart ComputeChart(const AlloyModel& model, const color::Colorimeter& colorimeter,
                              double x_from, double x_to, int steps, double angle_deg,
                              bool weight_labels) {
  if (steps < 2) throw Error("--steps: need at least 2 swatches, got " + std::to_string(steps));
  CompositionChart chart;
  chart.system = model.system().Name();
  chart.element_a = model.system().a.symbol;
  chart.element_b = model.system().b.symbol;
  chart.method = model.method();
  chart.illuminant = colorimeter.illuminant();
  chart.observer_deg = colorimeter.observer_deg();
  chart.angle_deg = angle_deg;
  chart.weight_labels = weight_labels;
  // Evenly spaced in the unit of the labels.
  const AlloySystem& system = model.system();
  const double lo = weight_labels ? WeightFromAtomicFraction(x_from, system) : x_from;
  const double hi = weight_labels ? WeightFromAtomicFraction(x_to, system) : x_to;
  for (int i = 0; i < steps; ++i) {
    const double t = lo + (hi - lo) * i / (steps - 1);
    const double x = i == 0           ? x_from
                     : i == steps - 1 ? x_to
                     : weight_labels  ? AtomicFromWeightFraction(t, system)
                                      : t;
    const color::ColorResult c = color::ColorFromXYZ(
        colorimeter,
        color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, model, x), angle_deg));
    const color::RGB& s = c.linear_srgb;
    chart.swatches.push_back({x, WeightFromAtomicFraction(x, model.system()), c.srgb8,
                              s.r < 0 || s.g < 0 || s.b < 0 || s.r > 1 || s.g > 1 || s.b > 1});
  }
  return chart;
}

namespace {

struct ChartLayout {
  int swatch, gap, margin;
};

ChartLayout LayoutOf(const CompositionChart& chart) {
  const int n = static_cast<int>(chart.swatches.size());
  const int swatch = n <= 16 ? 64 : std::max(4, 1000 / n);
  return {swatch, n <= 16 ? 6 : std::max(1, swatch / 10), 40};
}

}  // namespace

std::string ChartSvg(const CompositionChart& chart) {
  const ChartLayout l = LayoutOf(chart);
  const int n = static_cast<int>(chart.swatches.size());
  const int strip = n * l.swatch + (n - 1) * l.gap;
  const int width = std::max(strip + 2 * l.margin, 420);
  const int x0 = (width - strip) / 2, y0 = 48;
  const int height = y0 + l.swatch + 62;
  // Label every k-th swatch so that labels stay at least 40 px apart, and the last.
  const int every = std::max(1, (40 + l.swatch + l.gap - 1) / (l.swatch + l.gap));
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << " " << height
      << "\" font-family=\"Helvetica, Arial, sans-serif\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  svg << "<text x=\"" << width / 2 << "\" y=\"20\" text-anchor=\"middle\" font-size=\"15\" "
      << "font-weight=\"bold\">" << Escape(chart.system) << ": colour by composition</text>\n";
  svg << "<text x=\"" << width / 2 << "\" y=\"37\" text-anchor=\"middle\" font-size=\"11\" "
      << "fill=\"#555\">" << Escape(chart.method) << " model; " << Escape(chart.illuminant) << ", "
      << chart.observer_deg << "\u00b0 observer, incidence " << Num(chart.angle_deg)
      << "\u00b0; sRGB</text>\n";
  const char* unit = chart.weight_labels ? "wt%" : "at%";
  for (int i = 0; i < n; ++i) {
    const ChartSwatch& s = chart.swatches[i];
    const int x = x0 + i * (l.swatch + l.gap);
    const std::string hex = color::HexColor(s.srgb8);
    svg << "<rect class=\"swatch\" x=\"" << x << "\" y=\"" << y0 << "\" width=\"" << l.swatch
        << "\" height=\"" << l.swatch << "\" fill=\"" << hex << "\" stroke=\"#777\" "
        << "stroke-width=\"0.5\"><title>x = " << Num(s.x_atomic, "%.4g") << " ("
        << Num(100 * s.x_weight, "%.4g") << " wt% " << Escape(chart.element_a) << "): " << hex
        << (s.clipped ? ", outside the sRGB gamut (clipped)" : "") << "</title></rect>\n";
    if (i % every == 0 || i == n - 1) {
      const double pct = 100 * (chart.weight_labels ? s.x_weight : s.x_atomic);
      svg << "<text x=\"" << x + l.swatch / 2.0 << "\" y=\"" << y0 + l.swatch + 15
          << "\" text-anchor=\"middle\" font-size=\"12\">" << Num(pct, "%.3g") << "</text>\n";
      if (l.swatch >= 48) {
        svg << "<text x=\"" << x + l.swatch / 2.0 << "\" y=\"" << y0 + l.swatch + 28
            << "\" text-anchor=\"middle\" font-size=\"9\" fill=\"#777\">" << hex << "</text>\n";
      }
    }
  }
  const bool rising = chart.swatches.back().x_atomic >= chart.swatches.front().x_atomic;
  const auto end_label = [&](double x) {
    if (x <= 1e-9) return std::string(chart.element_b);
    if (x >= 1 - 1e-9) return std::string(chart.element_a);
    return std::string();
  };
  const std::string left = end_label(chart.swatches.front().x_atomic);
  const std::string right = end_label(chart.swatches.back().x_atomic);
  if (!left.empty()) {
    svg << "<text x=\"" << x0 - 6 << "\" y=\"" << y0 + l.swatch / 2 + 5
        << "\" text-anchor=\"end\" font-size=\"14\" font-weight=\"bold\">" << left << "</text>\n";
  }
  if (!right.empty()) {
    svg << "<text x=\"" << x0 + strip + 6 << "\" y=\"" << y0 + l.swatch / 2 + 5
        << "\" font-size=\"14\" font-weight=\"bold\">" << right << "</text>\n";
  }
  svg << "<text x=\"" << width / 2 << "\" y=\"" << height - 10
      << "\" text-anchor=\"middle\" font-size=\"12\" fill=\"#333\">" << unit << " "
      << Escape(chart.element_a) << (rising ? " \u2192" : " \u2190") << "</text>\n";
  svg << "</svg>\n";
  return svg.str();
}

render::ImageRGBA8 ChartImage(const CompositionChart& chart, int swatch_px, int gap_px) {
  const int n = static_cast<int>(chart.swatches.size());
  render::ImageRGBA8 image(n * swatch_px + (n + 1) * gap_px, swatch_px + 2 * gap_px);
  std::fill(image.rgba.begin(), image.rgba.end(), 255);
  for (int i = 0; i < n; ++i) {
    const int x0 = gap_px + i * (swatch_px + gap_px);
    for (int y = gap_px; y < gap_px + swatch_px; ++y) {
      for (int x = x0; x < x0 + swatch_px; ++x) {
        std::uint8_t* p = image.Pixel(x, y);
        for (int c = 0; c < 3; ++c) p[c] = chart.swatches[i].srgb8[c];
      }
    }
  }
  return image;
}

}  // namespace alloycolor::app
