// Colorimetry: spectral reflectance to CIE XYZ (paper eq. 5), and XYZ to the paper's RGB
// (eq. 6), linear and 8-bit sRGB (IEC 61966-2-1), CIELAB (CIE 15:2004) and CIEDE2000
// (CIE 142-2001; Sharma, Wu & Dalal 2005).
//
//   X = sum P(l) R(l) xbar(l) / sum P(l) ybar(l)   (likewise Y, Z)
//
// on the tables' 5 nm grid over the range both the illuminant and the observer cover
// (360-830 nm for A and D65, 380-830 nm for E, 380-780 nm for C, D50, F2 and F11, with
// either observer), taking the illuminant at the multiples of 5 nm without interpolation
// (A is tabulated at 1 nm), so that a perfect reflector has Y = 1. Tables are read from
// data/cie/*.csv.
#ifndef ALLOYCOLOR_COLOR_COLORIMETRY_H_
#define ALLOYCOLOR_COLOR_COLORIMETRY_H_

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace alloycolor::color {

struct XYZ {
  double X, Y, Z;
};
struct Lab {
  double L, a, b;
};
struct RGB {
  double r, g, b;
};

// Names accepted for the illuminant (A, C, D50, D65, E, F2, F11) and observer (2, 10).
std::vector<std::string> IlluminantNames();

// The weights of eq. 5 for one illuminant and observer, on their common 5 nm grid.
class Colorimeter {
 public:
  // Reads data_dir/cie/illuminant-NAME.csv and data_dir/cie/cmf-1931-2.csv or
  // cmf-1964-10.csv. Throws Error for an unknown illuminant name or observer, or a
  // damaged table (naming the file and line).
  static Colorimeter Load(const std::string& data_dir, const std::string& illuminant,
                          int observer_deg);

  const std::string& illuminant() const { return illuminant_; }
  int observer_deg() const { return observer_deg_; }
  const std::vector<double>& lambda_nm() const { return lambda_nm_; }

  // Reflectance sampled on lambda_nm() -> XYZ (Y = 1 for a perfect reflector).
  XYZ ReflectanceToXYZ(const std::vector<double>& reflectance) const;
  XYZ ReflectanceToXYZ(const double* reflectance) const;
  XYZ White() const { return white_; }

  // Normalised weights: X = sum wx[i] R[i], etc.
  const std::vector<double>& wx() const { return wx_; }
  const std::vector<double>& wy() const { return wy_; }
  const std::vector<double>& wz() const { return wz_; }

 private:
  std::string illuminant_;
  int observer_deg_ = 2;
  std::vector<double> lambda_nm_, wx_, wy_, wz_;
  XYZ white_{};
};

// eq. 6, kept as the paper's output: R = 1.90X - 0.53Y - 0.29Z, G = -0.99X + 2.00Y - 0.03Z,
// B = 0.06X - 0.12Y + 0.90Z.
RGB PaperRGBFromXYZ(const XYZ& xyz);
// IEC 61966-2-1 matrix, D65 white, no chromatic adaptation.
RGB LinearSRGBFromXYZ(const XYZ& xyz);
XYZ XYZFromLinearSRGB(const RGB& rgb);
// The sRGB transfer function (IEC 61966-2-1) and its inverse, on [0, 1].
double SRGBEncode(double linear);
double SRGBDecode(double encoded);
// Linear sRGB clamped to [0, 1], encoded, rounded to 0..255.
std::array<std::uint8_t, 3> SRGB8FromLinear(const RGB& linear);
// CIELAB relative to the given white (Y of the white as the reference).
Lab LabFromXYZ(const XYZ& xyz, const XYZ& white);
// CIEDE2000 with kL = kC = kH = 1.
double DeltaE00(const Lab& lab1, const Lab& lab2);
// A lower bound of DeltaE00 that costs a few square roots and no trigonometry, for scans
// that need DeltaE00 only where it may be small: of DeltaE00(lab, c) for every colour c in
// a box (L*, a*, b* and chroma C_ab each within [lo, hi]), or for one colour. With the terms
// of CIEDE2000 (Sharma, Wu & Dalal 2005): dL' = dL, and dC'^2 + dH'^2 = (1 + G)^2 da^2 + db^2
// >= da^2 + db^2 (G >= 0); S_H <= S_C, as T <= 1.93; C' <= 1.5 C_ab (G <= 1/2), so
// S_C <= 1 + 0.0675 mean(C_ab); |R_T| <= sin(60 deg) R_C(1.5 mean(C_ab)) (R_C grows with C),
// and where both colours have b* >= 0 (hues in [0, 180] degrees, the mean hue at least 95
// degrees from 275) sin(2 * 30 exp(-(95/25)^2) deg) R_C, about 6e-7 R_C;
// and c^2 + h^2 + R_T c h >= (1 - |R_T| / 2)(c^2 + h^2). Hence
//   DeltaE00^2 >= (dL / S_L)^2 + (1 - |R_T|max / 2)(da^2 + db^2) / S_C,max^2,
// with dL, da, db the least over the box and S_L, |R_T| and S_C the largest.
struct LabBox {
  double l_lo, l_hi, a_lo, a_hi, b_lo, b_hi, c_lo, c_hi;
  static LabBox Of(const Lab& lab);
  void Add(const Lab& lab);  // grows the box to hold lab
};
double DeltaE00LowerBound(const Lab& lab, const LabBox& box);
double DeltaE00LowerBound(const Lab& lab1, const Lab& lab2);

}  // namespace alloycolor::color

#endif  // ALLOYCOLOR_COLOR_COLORIMETRY_H_
