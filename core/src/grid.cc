#include "alloycolor/core/grid.h"

#include <algorithm>
#include <cmath>

#include "alloycolor/core/error.h"
#include "alloycolor/core/spectrum.h"

namespace alloycolor {

bool CoversVisible(double lo_nm, double hi_nm) {
  return lo_nm <= kVisibleMinNm + 1e-9 && hi_nm >= kVisibleMaxNm - 1e-9;
}

WavelengthRange CommonRange(const Dataset& dataset) {
  if (dataset.samples.empty()) throw Error(dataset.manifest_path + ": no samples");
  WavelengthRange range{-1e300, 1e300};
  for (const Sample& s : dataset.samples) {
    range.lo_nm = std::max(range.lo_nm, s.nk.lambda_min_nm());
    range.hi_nm = std::min(range.hi_nm, s.nk.lambda_max_nm());
  }
  if (!(range.lo_nm < range.hi_nm)) {
    throw Error(dataset.manifest_path + ": the samples share no wavelength range");
  }
  return range;
}

std::vector<double> DefaultGrid(double lo_nm, double hi_nm) {
  if (CoversVisible(lo_nm, hi_nm)) {
    const double first =
        std::ceil(std::max(lo_nm, kColourTableMinNm) / kGridStepNm - 1e-9) * kGridStepNm;
    const double last =
        std::floor(std::min(hi_nm, kColourTableMaxNm) / kGridStepNm + 1e-9) * kGridStepNm;
    return UniformGrid(first, last, kGridStepNm);
  }
  return UniformGrid(lo_nm, hi_nm, (hi_nm - lo_nm) / kInfraredGridSteps);
}

std::vector<double> DefaultGrid(const Dataset& dataset) {
  const WavelengthRange range = CommonRange(dataset);
  return DefaultGrid(range.lo_nm, range.hi_nm);
}

}  // namespace alloycolor
