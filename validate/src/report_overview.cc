// The report's opening (report_metrics.h): the verdict on the data set as a whole (how good
// the model is where, which samples are suspect or set aside, where to measure next), the
// colour against composition with its one-sigma band, and the error bars' verdict from
// their own counts.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/markup.h"
#include "report_metrics.h"

namespace alloycolor::validate {
namespace {

// P(X <= k) for X binomial(n, p).
double BinomialAtMost(int k, int n, double p) {
  if (k < 0) return 0;
  if (k >= n) return 1;
  double sum = 0;
  for (int i = 0; i <= k; ++i) {
    const double log_term = std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) +
                            i * std::log(p) + (n - i) * std::log1p(-p);
    sum += std::exp(log_term);
  }
  return std::min(sum, 1.0);
}

std::string Short(double v) { return Num(v, "%.3g"); }

std::string SampleLine(const SampleNote& n) {
  std::string line = "<b>" + EscapeXml(n.file) + "</b> (x = " + Num(n.x_atomic, "%.4g") + "): ";
  return line;
}

// The colour strip of the scan with its one-sigma as a band beneath, the samples and the
// suggestions marked.
std::string OverviewSvg(const WholeDataSet& w) {
  const double width = 640, left = 58, right = 20, strip_top = 10, strip_h = 36;
  const double plot_top = strip_top + strip_h + 8, plot_h = 120, bottom = 36;
  const double height = plot_top + plot_h + bottom, pw = width - left - right;
  const double x_lo = w.x.front(), x_hi = w.x.back();
  const double span = x_hi > x_lo ? x_hi - x_lo : 1;
  const auto px = [&](double x) { return left + (x - x_lo) / span * pw; };
  double s_hi = 0;
  for (double s : w.sigma) s_hi = std::max(s_hi, s);
  s_hi = s_hi > 0 ? s_hi * 1.1 : 1;
  const auto py = [&](double s) { return plot_top + plot_h - s / s_hi * plot_h; };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" width=\"" << width
      << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << " " << height
      << "\" role=\"img\" aria-label=\"colour and its one-sigma against composition\">"
      << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>";
  char buf[160];
  for (size_t i = 0; i < w.srgb8.size() && i < w.x.size(); ++i) {
    const double a = i == 0 ? px(w.x[0]) : 0.5 * (px(w.x[i - 1]) + px(w.x[i]));
    const double b = i + 1 == w.x.size() ? px(w.x[i]) : 0.5 * (px(w.x[i]) + px(w.x[i + 1]));
    std::snprintf(buf, sizeof buf, "<rect x=\"%.2f\" y=\"%.1f\" width=\"%.2f\" height=\"%.1f\" ", a,
                  strip_top, b - a + 0.3, strip_h);
    svg << buf << "fill=\"" << color::HexColor(w.srgb8[i]) << "\"/>";
  }
  svg << "<rect x=\"" << left << "\" y=\"" << plot_top << "\" width=\"" << pw << "\" height=\""
      << plot_h << "\" fill=\"none\" stroke=\"#999\"/>";
  if (!w.sigma.empty()) {
    std::string band = Num(px(w.x.front()), "%.1f") + "," + Num(py(0), "%.1f");
    for (size_t i = 0; i < w.x.size(); ++i) {
      band += " " + Num(px(w.x[i]), "%.1f") + "," + Num(py(w.sigma[i]), "%.1f");
    }
    band += " " + Num(px(w.x.back()), "%.1f") + "," + Num(py(0), "%.1f");
    svg << "<polygon points=\"" << band
        << "\" fill=\"#9ecae1\" stroke=\"#3182bd\"><title>one-sigma CIEDE2000</title></polygon>";
    for (double t : {0.0, s_hi / 2.2, s_hi / 1.1}) {
      svg << "<text x=\"" << left - 4 << "\" y=\"" << Num(py(t), "%.1f")
          << "\" dy=\"3\" text-anchor=\"end\" class=\"pl\">" << Num(t, "%.2g") << "</text>";
    }
    svg << "<text transform=\"translate(12," << plot_top + plot_h / 2
        << ") rotate(-90)\" text-anchor=\"middle\" class=\"pl\">1-sigma &#916;E00</text>";
  } else {
    svg << "<text x=\"" << left + pw / 2 << "\" y=\"" << plot_top + plot_h / 2
        << "\" text-anchor=\"middle\" class=\"pl\">" << EscapeXml(w.no_error_bar) << "</text>";
  }
  // Samples: ticks under the strip (suspects red); suggestions: numbered triangles.
  for (double x : w.sample_x) {
    std::snprintf(buf, sizeof buf, "<line x1=\"%.1f\" x2=\"%.1f\" y1=\"%.1f\" y2=\"%.1f\" ", px(x),
                  px(x), strip_top + strip_h, plot_top + plot_h);
    svg << buf << "stroke=\"#333\" stroke-width=\"1\"><title>sample at x = " << Num(x, "%.4g")
        << "</title></line>";
  }
  for (const SampleNote& n : w.suspects) {
    std::snprintf(buf, sizeof buf, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"5\" ", px(n.x_atomic),
                  plot_top + plot_h);
    svg << buf << "fill=\"#d62728\"><title>suspect: " << EscapeXml(n.file) << "</title></circle>";
  }
  for (const SampleNote& n : w.excluded) {
    if (n.x_atomic < x_lo || n.x_atomic > x_hi) continue;
    std::snprintf(buf, sizeof buf, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"5\" ", px(n.x_atomic),
                  plot_top + plot_h);
    svg << buf << "fill=\"#fff\" stroke=\"#d62728\"><title>set aside: " << EscapeXml(n.file)
        << "</title></circle>";
  }
  for (size_t k = 0; k < w.suggestions.size(); ++k) {
    const double x = px(w.suggestions[k].x_atomic), y = plot_top + plot_h + 2;
    std::snprintf(buf, sizeof buf, "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f\" ", x, y,
                  x - 6, y + 10, x + 6, y + 10);
    svg << buf << "fill=\"#2ca02c\"><title>measure next (" << k + 1
        << "): x = " << Num(w.suggestions[k].x_atomic, "%.4g") << "</title></polygon>";
    svg << "<text x=\"" << Num(x, "%.1f") << "\" y=\"" << Num(y + 21, "%.1f")
        << "\" text-anchor=\"middle\" class=\"pl\">" << k + 1 << "</text>";
  }
  for (double t : {x_lo, 0.5 * (x_lo + x_hi), x_hi}) {
    svg << "<text x=\"" << Num(px(t), "%.1f") << "\" y=\"" << Num(height - 4, "%.1f")
        << "\" text-anchor=\"middle\" class=\"pl\">x = " << Num(t, "%.3g") << "</text>";
  }
  svg << "</svg>";
  return svg.str();
}

}  // namespace

