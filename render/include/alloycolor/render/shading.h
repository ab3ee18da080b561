// Shading a metal surface: the colour of the light it reflects toward the viewer, always
// from the spectral Fresnel reflectance (optics.h, paper eq. 2-4) integrated against the
// illuminant and observer (colorimetry.h, eq. 5), never from an RGB stand-in for the metal.
//
// Every light of an environment has the spectral power distribution P(lambda) of the chosen
// illuminant, scaled by an achromatic factor E(w) >= 0 that depends on the direction w
// (E = 1: radiance of a perfect white diffuser under the illuminant). Then the colour seen
// at a surface point factors exactly into E and a reflection colour that needs only the
// cosine mu = cos(theta) of the viewing direction to the normal:
//
//  - Smooth surface (roughness 0): light from the mirror direction r, so
//      XYZ = E(r) * sum_l w(l) R(l, mu),   R = (Rs + Rp) / 2 of eq. 2-4,
//    w the colorimeter's weights of eq. 5.
//  - Rough surface: the GGX microfacet model (Walter et al. 2007) with slope width alpha,
//    Smith height-correlated masking-shadowing (Heitz 2014), single scattering. Its
//    directional albedo, spectral Fresnel integrated over the lobe,
//      A_XYZ(mu) = int D(h) G2(l, v) F_XYZ(v.h) / (4 mu) dl,   F_XYZ(c) = sum_l w(l) R(l, c),
//    is computed by quasi-Monte Carlo sampling of the visible normals (Heitz 2018, 1024
//    Hammersley points, the same points for every mu). In a lit environment the lobe's
//    lighting is taken apart from its colour (the "split sum" of Karis 2013):
//      XYZ ~= E_alpha(r) * A_XYZ(mu),  E_alpha = E averaged over the GGX lobe around r,
//    which is exact in a uniform environment and keeps the colour spectral everywhere.
//
// ReflectionTable tabulates sum_l w R (or A_XYZ) once per material and roughness at
// kReflectionTableSize values of mu evenly spaced on [0, 1] and interpolates linearly;
// DirectReflection evaluates the same quantity from the Fresnel equations at every call.
// ReflectionTableError compares the two.
//
// World coordinates: x to the right, y up, z toward the camera (the camera looks along -z).
#ifndef ALLOYCOLOR_RENDER_SHADING_H_
#define ALLOYCOLOR_RENDER_SHADING_H_

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"

