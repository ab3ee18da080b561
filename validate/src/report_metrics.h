// What the report writers share: the metrics as table columns, the winners of a row and the
// summaries per method (validate/src/report_json.cc, report_html.cc).
#ifndef ALLOYCOLOR_VALIDATE_REPORT_METRICS_H_
#define ALLOYCOLOR_VALIDATE_REPORT_METRICS_H_

#include <array>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "alloycolor/core/json.h"
#include "alloycolor/validate/report.h"

namespace alloycolor::validate {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// printf-formatted number.
std::string Num(double v, const char* format = "%g");

// "0.1, 0.3" (4 significant digits).
std::string XList(const std::vector<double>& xs);

struct Metric {
  std::string key;    // JSON summary key
  std::string label;  // HTML
  int angle = -1;     // index into angles_deg for delta_e00
  const char* format;
  double (*value)(const MethodResult&, int angle);
};

// Whether any method predicted a colour.
bool AnyColour(const ValidationReport& report);
// delta_e00 at each angle (when there is colour), then the spectral metrics.
std::vector<Metric> Metrics(const ValidationReport& report);
// A metric's value for one method and held-out sample; NaN where there is none.
double ValueOf(const HoldoutResult& h, const std::string& method, const Metric& metric);
// The methods with the lowest value in a row (ties within 1e-12 relative all win).
std::set<std::string> Best(const ValidationReport& report, const HoldoutResult& h,
                           const Metric& metric);

struct MetricSummary {
  int count = 0, wins = 0;
  double mean = kNaN, max = kNaN;
};
MetricSummary Summarise(const ValidationReport& report, const std::string& method,
                        const Metric& metric);

nlohmann::json ByAngle(const std::vector<double>& angles, const std::vector<double>& values);
nlohmann::json HexByAngle(const std::vector<double>& angles,
                          const std::vector<std::array<std::uint8_t, 3>>& srgb8);
nlohmann::json LabByAngle(const std::vector<double>& angles, const std::vector<color::Lab>& labs);
// "the colorimeter's grid 360-830 nm ..." for the report.
std::string ColourRangeText(const ValidationReport& report);

// The error bars' verdict from their own counts (report_overview.cc): "too small" where
// honest bars (68 % within one sigma, 95 % within two) would leave so few within two sigma
// with under 5 % probability, "too large" where they would put so many within one sigma
// with under 5 % probability, else "about right"; `text` says it with the counts.
struct HonestyVerdict {
  std::string kind = "none";
  std::string text;
};
HonestyVerdict JudgeHonesty(const SigmaCoverage& coverage);

// The report's opening (report_overview.cc): the data set as a whole, before the tables.
void WriteOverview(const ValidationReport& report, std::ostringstream& html);
nlohmann::json WholeJson(const WholeDataSet& whole);

}  // namespace alloycolor::validate

#endif  // ALLOYCOLOR_VALIDATE_REPORT_METRICS_H_
