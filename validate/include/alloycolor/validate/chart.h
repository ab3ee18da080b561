// A composition chart like the paper's handbook figure: the colour of a model at evenly
// spaced compositions (in the unit of the labels), computed with the chain of
// color/material_color.h. The SVG and PNG writers are the program's (app/chart.cc).
#ifndef ALLOYCOLOR_VALIDATE_CHART_H_
#define ALLOYCOLOR_VALIDATE_CHART_H_

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::validate {

struct ChartSwatch {
  double x_atomic;
  double x_weight;
  std::array<std::uint8_t, 3> srgb8;
  bool clipped;  // linear sRGB outside [0, 1] before clamping
};

struct CompositionChart {
  std::string system, element_a, element_b, method, illuminant;
  int observer_deg = 2;
  double angle_deg = 0;
  bool weight_labels = false;  // label compositions in wt% rather than at%
  std::vector<ChartSwatch> swatches;
};

// Colours of the model at `steps` compositions from x_from to x_to (atomic fractions),
// evenly spaced in weight fraction when labelled in wt%, else in atomic fraction; throws
// Error when the model does not cover 380-780 nm.
CompositionChart ComputeChart(const AlloyModel& model, const color::Colorimeter& colorimeter,
                              double x_from, double x_to, int steps, double angle_deg,
                              bool weight_labels);

}  // namespace alloycolor::validate

#endif  // ALLOYCOLOR_VALIDATE_CHART_H_
