// Wavelength grids and the policy that chooses them, in one place:
//  - colour needs n, k over the visible, kVisibleMinNm-kVisibleMaxNm (380-780 nm); data
//    that do not cover it are "infrared" data (the bundled Nb-Sn set) and get no colour;
//  - fits and predictions default to the colour tables' 5 nm grid over the range the
//    samples share, cut to 360-830 nm (the CIE tables' reach) for visible data, and to 100
//    steps over the shared range for infrared data.
#ifndef ALLOYCOLOR_CORE_GRID_H_
#define ALLOYCOLOR_CORE_GRID_H_

#include <vector>

#include "alloycolor/core/dataset.h"

namespace alloycolor {

inline constexpr double kVisibleMinNm = 380.0;
inline constexpr double kVisibleMaxNm = 780.0;
inline constexpr double kColourTableMinNm = 360.0;
inline constexpr double kColourTableMaxNm = 830.0;
inline constexpr double kGridStepNm = 5.0;
inline constexpr int kInfraredGridSteps = 100;

struct WavelengthRange {
  double lo_nm;
  double hi_nm;
};

// Whether [lo_nm, hi_nm] covers 380-780 nm (within 1e-9 nm).
bool CoversVisible(double lo_nm, double hi_nm);

// The range every sample covers; throws Error naming the manifest when they share none.
WavelengthRange CommonRange(const Dataset& dataset);

// The default grid for a range: every 5 nm inside 360-830 nm for visible data, else
// kInfraredGridSteps steps over the range.
std::vector<double> DefaultGrid(double lo_nm, double hi_nm);

// DefaultGrid over the samples' common range.
std::vector<double> DefaultGrid(const Dataset& dataset);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_GRID_H_
