// How far a model lies from one measured sample at the sample's composition. One
// definition for every place that asks: `validate` for a held-out sample, `fit` for its own
// training samples (the in-sample error) and `auto` for its folds' held-out samples.
//  - delta_e00: CIEDE2000 between the measured and the predicted colour of the polished
//    metal at normal incidence (both on the colorimeter's grid, held at the nearest
//    wavelength beyond their data as material_color.h does); NaN where the sample does
//    not cover 380-780 nm (infrared data have no colour).
//  - reflectance_rms: normal-incidence reflectance error over MetricGrid.
#ifndef ALLOYCOLOR_COLOR_SAMPLE_ERROR_H_
#define ALLOYCOLOR_COLOR_SAMPLE_ERROR_H_

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::color {

// The wavelengths on which a model and a measured spectrum are compared: 380-780 nm in
// 5 nm steps where both cover it, otherwise the measured wavelengths inside the model's
// range (`description` says which). Throws Error naming the sample when they share fewer
// than two wavelengths.
std::vector<double> MetricGrid(const AlloyModel& model, const NkSpectrum& measured,
                               std::string* description);

struct SampleError {
  double delta_e00 = std::numeric_limits<double>::quiet_NaN();
  double reflectance_rms = std::numeric_limits<double>::quiet_NaN();
  bool has_colour() const { return std::isfinite(delta_e00); }
  // The one number a method is scored by: the colour difference, or the reflectance error
  // for data without colour.
  double score() const { return has_colour() ? delta_e00 : reflectance_rms; }
};

// The model at sample.x_atomic against the sample. Throws Error (naming the model's
// source) where the model cannot be evaluated there.
SampleError ErrorAgainstSample(const Colorimeter& colorimeter, const AlloyModel& model,
                               const Sample& sample);

}  // namespace alloycolor::color

#endif  // ALLOYCOLOR_COLOR_SAMPLE_ERROR_H_
