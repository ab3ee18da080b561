#include "report_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "alloycolor/color/material_color.h"

namespace alloycolor::validate {

std::string Num(double v, const char* format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::string XList(const std::vector<double>& xs) {
  std::string s;
  for (double x : xs) s += (s.empty() ? "" : ", ") + Num(x, "%.4g");
  return s;
}

namespace {

double DeltaE00Value(const MethodResult& r, int angle) {
  return angle < static_cast<int>(r.delta_e00.size()) ? r.delta_e00[angle] : kNaN;
}

}  // namespace

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

double ValueOf(const HoldoutResult& h, const std::string& method, const Metric& metric) {
  const auto it = h.results.find(method);
  if (it == h.results.end() || it->second.lambda_nm.empty()) return kNaN;
  return metric.value(it->second, metric.angle);
}

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

MetricSummary Summarise(const ValidationReport& report, const std::string& method,
                        const Metric& metric) {
  MetricSummary s;
  double sum = 0;
  for (const HoldoutResult& h : report.holdouts) {
    const double v = ValueOf(h, method, metric);
    if (!std::isfinite(v) || !h.excluded.empty()) continue;  // set aside: shown, not counted
    ++s.count;
    sum += v;
    s.max = s.count == 1 ? v : std::max(s.max, v);
    if (Best(report, h, metric).count(method)) ++s.wins;
  }
  if (s.count > 0) s.mean = sum / s.count;
  return s;
}

nlohmann::json ByAngle(const std::vector<double>& angles, const std::vector<double>& values) {
  if (values.empty()) return nullptr;
  nlohmann::json out = nlohmann::json::object();
  for (size_t a = 0; a < angles.size() && a < values.size(); ++a) {
    out[Num(angles[a])] = NumberOrNull(values[a]);
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

}  // namespace alloycolor::validate