HonestyVerdict JudgeHonesty(const SigmaCoverage& s) {
  HonestyVerdict v;
  if (s.count == 0) return v;
  // Honest bars hold each error within one sigma with probability 0.683 and within two
  // with 0.954 (a normal error); a verdict needs counts that honest bars would give with
  // less than 5 % probability.
  const double p_too_small = BinomialAtMost(s.within_2, s.count, 0.954);
  const double p_too_large = 1 - BinomialAtMost(s.within_1 - 1, s.count, 0.683);
  if (p_too_small < 0.05) {
    v.kind = "too small";
    v.text = "too small: " + std::to_string(s.count - s.within_2) + " of " +
             std::to_string(s.count) + " errors beyond two sigma (honest bars: about 5 %; " +
             Num(100 * p_too_small, "%.2g") + " % chance of so many)";
  } else if (p_too_large < 0.05) {
    v.kind = "too large";
    v.text = "too large (over-cautious): " + std::to_string(s.within_1) + " of " +
             std::to_string(s.count) + " errors within one sigma (honest bars: about 68 %; " +
             Num(100 * p_too_large, "%.2g") + " % chance of so many)";
  } else {
    v.kind = "about right";
    v.text = "about right: " + std::to_string(s.within_1) + " of " + std::to_string(s.count) +
             " within one sigma, " + std::to_string(s.within_2) +
             " within two, as honest error bars would give" +
             (s.count < 10 ? " (few errors: a weak test)" : "");
  }
  return v;
}

