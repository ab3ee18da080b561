// The error bars of a fitted model (model/alloy_model.h PredictionError): the scale of its
// interpolation error from the leave-one-composition-out folds, calibrated on their colour
// errors; what it misses at its own training compositions; the scatter of replicate
// samples; and the resolution of the data.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>

#include "alloycolor/color/material_color.h"
#include "alloycolor/color/sample_error.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/spectrum.h"
#include "alloycolor/core/text.h"
#include "folds.h"

namespace alloycolor::fit {
namespace {

// The power of the gap in B where the data cannot measure it: the method's
// (MethodTraits::gap_exponent), and 2 for every method on three compositions, whose one
// fold is the straight line between the ends.
double GapExponent(const MethodInfo& method, const Dataset& dataset) {
  return DistinctCompositions(dataset).size() == 3 ? 2.0 : method.traits.gap_exponent;
}

// The finest decimal step the printed values need (1e-3 for "1.140", "2.5"): what a file's
// digits can resolve.
double DecimalStep(const std::vector<double>& values) {
  int decimals = 0;
  for (double v : values) {
    int d = 0;
    double scaled = std::abs(v);
    while (d < 12 && std::abs(scaled - std::round(scaled)) > 1e-6 * std::max(1.0, scaled)) {
      scaled *= 10;
      ++d;
    }
    decimals = std::max(decimals, d);
    if (decimals == 12) break;  // no finer step is counted
  }
  return std::pow(10.0, -decimals);
}

// The relative eps error of one measurement: n and k each off by the precision the
// manifest states (Dataset::precision_n, _k), or where it states none by a typical
// measurement's (kTypicalPrecisionNk), or where larger by what the data's digits can
// resolve (up to half a step: a uniform error, standard deviation step / sqrt(12)), so
// |d eps| / |eps| = 2 sqrt(sd_n^2 + sd_k^2) / |n + i k|; the median over the samples'
// wavelengths inside [lo, hi].
double MeasurementPrecision(const Dataset& dataset, double lo, double hi) {
  std::vector<double> relative;
  const double stated_n = dataset.precision_stated ? dataset.precision_n : kTypicalPrecisionNk;
  const double stated_k = dataset.precision_stated ? dataset.precision_k : kTypicalPrecisionNk;
  for (const Sample& s : dataset.samples) {
    const double sd_n = std::max(stated_n, DecimalStep(s.nk.n) / std::sqrt(12.0));
    const double sd_k = std::max(stated_k, DecimalStep(s.nk.k) / std::sqrt(12.0));
    for (size_t j = 0; j < s.nk.lambda_nm.size(); ++j) {
      if (s.nk.lambda_nm[j] < lo || s.nk.lambda_nm[j] > hi) continue;
      const double size = std::hypot(s.nk.n[j], s.nk.k[j]);
      if (size > 0) relative.push_back(2 * std::hypot(sd_n, sd_k) / size);
    }
  }
  if (relative.empty()) return 0;
  std::nth_element(relative.begin(), relative.begin() + relative.size() / 2, relative.end());
  return std::min(relative[relative.size() / 2], 1.0);
}

// The wavelengths of the misfit spectra: 5 nm over the colorimeters' 360-830 nm where the
// model covers it, and 60 more spread evenly in log wavelength over the model's range.
std::vector<double> MisfitGrid(double lo, double hi) {
  std::vector<double> grid;
  for (double l = 360; l <= 830 + 1e-9; l += 5) {
    if (l >= lo && l <= hi) grid.push_back(l);
  }
  for (int i = 0; i <= 60; ++i) grid.push_back(lo * std::pow(hi / lo, i / 60.0));
  grid.front() = std::max(grid.front(), lo);
  std::sort(grid.begin(), grid.end());
  std::vector<double> out;
  for (double l : grid) {
    l = std::clamp(l, lo, hi);
    if (out.empty() || l > out.back() * (1 + 1e-9)) out.push_back(l);
  }
  return out;
}

std::complex<double> Bounded(std::complex<double> v) {
  if (!std::isfinite(v.real()) || !std::isfinite(v.imag())) return 0.0;
  return {std::clamp(v.real(), -100.0, 100.0), std::clamp(v.imag(), -100.0, 100.0)};
}

// The model's misfit at each training composition and the replicates' scatter (see
// PredictionError), on `grid`.
void AddMisfit(const Dataset& dataset, const AlloyModel& model, const std::vector<double>& grid,
               PredictionError* error) {
  const std::vector<double> xs = DistinctCompositions(dataset);
  std::vector<std::vector<std::complex<double>>> misfit;
  double largest = 0;
  for (double x : xs) {
    const std::vector<std::complex<double>> predicted = model.Permittivity(x, grid);
    std::vector<const Sample*> here;
    for (const Sample& s : dataset.samples) {
      if (s.x_atomic == x) here.push_back(&s);
    }
    std::vector<std::complex<double>> mean(grid.size(), 0.0);
    std::vector<std::vector<std::complex<double>>> eps(here.size());
    for (size_t r = 0; r < here.size(); ++r) {
      // The grid's wavelengths the sample covers, [first, last): its own eps there.
      const NkSpectrum& nk = here[r]->nk;
      const size_t first =
          std::lower_bound(grid.begin(), grid.end(), nk.lambda_min_nm()) - grid.begin();
      const size_t last = std::max(
          first,
          static_cast<size_t>(std::upper_bound(grid.begin(), grid.end(), nk.lambda_max_nm()) -
                              grid.begin()));
      const std::vector<std::complex<double>> index =
          NkOn(nk, std::vector<double>(grid.begin() + first, grid.begin() + last));
      for (size_t j = 0; j < grid.size(); ++j) {
        const bool covered = j >= first && j < last;
        eps[r].push_back(covered ? index[j - first] * index[j - first] : predicted[j]);
        mean[j] += eps[r][j] / static_cast<double>(here.size());
      }
    }
    std::vector<std::complex<double>> relative(grid.size());
    for (size_t j = 0; j < grid.size(); ++j) {
      relative[j] = Bounded((mean[j] - predicted[j]) / std::abs(predicted[j]));
      largest = std::max(largest, std::abs(relative[j]));
    }
    misfit.push_back(std::move(relative));
    if (here.size() < 2) continue;
    const double n = static_cast<double>(here.size());
    for (size_t r = 0; r < here.size(); ++r) {
      std::vector<std::complex<double>> deviation(grid.size());
      for (size_t j = 0; j < grid.size(); ++j) {
        deviation[j] = Bounded((eps[r][j] - mean[j]) / std::abs(mean[j]) * std::sqrt(n / (n - 1)));
      }
      error->scatter.push_back(std::move(deviation));
    }
  }
  // An interpolating method passes through its samples: no misfit to carry.
  if (largest > 1e-9) error->misfit = std::move(misfit);
  if (!error->misfit.empty() || !error->scatter.empty()) error->misfit_lambda_nm = grid;
}

// A fold's relative eps errors per wavelength, over its B (reference gap, end factor 1).
struct FoldErrors {
  Fold* fold = nullptr;
  std::vector<double> over_bump;  // per held-out sample and wavelength, flattened
  bool end = false;               // held out in an end interval of its training samples
  std::vector<double> sum_sq;     // per wavelength: its part of the scale's sum of squares
  int count = 0;                  // its held-out samples
};

// The end factor: how much larger the end folds' errors are than the interior ones'
// (geometric means of their RMS), where the folds have both; at least 1.
double EndFactor(const std::vector<FoldErrors>& errors) {
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
  if (folds_of[0] == 0 || folds_of[1] == 0) return 1;
  // Shrunk towards 1 as few folds say little: weight k / (k + 2), k the smaller group.
  const double k = std::min(folds_of[0], folds_of[1]);
  return std::clamp(std::exp(k / (k + 2) * (log_sum[1] / folds_of[1] - log_sum[0] / folds_of[0])),
                    1.0, 10.0);
}

// |predicted - eps| / |eps| of a sample's measured eps at a wavelength (may be NaN).
double RelativeEpsError(std::complex<double> predicted, const Sample& s, double lambda_nm) {
  const std::complex<double> nk = NkAt(s.nk, lambda_nm), e = nk * nk;
  return std::abs(predicted - e) / std::abs(e);
}

// A fold's RMS relative eps error at its held-out samples of composition x over B's shape
// 4 t (1 - t) there (no gap factor), and its gap; NaN where it says nothing.
std::pair<double, double> ShapedError(const Fold& f, double x, const std::vector<double>& grid) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!f.model) return {nan, nan};
  const size_t i =
      std::upper_bound(f.compositions.begin(), f.compositions.end(), x) - f.compositions.begin();
  if (i == 0 || i == f.compositions.size()) return {nan, nan};
  const double gap = f.compositions[i] - f.compositions[i - 1];
  const double t = (x - f.compositions[i - 1]) / gap;
  const double shape = 4 * t * (1 - t);
  const auto predicted = f.model->Permittivity(x, grid);
  double sum_sq = 0;
  int count = 0;
  for (const Sample* s : f.held) {
    if (s->x_atomic != x) continue;
    for (size_t j = 0; j < grid.size(); ++j) {
      const double r = RelativeEpsError(predicted[j], *s, grid[j]);
      if (std::isfinite(r)) sum_sq += r * r, ++count;
    }
  }
  if (count == 0 || !(sum_sq > 0) || !(shape > 0)) return {nan, gap};
  return {std::sqrt(sum_sq / count) / shape, gap};
}

