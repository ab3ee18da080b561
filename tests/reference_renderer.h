// A straightforward renderer written from the description in renderer.h, one pixel at a
// time with no sharing between pixels and nothing prepared in advance: for each pixel its
// centre ray and its four corner rays, the outline test (a corner's hit differs from the
// centre's, or its depth by more than 0.08), the 4 x 4 samples on an outline, and at every
// hit the reflection colour at mu = cos(theta) times the environment's light in the mirror
// direction, converted to linear sRGB. The tests compare render::Renderer with it; bench/
// times it as the straightforward implementation.
//
// Geometry, independently of renderer.cc: the sphere in closed form; the ring by sphere
// tracing the exact distance to the torus from where the ray enters the bounding sphere
// (the straightforward method), to 1e-9, with the normal from the gradient of the torus'
// implicit equation (|p|^2 + R^2 - r^2)^2 = 4 R^2 (p_x^2 + p_z^2) in the ring's frame.
#ifndef ALLOYCOLOR_TESTS_REFERENCE_RENDERER_H_
#define ALLOYCOLOR_TESTS_REFERENCE_RENDERER_H_

#include <algorithm>
#include <cmath>
#include <memory>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/render/image.h"
#include "alloycolor/render/renderer.h"
#include "alloycolor/render/shading.h"

