// Inside the validate library: the report's line and marker charts as inline SVG.
#ifndef ALLOYCOLOR_VALIDATE_SRC_SVG_PLOT_H_
#define ALLOYCOLOR_VALIDATE_SRC_SVG_PLOT_H_

#include <string>
#include <vector>

namespace alloycolor::validate {

// One series: a line through its points, markers at them, or both; non-finite points
// break the line.
struct PlotSeries {
  std::string label, colour;
  std::vector<double> x, y;
  bool line = true;
  bool markers = false;
  bool hollow = false;
  double width = 1.6;
  std::string dash;
};

// A chart: its SVG id (unique in the page, for its clip path), titles and size in pixels.
struct PlotSpec {
  std::string id, title, x_label, y_label;
  int width = 370, height = 250;
  std::vector<PlotSeries> series;
};

// The chart with axes spanning every series' finite points, round ticks and a grid.
std::string SvgPlot(const PlotSpec& spec);

}  // namespace alloycolor::validate

#endif  // ALLOYCOLOR_VALIDATE_SRC_SVG_PLOT_H_