// The power of the gap in B measured on the data (PredictionError::gap_exponent): single
// folds' compositions held out again together with the next composition (when that is
// interior too; pairs that share no composition, so about half as many fits again), and
// the error at each of the two against the same composition's single fold: the
// least-squares slope through 0 of log(error ratio) on log(gap ratio), errors over B's
// shape 4 t (1 - t), kept in 0..GapExponent. The data can only lower the method's
// exponent: scatter between samples does not shrink with the gap, so real series give
// well under 1, and as the delivered model's gaps are smaller than the folds' the law
// there is flatter still, never steeper, than the slope measured between the folds' gaps
// (on smooth curves with added scatter, an uncapped slope of 2 or more made the bars too
// narrow). The method's own where no pair can be held out (three compositions).
double MeasuredGapExponent(const MethodInfo& method, const std::vector<Fold>& singles,
                           const Dataset& dataset, const FitSettings& settings,
                           const AlloyModel& model, const std::vector<double>& grid) {
  const double fallback = GapExponent(method, dataset);
  const std::vector<double> xs = DistinctCompositions(dataset);
  std::vector<std::vector<double>> pairs;
  for (const Fold& f : singles) {
    const size_t i = std::lower_bound(xs.begin(), xs.end(), f.x) - xs.begin();
    const bool taken = !pairs.empty() && pairs.back()[1] == f.x;
    if (f.model && !taken && i + 2 < xs.size()) pairs.push_back({f.x, xs[i + 1]});
  }
  if (pairs.empty()) return fallback;
  const std::vector<Fold> together = FitFolds(method, dataset, settings, model, pairs);
  double num = 0, den = 0;
  for (size_t k = 0; k < pairs.size(); ++k) {
    for (const double x : pairs[k]) {
      const auto single =
          std::find_if(singles.begin(), singles.end(), [x](const Fold& f) { return f.x == x; });
      if (single == singles.end()) continue;
      const auto [e1, g1] = ShapedError(*single, x, grid);
      const auto [e2, g2] = ShapedError(together[k], x, grid);
      if (!(e1 > 0) || !(e2 > 0) || !(g2 > g1)) continue;
      const double lg = std::log(g2 / g1);
      num += std::log(e2 / e1) * lg;
      den += lg * lg;
    }
  }
  if (!(den > 0)) return fallback;
  return std::clamp(num / den, 0.0, fallback);
}

