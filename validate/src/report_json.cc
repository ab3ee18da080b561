#include <cmath>

#include "alloycolor/validate/report.h"
#include "report_metrics.h"

namespace alloycolor::validate {

namespace {

// The measured Drude curves of one split's training and held-out samples.
nlohmann::json DrudeCurvesJson(const std::vector<DrudeCurve>& curves) {
  nlohmann::json drude = nlohmann::json::array();
  for (const DrudeCurve& c : curves) {
    nlohmann::json curve = {{"lambda_nm", c.lambda_nm}};
    const auto nulls = [](const std::vector<double>& v) {
      nlohmann::json a = nlohmann::json::array();
      for (double x : v) a.push_back(NumberOrNull(x));
      return a;
    };
    curve["train"] = {
        {"x", c.train_x}, {"tau_fs", nulls(c.train_tau_fs)}, {"mass_ratio", nulls(c.train_mass)}};
    curve["holdout"] = {{"x", c.holdout_x},
                        {"tau_fs", nulls(c.holdout_tau_fs)},
                        {"mass_ratio", nulls(c.holdout_mass)}};
    drude.push_back(curve);
  }
  return drude;
}

// One split: its training and held-out samples, errors, choices, in-sample errors, Drude curves.
nlohmann::json SplitJson(const SplitResult& s) {
  nlohmann::json split = {{"train_x", s.train_x},
                          {"holdout_x", s.holdout_x},
                          {"train_files", s.train_files},
                          {"holdout_files", s.holdout_files}};
  if (!s.errors.empty()) split["errors"] = s.errors;
  split["warnings"] = s.warnings;
  split["choices"] = s.choices;
  nlohmann::json in_sample = nlohmann::json::object();
  for (const auto& [method, rows] : s.in_sample) {
    nlohmann::json list = nlohmann::json::array();
    for (const InSampleError& r : rows) {
      list.push_back({{"x", r.x_atomic},
                      {"file", r.file},
                      {"delta_e00", NumberOrNull(r.delta_e00)},
                      {"reflectance_rms", NumberOrNull(r.reflectance_rms)}});
    }
    in_sample[method] = list;
  }
  split["in_sample"] = in_sample;
  split["drude_measured"] = DrudeCurvesJson(s.drude);
  return split;
}

// One method's scores on one held-out sample, or why it has none.
nlohmann::json MethodResultJson(const ValidationReport& report, const HoldoutResult& h,
                                const std::string& method) {
  const auto it = h.results.find(method);
  if (it == h.results.end()) {
    const auto& errors = report.splits[h.split].errors;
    const auto e = errors.find(method);
    return {{"error", e != errors.end() ? e->second : "not evaluated"}};
  }
  const MethodResult& r = it->second;
  if (r.lambda_nm.empty()) return {{"error", r.error}};
  nlohmann::json m = {{"delta_e00", ByAngle(report.angles_deg, r.delta_e00)},
                      {"reflectance_rms", r.reflectance_rms},
                      {"reflectance_max", r.reflectance_max},
                      {"n_max_abs", r.n_max_abs},
                      {"k_max_abs", r.k_max_abs},
                      {"delta_e00_sigma", ByAngle(report.angles_deg, r.delta_e00_sigma)},
                      {"srgb_hex", HexByAngle(report.angles_deg, r.srgb8)},
                      {"Lab", LabByAngle(report.angles_deg, r.lab)}};
  if (std::isfinite(r.x_recovered)) {
    m["recovered"] = {{"x_atomic", r.x_recovered},
                      {"x_sigma", NumberOrNull(r.x_recovered_sigma)},
                      {"error_at_percent", 100 * (r.x_recovered - h.x_atomic)}};
  }
  if (!r.error.empty()) m["note"] = r.error;
  return m;
}

// One held-out sample: what it is, its measured colour and every method's scores on it.
nlohmann::json HoldoutJson(const ValidationReport& report, const HoldoutResult& h) {
  nlohmann::json item = {{"x", h.x_atomic},
                         {"x_given", h.x_given},
                         {"file", h.file},
                         {"path", h.path},
                         {"replicate", h.replicate},
                         {"split", h.split},
                         {"train_x", report.splits[h.split].train_x},
                         {"metric_range", h.metric_range},
                         {"measured",
                          {{"srgb_hex", HexByAngle(report.angles_deg, h.srgb8)},
                           {"Lab", LabByAngle(report.angles_deg, h.lab)}}}};
  if (!h.colour_note.empty()) item["delta_e00_note"] = "not available: " + h.colour_note;
  if (!h.excluded.empty()) item["excluded"] = h.excluded;  // set aside: not in the summary
  nlohmann::json results = nlohmann::json::object();
  for (const std::string& method : report.methods) {
    results[method] = MethodResultJson(report, h, method);
  }
  item["results"] = results;
  return item;
}

// Every metric's count, mean, max and wins per method.
nlohmann::json SummaryJson(const ValidationReport& report) {
  nlohmann::json summary = nlohmann::json::object();
  for (const Metric& metric : Metrics(report)) {
    nlohmann::json row = nlohmann::json::object();
    for (const std::string& method : report.methods) {
      const MetricSummary s = Summarise(report, method, metric);
      row[method] = {{"count", s.count},
                     {"mean", NumberOrNull(s.mean)},
                     {"max", NumberOrNull(s.max)},
                     {"wins", s.wins}};
    }
    summary[metric.key] = row;
  }
  return summary;
}

// How often each method's colour errors fell within its own 1 and 2 sigma, per angle.
nlohmann::json SigmaHonestyJson(const ValidationReport& report) {
  nlohmann::json honesty = nlohmann::json::object();
  for (const std::string& method : report.methods) {
    for (size_t a = 0; a < report.angles_deg.size(); ++a) {
      const validate::SigmaCoverage s = validate::Coverage(report, method, static_cast<int>(a));
      if (s.count == 0) continue;
      const HonestyVerdict verdict = JudgeHonesty(s);
      honesty[method][Num(report.angles_deg[a])] = {
          {"count", s.count},
          {"within_1_sigma", s.within_1},
          {"within_2_sigma", s.within_2},
          {"median_observed_over_sigma", NumberOrNull(s.median_ratio)},
          {"verdict", verdict.kind},
          {"verdict_text", verdict.text}};
    }
  }
  return honesty;
}

// The composition recovered from each held-out sample's measured colour, per method.
nlohmann::json CompositionRecoveryJson(const ValidationReport& report) {
  nlohmann::json recovery = nlohmann::json::object();
  for (const std::string& method : report.methods) {
    const RecoverySummary s = Recovery(report, method);
    if (s.count == 0) continue;
    recovery[method] = {{"count", s.count},
                        {"mean_abs_error_at_percent", NumberOrNull(s.mean_abs_at_percent)},
                        {"with_sigma", s.with_sigma},
                        {"within_2_sigma", s.within_2}};
  }
  return recovery;
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
  for (const SplitResult& s : report.splits) splits.push_back(SplitJson(s));
  doc["splits"] = splits;
  nlohmann::json holdouts = nlohmann::json::array();
  for (const HoldoutResult& h : report.holdouts) holdouts.push_back(HoldoutJson(report, h));
  doc["holdouts"] = holdouts;
  doc["summary"] = SummaryJson(report);
  doc["sigma_honesty"] = SigmaHonestyJson(report);
  doc["composition_recovery"] = CompositionRecoveryJson(report);
  doc["dataset_warnings"] = report.dataset_warnings;
  if (report.whole.present()) doc["whole_data_set"] = WholeJson(report.whole);
  return doc;
}

// ---------------------------------------------------------------------------------------

}  // namespace alloycolor::validate
