#include "alloycolor/color/sample_error.h"

#include <algorithm>
#include <complex>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/spectrum.h"
#include "alloycolor/core/text.h"

namespace alloycolor::color {
std::vector<double> MetricGrid(const AlloyModel& model, const NkSpectrum& measured,
                               std::string* description) {
  const double lo = std::max(model.lambda_min_nm(), measured.lambda_min_nm());
  const double hi = std::min(model.lambda_max_nm(), measured.lambda_max_nm());
  if (lo <= kVisibleMinNm + 1e-9 && hi >= kVisibleMaxNm - 1e-9) {
    *description = "380-780 nm, 5 nm step";
    return UniformGrid(kVisibleMinNm, kVisibleMaxNm, kGridStepNm);
  }
  std::vector<double> grid;
  for (double l : measured.lambda_nm) {
    if (l >= lo - 1e-9 && l <= hi + 1e-9) grid.push_back(std::clamp(l, lo, hi));
  }
  if (grid.size() < 2) {
    throw Error(measured.source + " and the " + model.method() + " model share under two " +
                "wavelengths (" + FormatNumber(lo) + "-" + FormatNumber(hi) + " nm)");
  }
  *description = "the measured sample's " + std::to_string(grid.size()) + " wavelengths in " +
                 FormatNumber(grid.front()) + "-" + FormatNumber(grid.back()) +
                 " nm (the data do not cover 380-780 nm)";
  return grid;
}

SampleError ErrorAgainstSample(const Colorimeter& colorimeter, const AlloyModel& model,
                               const Sample& sample) {
  SampleError e;
  std::string description;
  const std::vector<double> grid = MetricGrid(model, sample.nk, &description);
  const std::vector<double> predicted =
      ReflectanceSpectrum(model.Index(sample.x_atomic, grid), 0.0);
  const std::vector<double> measured = ReflectanceSpectrum(NkOn(sample.nk, grid), 0.0);
  double sum2 = 0;
  for (size_t i = 0; i < grid.size(); ++i) sum2 += std::pow(predicted[i] - measured[i], 2);
  e.reflectance_rms = std::sqrt(sum2 / grid.size());
  std::vector<std::complex<double>> measured_index;
  try {
    measured_index = IndexOnGrid(colorimeter, sample.nk);
  } catch (const Error&) {
    return e;  // the sample has no colour
  }
  const Lab truth = LabFromXYZ(MaterialXYZ(colorimeter, measured_index, 0.0), colorimeter.White());
  const Lab model_lab =
      LabFromXYZ(MaterialXYZ(colorimeter, IndexOnGrid(colorimeter, model, sample.x_atomic), 0.0),
                 colorimeter.White());
  e.delta_e00 = DeltaE00(truth, model_lab);
  return e;
}

}  // namespace alloycolor::color
