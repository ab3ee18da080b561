#include "alloycolor/model/alloy_model.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/text.h"
#include "alloycolor/model/optics.h"
#include "alloycolor/model/registry.h"

namespace alloycolor {

const char* const kUncertaintyTooWide =
    "its uncertainty (parameters.covariance or uncertainty) is too wide to propagate; refit";

bool UsablePermittivity(double eps1, double eps2) {
  return std::abs(eps1) <= kMaxUsablePermittivity && std::abs(eps2) <= kMaxUsablePermittivity &&
         (eps1 != 0.0 || eps2 != 0.0);  // NaN fails the comparisons
}

namespace {

// Runs `evaluate`, an evaluation of `model`; an Error that does not name the model's source
// is given it in front.
template <typename F>
auto NamingSource(const AlloyModel& model, F evaluate) -> decltype(evaluate()) {
  try {
    return evaluate();
  } catch (const Error& e) {
    const std::string what = e.what();
    if (model.source().empty() || what.rfind(model.source() + ":", 0) == 0) throw;
    throw Error(model.source() + ": " + what);
  }
}

}  // namespace

std::vector<std::complex<double>> AlloyModel::Index(double x_atomic,
                                                    const std::vector<double>& lambda_nm) const {
  std::vector<std::complex<double>> eps =
      NamingSource(*this, [&] { return Permittivity(x_atomic, lambda_nm); });
  for (size_t i = 0; i < eps.size(); ++i) {
    std::complex<double>& e = eps[i];
    if (!UsablePermittivity(e.real(), e.imag())) FailUnusable(x_atomic, lambda_nm[i], e, false);
    const Complex<double> nk = IndexFromPermittivity(Complex<double>{e.real(), e.imag()});
    e = {nk.re, nk.im};
  }
  return eps;
}

int AlloyModel::TrainingCompositions() const {
  std::vector<double> xs;
  for (const TrainingSample& s : training_) xs.push_back(s.x_atomic);
  std::sort(xs.begin(), xs.end());
  return static_cast<int>(std::unique(xs.begin(), xs.end()) - xs.begin());
}

bool AlloyModel::HasUncertainty() const {
  // Measured on held-out folds (a fold's own model carries its parent's), or from terms of
  // the model's own where the data could have been held out.
  if (prediction_error_.present() && prediction_error_.folds > 0) return true;
  return TrainingCompositions() >= 3 && HasUncertaintyTerms();
}

std::string AlloyModel::NoErrorBarReason() const {
  if (HasUncertainty()) return "";
  const int compositions = TrainingCompositions();
  if (compositions < 3) {
    return "no error bar: " + std::to_string(compositions) + " composition" +
           (compositions == 1 ? "" : "s") +
           " (an error bar needs one held out, so three compositions or more)";
  }
  return "no error bar: the " + method() +
         " model was built without its leave-one-out error estimate";
}

std::vector<std::vector<std::complex<double>>> AlloyModel::CheckedDraws(
    double x_atomic, const std::vector<double>& lambda_nm, int count, std::uint32_t seed) const {
  std::vector<std::vector<std::complex<double>>> draws;
  if (!HasUncertainty()) return draws;
  try {
    draws = PermittivityDraws(x_atomic, lambda_nm, count, seed);
  } catch (const Error&) {  // a method that checks its own values (the smooth model)
    throw Error((source_.empty() ? std::string() : source_ + ": ") + "a draw of the " + method() +
                " model's uncertainty gives eps that is not finite at x = " +
                FormatNumber(x_atomic) + "; " + kUncertaintyTooWide);
  }
  for (const auto& draw : draws) {
    for (size_t i = 0; i < draw.size() && i < lambda_nm.size(); ++i) {
      if (!UsablePermittivity(draw[i].real(), draw[i].imag())) {
        FailUnusable(x_atomic, lambda_nm[i], draw[i], true);
      }
    }
  }
  return draws;
}

void AlloyModel::FailUnusable(double x_atomic, double lambda_nm, std::complex<double> eps,
                              bool draw) const {
  const std::string value = "eps = " + FormatNumber(eps.real()) + (eps.imag() < 0 ? "" : "+") +
                            FormatNumber(eps.imag()) + "i";
  const std::string where = " at x = " + FormatNumber(x_atomic) + ", " + FormatNumber(lambda_nm) +
                            " nm (" + value + ": not finite, zero or beyond 1e30)";
  const std::string name = source_.empty() ? std::string() : source_ + ": ";
  if (draw) {
    throw Error(name + "a draw of the " + method() + " model's uncertainty gives no usable " +
                "permittivity" + where + "; " + kUncertaintyTooWide);
  }
  throw Error(name + "the " + method() + " model gives no usable permittivity" + where +
              "; its parameters cannot be used there");
}

namespace {

// Any model on a grid, through AlloyModel::Permittivity.
class GenericBoundModel : public BoundModel {
 public:
  GenericBoundModel(const AlloyModel& model, std::vector<double> lambda_nm)
      : BoundModel(std::move(lambda_nm)), model_(model) {}
  void Permittivity(double x_atomic, double* eps1, double* eps2) const override {
    const std::vector<std::complex<double>> e =
        NamingSource(model_, [&] { return model_.Permittivity(x_atomic, lambda_nm()); });
    for (size_t i = 0; i < e.size(); ++i) {
      if (!UsablePermittivity(e[i].real(), e[i].imag())) {
        model_.FailUnusable(x_atomic, lambda_nm()[i], e[i], false);
      }
      eps1[i] = e[i].real();
      eps2[i] = e[i].imag();
    }
  }

