// The colour of a polished metal: n, k on the colorimeter's grid -> Fresnel reflectance
// at the angle of incidence (eq. 2-4) -> XYZ (eq. 5) -> every colour output.
//
// A spectrum must cover 380-780 nm; where the colorimeter's grid reaches beyond the data
// (360-380 and 780-830 nm carry under 0.1 % of Y), n and k are held at the nearest
// measured wavelength.
#ifndef ALLOYCOLOR_COLOR_MATERIAL_COLOR_H_
#define ALLOYCOLOR_COLOR_MATERIAL_COLOR_H_

#include <array>
#include <complex>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/spectrum.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::color {

struct ColorResult {
  XYZ xyz;
  Lab lab;
  RGB linear_srgb;
  std::array<std::uint8_t, 3> srgb8;
  RGB paper_rgb;
};

// Every output from XYZ, Lab relative to the colorimeter's white.
ColorResult ColorFromXYZ(const Colorimeter& colorimeter, const XYZ& xyz);

// The wavelengths at which to evaluate data covering [lo_nm, hi_nm] for the
// colorimeter's grid: the grid, held inside [lo_nm, hi_nm]. Throws Error naming `what`
// when the data do not cover 380-780 nm (or the illuminant's range, if narrower).
std::vector<double> EvaluationGrid(const Colorimeter& colorimeter, double lo_nm, double hi_nm,
                                   const std::string& what);

// n + i k on the colorimeter's grid.
std::vector<std::complex<double>> IndexOnGrid(const Colorimeter& colorimeter, const NkSpectrum& nk);
std::vector<std::complex<double>> IndexOnGrid(const Colorimeter& colorimeter,
                                              const AlloyModel& model, double x_atomic);

// R(lambda) = (Rs + Rp) / 2 at angle_deg for each index.
std::vector<double> ReflectanceSpectrum(const std::vector<std::complex<double>>& index,
                                        double angle_deg);

// XYZ of the polished metal at angle_deg.
XYZ MaterialXYZ(const Colorimeter& colorimeter, const std::vector<std::complex<double>>& index,
                double angle_deg);

// JSON object with XYZ, xyY, Lab, linear_srgb, srgb8, srgb_hex, paper_rgb, and whether
// linear sRGB was clipped.
nlohmann::json ColorJson(const ColorResult& color);

// One-sigma colour uncertainty of a model with uncertainty: the RMS CIEDE2000 difference
// between the central colour and `draws` colours from PermittivityDraws (seeded, so
// repeatable). Returns a negative value for a model without uncertainty.
double DeltaE00Sigma(const Colorimeter& colorimeter, const AlloyModel& model, double x_atomic,
                     double angle_deg, int draws = kUncertaintyDraws);
// The same at several angles from one set of draws (each value equals the single-angle
// call's).
std::vector<double> DeltaE00Sigma(const Colorimeter& colorimeter, const AlloyModel& model,
                                  double x_atomic, const std::vector<double>& angles_deg,
                                  int draws = kUncertaintyDraws);

// "#rrggbb".
std::string HexColor(const std::array<std::uint8_t, 3>& srgb8);

}  // namespace alloycolor::color

#endif  // ALLOYCOLOR_COLOR_MATERIAL_COLOR_H_