// The interpolation error's scale from the folds (nothing where no fold could be used),
// calibrated on their colour errors; sets each fold model's error too.
PredictionError FoldPredictionError(const MethodInfo& method, std::vector<Fold>& fitted,
                                    const Dataset& dataset, const FitSettings& settings,
                                    const AlloyModel& model) {
  const double lo = model.lambda_min_nm(), hi = model.lambda_max_nm();
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
  if (done.empty()) return {};
  const double reference_gap = gap_sum / done.size();
  const double gap_exponent = MeasuredGapExponent(method, fitted, dataset, settings, model, grid);
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
        const double r = RelativeEpsError(predicted[j], *s, grid[j]);
        fe.over_bump.push_back(std::isfinite(r) ? r / bump : 0.0);
      }
    }
    errors.push_back(std::move(fe));
  }
  if (errors.empty()) return {};
  const double end_factor = EndFactor(errors);
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
  if (count == 0) return {};
  PredictionError error;
  error.end_factor = end_factor;
  error.lambda_nm = grid;
  for (double v : sum_sq) error.scale.push_back(std::min(std::sqrt(v / count), 100.0));
  error.compositions = DistinctCompositions(dataset);
  error.reference_gap = reference_gap;
  error.gap_exponent = gap_exponent;
  error.folds = static_cast<int>(done.size());
  // Calibration on colour: the folds' observed against predicted one-sigma CIEDE2000
  // (SigmaCalibration), each fold's sigma from the scale of the other folds, so that its
  // own error does not enter it.
  if (settings.colorimeter != nullptr && CoversVisible(lo, hi)) {
    const color::Colorimeter& cm = *settings.colorimeter;
    std::vector<double> observed, predicted_sigma;
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
        const double e = color::DeltaE00(truth, predicted);
        if (!std::isfinite(e)) continue;
        observed.push_back(e);
        predicted_sigma.push_back(sigma);
        error.held_out.push_back({x, s->file, e, sigma});
      }
    }
    if (!observed.empty()) {
      error.calibration =
          SigmaCalibration(observed, predicted_sigma, static_cast<int>(errors.size()));
    }
  }
  return error;
}

}  // namespace

