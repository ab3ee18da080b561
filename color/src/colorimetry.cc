#include "alloycolor/color/colorimetry.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <utility>

#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/units.h"

namespace alloycolor::color {
namespace {

using Matrix3 = std::array<std::array<double, 3>, 3>;

// Wavelengths in the tables are integers of nm; a row is "at" a grid point
// within this.
constexpr double kLambdaToleranceNm = 1e-6;

// IEC 61966-2-1:1999, eq. (5): CIE XYZ (D65, Y = 1) to linear sRGB.
constexpr Matrix3 kMatrixXYZToSRGB = {
    {{3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}}};

// The paper's eq. 6, with its printed two-decimal coefficients.
constexpr Matrix3 kMatrixXYZToPaperRGB = {
    {{1.90, -0.53, -0.29}, {-0.99, 2.00, -0.03}, {0.06, -0.12, 0.90}}};

// IEC 61966-2-1 transfer function: the linear segment below kSRGBLinearMax
// (encoded value kSRGBEncodedMax), the 2.4 power law above.
constexpr double kSRGBLinearMax = 0.0031308;
constexpr double kSRGBEncodedMax = 0.04045;

// CIE 15:2004, eqs. 8.3-8.6: f(t) = t^(1/3) above (6/29)^3, linear below.
constexpr double kLabEpsilon = 216.0 / 24389.0;  // (6/29)^3
constexpr double kLabKappa = 24389.0 / 27.0;     // (29/3)^3

constexpr double k25Pow7 = 6103515625.0;  // 25^7, CIEDE2000

constexpr const char* kIlluminantNames[] = {"A", "C", "D50", "D65", "E", "F2", "F11"};

Matrix3 Inverse(const Matrix3& m) {
  const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
  const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
  const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
  Matrix3 inv;
  inv[0] = {c00 / det, (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det,
            (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det};
  inv[1] = {c01 / det, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det,
            (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det};
  inv[2] = {c02 / det, (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det,
            (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det};
  return inv;
}

// Linear sRGB to XYZ: the exact inverse of kMatrixXYZToSRGB, so that the two
// conversions round-trip; it agrees with the standard's rounded inverse (0.4124
// 0.3576 0.1805 ...) to 1e-4.
const Matrix3& MatrixSRGBToXYZ() {
  static const Matrix3 kMatrix = Inverse(kMatrixXYZToSRGB);
  return kMatrix;
}

std::array<double, 3> Apply(const Matrix3& m, double x, double y, double z) {
  return {m[0][0] * x + m[0][1] * y + m[0][2] * z, m[1][0] * x + m[1][1] * y + m[1][2] * z,
          m[2][0] * x + m[2][1] * y + m[2][2] * z};
}

std::string Trim(const std::string& s) {
  const auto is_space = [](unsigned char c) { return std::isspace(c) != 0; };
  auto begin = std::find_if_not(s.begin(), s.end(), is_space);
  auto end = std::find_if_not(s.rbegin(), s.rend(), is_space).base();
  return begin < end ? std::string(begin, end) : std::string();
}

std::vector<std::string> Split(const std::string& s, char separator) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  for (std::size_t end; (end = s.find(separator, begin)) != std::string::npos; begin = end + 1) {
    parts.push_back(s.substr(begin, end - begin));
  }
  parts.push_back(s.substr(begin));
  return parts;
}

std::string FormatNm(double lambda_nm) {
  std::ostringstream out;
  out << lambda_nm << " nm";
  return out.str();
}

std::string Upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string JoinedIlluminantNames() {
  std::string joined;
  for (const char* name : kIlluminantNames) {
    if (!joined.empty()) joined += ", ";
    joined += name;
  }
  return joined;
}

// A CIE table: rows of lambda_nm followed by non-negative values, strictly
// increasing in lambda_nm.
struct Table {
  std::string path;
  std::vector<double> lambda_nm;
  std::vector<std::vector<double>> values;  // values[row][column - 1]
};

// Reads a CSV table whose first non-comment line is exactly `header`. Lines
// starting with '#' and blank lines are skipped.
Table ReadTable(const std::string& path, const std::string& header) {
  // ReadFileText reads regular files only, with a size cap (not a FIFO, not /dev/zero).
  std::istringstream in(ReadFileText(path));
  const std::size_t columns = std::count(header.begin(), header.end(), ',') + 1;
  Table table;
  table.path = path;
  bool header_seen = false;
  std::string raw;
  for (int line_number = 1; std::getline(in, raw); ++line_number) {
    const std::string line = Trim(raw);
    const std::string where = path + ":" + std::to_string(line_number) + ": ";
    if (line.empty() || line[0] == '#') continue;
    if (!header_seen) {
      if (line != header) {
        throw Error(where + "expected the header '" + header + "', found '" + line + "'");
      }
      header_seen = true;
      continue;
    }
    std::vector<double> fields;
    for (const std::string& field : Split(line, ',')) {
      const std::string text = Trim(field);
      char* end = nullptr;
      errno = 0;
      const double value = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(value)) {
        throw Error(where + "'" + text + "' is not a finite number");
      }
      fields.push_back(value);
    }
    if (fields.size() != columns) {
      throw Error(where + "expected " + std::to_string(columns) + " fields, found " +
                  std::to_string(fields.size()));
    }
    if (!table.lambda_nm.empty() && fields[0] <= table.lambda_nm.back()) {
      throw Error(where + "wavelengths must increase (" + FormatNm(fields[0]) + " after " +
                  FormatNm(table.lambda_nm.back()) + ")");
    }
    for (std::size_t i = 1; i < fields.size(); ++i) {
      if (fields[i] < 0.0) throw Error(where + "negative value");
    }
    table.lambda_nm.push_back(fields[0]);
    table.values.emplace_back(fields.begin() + 1, fields.end());
  }
  if (!header_seen) throw Error(path + ": no header line '" + header + "'");
  if (table.lambda_nm.empty()) throw Error(path + ": no data rows");
  return table;
}

// The row of `table` at lambda_nm (no interpolation); throws if there is none.
const std::vector<double>& RowAt(const Table& table, double lambda_nm) {
  auto it = std::lower_bound(table.lambda_nm.begin(), table.lambda_nm.end(),
                             lambda_nm - kLambdaToleranceNm);
  if (it == table.lambda_nm.end() || std::abs(*it - lambda_nm) > kLambdaToleranceNm) {
    std::ostringstream message;
    message << table.path << ": no row at " << FormatNm(lambda_nm)
            << " (tables must be sampled at every multiple of " << kGridStepNm
            << " nm in their range)";
    throw Error(message.str());
  }
  return table.values[it - table.lambda_nm.begin()];
}

// CIE 15:2004 eq. 8.3-8.6 helper.
double LabF(double t) { return t > kLabEpsilon ? std::cbrt(t) : (kLabKappa * t + 16.0) / 116.0; }

double Degrees(double radians) { return radians * (180.0 / kPi); }
double Radians(double degrees) { return degrees * (kPi / 180.0); }

// c^7 by multiplication (std::pow is several times slower; CIEDE2000 runs in scans).
double Pow7(double c) {
  const double c2 = c * c;
  return c2 * c2 * c2 * c;
}

// Hue angle in degrees on [0, 360); 0 when a' = b = 0 (Sharma et al. 2005,
// eq. 4).
double HueDegrees(double b, double a_prime) {
  if (b == 0.0 && a_prime == 0.0) return 0.0;
  double h = Degrees(std::atan2(b, a_prime));
  if (h < 0.0) h += 360.0;
  return h;
}

}  // namespace

std::vector<std::string> IlluminantNames() {
  return {std::begin(kIlluminantNames), std::end(kIlluminantNames)};
}

Colorimeter Colorimeter::Load(const std::string& data_dir, const std::string& illuminant,
                              int observer_deg) {
  std::string name;
  for (const char* candidate : kIlluminantNames) {
    if (Upper(illuminant) == candidate) name = candidate;
  }
  if (name.empty()) {
    throw Error("unknown illuminant '" + illuminant + "'; valid names: " + JoinedIlluminantNames());
  }
  if (observer_deg != 2 && observer_deg != 10) {
    throw Error("unknown observer " + std::to_string(observer_deg) +
                " deg; valid observers: 2 (CIE 1931), 10 (CIE 1964)");
  }

  const std::string cie_dir = data_dir + "/cie/";
  const Table spd = ReadTable(cie_dir + "illuminant-" + name + ".csv", "lambda_nm,value");
  const Table cmf = ReadTable(cie_dir + (observer_deg == 2 ? "cmf-1931-2.csv" : "cmf-1964-10.csv"),
                              "lambda_nm,x_bar,y_bar,z_bar");

  const double first_nm =
      std::ceil(std::max(spd.lambda_nm.front(), cmf.lambda_nm.front()) / kGridStepNm -
                kLambdaToleranceNm) *
      kGridStepNm;
  const double last_nm =
      std::floor(std::min(spd.lambda_nm.back(), cmf.lambda_nm.back()) / kGridStepNm +
                 kLambdaToleranceNm) *
      kGridStepNm;
  if (first_nm > last_nm) {
    throw Error(spd.path + " and " + cmf.path + " share no wavelength range");
  }

  Colorimeter colorimeter;
  colorimeter.illuminant_ = name;
  colorimeter.observer_deg_ = observer_deg;
  double y_sum = 0.0;
  const int count = static_cast<int>(std::lround((last_nm - first_nm) / kGridStepNm)) + 1;
  for (int i = 0; i < count; ++i) {
    const double lambda_nm = first_nm + i * kGridStepNm;
    const double power = RowAt(spd, lambda_nm)[0];
    const std::vector<double>& bar = RowAt(cmf, lambda_nm);
    colorimeter.lambda_nm_.push_back(lambda_nm);
    colorimeter.wx_.push_back(power * bar[0]);
    colorimeter.wy_.push_back(power * bar[1]);
    colorimeter.wz_.push_back(power * bar[2]);
    y_sum += power * bar[1];
  }
  if (!(y_sum > 0.0)) {
    throw Error(spd.path + ": the illuminant has no power where " + cmf.path + " has y_bar > 0");
  }
  for (std::vector<double>* w : {&colorimeter.wx_, &colorimeter.wy_, &colorimeter.wz_}) {
    for (double& value : *w) value /= y_sum;
  }
  // The division leaves sum(wy) a few ulps from 1. Setting the last weight to 1
  // minus the sum of the others (exact, by Sterbenz's lemma, as that sum is
  // near 1) moves it by ~1e-16 and makes a perfect reflector, summed in
  // ReflectanceToXYZ's order, give Y = 1.
  std::vector<double>& wy = colorimeter.wy_;
  if (wy.size() >= 2) {
    double others = 0.0;
    for (std::size_t i = 0; i + 1 < wy.size(); ++i) others += wy[i];
    wy.back() = 1.0 - others;
  }
  const std::vector<double> ones(colorimeter.lambda_nm_.size(), 1.0);
  colorimeter.white_ = colorimeter.ReflectanceToXYZ(ones);
  return colorimeter;
}

XYZ Colorimeter::ReflectanceToXYZ(const std::vector<double>& reflectance) const {
  if (reflectance.size() != lambda_nm_.size()) {
    throw Error("reflectance has " + std::to_string(reflectance.size()) +
                " samples; the colorimeter for illuminant " + illuminant_ + " needs " +
                std::to_string(lambda_nm_.size()) + " (its 5 nm grid)");
  }
  return ReflectanceToXYZ(reflectance.data());
}

XYZ Colorimeter::ReflectanceToXYZ(const double* reflectance) const {
  XYZ xyz{0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < lambda_nm_.size(); ++i) {
    xyz.X += wx_[i] * reflectance[i];
    xyz.Y += wy_[i] * reflectance[i];
    xyz.Z += wz_[i] * reflectance[i];
  }
  return xyz;
}

RGB PaperRGBFromXYZ(const XYZ& xyz) {
  const auto rgb = Apply(kMatrixXYZToPaperRGB, xyz.X, xyz.Y, xyz.Z);
  return {rgb[0], rgb[1], rgb[2]};
}

RGB LinearSRGBFromXYZ(const XYZ& xyz) {
  const auto rgb = Apply(kMatrixXYZToSRGB, xyz.X, xyz.Y, xyz.Z);
  return {rgb[0], rgb[1], rgb[2]};
}

XYZ XYZFromLinearSRGB(const RGB& rgb) {
  const auto xyz = Apply(MatrixSRGBToXYZ(), rgb.r, rgb.g, rgb.b);
  return {xyz[0], xyz[1], xyz[2]};
}

double SRGBEncode(double linear) {
  if (linear <= kSRGBLinearMax) return 12.92 * linear;
  return 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double SRGBDecode(double encoded) {
  if (encoded <= kSRGBEncodedMax) return encoded / 12.92;
  return std::pow((encoded + 0.055) / 1.055, 2.4);
}

std::array<std::uint8_t, 3> SRGB8FromLinear(const RGB& linear) {
  const auto to8 = [](double value) {
    // NaN compares false both ways and ends up as 0, like a negative value.
    const double clamped = value > 0.0 ? std::min(value, 1.0) : 0.0;
    return static_cast<std::uint8_t>(std::lround(255.0 * SRGBEncode(clamped)));
  };
  return {to8(linear.r), to8(linear.g), to8(linear.b)};
}

Lab LabFromXYZ(const XYZ& xyz, const XYZ& white) {
  const double fx = LabF(xyz.X / white.X);
  const double fy = LabF(xyz.Y / white.Y);
  const double fz = LabF(xyz.Z / white.Z);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

// Sharma, Wu & Dalal (2005), eqs. 1-22, with kL = kC = kH = 1.
double DeltaE00(const Lab& lab1, const Lab& lab2) {
  // eqs. 2-7: a', C', h'.
  const double c1_ab = std::sqrt(lab1.a * lab1.a + lab1.b * lab1.b);
  const double c2_ab = std::sqrt(lab2.a * lab2.a + lab2.b * lab2.b);
  const double c_ab_mean = 0.5 * (c1_ab + c2_ab);
  const double c_ab_mean7 = Pow7(c_ab_mean);
  const double g = 0.5 * (1.0 - std::sqrt(c_ab_mean7 / (c_ab_mean7 + k25Pow7)));
  const double a1 = (1.0 + g) * lab1.a;
  const double a2 = (1.0 + g) * lab2.a;
  const double c1 = std::sqrt(a1 * a1 + lab1.b * lab1.b);
  const double c2 = std::sqrt(a2 * a2 + lab2.b * lab2.b);
  const double h1 = HueDegrees(lab1.b, a1);
  const double h2 = HueDegrees(lab2.b, a2);
  const bool achromatic = c1 * c2 == 0.0;

  // eqs. 8-11: differences.
  const double delta_l = lab2.L - lab1.L;
  const double delta_c = c2 - c1;
  double delta_h = 0.0;
  if (!achromatic) {
    delta_h = h2 - h1;
    if (delta_h > 180.0) {
      delta_h -= 360.0;
    } else if (delta_h < -180.0) {
      delta_h += 360.0;
    }
  }
  const double delta_big_h = 2.0 * std::sqrt(c1 * c2) * std::sin(Radians(0.5 * delta_h));

  // eqs. 12-22: means, weights and rotation.
  const double l_mean = 0.5 * (lab1.L + lab2.L);
  const double c_mean = 0.5 * (c1 + c2);
  double h_mean = h1 + h2;
  if (!achromatic) {
    if (std::abs(h1 - h2) <= 180.0) {
      h_mean = 0.5 * (h1 + h2);
    } else if (h1 + h2 < 360.0) {
      h_mean = 0.5 * (h1 + h2 + 360.0);
    } else {
      h_mean = 0.5 * (h1 + h2 - 360.0);
    }
  }
  // T of eq. 15, its four cosines from cos and sin of h_mean by the multiple-angle and
  // angle-sum identities (one sine and cosine instead of four cosines: scans over
  // composition evaluate CIEDE2000 thousands of times per target).
  const double hr = Radians(h_mean);
  const double c1h = std::cos(hr), s1h = std::sin(hr);
  const double c2h = 2.0 * c1h * c1h - 1.0, s2h = 2.0 * s1h * c1h;
  const double c3h = c1h * c2h - s1h * s2h, s3h = s1h * c2h + c1h * s2h;
  const double c4h = c2h * c2h - s2h * s2h, s4h = 2.0 * s2h * c2h;
  static const double kCos30 = std::cos(Radians(30.0)), kSin30 = 0.5;
  static const double kCos6 = std::cos(Radians(6.0)), kSin6 = std::sin(Radians(6.0));
  static const double kCos63 = std::cos(Radians(63.0)), kSin63 = std::sin(Radians(63.0));
  const double t = 1.0 - 0.17 * (c1h * kCos30 + s1h * kSin30) +  // cos(h - 30)
                   0.24 * c2h +                                  // cos(2h)
                   0.32 * (c3h * kCos6 - s3h * kSin6) -          // cos(3h + 6)
                   0.20 * (c4h * kCos63 + s4h * kSin63);         // cos(4h - 63)
  const double delta_theta =
      30.0 * std::exp(-((h_mean - 275.0) / 25.0) * ((h_mean - 275.0) / 25.0));
  const double c_mean7 = Pow7(c_mean);
  const double r_c = 2.0 * std::sqrt(c_mean7 / (c_mean7 + k25Pow7));
  const double l50 = (l_mean - 50.0) * (l_mean - 50.0);
  const double s_l = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double s_c = 1.0 + 0.045 * c_mean;
  const double s_h = 1.0 + 0.015 * c_mean * t;
  const double r_t = -std::sin(Radians(2.0 * delta_theta)) * r_c;

  const double dl = delta_l / s_l;
  const double dc = delta_c / s_c;
  const double dh = delta_big_h / s_h;
  return std::sqrt(dl * dl + dc * dc + dh * dh + r_t * dc * dh);
}

LabBox LabBox::Of(const Lab& lab) {
  const double c = std::sqrt(lab.a * lab.a + lab.b * lab.b);
  return {lab.L, lab.L, lab.a, lab.a, lab.b, lab.b, c, c};
}

void LabBox::Add(const Lab& lab) {
  const LabBox p = Of(lab);
  l_lo = std::min(l_lo, p.l_lo), l_hi = std::max(l_hi, p.l_hi);
  a_lo = std::min(a_lo, p.a_lo), a_hi = std::max(a_hi, p.a_hi);
  b_lo = std::min(b_lo, p.b_lo), b_hi = std::max(b_hi, p.b_hi);
  c_lo = std::min(c_lo, p.c_lo), c_hi = std::max(c_hi, p.c_hi);
}

double DeltaE00LowerBound(const Lab& lab, const LabBox& box) {
  const auto gap = [](double v, double lo, double hi) { return std::max({0.0, lo - v, v - hi}); };
  const double c_ab_mean = 0.5 * (std::sqrt(lab.a * lab.a + lab.b * lab.b) + box.c_hi);
  const double c_max7 = Pow7(1.5 * c_ab_mean);
  // The rotation: delta_theta <= 30 degrees; where both colours have b* >= 0 their hues h'
  // lie in [0, 180] degrees, so the mean hue lies 95 degrees or more from 275 and
  // delta_theta <= 30 exp(-(95/25)^2) degrees.
  static const double kSinAny = std::sin(Radians(60.0));
  static const double kSinUpper =
      std::sin(Radians(60.0 * std::exp(-(95.0 / 25.0) * (95.0 / 25.0))));
  const double sin_max = lab.b >= 0.0 && box.b_lo >= 0.0 ? kSinUpper : kSinAny;
  const double r_t_max = sin_max * 2.0 * std::sqrt(c_max7 / (c_max7 + k25Pow7));
  const double s_c_max = 1.0 + 0.0675 * c_ab_mean;
  // S_L grows with |mean L - 50|: largest at the box's end farther from 50.
  const double l_far = std::max(std::abs(0.5 * (lab.L + box.l_lo) - 50.0),
                                std::abs(0.5 * (lab.L + box.l_hi) - 50.0));
  const double s_l = 1.0 + 0.015 * l_far * l_far / std::sqrt(20.0 + l_far * l_far);
  const double dl = gap(lab.L, box.l_lo, box.l_hi) / s_l;
  const double da = gap(lab.a, box.a_lo, box.a_hi), db = gap(lab.b, box.b_lo, box.b_hi);
  return std::sqrt(dl * dl + (1.0 - 0.5 * r_t_max) * (da * da + db * db) / (s_c_max * s_c_max));
}

double DeltaE00LowerBound(const Lab& lab1, const Lab& lab2) {
  return DeltaE00LowerBound(lab1, LabBox::Of(lab2));
}

}  // namespace alloycolor::color
