#include <algorithm>
#include <cstdio>
#include <sstream>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/markup.h"
#include "report.h"

namespace alloycolor::app {

namespace {

// printf-formatted number.
std::string Num(double v, const char* format = "%g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

struct ChartLayout {
  int swatch, gap, margin;
};

ChartLayout LayoutOf(const CompositionChart& chart) {
  const int n = static_cast<int>(chart.swatches.size());
  const int swatch = n <= 16 ? 64 : std::max(4, 1000 / n);
  return {swatch, n <= 16 ? 6 : std::max(1, swatch / 10), 40};
}

}  // namespace

std::string ChartSvg(const CompositionChart& chart) {
  const ChartLayout l = LayoutOf(chart);
  const int n = static_cast<int>(chart.swatches.size());
  const int strip = n * l.swatch + (n - 1) * l.gap;
  const int width = std::max(strip + 2 * l.margin, 420);
  const int x0 = (width - strip) / 2, y0 = 48;
  const int height = y0 + l.swatch + 62;
  // Label every k-th swatch so that labels stay at least 40 px apart, and the last.
  const int every = std::max(1, (40 + l.swatch + l.gap - 1) / (l.swatch + l.gap));
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << " " << height
      << "\" font-family=\"Helvetica, Arial, sans-serif\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  svg << "<text x=\"" << width / 2 << "\" y=\"20\" text-anchor=\"middle\" font-size=\"15\" "
      << "font-weight=\"bold\">" << EscapeXml(chart.system) << ": colour by composition</text>\n";
  svg << "<text x=\"" << width / 2 << "\" y=\"37\" text-anchor=\"middle\" font-size=\"11\" "
      << "fill=\"#555\">" << EscapeXml(chart.method) << " model; " << EscapeXml(chart.illuminant)
      << ", " << chart.observer_deg << "\u00b0 observer, incidence " << Num(chart.angle_deg)
      << "\u00b0; sRGB</text>\n";
  const char* unit = chart.weight_labels ? "wt%" : "at%";
  for (int i = 0; i < n; ++i) {
    const validate::ChartSwatch& s = chart.swatches[i];
    const int x = x0 + i * (l.swatch + l.gap);
    const std::string hex = color::HexColor(s.srgb8);
    svg << "<rect class=\"swatch\" x=\"" << x << "\" y=\"" << y0 << "\" width=\"" << l.swatch
        << "\" height=\"" << l.swatch << "\" fill=\"" << hex << "\" stroke=\"#777\" "
        << "stroke-width=\"0.5\"><title>x = " << Num(s.x_atomic, "%.4g") << " ("
        << Num(100 * s.x_weight, "%.4g") << " wt% " << EscapeXml(chart.element_a) << "): " << hex
        << (s.clipped ? ", outside the sRGB gamut (clipped)" : "") << "</title></rect>\n";
    if (i % every == 0 || i == n - 1) {
      const double pct = 100 * (chart.weight_labels ? s.x_weight : s.x_atomic);
      svg << "<text x=\"" << x + l.swatch / 2.0 << "\" y=\"" << y0 + l.swatch + 15
          << "\" text-anchor=\"middle\" font-size=\"12\">" << Num(pct, "%.3g") << "</text>\n";
      if (l.swatch >= 48) {
        svg << "<text x=\"" << x + l.swatch / 2.0 << "\" y=\"" << y0 + l.swatch + 28
            << "\" text-anchor=\"middle\" font-size=\"9\" fill=\"#777\">" << hex << "</text>\n";
      }
    }
  }
  const bool rising = chart.swatches.back().x_atomic >= chart.swatches.front().x_atomic;
  const auto end_label = [&](double x) {
    if (x <= 1e-9) return std::string(chart.element_b);
    if (x >= 1 - 1e-9) return std::string(chart.element_a);
    return std::string();
  };
  const std::string left = end_label(chart.swatches.front().x_atomic);
  const std::string right = end_label(chart.swatches.back().x_atomic);
  if (!left.empty()) {
    svg << "<text x=\"" << x0 - 6 << "\" y=\"" << y0 + l.swatch / 2 + 5
        << "\" text-anchor=\"end\" font-size=\"14\" font-weight=\"bold\">" << EscapeXml(left)
        << "</text>\n";
  }
  if (!right.empty()) {
    svg << "<text x=\"" << x0 + strip + 6 << "\" y=\"" << y0 + l.swatch / 2 + 5
        << "\" font-size=\"14\" font-weight=\"bold\">" << EscapeXml(right) << "</text>\n";
  }
  svg << "<text x=\"" << width / 2 << "\" y=\"" << height - 10
      << "\" text-anchor=\"middle\" font-size=\"12\" fill=\"#333\">" << unit << " "
      << EscapeXml(chart.element_a) << (rising ? " \u2192" : " \u2190") << "</text>\n";
  svg << "</svg>\n";
  return svg.str();
}

render::ImageRGBA8 ChartImage(const CompositionChart& chart, int swatch_px, int gap_px) {
  const int n = static_cast<int>(chart.swatches.size());
  render::ImageRGBA8 image(n * swatch_px + (n + 1) * gap_px, swatch_px + 2 * gap_px);
  std::fill(image.rgba.begin(), image.rgba.end(), 255);
  for (int i = 0; i < n; ++i) {
    const int x0 = gap_px + i * (swatch_px + gap_px);
    for (int y = gap_px; y < gap_px + swatch_px; ++y) {
      for (int x = x0; x < x0 + swatch_px; ++x) {
        std::uint8_t* p = image.Pixel(x, y);
        for (int c = 0; c < 3; ++c) p[c] = chart.swatches[i].srgb8[c];
      }
    }
  }
  return image;
}
}  // namespace alloycolor::app