 private:
  const AlloyModel& model_;
};

}  // namespace

std::vector<Complex<double>> BoundModel::Permittivity(double x_atomic) const {
  const size_t m = lambda_nm_.size();
  std::vector<double> eps1(m), eps2(m);
  Permittivity(x_atomic, eps1.data(), eps2.data());
  std::vector<Complex<double>> eps(m);
  for (size_t i = 0; i < m; ++i) eps[i] = {eps1[i], eps2[i]};
  return eps;
}

std::unique_ptr<BoundModel> AlloyModel::Bind(const std::vector<double>& lambda_nm) const {
  CheckLambda(lambda_nm);
  return std::make_unique<GenericBoundModel>(*this, lambda_nm);
}

double PredictionError::Bump(double x) const {
  const size_t n = compositions.size();
  size_t hi = std::upper_bound(compositions.begin(), compositions.end(), x) - compositions.begin();
  hi = std::clamp<size_t>(hi, 1, n - 1);
  const double h = compositions[hi] - compositions[hi - 1];
  const double t = (x - compositions[hi - 1]) / h;
  const bool end = n > 2 && (hi == 1 || hi == n - 1);
  return (end ? end_factor : 1.0) * 4 * std::abs(t * (1 - t)) *
         std::pow(h / reference_gap, gap_exponent);
}

double PredictionError::ScaleAt(double l) const {
  if (l <= lambda_nm.front()) return scale.front();
  if (l >= lambda_nm.back()) return scale.back();
  const size_t hi = std::upper_bound(lambda_nm.begin(), lambda_nm.end(), l) - lambda_nm.begin();
  const double t = (l - lambda_nm[hi - 1]) / (lambda_nm[hi] - lambda_nm[hi - 1]);
  return scale[hi - 1] + (scale[hi] - scale[hi - 1]) * t;
}

namespace {

// Position of l on an increasing grid: the interval's upper index and the fraction.
std::pair<size_t, double> GridPosition(const std::vector<double>& grid, double l) {
  if (l <= grid.front()) return {1, 0.0};
  if (l >= grid.back()) return {grid.size() - 1, 1.0};
  const size_t hi = std::upper_bound(grid.begin(), grid.end(), l) - grid.begin();
  return {hi, (l - grid[hi - 1]) / (grid[hi] - grid[hi - 1])};
}

std::complex<double> SpectrumAt(const std::vector<double>& grid,
                                const std::vector<std::complex<double>>& values, double l) {
  const auto [hi, t] = GridPosition(grid, l);
  return values[hi - 1] + (values[hi] - values[hi - 1]) * t;
}

}  // namespace

std::complex<double> PredictionError::MisfitAt(double x, double l) const {
  if (misfit.empty() || misfit_lambda_nm.empty()) return 0.0;
  const auto [hi, t] = GridPosition(compositions, x);
  return SpectrumAt(misfit_lambda_nm, misfit[hi - 1], l) * (1 - t) +
         SpectrumAt(misfit_lambda_nm, misfit[hi], l) * t;
}

std::complex<double> PredictionError::ScatterAt(size_t r, double l) const {
  return SpectrumAt(misfit_lambda_nm, scatter[r], l);
}

void AlloyModel::set_prediction_error(PredictionError e) {
  const std::string where = "uncertainty.";
  if (e.lambda_nm.size() < 2 || e.scale.size() != e.lambda_nm.size()) {
    throw Error(where + "scale: one value per wavelength of lambda_nm, two at least");
  }
  for (size_t j = 0; j < e.lambda_nm.size(); ++j) {
    if (!std::isfinite(e.lambda_nm[j]) || (j > 0 && !(e.lambda_nm[j] > e.lambda_nm[j - 1]))) {
      throw Error(where + "lambda_nm: must increase");
    }
    // A relative error of 100 between samples already says "no idea"; more overflows.
    if (!(e.scale[j] >= 0 && e.scale[j] <= 100)) throw Error(where + "scale: must lie in 0..100");
  }
  if (e.compositions.size() < 2) throw Error(where + "compositions: two at least");
  for (size_t i = 0; i < e.compositions.size(); ++i) {
    if (!std::isfinite(e.compositions[i]) ||
        (i > 0 && !(e.compositions[i] > e.compositions[i - 1]))) {
      throw Error(where + "compositions: must increase");
    }
  }
  if (!(e.reference_gap > 0 && e.reference_gap <= 1e6)) {
    throw Error(where + "reference_gap: must be positive");
  }
  if (!(e.gap_exponent >= 0 && e.gap_exponent <= 4)) {
    throw Error(where + "gap_exponent: must lie in 0..4");
  }
  if (!(e.end_factor >= 1 && e.end_factor <= 100)) {
    throw Error(where + "end_factor: must lie in 1..100");
  }
  if (!(e.calibration > 0 && e.calibration <= 1e3)) {
    throw Error(where + "calibration: must lie in (0, 1000]");
  }
  if (!(e.precision >= 0 && e.precision <= 1)) throw Error(where + "precision: must lie in 0..1");
  const auto check_spectra = [&](const char* key,
                                 const std::vector<std::vector<std::complex<double>>>& spectra) {
    for (const auto& v : spectra) {
      if (v.size() != e.misfit_lambda_nm.size()) {
        throw Error(where + key + ": one value per wavelength of misfit_lambda_nm");
      }
      for (const auto& c : v) {
        // A relative error of 100 already says "no idea"; more overflows the draws.
        if (!(std::abs(c.real()) <= 100 && std::abs(c.imag()) <= 100)) {
          throw Error(where + key + ": values must lie in -100..100");
        }
      }
    }
  };
  if (!e.misfit.empty() || !e.scatter.empty()) {
    if (e.misfit_lambda_nm.size() < 2) throw Error(where + "misfit_lambda_nm: two at least");
    for (size_t j = 1; j < e.misfit_lambda_nm.size(); ++j) {
      if (!(e.misfit_lambda_nm[j] > e.misfit_lambda_nm[j - 1])) {
        throw Error(where + "misfit_lambda_nm: must increase");
      }
    }
    if (!e.misfit.empty() && e.misfit.size() != e.compositions.size()) {
      throw Error(where + "misfit: one spectrum per composition");
    }
    check_spectra("misfit", e.misfit);
    check_spectra("scatter", e.scatter);
  }
  prediction_error_ = std::move(e);
}

std::vector<std::vector<std::complex<double>>> AlloyModel::PermittivityDraws(
    double x_atomic, const std::vector<double>& lambda_nm, int count, std::uint32_t seed) const {
  if (!prediction_error_.present()) return {};
  const PredictionError& e = prediction_error_;
  const std::vector<std::complex<double>> centre = Permittivity(x_atomic, lambda_nm);
  const double amplitude = e.calibration * e.Bump(x_atomic) / std::sqrt(2.0);
  std::vector<double> scale(lambda_nm.size());
  for (size_t i = 0; i < lambda_nm.size(); ++i) scale[i] = amplitude * e.ScaleAt(lambda_nm[i]);
  // The misfit and scatter spectra on the draws' grid (relative to |eps|).
  std::vector<std::complex<double>> misfit(lambda_nm.size(), 0.0);
  std::vector<std::vector<std::complex<double>>> scatter(e.scatter.size());
  for (size_t i = 0; i < lambda_nm.size(); ++i) misfit[i] = e.MisfitAt(x_atomic, lambda_nm[i]);
  for (size_t r = 0; r < scatter.size(); ++r) {
    for (double l : lambda_nm) scatter[r].push_back(e.ScatterAt(r, l));
  }
  std::mt19937 rng(seed);
  std::mt19937 precision_rng(seed + 1);  // apart, so that the scale's draws stay as they were
  std::normal_distribution<double> normal;
  std::vector<std::vector<std::complex<double>>> draws(count, centre);
  // Antithetic pairs: draw 2k + 1 takes the normal terms of draw 2k with the other sign,
  // so that no pair comes nearer the misfit's point than the misfit alone.
  std::complex<double> z, noise;
  for (int d = 0; d < count; ++d) {
    if (d % 2 == 0) {
      z = {normal(rng), normal(rng)};
      if (e.precision > 0) noise = {normal(precision_rng), normal(precision_rng)};
    } else {
      z = -z;
      noise = -noise;
    }
    const double scatter_sign = (d / 2) % 2 == 0 ? 1.0 : -1.0;
    const std::vector<std::complex<double>>* replicate =
        scatter.empty() ? nullptr : &scatter[(d / 4) % scatter.size()];
    const std::complex<double> floor = e.precision / std::sqrt(2.0) * noise;
    for (size_t i = 0; i < centre.size(); ++i) {
      std::complex<double> relative = scale[i] * z + misfit[i] + floor;
      if (replicate != nullptr) relative += scatter_sign * (*replicate)[i];
      std::complex<double> v = centre[i] + std::abs(centre[i]) * relative;
      if (v.imag() < 0) v.imag(0.0);  // a draw stays passive
      draws[d][i] = v;
    }
  }
  return draws;
}

bool AlloyModel::DrudeAt(double x_atomic, double lambda_nm, DrudePoint* out) const {
  if (!(lambda_nm >= lambda_min_nm_ - 1e-9 && lambda_nm <= lambda_max_nm_ + 1e-9)) return false;
  const std::complex<double> eps =
      Permittivity(x_atomic, {std::clamp(lambda_nm, lambda_min_nm_, lambda_max_nm_)})[0];
  if (!DrudeInvertible(eps.real(), eps.imag())) return false;
  *out = InvertDrude(OmegaEvFromLambdaNm(lambda_nm), eps.real(), eps.imag());
  return true;
}

std::string SigmaVerdict(double error, double sigma) {
  if (!(sigma > 0) || !std::isfinite(sigma)) return "no error bar";
  if (!std::isfinite(error)) return "no error";
  if (error <= sigma) return "within one sigma";
  if (error <= 2 * sigma) return "within two sigma";
  return "beyond two sigma";
}

void AlloyModel::CheckInRange(double x_atomic) const {
  if (!(x_atomic >= x_min_ - 1e-9 && x_atomic <= x_max_ + 1e-9)) {
    std::ostringstream msg;
    msg << "composition x = " << x_atomic << " lies outside the fitted range [" << x_min_ << ", "
        << x_max_ << "] of the " << method() << " model (use --extrapolate)";
    throw Error(msg.str());
  }
}

void AlloyModel::CheckLambda(const std::vector<double>& lambda_nm) const {
  for (double l : lambda_nm) {
    if (!(l >= lambda_min_nm_ - 1e-9 && l <= lambda_max_nm_ + 1e-9)) {
      std::ostringstream msg;
      msg << "wavelength " << l << " nm lies outside the " << method() << " model's range "
          << lambda_min_nm_ << "-" << lambda_max_nm_ << " nm";
      throw Error(msg.str());
    }
  }
}

void AlloyModel::SetCommon(const Dataset& dataset, double lambda_min_nm, double lambda_max_nm) {
  system_ = dataset.system;
  composition_ = dataset.composition;
  training_.clear();
  for (const Sample& s : dataset.samples) {
    training_.push_back({s.x_atomic, s.x_given, s.file, s.checksum});
  }
  if (training_.empty()) throw Error(dataset.manifest_path + ": no samples");
  source_ = dataset.manifest_path;
  x_min_ = training_.front().x_atomic;
  x_max_ = training_.back().x_atomic;
  lambda_min_nm_ = lambda_min_nm;
  lambda_max_nm_ = lambda_max_nm;
}

}  // namespace alloycolor
