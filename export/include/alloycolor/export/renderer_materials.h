// Materials for RGB renderers: a spectral conductor reduced to the few numbers that RGB
// shading models take, and what each reduction loses.
//
// The truth is the spectral colour of the polished metal at incidence angle theta: the
// Fresnel reflectance R(lambda, theta) of N = n + ik (eq. 2-4, unpolarised), integrated to
// CIE XYZ under D65 with the CIE 1931 2-degree observer (eq. 5), then linear sRGB
// (IEC 61966-2-1: Rec. 709 primaries, D65 white) — color::MaterialXYZ and
// color::LinearSRGBFromXYZ. An RGB renderer evaluates its Fresnel curve per channel and the
// channel values are taken as linear sRGB. Four reductions, each compared with the truth
// by CIEDE2000 (Lab with the D65 white) at every kFitAnglesDeg angle, 0-85 degrees:
//
//  - RGB conductor: per channel c a complex index eta_c + i k_c whose Fresnel reflectance
//    R(eta_c + i k_c, theta) (the same eq. 2-4 with one index) is fitted by
//    Levenberg-Marquardt to the channel of the spectral colour over 0-85 degrees, on
//    cube roots (as Lab's lightness weighs them), then all six numbers together on the
//    CIEDE2000 differences (kept if that lowers the largest one). For Mitsuba 3 RGB variants
//    (conductor with rgb eta/k), Blender's Metallic BSDF in physical-conductor mode, MaterialX
//    conductor_bsdf (ior, extinction).
//  - F82-tint (OpenPBR base_metalness = 1, Adobe Standard Material; Kutz et al. 2021,
//    "Novel aspects of the Adobe Standard Material"; Hoffman 2019):
//      F0 = spectral colour at 0 degrees, F82 = spectral colour at 82 degrees,
//      Schlick(F0, mu) = F0 + (1 - F0)(1 - mu)^5,  tint = F82 / Schlick(F0, cos 82 deg),
//      F(mu) = Schlick(F0, mu) - b mu (1 - mu)^6,
//      b = Schlick(F0, mu_bar) (1 - tint) / (mu_bar (1 - mu_bar)^6),  mu_bar = 1/7,
//    as OpenPBR writes it (mu_bar = 1/7 is 81.79 degrees, "roughly 82").
//  - Gulbrandsen 2014 ("Artist friendly metallic Fresnel", JCGT 3(4)): reflectivity r and
//    edge tint g per channel,
//      n_min = (1 - r)/(1 + r),  n_max = (1 + sqrt r)/(1 - sqrt r),
//      n(r, g) = g n_min + (1 - g) n_max,  k(r, g) = sqrt((r (n + 1)^2 - (n - 1)^2)/(1 - r)),
//    so that R(n, k, 0) = r exactly; r = F0 (held in [0, 0.99] as MaterialX does) and g is solved
//    (bisection, g in [0, 1]) so that R(n, k, 82 deg) equals F82: F0 and the edge colour are
//    reproduced. For Standard Surface (metalness 1: base_color = r, specular_color = g) and
//    MaterialX artistic_ior (reflectivity, edge_color).
//  - Schlick with F0 alone: what glTF 2.0's metal-roughness model (baseColorFactor = F0,
//    metallicFactor = 1) renders.
//
// Everything is dimensionless; angles in degrees.
#ifndef ALLOYCOLOR_EXPORT_RENDERER_MATERIALS_H_
#define ALLOYCOLOR_EXPORT_RENDERER_MATERIALS_H_

#include <array>
#include <complex>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"

namespace alloycolor::exports {

inline constexpr double kF82AngleDeg = 82.0;
inline constexpr double kOpenPbrMuBar = 1.0 / 7.0;
inline constexpr double kMaxAngleDeg = 85.0;
inline constexpr double kAngleStepDeg = 0.5;
// r is kept below 1 (k grows without bound as r -> 1), as MaterialX's artistic_ior does.
inline constexpr double kGulbrandsenMaxR = 0.99;

// 0, 0.5, ..., 85 degrees: where the fits are made and the errors measured.
std::vector<double> FitAnglesDeg();

// The closed forms above, per channel (mu = cos theta).
double SchlickFresnel(double f0, double mu);
double F82TintFresnel(double f0, double tint, double mu);
std::complex<double> GulbrandsenIndex(double r, double g);
// eq. 2-4 for one index at angle theta (degrees).
double ConductorReflectance(std::complex<double> index, double angle_deg);

// The largest CIEDE2000 difference over the angles, and where it is.
struct AngularError {
  double max_delta_e00 = 0.0;
  double at_angle_deg = 0.0;
};

struct RgbConductor {
  color::RGB eta{}, k{};
  std::string fit;  // which stages were kept
  AngularError error;
};

struct F82Tint {
  color::RGB f0{}, f82{}, tint{};
  AngularError error;          // of the F82-tint model with this F0 and tint
  AngularError schlick_error;  // of Schlick with F0 alone (glTF's metal)
};

struct Gulbrandsen {
  color::RGB r{}, g{};
  std::array<bool, 3> r_clamped{};  // F0 outside [0, kGulbrandsenMaxR]: r at the bound
  std::array<bool, 3> g_clamped{};  // F82 out of reach for g in [0, 1]: g at the bound
  AngularError error;
};

struct RendererMaterials {
  std::vector<double> angle_deg;         // FitAnglesDeg()
  std::vector<color::RGB> spectral_rgb;  // linear sRGB of the truth at each angle
  std::vector<color::Lab> spectral_lab;  // relative to the D65 white
  RgbConductor rgb_conductor;
  F82Tint f82;
  Gulbrandsen gulbrandsen;
};

// `d65` must be a D65, 2-degree colorimeter; `index` is n + ik on its grid
// (color::IndexOnGrid). Throws Error (naming `what`) for another illuminant or an index
// that is not finite. A spectral colour outside the sRGB gamut (gold's red channel is
// above 1 at normal incidence) is kept as it is: F0 and F82 report it, the fits come as
// close as their curves allow, and the angular errors say what is lost.
RendererMaterials FitRendererMaterials(const color::Colorimeter& d65,
                                       const std::vector<std::complex<double>>& index,
                                       const std::string& what);

// The largest CIEDE2000 difference between the truth and an RGB Fresnel curve given per
// angle (linear sRGB), over materials.angle_deg.
AngularError AngularDeltaE00(const color::Colorimeter& d65, const RendererMaterials& materials,
                             const std::vector<color::RGB>& approximation);

}  // namespace alloycolor::exports

#endif  // ALLOYCOLOR_EXPORT_RENDERER_MATERIALS_H_