void WriteOverview(const ValidationReport& report, std::ostringstream& html) {
  const WholeDataSet& w = report.whole;
  if (!w.present()) return;
  html << "<h2>In short</h2><ul>";
  if (!w.error.empty()) {
    html << "<li>The whole data set could not be fitted: " << EscapeXml(w.error) << "</li></ul>";
    return;
  }
  html << "<li><b>The model</b> a fit of every sample gives: <b>" << EscapeXml(w.method) << "</b>"
       << (w.choice.empty() ? "" : " (" + EscapeXml(w.choice) + ")") << ". ";
  if (!w.sigma.empty()) {
    const auto hi = std::max_element(w.sigma.begin(), w.sigma.end());
    const auto lo = std::min_element(w.sigma.begin(), w.sigma.end());
    double mean = 0;
    for (double s : w.sigma) mean += s / w.sigma.size();
    html << "Its one-sigma &Delta;E<sub>00</sub> runs from " << Short(*lo) << " to " << Short(*hi)
         << " (mean " << Short(mean) << ") across x = " << Num(w.x.front(), "%.4g") << "&ndash;"
         << Num(w.x.back(), "%.4g") << ", largest at x = " << Num(w.x[hi - w.sigma.begin()], "%.3g")
         << ".";
  } else {
    html << EscapeXml(w.no_error_bar.empty() ? "No colour error bar (no colour)."
                                             : w.no_error_bar + ".");
  }
  html << "</li>";
  if (!w.samples_checked) {
    html << "<li>The samples were not checked.</li>";
  } else if (w.suspects.empty()) {
    html << "<li><b>No suspect sample</b>: each is in line with the rest of the series "
            "(metallic where its neighbours are; held out, within its error bar).</li>";
  } else {
    for (const SampleNote& n : w.suspects) {
      html << "<li class=\"bad\"><b>Suspect</b>: " << EscapeXml(n.reason) << "</li>";
    }
  }
  for (const SampleNote& n : w.excluded) {
    html << "<li><b>Set aside</b> by the manifest, " << SampleLine(n) << EscapeXml(n.reason);
    if (std::isfinite(n.delta_e00)) {
      html << "; the model, which never saw it, predicts it off by &Delta;E<sub>00</sub> "
           << Short(n.delta_e00)
           << (std::isfinite(n.sigma_de00) ? " at one-sigma " + Short(n.sigma_de00) : "");
    }
    html << "</li>";
  }
  if (!w.suggestions.empty()) {
    html << "<li><b>Measure next</b> (" << EscapeXml(w.suggest_rule) << "): ";
    for (size_t k = 0; k < w.suggestions.size(); ++k) {
      const color::Suggestion& s = w.suggestions[k];
      html << (k ? "; then " : "") << "x = " << Num(s.x_atomic, "%.3g");
      if (std::isfinite(s.sigma)) {
        html << " (one-sigma " << Short(s.sigma) << " now; measured, the largest would be "
             << Short(s.max_sigma_after) << ")";
      }
    }
    html << ".</li>";
  }
  // The error bars, from their counts, for the methods of this report.
  for (const std::string& m : report.methods) {
    for (size_t a = 0; a < report.angles_deg.size(); ++a) {
      const SigmaCoverage s = Coverage(report, m, static_cast<int>(a));
      if (s.count == 0 || report.angles_deg[a] != 0) continue;
      html << "<li><b>" << EscapeXml(m)
           << "</b>'s error bars on the held-out samples: " << EscapeXml(JudgeHonesty(s).text)
           << ".</li>";
    }
  }
  html << "</ul>";
  if (!w.x.empty()) html << "<div class=\"plots\">" << OverviewSvg(w) << "</div>";
  html << "<p class=\"meta\">The strip: the model's colour at normal incidence across "
          "composition; beneath, its one-sigma &Delta;E<sub>00</sub>; ticks: the samples "
          "(red dots: suspect; open: set aside); green triangles: where to measure next.</p>";
}

nlohmann::json WholeJson(const WholeDataSet& w) {
  const auto notes = [](const std::vector<SampleNote>& list) {
    nlohmann::json out = nlohmann::json::array();
    for (const SampleNote& n : list) {
      out.push_back({{"file", n.file},
                     {"x", n.x_atomic},
                     {"check", n.check},
                     {"reason", n.reason},
                     {"delta_e00", NumberOrNull(n.delta_e00)},
                     {"sigma_de00", NumberOrNull(n.sigma_de00)}});
    }
    return out;
  };
  nlohmann::json suggestions = nlohmann::json::array();
  for (const color::Suggestion& s : w.suggestions) {
    suggestions.push_back({{"x", s.x_atomic},
                           {"sigma_de00", NumberOrNull(s.sigma)},
                           {"max_sigma_after", NumberOrNull(s.max_sigma_after)},
                           {"mean_sigma_after", NumberOrNull(s.mean_sigma_after)}});
  }
  nlohmann::json out = {{"method", w.method},
                        {"choice", w.choice},
                        {"error", w.error},
                        {"error_bar", w.no_error_bar.empty() ? "one sigma" : w.no_error_bar},
                        {"samples_checked", w.samples_checked},
                        {"suspect_samples", notes(w.suspects)},
                        {"excluded_samples", notes(w.excluded)},
                        {"suggestions", suggestions},
                        {"suggest_rule", w.suggest_rule},
                        {"x", w.x}};
  out["sigma_de00"] = w.sigma;
  return out;
}

}  // namespace alloycolor::validate
