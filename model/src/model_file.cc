// The model file (model/alloy_model.h, docs/model-format.md): AlloyModel::ToJson writes
// it, ReadCommon and the method readers read it back, ModelFromJson checks it can be used.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/text.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/registry.h"

namespace alloycolor {

namespace {

nlohmann::json SampleNotesJson(const std::vector<SampleNote>& notes) {
  nlohmann::json list = nlohmann::json::array();
  for (const SampleNote& n : notes) {
    nlohmann::json row = {{"file", n.file},
                          {"x", n.x_atomic},
                          {"x_given", n.x_given},
                          {"check", n.check},
                          {"reason", n.reason}};
    if (!n.figure_name.empty()) {
      row["figure"] = NumberOrNull(n.figure);
      row["figure_is"] = n.figure_name;
    }
    row["delta_e00"] = NumberOrNull(n.delta_e00);
    row["sigma_de00"] = NumberOrNull(n.sigma_de00);
    row["reflectance_rms"] = NumberOrNull(n.reflectance_rms);
    list.push_back(row);
  }
  return list;
}

nlohmann::json HistoryJson(const std::vector<HistoryEntry>& history) {
  nlohmann::json list = nlohmann::json::array();
  for (const HistoryEntry& h : history) {
    nlohmann::json added = nlohmann::json::array(), removed = nlohmann::json::array(),
                   changed = nlohmann::json::array();
    for (const AddedSample& a : h.added) {
      nlohmann::json row = {
          {"file", a.file}, {"x", a.x_atomic}, {"x_given", a.x_given}, {"checksum", a.checksum}};
      if (!a.verdict.empty()) {
        row["delta_e00"] = NumberOrNull(a.delta_e00);
        row["sigma_de00"] = NumberOrNull(a.sigma_de00);
        row["reflectance_rms"] = NumberOrNull(a.reflectance_rms);
        row["verdict"] = a.verdict;
      }
      added.push_back(row);
    }
    for (const auto& [list_of, out] : {std::pair{&h.removed, &removed}, {&h.changed, &changed}}) {
      for (const TrainingSample& t : *list_of) {
        out->push_back({{"file", t.file}, {"x", t.x_atomic}, {"checksum", t.checksum}});
      }
    }
    nlohmann::json entry = {
        {"date", h.date.empty() ? nlohmann::json(nullptr) : nlohmann::json(h.date)},
        {"method", h.method},
        {"samples", h.samples},
        {"added", added},
        {"removed", removed},
        {"changed", changed}};
    if (!h.previous_method.empty()) entry["previous_method"] = h.previous_method;
    list.push_back(entry);
  }
  return list;
}

}  // namespace

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
  if (!parameter_curves_.is_null()) doc["parameters"]["curves"] = parameter_curves_;
  if (!excluded_.empty()) doc["excluded_samples"] = SampleNotesJson(excluded_);
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
  if (samples_checked_) fit["suspect_samples"] = SampleNotesJson(suspects_);
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
  if (!history_.empty()) doc["history"] = HistoryJson(history_);
  doc["warnings"] = warnings_;
  return doc;
}

namespace {

// The longest wavelength a model file may state: 1 mm, the far infrared's end. Beyond it
// the grids built over the range would not fit in memory.
constexpr double kMaxModelWavelengthNm = 1e6;

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
// method's own details (suspect_samples is read by ReadSampleNotes).
void ReadFitSummary(const nlohmann::json& fit, FitSummary* summary) {
  if (!fit.is_object()) throw Error("fit: expected an object");
  if (fit.contains("method")) ReadSolverSummary(fit, summary);
  if (fit.contains("selection")) ReadMethodSelection(fit.at("selection"), &summary->selection);
  summary->details = fit;
  for (const char* key : {"method", "degree", "final_cost", "iterations", "converged",
                          "termination", "rms_relative_eps", "selection", "suspect_samples"}) {
    summary->details.erase(key);
  }
}

// A number or null (NaN) at `key` of `object`, absent: NaN.
double NumberOrNaN(const nlohmann::json& object, const char* key, const std::string& where) {
  if (!object.contains(key) || object.at(key).is_null()) return std::nan("");
  return Number(object.at(key), where + "." + key);
}

// Calls read(object, "where[i]") for each element of the array `list`, an object each.
template <typename F>
void ForEachObject(const nlohmann::json& list, const std::string& where, F read) {
  if (!list.is_array()) throw Error(where + ": expected an array");
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string at = where + "[" + std::to_string(i) + "]";
    if (!list[i].is_object()) throw Error(at + ": expected an object");
    read(list[i], at);
  }
}

