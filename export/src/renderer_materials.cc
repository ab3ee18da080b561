#include "alloycolor/export/renderer_materials.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/units.h"
#include "alloycolor/model/optics.h"

namespace alloycolor::exports {
namespace {

double Channel(const color::RGB& c, int i) { return i == 0 ? c.r : (i == 1 ? c.g : c.b); }
double& Channel(color::RGB& c, int i) { return i == 0 ? c.r : (i == 1 ? c.g : c.b); }

double CosDeg(double angle_deg) { return std::cos(angle_deg * kPi / 180.0); }

// Parameters of the RGB conductor are ln eta, ln k, held to [ln 1e-4, ln 100]: a channel
// brighter than any conductor (above 1) drives them to the bounds, not to overflow, and
// 100 is the largest IOR and Extinction Blender's Metallic BSDF takes.
const double kMinLog = std::log(1e-4);
const double kMaxLog = std::log(100.0);

std::complex<double> IndexFromLogs(double log_eta, double log_k) {
  const auto value = [](double log_v) {
    return std::clamp(std::exp(std::clamp(log_v, kMinLog, kMaxLog)), 1e-4, 100.0);
  };
  return {value(log_eta), value(log_k)};
}

// Levenberg-Marquardt with a central-difference Jacobian on a few parameters.
template <typename Residuals>
Eigen::VectorXd LevenbergMarquardt(const Residuals& residuals, Eigen::VectorXd p,
                                   int max_iterations) {
  const auto clamp = [](Eigen::VectorXd v) { return v.cwiseMax(kMinLog).cwiseMin(kMaxLog); };
  p = clamp(p);
  double lambda = 1e-3;
  Eigen::VectorXd r = residuals(p);
  double cost = r.squaredNorm();
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    Eigen::MatrixXd jacobian(r.size(), p.size());
    for (int j = 0; j < p.size(); ++j) {
      constexpr double kStep = 1e-6;
      Eigen::VectorXd plus = p, minus = p;
      plus[j] += kStep;
      minus[j] -= kStep;
      jacobian.col(j) = (residuals(plus) - residuals(minus)) / (2 * kStep);
    }
    const Eigen::MatrixXd jtj = jacobian.transpose() * jacobian;
    const Eigen::VectorXd jtr = jacobian.transpose() * r;
    bool improved = false;
    while (lambda < 1e12) {
      Eigen::MatrixXd a = jtj;
      a.diagonal() += lambda * jtj.diagonal().cwiseMax(1e-12);
      const Eigen::VectorXd step = a.ldlt().solve(-jtr);
      const Eigen::VectorXd candidate = clamp(p + step);
      const Eigen::VectorXd rc = residuals(candidate);
      const double cost_c = rc.squaredNorm();
      if (std::isfinite(cost_c) && cost_c < cost) {
        const double gain = cost - cost_c;
        const double moved = (candidate - p).norm();
        p = candidate;
        r = rc;
        cost = cost_c;
        lambda = std::max(lambda / 10, 1e-12);
        improved = true;
        if (gain < 1e-14 * std::max(cost, 1e-30) || moved < 1e-10) return p;
        break;
      }
      lambda *= 10;
    }
    if (!improved) break;
  }
  return p;
}

// Residuals of one channel's conductor against the target: cube roots, as Lab weighs
// lightness.
Eigen::VectorXd ChannelResiduals(const Eigen::VectorXd& p, const std::vector<double>& angle_deg,
                                 const std::vector<double>& target) {
  const std::complex<double> index = IndexFromLogs(p[0], p[1]);
  Eigen::VectorXd r(angle_deg.size());
  for (std::size_t i = 0; i < angle_deg.size(); ++i) {
    r[i] = std::cbrt(ConductorReflectance(index, angle_deg[i])) - std::cbrt(target[i]);
  }
  return r;
}

// g in [0, 1] with R(GulbrandsenIndex(r, g), angle) = target, by bisection (R at a fixed
// angle decreases as g goes from 0 to 1 for angles below Brewster's, is monotone on the
// interval either way; the side is taken from the ends).
double SolveEdgeTint(double r, double target, double angle_deg, bool* clamped) {
  const auto f = [&](double g) {
    return ConductorReflectance(GulbrandsenIndex(r, g), angle_deg) - target;
  };
  double lo = 0.0, hi = 1.0;
  const double f_lo = f(lo), f_hi = f(hi);
  *clamped = false;
  if (f_lo * f_hi > 0) {
    *clamped = true;
    return std::abs(f_lo) < std::abs(f_hi) ? lo : hi;
  }
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    if ((f(mid) > 0) == (f_lo > 0)) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

color::Lab LabOfRGB(const color::Colorimeter& d65, const color::RGB& rgb) {
  return color::LabFromXYZ(color::XYZFromLinearSRGB(rgb), d65.White());
}

}  // namespace

std::vector<double> FitAnglesDeg() {
  std::vector<double> angles;
  const int count = static_cast<int>(std::lround(kMaxAngleDeg / kAngleStepDeg));
  for (int i = 0; i <= count; ++i) angles.push_back(i * kAngleStepDeg);
  return angles;
}

double SchlickFresnel(double f0, double mu) { return f0 + (1 - f0) * std::pow(1 - mu, 5); }

double F82TintFresnel(double f0, double tint, double mu) {
  const double mb = kOpenPbrMuBar;
  const double b = SchlickFresnel(f0, mb) * (1 - tint) / (mb * std::pow(1 - mb, 6));
  return SchlickFresnel(f0, mu) - b * mu * std::pow(1 - mu, 6);
}

std::complex<double> GulbrandsenIndex(double r, double g) {
  const double sr = std::sqrt(r);
  const double n_min = (1 - r) / (1 + r);
  const double n_max = (1 + sr) / (1 - sr);
  const double n = g * n_min + (1 - g) * n_max;
  const double k2 = (r * (n + 1) * (n + 1) - (n - 1) * (n - 1)) / (1 - r);
  return {n, std::sqrt(std::max(k2, 0.0))};
}

double ConductorReflectance(std::complex<double> index, double angle_deg) {
  const double cos_psi = std::max(CosDeg(angle_deg), 0.0);
  return FresnelReflectance(Complex<double>{index.real(), index.imag()}, cos_psi).Average();
}

AngularError AngularDeltaE00(const color::Colorimeter& d65, const RendererMaterials& materials,
                             const std::vector<color::RGB>& approximation) {
  AngularError error;
  for (std::size_t i = 0; i < materials.angle_deg.size(); ++i) {
    const double de = color::DeltaE00(materials.spectral_lab[i], LabOfRGB(d65, approximation[i]));
    if (de > error.max_delta_e00 || i == 0) {
      error.max_delta_e00 = de;
      error.at_angle_deg = materials.angle_deg[i];
    }
  }
  return error;
}

namespace {

// Linear sRGB at each angle of the RGB conductor whose (log eta, log k) per channel are q.
std::vector<color::RGB> ConductorCurve(const Eigen::VectorXd& q,
                                       const std::vector<double>& angles_deg) {
  std::vector<color::RGB> rgb;
  for (double angle : angles_deg) {
    color::RGB v{};
    for (int c = 0; c < 3; ++c) {
      Channel(v, c) = ConductorReflectance(IndexFromLogs(q[2 * c], q[2 * c + 1]), angle);
    }
    rgb.push_back(v);
  }
  return rgb;
}

// The RGB conductor fitted per channel on cube roots, from the best of a few starts.
Eigen::VectorXd FitConductorPerChannel(const RendererMaterials& m) {
  Eigen::VectorXd p(6);
  for (int c = 0; c < 3; ++c) {
    std::vector<double> target;
    for (const color::RGB& rgb : m.spectral_rgb) target.push_back(Channel(rgb, c));
    const auto residuals = [&](const Eigen::VectorXd& q) {
      return ChannelResiduals(q, m.angle_deg, target);
    };
    Eigen::VectorXd best(2);
    double best_cost = INFINITY;
    for (double eta : {0.05, 0.2, 0.5, 1.0, 2.0, 4.0}) {
      for (double k : {0.5, 1.5, 3.0, 6.0, 12.0}) {
        const Eigen::Vector2d q(std::log(eta), std::log(k));
        const double cost = residuals(q).squaredNorm();
        if (cost < best_cost) {
          best_cost = cost;
          best = q;
        }
      }
    }
    p.segment<2>(2 * c) = LevenbergMarquardt(residuals, best, 200);
  }
  return p;
}

// The RGB conductor closest to the spectral colour over angle.
RgbConductor FitRgbConductor(const color::Colorimeter& d65, const RendererMaterials& m) {
  // First per channel on cube roots, from the best of a few starts; then all six
  // parameters together on the CIEDE2000 differences themselves, which matters where the
  // colour lies outside the sRGB gamut (a channel above 1 cannot be matched: the others
  // move to keep the colour close). The one with the smaller largest difference is kept.
  RgbConductor conductor;
  Eigen::VectorXd p = FitConductorPerChannel(m);
  constexpr double kPower = 2.0;  // sum of dE^4: close to the largest dE
  const auto delta_e = [&](const Eigen::VectorXd& q) {
    const std::vector<color::RGB> rgb = ConductorCurve(q, m.angle_deg);
    Eigen::VectorXd r(rgb.size());
    for (std::size_t i = 0; i < rgb.size(); ++i) {
      r[i] = std::pow(color::DeltaE00(m.spectral_lab[i], LabOfRGB(d65, rgb[i])), kPower);
    }
    return r;
  };
  const Eigen::VectorXd p_de = LevenbergMarquardt(delta_e, p, 60);
  if (delta_e(p_de).maxCoeff() < delta_e(p).maxCoeff()) {
    p = p_de;
    conductor.fit =
        "per-channel least squares on cube roots, then the sum of CIEDE2000^4 over angles";
  } else {
    conductor.fit = "per-channel least squares on cube roots";
  }
  // A channel driven to R = 1 may end at eta = k = 1e-4 (N -> 0) as well as at
  // eta = 1e-4, k = 100; the metal-like one is written when it does as well.
  for (int c = 0; c < 3; ++c) {
    if (p[2 * c] <= kMinLog + 1e-9 && p[2 * c + 1] < 0) {
      Eigen::VectorXd q = p;
      q[2 * c + 1] = kMaxLog;
      if (delta_e(q).maxCoeff() <= delta_e(p).maxCoeff() + 1e-9) p = q;
    }
  }
  for (int c = 0; c < 3; ++c) {
    const std::complex<double> index = IndexFromLogs(p[2 * c], p[2 * c + 1]);
    Channel(conductor.eta, c) = index.real();
    Channel(conductor.k, c) = index.imag();
  }
  conductor.error = AngularDeltaE00(d65, m, ConductorCurve(p, m.angle_deg));
  return conductor;
}

// Fits the F82-tint and Gulbrandsen parameters to the colours at 0 and 82 degrees.
void FitEdgeTints(const color::RGB& f0, const color::RGB& f82, RendererMaterials* m) {
  m->f82.f0 = f0;
  m->f82.f82 = f82;
  for (int c = 0; c < 3; ++c) {
    Channel(m->f82.tint, c) =
        Channel(f82, c) / SchlickFresnel(Channel(f0, c), CosDeg(kF82AngleDeg));
    const double r = std::clamp(Channel(f0, c), 0.0, kGulbrandsenMaxR);
    Channel(m->gulbrandsen.r, c) = r;
    m->gulbrandsen.r_clamped[c] = r != Channel(f0, c);
    bool clamped = false;
    Channel(m->gulbrandsen.g, c) = SolveEdgeTint(r, Channel(f82, c), kF82AngleDeg, &clamped);
    m->gulbrandsen.g_clamped[c] = clamped;
  }
}

// Scores the F82-tint, Schlick and Gulbrandsen curves against the spectral colour over angle.
void ScoreEdgeTints(const color::Colorimeter& d65, const color::RGB& f0, RendererMaterials* m) {
  std::vector<color::RGB> f82_model, schlick, gulbrandsen;
  for (double angle : m->angle_deg) {
    const double mu = CosDeg(angle);
    color::RGB b{}, s{}, g{};
    for (int c = 0; c < 3; ++c) {
      Channel(b, c) = F82TintFresnel(Channel(f0, c), Channel(m->f82.tint, c), mu);
      Channel(s, c) = SchlickFresnel(Channel(f0, c), mu);
      Channel(g, c) = ConductorReflectance(
          GulbrandsenIndex(Channel(m->gulbrandsen.r, c), Channel(m->gulbrandsen.g, c)), angle);
    }
    f82_model.push_back(b);
    schlick.push_back(s);
    gulbrandsen.push_back(g);
  }
  m->f82.error = AngularDeltaE00(d65, *m, f82_model);
  m->f82.schlick_error = AngularDeltaE00(d65, *m, schlick);
  m->gulbrandsen.error = AngularDeltaE00(d65, *m, gulbrandsen);
}

}  // namespace

RendererMaterials FitRendererMaterials(const color::Colorimeter& d65,
                                       const std::vector<std::complex<double>>& index,
                                       const std::string& what) {
  if (d65.illuminant() != "D65" || d65.observer_deg() != 2) {
    throw Error(
        "renderer materials are fitted in linear sRGB under D65 with the 2-degree "
        "observer, not " +
        d65.illuminant() + " " + std::to_string(d65.observer_deg()) + "-degree");
  }
  for (const auto& nk : index) {
    if (!std::isfinite(nk.real()) || !std::isfinite(nk.imag())) {
      throw Error(what + ": n or k is not finite");
    }
  }
  RendererMaterials m;
  m.angle_deg = FitAnglesDeg();
  for (double angle : m.angle_deg) {
    const color::XYZ xyz = color::MaterialXYZ(d65, index, angle);
    m.spectral_rgb.push_back(color::LinearSRGBFromXYZ(xyz));
    m.spectral_lab.push_back(color::LabFromXYZ(xyz, d65.White()));
  }
  const color::RGB f0 = m.spectral_rgb.front();
  const color::RGB f82 = color::LinearSRGBFromXYZ(color::MaterialXYZ(d65, index, kF82AngleDeg));
  m.rgb_conductor = FitRgbConductor(d65, m);
  FitEdgeTints(f0, f82, &m);
  ScoreEdgeTints(d65, f0, &m);
  return m;
}

}  // namespace alloycolor::exports