namespace alloycolor::render {

struct Vec3 {
  double x, y, z;
};
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(double s, const Vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline double Dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 Cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec3 Normalize(const Vec3& a) { return (1.0 / std::sqrt(Dot(a, a))) * a; }
// The mirror direction of v (pointing away from the surface) about the unit normal n.
inline Vec3 Reflect(const Vec3& v, const Vec3& n) { return (2.0 * Dot(v, n)) * n - v; }

inline constexpr int kReflectionTableSize = 1025;
inline constexpr int kLobeSamples = 1024;
// Roughness (GGX alpha) accepted: 0 (mirror) to 1.
inline constexpr double kMaxRoughness = 1.0;

// Reflection colour against mu evaluated spectrally at every call (slow; the reference).
class DirectReflection {
 public:
  // index: n + i k on the colorimeter's grid (IndexOnGrid). Throws Error for a size
  // mismatch or a roughness outside [0, kMaxRoughness].
  DirectReflection(const color::Colorimeter& colorimeter, std::vector<std::complex<double>> index,
                   double roughness_alpha);

  // XYZ for mu = cos(theta) in [0, 1] (clamped): sum_l w R(l, mu), or A_XYZ(mu) for a
  // rough surface.
  color::XYZ At(double mu) const;
  // sum_l w R(l, c) for a smooth surface at cosine c, whatever the roughness.
  color::XYZ FresnelXYZ(double c) const;
  double roughness() const { return alpha_; }
  // The same material with another roughness.
  DirectReflection WithRoughness(double roughness_alpha) const;

 private:
  std::vector<double> wx_, wy_, wz_;  // the colorimeter's weights
  std::vector<std::complex<double>> index_;
  double alpha_;
};

// Reflection colour against mu, tabulated.
class ReflectionTable {
 public:
  // Builds the table from the spectral Fresnel reflectance (for a rough surface, through
  // a finer smooth table that the lobe integral reads).
  explicit ReflectionTable(const DirectReflection& direct, int size = kReflectionTableSize);

  color::XYZ At(double mu) const {
    const double t = (mu > 0.0 ? (mu < 1.0 ? mu : 1.0) : 0.0) * last_;
    int i = static_cast<int>(t);
    if (i >= last_) i = last_ - 1;
    const double f = t - i;
    const double* a = &xyz_[3 * i];
    return {a[0] + f * (a[3] - a[0]), a[1] + f * (a[4] - a[1]), a[2] + f * (a[5] - a[2])};
  }
  int size() const { return last_ + 1; }
  double roughness() const { return alpha_; }
  // X, Y, Z at the nodes mu = i / (size - 1), node by node.
  const std::vector<double>& nodes() const { return xyz_; }

 private:
  std::vector<double> xyz_;  // X, Y, Z at mu = i / (size - 1)
  int last_;
  double alpha_;
};

// Largest relative difference max_c |table_c - direct_c| / |direct_c| (c = X, Y, Z) over
// `samples` values of mu spread over (0, 1] away from the table's nodes.
double ReflectionTableError(const ReflectionTable& table, const DirectReflection& direct,
                            int samples);

// The accuracy guard every face applies before shading from a table: the table is refined
// (size 4 (size - 1) + 1, from kReflectionTableSize up to kMaxReflectionTableSize) until its
// ReflectionTableError over kTableCheckSamples values of mu (kRoughTableCheckSamples for a
// rough surface, whose direct evaluation is slow) is at most kTableErrorLimit. None of the
// bundled metals needs more than the first size.
inline constexpr int kTableCheckSamples = 500;
inline constexpr int kRoughTableCheckSamples = 24;
inline constexpr double kTableErrorLimit = 1e-4;
inline constexpr int kMaxReflectionTableSize = 65537;

struct CheckedTable {
  ReflectionTable table;
  double error;  // its ReflectionTableError
};
// Throws Error naming `what` (the material) when even the largest table misses the limit:
// such a material is rendered by direct spectral evaluation instead.
CheckedTable GuardedTable(const DirectReflection& direct, const std::string& what);

// Lighting of the scene.
enum class Lighting { kUniform, kStudio };
// "uniform" or "studio"; throws Error naming the accepted names otherwise.
Lighting LightingFromName(const std::string& name);
std::string LightingName(Lighting lighting);

// The achromatic factor E(w) of an environment.
//  - Uniform: E = 1 in every direction (a white integrating sphere).
//  - Studio: a product-shot set, a light tent: walls brightening overhead, a dark gap just
//    above the table's edge (the horizon line polished metal shows), the lit table below
//    it, a black flag to the front right, a large key softbox above left (E = 3.5), a
//    narrow fill strip to the right and a strip light above and behind. Lights have soft
//    (smoothstep) edges, so that mirror reflections of them are soft. All of them have the
//    illuminant's spectrum: the metal alone colours the light.
class Environment {
 public:
  explicit Environment(Lighting lighting) : lighting_(lighting) {}
  Lighting lighting() const { return lighting_; }
  // E in unit direction w.
  double Radiance(const Vec3& w) const;
  // E of the backdrop seen directly behind the object at image position (u, v), both in
  // [0, 1] from the top-left corner.
  double Backdrop(double u, double v) const;

 private:
  Lighting lighting_;
};

// E averaged over a GGX lobe of slope width alpha around a direction r, with the normal and
// the viewing direction taken along r (Karis 2013): sum E(l) (r.l) / sum (r.l) over
// half-vectors h drawn from D, l = Reflect(r, h). Tabulated on a latitude-longitude grid
// whose texels are no wider than about alpha / 2 (up to 512 x 256) and read bilinearly.
class PrefilteredEnvironment {
 public:
  // alpha > 0. threads: how many threads to use (at least 1).
  PrefilteredEnvironment(const Environment& environment, double roughness_alpha, int threads);
  double At(const Vec3& r) const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<float> texels_;  // row-major, row 0 at theta = 0 (y = +1)
};

}  // namespace alloycolor::render

#endif  // ALLOYCOLOR_RENDER_SHADING_H_