// A list of sample notes (fit.suspect_samples, excluded_samples).
std::vector<SampleNote> ReadSampleNotes(const nlohmann::json& list, const std::string& where) {
  std::vector<SampleNote> notes;
  ForEachObject(list, where, [&notes](const nlohmann::json& row, const std::string& at) {
    SampleNote n;
    n.file = String(Field(row, "file", at), at + ".file");
    n.x_atomic = Number(Field(row, "x", at), at + ".x");
    n.x_given = row.contains("x_given") ? Number(row.at("x_given"), at + ".x_given") : n.x_atomic;
    n.check = String(Field(row, "check", at), at + ".check");
    n.reason = String(Field(row, "reason", at), at + ".reason");
    if (row.contains("figure_is")) {
      n.figure_name = String(row.at("figure_is"), at + ".figure_is");
      n.figure = NumberOrNaN(row, "figure", at);
    }
    n.delta_e00 = NumberOrNaN(row, "delta_e00", at);
    n.sigma_de00 = NumberOrNaN(row, "sigma_de00", at);
    n.reflectance_rms = NumberOrNaN(row, "reflectance_rms", at);
    notes.push_back(std::move(n));
  });
  return notes;
}

// The model file's "history": the model's lineage (HistoryEntry).
std::vector<HistoryEntry> ReadHistory(const nlohmann::json& list) {
  std::vector<HistoryEntry> history;
  ForEachObject(list, "history", [&history](const nlohmann::json& row, const std::string& at) {
    HistoryEntry h;
    const nlohmann::json& date = Field(row, "date", at);
    h.date = date.is_null() ? std::string() : String(date, at + ".date");
    h.method = String(Field(row, "method", at), at + ".method");
    if (row.contains("previous_method")) {
      h.previous_method = String(row.at("previous_method"), at + ".previous_method");
    }
    std::int64_t samples = 0;
    if (!WholeNumber(Field(row, "samples", at), 0, 1000000000, &samples)) {
      throw Error(at + ".samples: expected a whole number");
    }
    h.samples = static_cast<int>(samples);
    ForEachObject(Field(row, "added", at), at + ".added",
                  [&h](const nlohmann::json& a, const std::string& a_at) {
                    AddedSample s;
                    s.file = String(Field(a, "file", a_at), a_at + ".file");
                    s.x_atomic = Number(Field(a, "x", a_at), a_at + ".x");
                    s.x_given = a.contains("x_given") ? Number(a.at("x_given"), a_at + ".x_given")
                                                      : s.x_atomic;
                    if (a.contains("checksum"))
                      s.checksum = String(a.at("checksum"), a_at + ".checksum");
                    s.delta_e00 = NumberOrNaN(a, "delta_e00", a_at);
                    s.sigma_de00 = NumberOrNaN(a, "sigma_de00", a_at);
                    s.reflectance_rms = NumberOrNaN(a, "reflectance_rms", a_at);
                    if (a.contains("verdict"))
                      s.verdict = String(a.at("verdict"), a_at + ".verdict");
                    h.added.push_back(std::move(s));
                  });
    for (const auto& [key, out] : {std::pair{"removed", &h.removed}, {"changed", &h.changed}}) {
      ForEachObject(Field(row, key, at), at + "." + key,
                    [out = out](const nlohmann::json& l, const std::string& t_at) {
                      TrainingSample t{};
                      t.file = String(Field(l, "file", t_at), t_at + ".file");
                      t.x_atomic = Number(Field(l, "x", t_at), t_at + ".x");
                      t.x_given = t.x_atomic;
                      if (l.contains("checksum")) {
                        t.checksum = String(l.at("checksum"), t_at + ".checksum");
                      }
                      out->push_back(std::move(t));
                    });
    }
    history.push_back(std::move(h));
  });
  return history;
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
  suspects_.clear();
  samples_checked_ = false;
  if (doc.contains("fit") && doc.at("fit").contains("suspect_samples")) {
    set_suspect_samples(
        ReadSampleNotes(doc.at("fit").at("suspect_samples"), "fit.suspect_samples"));
  }
  excluded_ = doc.contains("excluded_samples")
                  ? ReadSampleNotes(doc.at("excluded_samples"), "excluded_samples")
                  : std::vector<SampleNote>{};
  history_ = doc.contains("history") ? ReadHistory(doc.at("history")) : std::vector<HistoryEntry>{};
  parameter_curves_ = nullptr;
  if (doc.contains("parameters") && doc.at("parameters").is_object() &&
      doc.at("parameters").contains("curves")) {
    parameter_curves_ = doc.at("parameters").at("curves");
    if (!parameter_curves_.is_object()) throw Error("parameters.curves: expected an object");
  }
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
  for (double l = kColourTableMinNm; l <= kColourTableMaxNm; l += kGridStepNm) {
    colour.push_back(std::clamp(l, lo, hi));
  }
  if (hi < kColourTableMinNm || lo > kColourTableMaxNm) {
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
  } catch (const nlohmann::json::exception& e) {         // parse_error, or out_of_range for 1e999
    Fail(path + ": not valid JSON (" + e.what() + ")");  // Fail: its bytes made safe
  }
  return ModelFromJson(doc, path);
}

std::string ModelFileText(const AlloyModel& model) { return JsonText(model.ToJson(), 1) + "\n"; }

}  // namespace alloycolor
