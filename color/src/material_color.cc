#include "alloycolor/color/material_color.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "alloycolor/color/reflectance_arrays.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/text.h"
#include "alloycolor/model/optics.h"

namespace alloycolor::color {

ColorResult ColorFromXYZ(const Colorimeter& colorimeter, const XYZ& xyz) {
  ColorResult c;
  c.xyz = xyz;
  c.lab = LabFromXYZ(xyz, colorimeter.White());
  c.linear_srgb = LinearSRGBFromXYZ(xyz);
  c.srgb8 = SRGB8FromLinear(c.linear_srgb);
  c.paper_rgb = PaperRGBFromXYZ(xyz);
  return c;
}

std::vector<double> EvaluationGrid(const Colorimeter& colorimeter, double lo_nm, double hi_nm,
                                   const std::string& what) {
  const std::vector<double>& grid = colorimeter.lambda_nm();
  const double need_lo = std::max(kVisibleMinNm, grid.front());
  const double need_hi = std::min(kVisibleMaxNm, grid.back());
  if (lo_nm > need_lo + 1e-9 || hi_nm < need_hi - 1e-9) {
    std::ostringstream msg;
    msg << what << ": covers " << lo_nm << "-" << hi_nm << " nm; colour needs " << need_lo << "-"
        << need_hi << " nm";
    throw Error(msg.str());
  }
  std::vector<double> held(grid.size());
  for (size_t i = 0; i < grid.size(); ++i) held[i] = std::clamp(grid[i], lo_nm, hi_nm);
  return held;
}

std::vector<std::complex<double>> IndexOnGrid(const Colorimeter& colorimeter,
                                              const NkSpectrum& nk) {
  const std::vector<double> grid =
      EvaluationGrid(colorimeter, nk.lambda_min_nm(), nk.lambda_max_nm(), nk.source);
  return NkOn(nk, grid);
}

std::vector<std::complex<double>> IndexOnGrid(const Colorimeter& colorimeter,
                                              const AlloyModel& model, double x_atomic) {
  const std::vector<double> grid =
      EvaluationGrid(colorimeter, model.lambda_min_nm(), model.lambda_max_nm(),
                     "the " + model.method() + " model");
  return model.Index(x_atomic, grid);
}

std::vector<double> ReflectanceSpectrum(const std::vector<std::complex<double>>& index,
                                        double angle_deg) {
  const double cos_psi = std::cos(angle_deg * M_PI / 180.0);
  std::vector<double> r(index.size());
  for (size_t i = 0; i < index.size(); ++i) {
    const Complex<double> nk{index[i].real(), index[i].imag()};
    r[i] = FresnelReflectance(nk, std::max(cos_psi, 0.0)).Average();
  }
  return r;
}

XYZ MaterialXYZ(const Colorimeter& colorimeter, const std::vector<std::complex<double>>& index,
                double angle_deg) {
  return colorimeter.ReflectanceToXYZ(ReflectanceSpectrum(index, angle_deg));
}

std::string HexColor(const std::array<std::uint8_t, 3>& srgb8) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", srgb8[0], srgb8[1], srgb8[2]);
  return buf;
}

nlohmann::json ColorJson(const ColorResult& c) {
  const double sum = c.xyz.X + c.xyz.Y + c.xyz.Z;
  const RGB& s = c.linear_srgb;
  const bool clipped = s.r < 0 || s.g < 0 || s.b < 0 || s.r > 1 || s.g > 1 || s.b > 1;
  return {{"XYZ", {c.xyz.X, c.xyz.Y, c.xyz.Z}},
          {"xyY", {sum > 0 ? c.xyz.X / sum : 0.0, sum > 0 ? c.xyz.Y / sum : 0.0, c.xyz.Y}},
          {"Lab", {c.lab.L, c.lab.a, c.lab.b}},
          {"linear_srgb", {s.r, s.g, s.b}},
          {"srgb8", {c.srgb8[0], c.srgb8[1], c.srgb8[2]}},
          {"srgb_hex", HexColor(c.srgb8)},
          {"srgb_clipped", clipped},
          {"paper_rgb", {c.paper_rgb.r, c.paper_rgb.g, c.paper_rgb.b}}};
}

}  // namespace alloycolor::color

namespace alloycolor::color {

double DeltaE00Sigma(const Colorimeter& colorimeter, const AlloyModel& model, double x_atomic,
                     double angle_deg, int draws) {
  return DeltaE00Sigma(colorimeter, model, x_atomic, std::vector<double>{angle_deg}, draws)[0];
}

std::vector<double> DeltaE00Sigma(const Colorimeter& colorimeter, const AlloyModel& model,
                                  double x_atomic, const std::vector<double>& angles_deg,
                                  int draws) {
  std::vector<double> sigma(angles_deg.size(), -1.0);
  if (!model.HasUncertainty() || draws <= 0) return sigma;
  const std::vector<double> grid =
      EvaluationGrid(colorimeter, model.lambda_min_nm(), model.lambda_max_nm(),
                     "the " + model.method() + " model");
  const std::vector<std::complex<double>> central_index = model.Index(x_atomic, grid);
  const auto eps_draws = model.CheckedDraws(x_atomic, grid, draws);
  if (eps_draws.empty()) return sigma;
  // The draws' colours from their eps on arrays (the sweep's Fresnel step, equal to
  // MaterialXYZ of their index to rounding): no index, no reflectance spectrum per draw.
  const size_t m = grid.size();
  std::vector<double> eps1(m * eps_draws.size()), eps2(m * eps_draws.size());
  for (size_t d = 0; d < eps_draws.size(); ++d) {
    for (size_t i = 0; i < m; ++i) {
      eps1[d * m + i] = eps_draws[d][i].real();
      eps2[d * m + i] = eps_draws[d][i].imag();
    }
  }
  for (size_t a = 0; a < angles_deg.size(); ++a) {
    const Lab central =
        LabFromXYZ(MaterialXYZ(colorimeter, central_index, angles_deg[a]), colorimeter.White());
    const double cos_psi = std::max(std::cos(angles_deg[a] * M_PI / 180.0), 0.0);
    double sum = 0;
    for (size_t d = 0; d < eps_draws.size(); ++d) {
      double xyz[3];
      ReflectanceSums(m, &eps1[d * m], &eps2[d * m], cos_psi, angles_deg[a] == 0.0,
                      colorimeter.wx().data(), colorimeter.wy().data(), colorimeter.wz().data(),
                      xyz);
      const Lab lab = LabFromXYZ(XYZ{xyz[0], xyz[1], xyz[2]}, colorimeter.White());
      const double de = DeltaE00(central, lab);
      sum += de * de;
    }
    sigma[a] = std::sqrt(sum / eps_draws.size());
    if (!std::isfinite(sigma[a])) {
      throw Error((model.source().empty() ? std::string() : model.source() + ": ") +
                  "the colours of the " + model.method() + " model's uncertainty draws at x = " +
                  FormatNumber(x_atomic) + " are not finite; " + kUncertaintyTooWide);
    }
  }
  return sigma;
}

}  // namespace alloycolor::color