namespace alloycolor::testing {

struct ReferenceHit {
  bool hit = false;
  double depth = 0.0;  // distance from the plane z = 4 along -z
  double n[3] = {0.0, 0.0, 1.0};
};

// The ray along -z through world point (u, v).
inline ReferenceHit ReferenceIntersect(render::Shape shape, double u, double v) {
  ReferenceHit out;
  const double d2 = u * u + v * v;
  if (shape == render::Shape::kSphere) {
    if (d2 > 1.0) return out;
    const double z = std::sqrt(1.0 - d2);
    out.hit = true;
    out.depth = 4.0 - z;
    out.n[0] = u;
    out.n[1] = v;
    out.n[2] = z;
    return out;
  }
  if (d2 >= 1.0) return out;
  const double e = render::kRingElevationDeg * M_PI / 180.0;
  const double ce = std::cos(e), se = std::sin(e);
  const double big = render::kRingMajorRadius, tube = render::kRingTubeRadius;
  // The ring's frame: x = (1, 0, 0), y = its axis (0, cos e, sin e), z = x cross y.
  const auto local = [&](double z, double p[3]) {
    p[0] = u;
    p[1] = v * ce + z * se;
    p[2] = -v * se + z * ce;
  };
  const double top = std::sqrt(1.0 - d2);
  double z = top;
  for (int step = 0; step < 2000 && z >= -top; ++step) {
    double p[3];
    local(z, p);
    const double q = std::hypot(p[0], p[2]) - big;
    const double distance = std::hypot(q, p[1]) - tube;
    if (distance < 1e-9) {
      const double a = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + big * big - tube * tube;
      const double g[3] = {4.0 * a * p[0] - 8.0 * big * big * p[0], 4.0 * a * p[1],
                           4.0 * a * p[2] - 8.0 * big * big * p[2]};
      // World = g_x (1, 0, 0) + g_y (0, cos e, sin e) + g_z (0, -sin e, cos e).
      const double w[3] = {g[0], g[1] * ce - g[2] * se, g[1] * se + g[2] * ce};
      const double norm = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
      out.hit = true;
      out.depth = 4.0 - z;
      for (int c = 0; c < 3; ++c) out.n[c] = w[c] / norm;
      return out;
    }
    z -= distance;
  }
  return out;
}

// xyz_at(mu) gives the reflection colour (ReflectionTable or DirectReflection At).
template <typename XyzAt>
render::LinearImage ReferenceRender(const color::Colorimeter& colorimeter,
                                    const render::RenderOptions& options, const XyzAt& xyz_at) {
  const int size = options.size;
  const double scale = render::kObjectFraction * size;
  const render::Environment environment(options.lighting);
  std::unique_ptr<render::PrefilteredEnvironment> prefiltered;
  if (options.lighting == render::Lighting::kStudio && options.roughness > 0.0) {
    prefiltered = std::make_unique<render::PrefilteredEnvironment>(environment, options.roughness,
                                                                   std::max(options.threads, 1));
  }
  const bool uniform = options.lighting == render::Lighting::kUniform;
  const bool transparent = options.background == render::Background::kTransparent;
  const color::XYZ white = colorimeter.White();
  const auto trace = [&](double px, double py) {
    return ReferenceIntersect(options.shape, (px - 0.5 * size) / scale, (0.5 * size - py) / scale);
  };
  const auto shade = [&](const ReferenceHit& hit) {
    const color::XYZ c = xyz_at(std::max(0.0, hit.n[2]));
    if (uniform) return c;
    // Mirror of the view direction (0, 0, 1): r = 2 n_z n - (0, 0, 1).
    const render::Vec3 r{2.0 * hit.n[2] * hit.n[0], 2.0 * hit.n[2] * hit.n[1],
                         2.0 * hit.n[2] * hit.n[2] - 1.0};
    const double light = prefiltered ? prefiltered->At(r) : environment.Radiance(r);
    return color::XYZ{light * c.X, light * c.Y, light * c.Z};
  };
  const auto backdrop = [&](double px, double py) {
    const double b = environment.Backdrop(px / size, py / size);
    return color::XYZ{b * white.X, b * white.Y, b * white.Z};
  };
  render::LinearImage image(size, size);
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      const ReferenceHit centre = trace(i + 0.5, j + 0.5);
      bool outline = false;
      for (int corner = 0; corner < 4; ++corner) {
        const ReferenceHit c = trace(i + corner % 2, j + corner / 2);
        if (c.hit != centre.hit || (centre.hit && std::abs(c.depth - centre.depth) > 0.08)) {
          outline = true;
        }
      }
      color::XYZ xyz{0.0, 0.0, 0.0};
      double alpha = 1.0;
      if (!outline) {
        if (centre.hit) {
          xyz = shade(centre);
        } else if (transparent) {
          alpha = 0.0;
        } else {
          xyz = backdrop(i + 0.5, j + 0.5);
        }
      } else {
        color::XYZ object{0.0, 0.0, 0.0}, background{0.0, 0.0, 0.0};
        int hits = 0;
        const int n = render::kEdgeSamples;
        for (int b = 0; b < n; ++b) {
          for (int a = 0; a < n; ++a) {
            const double px = i + (a + 0.5) / n, py = j + (b + 0.5) / n;
            const ReferenceHit hit = trace(px, py);
            const color::XYZ c = hit.hit ? shade(hit) : backdrop(px, py);
            color::XYZ& sum = hit.hit ? object : background;
            sum.X += c.X;
            sum.Y += c.Y;
            sum.Z += c.Z;
            hits += hit.hit;
          }
        }
        const double coverage = static_cast<double>(hits) / (n * n);
        color::XYZ colour{0.0, 0.0, 0.0};
        if (uniform && centre.hit) {
          colour = shade(centre);
        } else if (hits > 0) {
          colour = {object.X / hits, object.Y / hits, object.Z / hits};
        }
        if (transparent) {
          xyz = colour;
          alpha = coverage;
        } else {
          const int misses = n * n - hits;
          const double f = misses > 0 ? (1.0 - coverage) / misses : 0.0;
          xyz = {coverage * colour.X + f * background.X, coverage * colour.Y + f * background.Y,
                 coverage * colour.Z + f * background.Z};
        }
      }
      const color::RGB rgb = color::LinearSRGBFromXYZ(xyz);
      float* pixel = image.Pixel(i, j);
      pixel[0] = static_cast<float>(rgb.r);
      pixel[1] = static_cast<float>(rgb.g);
      pixel[2] = static_cast<float>(rgb.b);
      pixel[3] = static_cast<float>(alpha);
    }
  }
  return image;
}

}  // namespace alloycolor::testing

#endif  // ALLOYCOLOR_TESTS_REFERENCE_RENDERER_H_
