#include <algorithm>
#include <cmath>
#include <sstream>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/markup.h"
#include "alloycolor/validate/report.h"
#include "report_metrics.h"
#include "svg_plot.h"

namespace alloycolor::validate {

namespace {

const char* const kPalette[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd",
                                "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

std::string MethodColour(const ValidationReport& report, const std::string& method) {
  const auto it = std::find(report.methods.begin(), report.methods.end(), method);
  const size_t i = it - report.methods.begin();
  return kPalette[i % (sizeof kPalette / sizeof kPalette[0])];
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
    html += "<span><i style=\"background:" + MethodColour(report, m) + "\"></i>" + EscapeXml(m) +
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

// The held-out composition in a table row: x, the manifest's weight fraction if given, and
// for a replicate (one of several samples at its composition) its file.
std::string RowLabel(const ValidationReport& report, const HoldoutResult& h) {
  return Num(h.x_atomic, "%.4g") +
         (WeightManifest(report) ? " <small>(" + Num(h.x_given, "%.4g") + " wt)</small>" : "") +
         (h.replicate ? " <small>" + EscapeXml(h.file) + "</small>" : "") +
         (h.excluded.empty()
              ? ""
              : " <small>set aside: " + EscapeXml(h.excluded) + " (not in the means)</small>");
}

void WriteVerdict(const ValidationReport& report, std::ostringstream& html) {
  html << "<h2>Which method</h2><ul>";
  for (const Metric& metric : Metrics(report)) {
    std::vector<std::pair<double, std::string>> ranked;
    std::map<std::string, MetricSummary> sums;
    for (const std::string& m : report.methods) {
      sums[m] = Summarise(report, m, metric);
      if (sums[m].count > 0) ranked.push_back({sums[m].mean, m});
    }
    if (ranked.empty()) continue;
    std::sort(ranked.begin(), ranked.end());
    html << "<li><b>" << metric.label << "</b>: lowest mean <b>" << EscapeXml(ranked[0].second)
         << "</b>";
    for (size_t i = 0; i < ranked.size(); ++i) {
      const MetricSummary& s = sums[ranked[i].second];
      html << (i == 0 ? " (" : "; ") << (i == 0 ? "" : EscapeXml(ranked[i].second) + " ") << "mean "
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
    for (const std::string& m : report.methods) html << "<th>" << EscapeXml(m) << "</th>";
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
      const validate::SigmaCoverage s = validate::Coverage(report, m, static_cast<int>(a));
      if (s.count == 0) continue;
      const double frac1 = double(s.within_1) / s.count;
      const HonestyVerdict judged = JudgeHonesty(s);
      const std::string verdict = judged.kind == "too small"
                                      ? "<span class=\"bad\">" + EscapeXml(judged.text) + "</span>"
                                      : EscapeXml(judged.text);
      rows << "<tr><td class=\"l\">" << EscapeXml(m) << "</td><td>" << Num(report.angles_deg[a])
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
          "and 95% within two; the verdict says so only where the counts would be unlikely "
          "(under 5 %) for honest bars.</p>"
       << "<table><tr><th class=\"l\">method</th><th>angle</th><th>&Delta;E &le; "
          "1&sigma;</th><th>&Delta;E &le; 2&sigma;</th><th>median &Delta;E/&sigma;</th><th "
          "class=\"l\">verdict</th></tr>"
       << rows.str() << "</table>";
}

// The composition recovered from each held-out sample's measured colour (normal incidence,
// the best match within the model's range) against its true composition.
void WriteRecovery(const ValidationReport& report, std::ostringstream& html) {
  std::ostringstream summary, samples;
  for (const std::string& m : report.methods) {
    const RecoverySummary s = Recovery(report, m);
    if (s.count == 0) continue;
    summary << "<tr><td class=\"l\">" << EscapeXml(m) << "</td><td>" << s.count << "</td><td>"
            << Num(s.mean_abs_at_percent, "%.3f") << "</td><td>"
            << (s.with_sigma > 0
                    ? std::to_string(s.within_2) + " of " + std::to_string(s.with_sigma)
                    : std::string("&ndash;"))
            << "</td></tr>";
  }
  html << "<h2>Composition recovered from colour</h2>";
  if (summary.str().empty()) {
    html << "<p class=\"meta\">No held-out sample has a colour to match.</p>";
    return;
  }
  for (const HoldoutResult& h : report.holdouts) {
    samples << "<tr><td>" << Num(h.x_atomic, "%.4g") << "</td>";
    for (const std::string& m : report.methods) {
      const auto it = h.results.find(m);
      if (it == h.results.end() || !std::isfinite(it->second.x_recovered)) {
        samples << "<td>&ndash;</td>";
        continue;
      }
      const MethodResult& r = it->second;
      samples << "<td>" << Num(r.x_recovered, "%.4f");
      if (std::isfinite(r.x_recovered_sigma)) {
        samples << " &plusmn; " << Num(r.x_recovered_sigma, "%.4f");
      }
      samples << " (" << Num(100 * (r.x_recovered - h.x_atomic), "%+.2f") << " at%)</td>";
    }
    samples << "</tr>";
  }
  html << "<p class=\"meta\">Each held-out sample's measured colour at normal incidence "
          "matched by each method's model (the composition within its range whose colour is "
          "closest, <code>alloycolor match</code>), against the sample's true composition; "
          "one-sigma from the model's colour uncertainty over the rate colour changes with "
          "composition.</p><table><tr><th class=\"l\">method</th><th>samples</th><th>mean "
          "|error| (at%)</th><th>true within 2&sigma;</th></tr>"
       << summary.str() << "</table><table><tr><th>true x</th>";
  for (const std::string& m : report.methods) html << "<th>" << EscapeXml(m) << "</th>";
  html << "</tr>" << samples.str() << "</table>";
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

// Each method's model against its own training samples, beside its error on the samples
// held out of this split: a model that misses the samples it was given says so here.
void WriteInSample(const ValidationReport& report, const SplitResult& split, int s,
                   std::ostringstream& html) {
  if (split.in_sample.empty()) return;
  html << "<table><tr><th>method</th><th>in-sample, mean</th><th>in-sample, worst (sample)</th>"
          "<th>held out, mean</th></tr>";
  for (const auto& [method, rows] : split.in_sample) {
    double sum = 0, worst = -1;
    int count = 0;
    std::string worst_file;
    bool colour = true;
    for (const InSampleError& r : rows) {
      colour = colour && std::isfinite(r.delta_e00);
    }
    for (const InSampleError& r : rows) {
      const double v = colour ? r.delta_e00 : r.reflectance_rms;
      if (!std::isfinite(v)) continue;
      sum += v;
      ++count;
      if (v > worst) {
        worst = v;
        worst_file = r.file;
      }
    }
    double held_sum = 0;
    int held = 0;
    for (const HoldoutResult& h : report.holdouts) {
      if (h.split != s) continue;
      const auto it = h.results.find(method);
      if (it == h.results.end() || !it->second.error.empty()) continue;
      const double v = colour && !it->second.delta_e00.empty() ? it->second.delta_e00[0]
                                                               : it->second.reflectance_rms;
      if (!std::isfinite(v)) continue;
      held_sum += v;
      ++held;
    }
    const char* unit = colour ? "dE00 " : "R RMS ";
    html << "<tr><td>" << EscapeXml(method) << "</td><td>"
         << (count ? unit + Num(sum / count, "%.3g") : std::string("-")) << "</td><td>"
         << (count ? unit + Num(worst, "%.3g") + " (" + EscapeXml(worst_file) + ")"
                   : std::string("-"))
         << "</td><td>" << (held ? unit + Num(held_sum / held, "%.3g") : std::string("-"))
         << "</td></tr>";
  }
  html << "</table><p class=\"note\">In-sample: each model against the samples it was "
          "trained on (normal incidence): a model that misses its own samples contradicts the "
          "data it was given.</p>";
}

void WriteHoldout(const ValidationReport& report, const HoldoutResult& h, int index,
                  std::ostringstream& html) {
  html << "<h4>Held out: " << EscapeXml(XLabel(report, h)) << " &mdash; " << EscapeXml(h.file)
       << "</h4>";
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
        std::string cap = "<b>" + EscapeXml(m) + "</b><br>" + color::HexColor(r.srgb8[a]) +
                          "<br>&Delta;E " + Num(r.delta_e00[a], "%.2f");
        if (a < r.delta_e00_sigma.size()) {
          cap += " (&sigma; " + Num(r.delta_e00_sigma[a], "%.2f") + ")";
        }
        html << Swatch(r.srgb8[a], cap);
      }
      html << "</div>";
    }
  } else {
    html << "<p class=\"note\">No colour: " << EscapeXml(h.colour_note)
         << ". &Delta;E<sub>00</sub> is not available; n, k and reflectance are compared "
            "over "
         << EscapeXml(h.metric_range.empty() ? "the data's range" : h.metric_range) << ".</p>";
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
    html << "<tr><td class=\"l\">" << EscapeXml(m) << "</td>";
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
         << EscapeXml(note) << "</td></tr>";
  }
  html << "</table>";
  if (h.lambda_nm.empty()) return;
  // Spectra.
  html << "<p class=\"meta\">Spectra over " << EscapeXml(h.metric_range)
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
       << EscapeXml(title) << "</title><style>" << kStyle << "</style></head><body>\n";
  html << "<h1>" << EscapeXml(title) << "</h1>";
  html << "<p class=\"meta\">Data: " << EscapeXml(report.name) << " &mdash; <code>"
       << EscapeXml(report.data) << "</code><br>Methods: ";
  for (size_t i = 0; i < report.methods.size(); ++i) {
    html << (i ? ", " : "") << EscapeXml(report.methods[i]);
  }
  html << ". "
       << (report.mode == "loo" ? "Leave-one-out: each interior sample held out in "
                                  "turn, every method refitted without it."
                                : "Held out: the given compositions, every method "
                                  "refitted without them.")
       << "<br>Colour: illuminant " << EscapeXml(report.illuminant) << ", " << report.observer_deg
       << "&deg; observer, incidence ";
  for (size_t a = 0; a < report.angles_deg.size(); ++a) {
    html << (a ? ", " : "") << Num(report.angles_deg[a]) << "&deg;";
  }
  html << ". Compositions x are atomic fractions of " << EscapeXml(report.element_a)
       << (report.composition == "weight_fraction_a" ? " (the manifest gives weight fractions)"
                                                     : "")
       << ".<br>Generated by alloycolor " ALLOYCOLOR_VERSION ".</p>";

  WriteOverview(report, html);
  // What each metric covers.
  html << "<h2>What is compared</h2><ul class=\"meta\">";
  if (AnyColour(report)) {
    html << "<li>&Delta;E<sub>00</sub> (CIEDE2000) between measured and predicted colour of "
            "the polished metal, over "
         << EscapeXml(ColourRangeText(report)) << ".</li>";
  } else {
    std::string why;
    for (const HoldoutResult& h : report.holdouts) {
      if (why.empty()) why = h.colour_note;
    }
    html << "<li class=\"note\">&Delta;E<sub>00</sub> is <b>not available</b>: " << EscapeXml(why)
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
  for (const std::string& r : ranges) html << (i++ ? "; " : "") << EscapeXml(r);
  html << ".</li></ul>";
  if (!report.dataset_warnings.empty()) {
    html << "<details><summary class=\"meta\">Data set warnings (" << report.dataset_warnings.size()
         << ")</summary><ul class=\"meta\">";
    for (const std::string& w : report.dataset_warnings) html << "<li>" << EscapeXml(w) << "</li>";
    html << "</ul></details>";
  }

  WriteVerdict(report, html);
  WriteSummaryTables(report, html);
  WriteHonesty(report, html);
  WriteRecovery(report, html);

  html << "<h2>Held-out compositions</h2>";
  int holdout_index = 0;
  for (size_t s = 0; s < report.splits.size(); ++s) {
    const SplitResult& split = report.splits[s];
    html << "<h3>Trained on x = " << XList(split.train_x)
         << "; held out x = " << XList(split.holdout_x) << "</h3>";
    bool replicates = false;
    for (const HoldoutResult& h : report.holdouts) {
      replicates = replicates || (h.split == static_cast<int>(s) && h.replicate);
    }
    if (replicates) {
      // Replicates share x: their files tell them apart.
      html << "<p class=\"meta\">Held out: ";
      for (size_t i = 0; i < split.holdout_files.size(); ++i) {
        html << (i ? ", " : "") << EscapeXml(split.holdout_files[i])
             << " (x = " << Num(split.holdout_x[i], "%.4g") << ")";
      }
      html << ". Trained on: ";
      for (size_t i = 0; i < split.train_files.size(); ++i) {
        html << (i ? ", " : "") << EscapeXml(split.train_files[i])
             << " (x = " << Num(split.train_x[i], "%.4g") << ")";
      }
      html << ".</p>";
    }
    for (const auto& [method, error] : split.errors) {
      html << "<p class=\"note\">" << EscapeXml(method)
           << " could not be built: " << EscapeXml(error) << "</p>";
    }
    for (const auto& [method, choice] : split.choices) {
      html << "<p class=\"note\"><b>" << EscapeXml(method) << "</b> chose " << EscapeXml(choice)
           << "</p>";
    }
    for (const auto& [method, warnings] : split.warnings) {
      if (warnings.empty()) continue;
      html << "<details><summary class=\"meta\">" << EscapeXml(method) << ": " << warnings.size()
           << " warning(s)</summary><ul class=\"meta\">";
      for (const std::string& w : warnings) html << "<li>" << EscapeXml(w) << "</li>";
      html << "</ul></details>";
    }
    WriteInSample(report, split, static_cast<int>(s), html);
    for (const HoldoutResult& h : report.holdouts) {
      if (h.split == static_cast<int>(s)) WriteHoldout(report, h, holdout_index++, html);
    }
    WriteDrude(report, split, static_cast<int>(s), html);
  }
  html << "\n</body></html>\n";
  return html.str();
}

}  // namespace alloycolor::validate
