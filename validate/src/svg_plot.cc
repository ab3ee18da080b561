#include "svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "alloycolor/core/markup.h"
#include "report_metrics.h"

namespace alloycolor::validate {

namespace {

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

}  // namespace

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
      << "\" role=\"img\" aria-label=\"" << EscapeXml(spec.title) << "\">";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>";
  svg << "<text x=\"" << left + pw / 2 << "\" y=\"16\" text-anchor=\"middle\" "
      << "class=\"pt\">" << EscapeXml(spec.title) << "</text>";
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
      << "\" text-anchor=\"middle\" class=\"pl\">" << EscapeXml(spec.x_label) << "</text>";
  svg << "<text transform=\"translate(12," << top + ph / 2 << ") rotate(-90)\" "
      << "text-anchor=\"middle\" class=\"pl\">" << EscapeXml(spec.y_label) << "</text>";
  svg << "<g clip-path=\"url(#" << spec.id << ")\">";
  for (const PlotSeries& s : spec.series) {
    if (s.line) {
      std::string points;
      const auto flush = [&]() {
        if (points.find(' ') != std::string::npos) {
          svg << "<polyline fill=\"none\" stroke=\"" << s.colour << "\" stroke-width=\"" << s.width
              << "\"" << (s.dash.empty() ? "" : " stroke-dasharray=\"" + s.dash + "\"")
              << " points=\"" << points << "\"><title>" << EscapeXml(s.label)
              << "</title></polyline>";
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
            << "\" stroke=\"" << s.colour << "\" stroke-width=\"1.5\"><title>" << EscapeXml(s.label)
            << ": " << Num(s.x[i], "%.4g") << ", " << Num(s.y[i], "%.4g") << "</title></circle>";
      }
    }
  }
  svg << "</g></svg>";
  return svg.str();
}

}  // namespace alloycolor::validate
