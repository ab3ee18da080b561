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

std::vector<std::vector<std::complex<double>>> AlloyModel::CheckedDraws(
    double x_atomic, const std::vector<double>& lambda_nm, int count, std::uint32_t seed) const {
  std::vector<std::vector<std::complex<double>>> draws;
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

// The longest wavelength a model file may state: 1 mm, the far infrared's end. Beyond it
// the grids built over the range would not fit in memory.
constexpr double kMaxModelWavelengthNm = 1e6;

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

ParameterTable AlloyModel::Parameters(const std::vector<double>& xs) const {
  std::vector<double> lambda = {450, 550, 650};
  if (!(lambda_min_nm_ <= 450 && lambda_max_nm_ >= 650)) {
    lambda.clear();
    for (double f : {0.1, 0.5, 0.9}) {
      lambda.push_back(std::round(lambda_min_nm_ + (lambda_max_nm_ - lambda_min_nm_) * f));
    }
  }
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  constexpr int kDraws = 256;
  ParameterTable table;
  table.notes = {
      "tau = hbar / gamma and m*/m_e = e^2 hbar^2 N_e / (eps0 m_e (hbar wp)^2) from "
      "the pointwise Drude inversion of the " +
      method() + " model (eq. 11, 12)" +
      (HasUncertainty()
           ? "; sigma from " + std::to_string(kDraws) + " draws of the model's uncertainty"
           : "")};
  table.columns = {"N_e_m^-3"};
  for (double l : lambda) {
    std::ostringstream tau, mass;
    tau << "tau_fs@" << l << "nm";
    mass << "m*/m_e@" << l << "nm";
    table.columns.push_back(tau.str());
    table.columns.push_back(mass.str());
  }
  for (double x : xs) {
    const double n_e = FreeElectronDensityM3(x, system_);
    const auto draws = CheckedDraws(x, lambda, kDraws);
    std::vector<ParameterTable::Quantity> row = {{n_e, 0.0}};
    for (size_t i = 0; i < lambda.size(); ++i) {
      DrudePoint p;
      if (!DrudeAt(x, lambda[i], &p)) {
        row.push_back({kNaN, kNaN});
        row.push_back({kNaN, kNaN});
        continue;
      }
      const double tau = TauFsFromGammaEv(p.gamma_ev);
      const double mass = EffectiveMassRatio(n_e, p.wp2_ev2);
      double s_tau = 0, s_mass = 0;
      int used = 0;
      for (const auto& d : draws) {
        if (!DrudeInvertible(d[i].real(), d[i].imag())) continue;
        const DrudePoint q = InvertDrude(OmegaEvFromLambdaNm(lambda[i]), d[i].real(), d[i].imag());
        s_tau += std::pow(TauFsFromGammaEv(q.gamma_ev) - tau, 2);
        s_mass += std::pow(EffectiveMassRatio(n_e, q.wp2_ev2) - mass, 2);
        ++used;
      }
      row.push_back({tau, used ? std::sqrt(s_tau / used) : 0.0});
      row.push_back({mass, used ? std::sqrt(s_mass / used) : 0.0});
    }
    table.x_atomic.push_back(x);
    table.rows.push_back(std::move(row));
  }
  return table;
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

nlohmann::json AlloyModel::ToJson() const {
  nlohmann::json doc;
  doc["format"] = kModelFormatName;
  doc["version"] = kModelFormatVersion;
  doc["method"] = method();
  doc["system"] = {{"a", system_.a.symbol}, {"b", system_.b.symbol}};
  doc["composition"] = composition_;
  doc["x_range"] = {x_min_, x_max_};
  doc["lambda_range_nm"] = {lambda_min_nm_, lambda_max_nm_};
  nlohmann::json samples = nlohmann::json::array();
  for (const TrainingSample& s : training_) {
    samples.push_back(
        {{"x", s.x_atomic}, {"x_given", s.x_given}, {"file", s.file}, {"checksum", s.checksum}});
  }
  doc["training_samples"] = samples;
  doc["parameters"] = ParametersJson();
  nlohmann::json fit = fit_summary_.details;
  if (fit_summary_.present()) {
    fit["method"] = fit_summary_.solver;
    fit["degree"] = fit_summary_.degree;
    fit["final_cost"] = fit_summary_.final_cost;
    fit["iterations"] = fit_summary_.iterations;
    fit["converged"] = fit_summary_.converged;
    fit["termination"] = fit_summary_.termination;
    fit["rms_relative_eps"] = fit_summary_.rms_relative_eps;
  }
  if (fit_summary_.selection.present()) {
    nlohmann::json scores = nlohmann::json::array();
    for (const MethodScore& m : fit_summary_.selection.scores) {
      nlohmann::json row = {{"method", m.method}, {"folds", m.folds}};
      if (m.end_miss > 0) row["end_miss"] = m.end_miss;
      if (m.error.empty()) {
        row["mean"] = m.mean;
        row["max"] = m.max;
      } else {
        row["error"] = m.error;
      }
      scores.push_back(row);
    }
    fit["selection"] = {{"by", "auto: leave-one-composition-out on the training samples"},
                        {"metric", fit_summary_.selection.metric},
                        {"reason", fit_summary_.selection.reason},
                        {"scores", scores}};
  }
  doc["fit"] = fit;
  if (prediction_error_.present()) {
    const PredictionError& e = prediction_error_;
    doc["uncertainty"] = {
        {"estimated_by", "leave-one-composition-out over " + std::to_string(e.folds) +
                             " folds (relative eps error scale * B(x); docs/model-format.md)"},
        {"folds", e.folds},
        {"lambda_nm", e.lambda_nm},
        {"scale", e.scale},
        {"compositions", e.compositions},
        {"reference_gap", e.reference_gap},
        {"gap_exponent", e.gap_exponent},
        {"end_factor", e.end_factor},
        {"calibration", e.calibration}};
    nlohmann::json& u = doc["uncertainty"];
    if (e.precision > 0) u["precision"] = e.precision;
    const auto spectra = [](const std::vector<std::vector<std::complex<double>>>& list) {
      nlohmann::json a = nlohmann::json::array();
      for (const auto& v : list) {
        nlohmann::json re = nlohmann::json::array(), im = nlohmann::json::array();
        for (const auto& c : v) {
          re.push_back(c.real());
          im.push_back(c.imag());
        }
        a.push_back({{"re", re}, {"im", im}});
      }
      return a;
    };
    if (!e.misfit.empty() || !e.scatter.empty()) {
      u["misfit_lambda_nm"] = e.misfit_lambda_nm;
      if (!e.misfit.empty()) u["misfit"] = spectra(e.misfit);
      if (!e.scatter.empty()) u["scatter"] = spectra(e.scatter);
    }
  }
  if (!in_sample_.empty()) {
    nlohmann::json rows = nlohmann::json::array();
    for (const InSampleError& r : in_sample_) {
      nlohmann::json row = {{"x", r.x_atomic}, {"file", r.file}};
      row["delta_e00"] = std::isfinite(r.delta_e00) ? nlohmann::json(r.delta_e00) : nullptr;
      row["reflectance_rms"] = r.reflectance_rms;
      rows.push_back(row);
    }
    doc["in_sample"] = rows;
  }
  doc["warnings"] = warnings_;
  return doc;
}

namespace {

// Field access that names the culprit.
const nlohmann::json& Field(const nlohmann::json& doc, const char* key, const std::string& where) {
  if (!doc.is_object() || !doc.contains(key)) {
    throw Error(where + ": missing field '" + key + "'");
  }
  return doc.at(key);
}

double Number(const nlohmann::json& value, const std::string& where) {
  if (!value.is_number()) throw Error(where + ": expected a number");
  const double v = value.get<double>();
  if (!std::isfinite(v)) throw Error(where + ": not a finite number");
  return v;
}

std::string String(const nlohmann::json& value, const std::string& where) {
  if (!value.is_string()) throw Error(where + ": expected a string");
  return value.get<std::string>();
}

// Reads the model file's "training_samples": the compositions and files fitted.
void ReadTrainingSamples(const nlohmann::json& doc, std::vector<TrainingSample>* training) {
  const nlohmann::json& ts = Field(doc, "training_samples", "model");
  if (!ts.is_array()) throw Error("training_samples: expected an array");
  training->clear();
  for (size_t i = 0; i < ts.size(); ++i) {
    const std::string where = "training_samples[" + std::to_string(i) + "]";
    training->push_back({Number(Field(ts[i], "x", where), where + ".x"),
                         Number(Field(ts[i], "x_given", where), where + ".x_given"),
                         String(Field(ts[i], "file", where), where + ".file"),
                         String(Field(ts[i], "checksum", where), where + ".checksum")});
  }
}

// Reads the model file's optional "in_sample": the model's errors on its own samples.
void ReadInSample(const nlohmann::json& doc, std::vector<InSampleError>* in_sample) {
  in_sample->clear();
  if (!doc.contains("in_sample")) return;
  const nlohmann::json& rows = doc.at("in_sample");
  if (!rows.is_array()) throw Error("in_sample: expected an array");
  for (size_t i = 0; i < rows.size(); ++i) {
    const std::string where = "in_sample[" + std::to_string(i) + "]";
    InSampleError r;
    r.x_atomic = Number(Field(rows[i], "x", where), where + ".x");
    r.file = String(Field(rows[i], "file", where), where + ".file");
    const nlohmann::json& de = Field(rows[i], "delta_e00", where);
    r.delta_e00 = de.is_null() ? std::nan("") : Number(de, where + ".delta_e00");
    r.reflectance_rms =
        Number(Field(rows[i], "reflectance_rms", where), where + ".reflectance_rms");
    if (!(r.reflectance_rms >= 0) || (std::isfinite(r.delta_e00) && !(r.delta_e00 >= 0))) {
      throw Error(where + ": errors must be >= 0");
    }
    in_sample->push_back(std::move(r));
  }
}

// The list of numbers under key in the "uncertainty" object u.
std::vector<double> UncertaintyNumbers(const nlohmann::json& u, const char* key) {
  const nlohmann::json& a = Field(u, key, "uncertainty");
  if (!a.is_array()) throw Error(std::string("uncertainty.") + key + ": expected an array");
  std::vector<double> v;
  for (size_t i = 0; i < a.size(); ++i) {
    v.push_back(Number(a[i], std::string("uncertainty.") + key + "[" + std::to_string(i) + "]"));
  }
  return v;
}

// The list of complex spectra ({re, im}) under key in the "uncertainty" object u.
std::vector<std::vector<std::complex<double>>> UncertaintySpectra(const nlohmann::json& u,
                                                                  const char* key) {
  std::vector<std::vector<std::complex<double>>> list;
  const nlohmann::json& a = u.at(key);
  const std::string where = std::string("uncertainty.") + key;
  if (!a.is_array()) throw Error(where + ": expected an array");
  for (size_t r = 0; r < a.size(); ++r) {
    const std::string at = where + "[" + std::to_string(r) + "]";
    const nlohmann::json& re = Field(a[r], "re", at);
    const nlohmann::json& im = Field(a[r], "im", at);
    if (!re.is_array() || !im.is_array() || re.size() != im.size()) {
      throw Error(at + ": expected arrays re and im of one length");
    }
    std::vector<std::complex<double>> v;
    for (size_t j = 0; j < re.size(); ++j) {
      v.emplace_back(Number(re[j], at + ".re"), Number(im[j], at + ".im"));
    }
    list.push_back(std::move(v));
  }
  return list;
}

// The model file's "uncertainty" object as the model's prediction error.
PredictionError ReadPredictionError(const nlohmann::json& u) {
  if (!u.is_object()) throw Error("uncertainty: expected an object");
  PredictionError e;
  e.lambda_nm = UncertaintyNumbers(u, "lambda_nm");
  e.scale = UncertaintyNumbers(u, "scale");
  e.compositions = UncertaintyNumbers(u, "compositions");
  e.reference_gap = Number(Field(u, "reference_gap", "uncertainty"), "uncertainty.reference_gap");
  e.calibration = Number(Field(u, "calibration", "uncertainty"), "uncertainty.calibration");
  // Files before the gap exponent: B linear in the gap.
  if (u.contains("gap_exponent")) {
    e.gap_exponent = Number(u["gap_exponent"], "uncertainty.gap_exponent");
  }
  // Files before the end factor: every interval alike.
  if (u.contains("end_factor")) {
    e.end_factor = Number(u["end_factor"], "uncertainty.end_factor");
  }
  const double folds = Number(Field(u, "folds", "uncertainty"), "uncertainty.folds");
  if (folds != std::floor(folds) || folds < 0 || folds > 1e6) {
    throw Error("uncertainty.folds: expected a whole number >= 0");
  }
  e.folds = static_cast<int>(folds);
  if (u.contains("precision")) e.precision = Number(u["precision"], "uncertainty.precision");
  if (u.contains("misfit") || u.contains("scatter")) {
    e.misfit_lambda_nm = UncertaintyNumbers(u, "misfit_lambda_nm");
    if (u.contains("misfit")) e.misfit = UncertaintySpectra(u, "misfit");
    if (u.contains("scatter")) e.scatter = UncertaintySpectra(u, "scatter");
  }
  return e;
}

// Reads the solver's account in the model file's "fit" object: method, degree, cost,
// iterations, convergence.
void ReadSolverSummary(const nlohmann::json& fit, FitSummary* summary) {
  summary->solver = String(fit.at("method"), "fit.method");
  const double degree = Number(Field(fit, "degree", "fit"), "fit.degree");
  if (degree != std::floor(degree) || degree < -1 || degree > 100) {
    throw Error("fit.degree: expected a whole number");
  }
  summary->degree = static_cast<int>(degree);
  summary->final_cost = Number(Field(fit, "final_cost", "fit"), "fit.final_cost");
  const double iterations = Number(Field(fit, "iterations", "fit"), "fit.iterations");
  if (iterations != std::floor(iterations) || iterations < 0 || iterations > 1e9) {
    throw Error("fit.iterations: expected a whole number");
  }
  summary->iterations = static_cast<int>(iterations);
  const nlohmann::json& converged = Field(fit, "converged", "fit");
  if (!converged.is_boolean()) throw Error("fit.converged: expected true or false");
  summary->converged = converged.get<bool>();
  summary->termination = String(Field(fit, "termination", "fit"), "fit.termination");
  summary->rms_relative_eps = Number(Field(fit, "rms_relative_eps", "fit"), "fit.rms_relative_eps");
}

// Reads the model file's "fit.selection": how auto chose the method, with every score.
void ReadMethodSelection(const nlohmann::json& sel, MethodSelection* selection) {
  selection->metric = String(Field(sel, "metric", "fit.selection"), "fit.selection.metric");
  selection->reason = String(Field(sel, "reason", "fit.selection"), "fit.selection.reason");
  const nlohmann::json& scores = Field(sel, "scores", "fit.selection");
  if (!scores.is_array()) throw Error("fit.selection.scores: expected an array");
  for (size_t i = 0; i < scores.size(); ++i) {
    const std::string where = "fit.selection.scores[" + std::to_string(i) + "]";
    MethodScore m;
    m.method = String(Field(scores[i], "method", where), where + ".method");
    m.folds = static_cast<int>(Number(Field(scores[i], "folds", where), where + ".folds"));
    if (scores[i].contains("end_miss")) {
      m.end_miss = Number(scores[i].at("end_miss"), where + ".end_miss");
    }
    if (scores[i].contains("error")) {
      m.error = String(scores[i].at("error"), where + ".error");
    } else {
      m.mean = Number(Field(scores[i], "mean", where), where + ".mean");
      m.max = Number(Field(scores[i], "max", where), where + ".max");
    }
    selection->scores.push_back(m);
  }
}

// Reads the model file's "fit" object: the solver's account, auto's selection, and the
// method's own details.
void ReadFitSummary(const nlohmann::json& fit, FitSummary* summary) {
  if (!fit.is_object()) throw Error("fit: expected an object");
  if (fit.contains("method")) ReadSolverSummary(fit, summary);
  if (fit.contains("selection")) ReadMethodSelection(fit.at("selection"), &summary->selection);
  summary->details = fit;
  for (const char* key : {"method", "degree", "final_cost", "iterations", "converged",
                          "termination", "rms_relative_eps", "selection"}) {
    summary->details.erase(key);
  }
}

}  // namespace

void AlloyModel::ReadCommon(const nlohmann::json& doc) {
  // The caller has checked format and version; `where` prefixes come from the caller's
  // source name through the Error messages of the helpers above.
  const nlohmann::json& sys = Field(doc, "system", "model");
  system_.a = FindElement(String(Field(sys, "a", "system"), "system.a"));
  system_.b = FindElement(String(Field(sys, "b", "system"), "system.b"));
  composition_ = String(Field(doc, "composition", "model"), "composition");
  const nlohmann::json& xr = Field(doc, "x_range", "model");
  if (!xr.is_array() || xr.size() != 2) throw Error("x_range: expected [lo, hi]");
  x_min_ = Number(xr[0], "x_range[0]");
  x_max_ = Number(xr[1], "x_range[1]");
  const nlohmann::json& lr = Field(doc, "lambda_range_nm", "model");
  if (!lr.is_array() || lr.size() != 2) throw Error("lambda_range_nm: expected [lo, hi]");
  lambda_min_nm_ = Number(lr[0], "lambda_range_nm[0]");
  lambda_max_nm_ = Number(lr[1], "lambda_range_nm[1]");
  if (!(x_min_ <= x_max_) || !(lambda_min_nm_ < lambda_max_nm_)) {
    throw Error("x_range or lambda_range_nm: empty range");
  }
  if (!(x_min_ >= 0 && x_max_ <= 1)) throw Error("x_range: outside [0, 1]");
  if (!(lambda_min_nm_ > 0 && lambda_max_nm_ <= kMaxModelWavelengthNm)) {
    throw Error("lambda_range_nm: [" + FormatNumber(lambda_min_nm_) + ", " +
                FormatNumber(lambda_max_nm_) + "] lies outside (0, " +
                FormatNumber(kMaxModelWavelengthNm) + "] nm");
  }
  if (std::string(system_.a.symbol) == system_.b.symbol) {
    throw Error(std::string("system: a and b are both '") + system_.a.symbol + "'");
  }
  ReadTrainingSamples(doc, &training_);
  ReadInSample(doc, &in_sample_);
  prediction_error_ = PredictionError{};
  if (doc.contains("uncertainty")) set_prediction_error(ReadPredictionError(doc.at("uncertainty")));
  fit_summary_ = FitSummary{};
  if (doc.contains("fit")) ReadFitSummary(doc.at("fit"), &fit_summary_);
  warnings_.clear();
  if (doc.contains("warnings")) {
    const nlohmann::json& w = doc.at("warnings");
    if (!w.is_array()) throw Error("warnings: expected an array");
    for (const auto& line : w) warnings_.push_back(String(line, "warnings[]"));
  }
}

void CheckModelUsable(const AlloyModel& model) {
  const std::string name = model.source().empty() ? std::string() : model.source() + ": ";
  const double lo = model.lambda_min_nm(), hi = model.lambda_max_nm();
  const std::vector<double> native = model.native_grid_nm();
  if (!native.empty()) {
    const double tolerance = 1e-9 * hi;
    const auto [low, high] = std::minmax_element(native.begin(), native.end());
    if (!(std::abs(*low - lo) <= tolerance && std::abs(*high - hi) <= tolerance)) {
      throw Error(name + "parameters.lambda_nm: the grid runs " + FormatNumber(*low) + "-" +
                  FormatNumber(*high) + " nm, not over lambda_range_nm [" + FormatNumber(lo) +
                  ", " + FormatNumber(hi) + "]");
    }
  }
  // The colour tables' grid held inside the range (as the colour commands evaluate it), or
  // for a model outside the visible 101 wavelengths across its range; and the native grid.
  std::vector<double> colour;
  for (double l = 360.0; l <= 830.0; l += 5.0) colour.push_back(std::clamp(l, lo, hi));
  if (hi < 360.0 || lo > 830.0) {
    colour.clear();
    for (int i = 0; i <= 100; ++i) colour.push_back(lo + (hi - lo) * i / 100.0);
  }
  std::vector<double> lambda = colour;
  const size_t native_step = native.size() / 1000 + 1;
  for (size_t i = 0; i < native.size(); i += native_step) lambda.push_back(native[i]);
  std::vector<double> xs = {model.x_min(), model.x_max()};
  const auto& training = model.training_samples();
  const size_t training_step = training.size() / 25 + 1;
  for (size_t i = 0; i < training.size(); i += training_step) {
    if (training[i].x_atomic >= model.x_min() && training[i].x_atomic <= model.x_max()) {
      xs.push_back(training[i].x_atomic);
    }
  }
  for (double x : xs) model.Index(x, lambda);
  if (model.HasUncertainty()) {
    for (double x : {model.x_min(), 0.5 * (model.x_min() + model.x_max()), model.x_max()}) {
      model.CheckedDraws(x, colour);
    }
  }
}

std::unique_ptr<AlloyModel> ModelFromJson(const nlohmann::json& doc, const std::string& source) {
  try {
    if (!doc.is_object()) throw Error("not a JSON object");
    const std::string format = String(Field(doc, "format", "model"), "format");
    if (format != kModelFormatName) {
      throw Error("format is '" + format + "', expected '" + kModelFormatName + "'");
    }
    const nlohmann::json& version = Field(doc, "version", "model");
    std::int64_t version_number = 0;
    if (!WholeNumber(version, 0, INT64_MAX, &version_number) ||
        version_number != kModelFormatVersion) {
      throw Error("unsupported version " + version.dump() + " (this program reads version " +
                  std::to_string(kModelFormatVersion) + ")");
    }
    const std::string method = String(Field(doc, "method", "model"), "method");
    std::unique_ptr<AlloyModel> model = RequireMethod(method).read(doc, source);
    model->set_source(source);
    CheckModelUsable(*model);
    return model;
  } catch (const nlohmann::json::exception& e) {
    throw Error(source + ": damaged model: " + e.what());
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind(source + ":", 0) == 0) throw;
    throw Error(source + ": " + what);
  }
}

std::unique_ptr<AlloyModel> ReadModelFile(const std::string& path) {
  const std::string text = ReadFileText(path);
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text, RejectDuplicateKeys(path));
  } catch (const nlohmann::json::exception& e) {  // parse_error, or out_of_range for 1e999
    // Fail: the bytes nlohmann quotes ("last read: '\xFF'") made safe.
    Fail(path + ": not valid JSON (" + e.what() + ")");
  }
  return ModelFromJson(doc, path);
}

std::string ModelFileText(const AlloyModel& model) { return JsonText(model.ToJson(), 1) + "\n"; }

}  // namespace alloycolor