void RecordInSampleError(const Dataset& dataset, const FitSettings& settings, AlloyModel* model) {
  std::vector<InSampleError> rows;
  for (const Sample& s : dataset.samples) {
    InSampleError row;
    row.x_atomic = s.x_atomic;
    row.file = s.file;
    row.delta_e00 = std::nan("");
    try {
      if (settings.colorimeter != nullptr) {
        const color::SampleError e = color::ErrorAgainstSample(*settings.colorimeter, *model, s);
        row.delta_e00 = e.delta_e00;
        row.reflectance_rms = e.reflectance_rms;
      } else {
        row.reflectance_rms = std::nan("");
      }
    } catch (const Error& e) {
      model->AddWarning(model->method() + " cannot be compared with its own sample " + s.file +
                        ": " + e.what());
      continue;
    }
    if (!std::isfinite(row.reflectance_rms)) continue;
    const bool colour = std::isfinite(row.delta_e00);
    if (colour ? row.delta_e00 > kInSampleMissDe00
               : row.reflectance_rms > kInSampleMissReflectance) {
      char what[200];
      if (colour) {
        std::snprintf(what, sizeof what, "by CIEDE2000 %.3g (reflectance RMS %.3g)", row.delta_e00,
                      row.reflectance_rms);
      } else {
        std::snprintf(what, sizeof what, "by reflectance RMS %.3g", row.reflectance_rms);
      }
      model->AddWarning(model->method() + " misses its own sample " + s.file +
                        " (x = " + FormatNumber(s.x_atomic) + ") " + what +
                        "; its one-sigma there covers the miss");
    }
    rows.push_back(std::move(row));
  }
  model->set_in_sample(std::move(rows));
}

void CarryPredictionError(const Dataset& dataset, PredictionError error, AlloyModel* model) {
  error.misfit.clear();
  error.scatter.clear();
  error.misfit_lambda_nm.clear();
  AddMisfit(dataset, *model, MisfitGrid(model->lambda_min_nm(), model->lambda_max_nm()), &error);
  model->set_prediction_error(std::move(error));
}

double SigmaCalibration(const std::vector<double>& errors, const std::vector<double>& sigmas,
                        int folds) {
  // The one-sigma is the RMS colour difference of the draws: the folds' sum of squared
  // errors over that of their sigmas. A ratio of sums, not a mean of ratios: with two
  // folds, each sigma from the other fold's error, the ratios are about e1 / e2 and
  // e2 / e1, whose squares' mean grows without bound as the two errors part, though the
  // errors' scale is known no worse.
  double errors_sq = 0, sigmas_sq = 0;
  for (size_t k = 0; k < std::min(errors.size(), sigmas.size()); ++k) {
    if (!std::isfinite(errors[k]) || !(sigmas[k] > 0) || !std::isfinite(sigmas[k])) continue;
    errors_sq += errors[k] * errors[k];
    sigmas_sq += sigmas[k] * sigmas[k];
  }
  if (!(sigmas_sq > 0)) return 1;
  // The scale is estimated from `folds` errors: a new error over it is Student's t with
  // that many degrees of freedom, not normal, and the one-sigma is t's 84.1 % point (where
  // the normal's is 1): 1 + 1 / (2 k) + 1 / (4 k^2), Cornish and Fisher's expansion to the
  // second order (1.31 for two folds, against 1.32 exactly). One fold sets its own sigma.
  const double k = folds;
  const double t = folds >= 2 ? 1 + 1 / (2 * k) + 1 / (4 * k * k) : 1.0;
  return std::clamp(t * std::sqrt(errors_sq / sigmas_sq), 1e-3, 1e3);
}

void EstimatePredictionError(const MethodInfo& method, std::vector<Fold>& fitted,
                             const Dataset& dataset, const FitSettings& settings,
                             AlloyModel* model) {
  PredictionError error = FoldPredictionError(method, fitted, dataset, settings, *model);
  const double lo = model->lambda_min_nm(), hi = model->lambda_max_nm();
  AddMisfit(dataset, *model, MisfitGrid(lo, hi), &error);
  // No folds (two compositions): nothing was held out, so no error bar is claimed.
  if (!error.present()) return;
  error.precision = MeasurementPrecision(dataset, lo, hi);
  model->set_prediction_error(std::move(error));
}

}  // namespace alloycolor::fit
