// The composition chart as documents: an SVG chart and the chart's swatches as an image.
// These only format what validate/ computed (validate/chart.h); the validation report's
// JSON and HTML writers live in validate/report.h, shared with the Python module.
#ifndef ALLOYCOLOR_APP_REPORT_H_
#define ALLOYCOLOR_APP_REPORT_H_

#include <nlohmann/json.hpp>
#include <string>

#include "alloycolor/render/image.h"
#include "alloycolor/validate/chart.h"
#include "alloycolor/validate/report.h"
#include "alloycolor/validate/validation.h"

namespace alloycolor::app {

using validate::CompositionChart;
using validate::DrudeCurve;
using validate::HoldoutResult;
using validate::MethodResult;
using validate::SplitResult;
using validate::ValidationHtml;
using validate::ValidationJson;
using validate::ValidationReport;

// SVG with the swatches, the composition under each and the elements at the ends.
std::string ChartSvg(const CompositionChart& chart);

// The chart without text, for a PNG: swatches of swatch_px squared on white, gap_px between
// them and around them.
render::ImageRGBA8 ChartImage(const CompositionChart& chart, int swatch_px, int gap_px);

}  // namespace alloycolor::app

#endif  // ALLOYCOLOR_APP_REPORT_H_
