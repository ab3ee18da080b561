// Pictures of solid objects made of a metal: every pixel's colour comes from the spectral
// Fresnel reflectance at that pixel's angle of incidence (shading.h), never from an RGB
// approximation of the metal.
//
// Scene: one object in a square tile of size x size pixels, seen by an orthographic camera
// looking along -z (world: x right, y up, z toward the camera). Pixel (i, j), column i and
// row j from the top-left corner, covers [i, i + 1) x [j, j + 1); its ray runs through its
// centre (i + 1/2, j + 1/2). With s = kObjectFraction * size, a pixel position (px, py)
// maps to the world point (px - size / 2, size / 2 - py) / s, so that the object spans
// [-1, 1] horizontally.
//  - sphere: radius 1 at the origin. At world (u, v) with u^2 + v^2 <= 1 the normal is
//    (u, v, sqrt(1 - u^2 - v^2)) and the angle of incidence theta (between the view
//    direction, the normal and the mirrored light) has cos theta = sqrt(1 - u^2 - v^2).
//  - ring: a torus of major radius kRingMajorRadius and tube radius kRingTubeRadius
//    (outer radius 1) whose axis (0, cos e, sin e) is tilted toward the camera by the
//    elevation e = kRingElevationDeg, like a ring lying on a table seen from above.
//
// Lighting (shading.h):
//  - uniform: a uniform white environment of the illuminant (E = 1), so each pixel is the
//    colour of R(theta) at the angle of its centre ray: exactly, whatever the pixel's
//    coverage (the centre of a sphere is the normal-incidence colour; the rim goes toward
//    white). With a roughness above 0 it is the rough surface's directional albedo.
//  - studio: a product-shot environment; reflected light E(r) * R, r the mirror direction,
//    or the GGX lobe of the roughness (split sum).
// Pixels on the object's outline or on a jump in depth are sampled 4 x 4 times: alpha is
// the coverage; in studio light the colour is the mean of the samples. The background is
// transparent or the studio backdrop (neutral: the illuminant's white scaled, a soft
// gradient). XYZ become linear sRGB (IEC 61966-2-1, no chromatic adaptation, as the
// `color` command). Rows are shaded in parallel with std::thread. Light reaches the object
// from the environment only: no shadows and no inter-reflections (the ring does not
// reflect itself).
//
// Speed: nothing above but the reflection colour depends on the material. The Renderer
// therefore traces its tile once, when it is constructed: for every pixel the cosines mu
// of its rays' hits and the light E of each (the environment in the mirror direction, or
// 1), its coverage and its backdrop, folded into weights so that a pixel is
//   sum_s weight_s * RGB(mu_s) + background * RGB(white)
// (one term for a pixel inside the object, none for the backdrop, one per hit sample on an
// outline). Render then only reads the material's colour at each term: every shape and
// light costs about the same per image. mu and the weights are kept as float (relative
// error below 1e-7, the precision of the image's own samples).
#ifndef ALLOYCOLOR_RENDER_RENDERER_H_
#define ALLOYCOLOR_RENDER_RENDERER_H_

#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/core/setting.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/render/image.h"
#include "alloycolor/render/shading.h"

namespace alloycolor::render {

inline constexpr double kObjectFraction = 0.45;
inline constexpr double kRingMajorRadius = 0.86;
inline constexpr double kRingTubeRadius = 0.14;
inline constexpr double kRingElevationDeg = 35.0;
inline constexpr int kEdgeSamples = 4;  // per side
inline constexpr int kMaxTileSize = 4096;
inline constexpr long long kMaxImagePixels = 4096LL * 4096LL;

enum class Shape { kSphere, kRing };
// "sphere" or "ring"; throws Error naming the accepted names otherwise.
Shape ShapeFromName(const std::string& name);
std::string ShapeName(Shape shape);

enum class Background { kTransparent, kBackdrop };
// "transparent" or "backdrop".
Background BackgroundFromName(const std::string& name);
// The background unless one is chosen: transparent in uniform light (the object's colour
// alone), the backdrop in studio light.
Background DefaultBackground(Lighting lighting);

struct RenderOptions {
  Shape shape = Shape::kSphere;
  int size = 512;  // tile width and height in pixels, 1 to kMaxTileSize
  Lighting lighting = Lighting::kStudio;
  double roughness = 0.0;  // GGX alpha, 0 (mirror) to kMaxRoughness
  Background background = Background::kBackdrop;
  int threads = 0;     // 0: one per hardware thread
  CancelCheck cancel;  // called before each block of rows traced or shaded (core/progress.h)
};

// The picture's settings as every face takes them (the program's render, Python's
// Model.render and Spectrum.render), checked before any work and named as `spelling`
// spells them ("size" or "--size"): size 1-kMaxTileSize pixels, roughness 0-kMaxRoughness
// (GGX alpha), threads not negative, and `direct` spectral evaluation at every pixel only
// at roughness 0.
void CheckRenderOptions(const RenderOptions& options, bool direct,
                        OptionSpelling spelling = OptionSpelling::kName);

// What a page needs to shade a tile itself: for each pixel, the unit normal n (n.z >= 0:
// the first surface the centre ray meets faces the camera) and the coverage in [0, 1],
// found exactly as Render finds them (the same geometry, the same outline test and 4 x 4
// samples on edges). Where the centre ray misses but samples hit, the normal is the
// normalised mean of theirs. Uncovered pixels have coverage 0 and normal (0, 0, 1).
struct NormalMap {
  int size = 0;
  std::vector<float> normal;    // size * size * 3, top row first
  std::vector<float> coverage;  // size * size
};
// Throws Error for a size outside 1-kMaxTileSize.
NormalMap TraceNormals(Shape shape, int size);

// How a picture names an alloy's tile (its title, its errors): "Au-Ag x=0.75".
std::string AlloyLabel(const AlloyModel& model, double x_atomic);

namespace internal {
struct TilePlan;
}  // namespace internal

class Renderer {
 public:
  // Checks the options (Error naming the one at fault), prepares the environment (for a
  // rough surface in studio light, its prefiltered version) and traces the tile (above).
  Renderer(const color::Colorimeter& colorimeter, const RenderOptions& options);
  ~Renderer();
  Renderer(Renderer&&) noexcept;

  const RenderOptions& options() const { return options_; }

  // The reflection colour of a material (n + i k on the colorimeter's grid) at the
  // options' roughness, direct and tabulated.
  DirectReflection Direct(const std::vector<std::complex<double>>& index) const;
  ReflectionTable Table(const std::vector<std::complex<double>>& index) const;

  // One tile shaded from the table (fast) or from direct spectral evaluation at every
  // sample (slow; smooth surfaces only). Throws Error when the roughness differs from the
  // options'.
  LinearImage Render(const ReflectionTable& table) const;
  LinearImage Render(const DirectReflection& direct) const;

 private:
  // Shades the traced tile; rgb(mu, out) writes the linear sRGB reflection colour.
  template <typename ColourAt>
  LinearImage Shade(const ColourAt& rgb) const;

  color::Colorimeter colorimeter_;
  RenderOptions options_;
  Environment environment_;
  std::unique_ptr<PrefilteredEnvironment> prefiltered_;
  std::unique_ptr<internal::TilePlan> plan_;
};

}  // namespace alloycolor::render

#endif  // ALLOYCOLOR_RENDER_RENDERER_H_
