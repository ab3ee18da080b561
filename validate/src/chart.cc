#include "alloycolor/validate/chart.h"

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"

namespace alloycolor::validate {

CompositionChart ComputeChart(const AlloyModel& model, const color::Colorimeter& colorimeter,
                              double x_from, double x_to, int steps, double angle_deg,
                              bool weight_labels) {
  if (steps < 2) throw Error("--steps: need at least 2 swatches, got " + std::to_string(steps));
  CompositionChart chart;
  chart.system = model.system().Name();
  chart.element_a = model.system().a.symbol;
  chart.element_b = model.system().b.symbol;
  chart.method = model.method();
  chart.illuminant = colorimeter.illuminant();
  chart.observer_deg = colorimeter.observer_deg();
  chart.angle_deg = angle_deg;
  chart.weight_labels = weight_labels;
  // Evenly spaced in the unit of the labels.
  const AlloySystem& system = model.system();
  const double lo = weight_labels ? WeightFromAtomicFraction(x_from, system) : x_from;
  const double hi = weight_labels ? WeightFromAtomicFraction(x_to, system) : x_to;
  for (int i = 0; i < steps; ++i) {
    const double t = lo + (hi - lo) * i / (steps - 1);
    const double x = i == 0           ? x_from
                     : i == steps - 1 ? x_to
                     : weight_labels  ? AtomicFromWeightFraction(t, system)
                                      : t;
    const color::ColorResult c = color::ColorFromXYZ(
        colorimeter,
        color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, model, x), angle_deg));
    const color::RGB& s = c.linear_srgb;
    chart.swatches.push_back({x, WeightFromAtomicFraction(x, model.system()), c.srgb8,
                              s.r < 0 || s.g < 0 || s.b < 0 || s.r > 1 || s.g > 1 || s.b > 1});
  }
  return chart;
}

}  // namespace alloycolor::validate
