#include "alloycolor/render/renderer.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "alloycolor/core/error.h"
#include "alloycolor/core/units.h"
#include "parallel.h"

namespace alloycolor::render {
namespace {

// Where rays start, in front of every object (world units).
constexpr double kRayStartZ = 4.0;
// A pixel whose corners' depths differ from its centre's by more than this (world units)
// straddles an occlusion edge (the ring) or a steep slope (a sphere's rim) and is
// supersampled.
constexpr double kDepthJump = 0.08;
constexpr int kTraceSteps = 300;
constexpr double kTraceEpsilon = 1e-6;

struct Hit {
  bool hit = false;
  double t = 0.0;  // distance along the ray from z = kRayStartZ
  Vec3 normal{0.0, 0.0, 1.0};
};

// What the edge test keeps of a hit at a pixel corner.
struct CornerHit {
  bool hit;
  double t;
};

// Linear sRGB from XYZ (LinearSRGBFromXYZ, a linear map) as a matrix, for the inner loop.
struct SRGBMatrix {
  double m[3][3];
  SRGBMatrix() {
    const color::XYZ unit[3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
    for (int c = 0; c < 3; ++c) {
      const color::RGB column = color::LinearSRGBFromXYZ(unit[c]);
      m[0][c] = column.r;
      m[1][c] = column.g;
      m[2][c] = column.b;
    }
  }
};

// The object, intersected by the orthographic ray through world point (x, y).
class Geometry {
 public:
  explicit Geometry(Shape shape) : shape_(shape) {
    const double e = kRingElevationDeg * kPi / 180.0;
    axis_y_ = {0.0, std::cos(e), std::sin(e)};
    axis_x_ = {1.0, 0.0, 0.0};
    axis_z_ = Cross(axis_x_, axis_y_);
  }

  Hit Intersect(double x, double y) const {
    return shape_ == Shape::kSphere ? Sphere(x, y) : Ring(x, y);
  }

 private:
  static Hit Sphere(double x, double y) {
    Hit hit;
    const double d2 = x * x + y * y;
    if (d2 > 1.0) return hit;
    const double z = std::sqrt(1.0 - d2);
    hit.hit = true;
    hit.t = kRayStartZ - z;
    hit.normal = {x, y, z};
    return hit;
  }

  // Signed distance to the torus (exact), in the ring's frame.
  static double TorusDistance(const Vec3& p) {
    const double q = std::sqrt(p.x * p.x + p.z * p.z) - kRingMajorRadius;
    return std::sqrt(q * q + p.y * p.y) - kRingTubeRadius;
  }

  Vec3 ToLocal(const Vec3& p) const { return {Dot(p, axis_x_), Dot(p, axis_y_), Dot(p, axis_z_)}; }

  // Sphere tracing of the exact distance inside the bounding sphere (radius 1).
  Hit Ring(double x, double y) const {
    Hit hit;
    const double d2 = x * x + y * y;
    if (d2 >= 1.0) return hit;
    const double half = std::sqrt(1.0 - d2);
    const Vec3 origin = ToLocal(Vec3{x, y, 0.0});
    const Vec3 dir = ToLocal(Vec3{0.0, 0.0, -1.0});
    double s = -half;  // along -z from the world plane z = 0: z = -s
    for (int step = 0; step < kTraceSteps && s <= half; ++step) {
      const Vec3 p = origin + s * dir;
      const double d = TorusDistance(p);
      if (d < kTraceEpsilon) {
        const double radial = std::sqrt(p.x * p.x + p.z * p.z);
        const Vec3 centre = radial > 0.0 ? (kRingMajorRadius / radial) * Vec3{p.x, 0.0, p.z}
                                         : Vec3{kRingMajorRadius, 0.0, 0.0};
        const Vec3 n = Normalize(p - centre);
        hit.hit = true;
        hit.t = kRayStartZ + s;
        hit.normal = n.x * axis_x_ + n.y * axis_y_ + n.z * axis_z_;
        return hit;
      }
      s += d;
    }
    return hit;
  }

  Shape shape_;
  Vec3 axis_x_{}, axis_y_{}, axis_z_{};
};

void CheckOptions(const RenderOptions& o) {
  if (o.size < 1 || o.size > kMaxTileSize) {
    throw Error("image size " + std::to_string(o.size) + " lies outside 1-" +
                std::to_string(kMaxTileSize) + " pixels");
  }
  if (!(o.roughness >= 0.0 && o.roughness <= kMaxRoughness)) {
    std::ostringstream msg;
    msg << "roughness " << o.roughness << " lies outside 0-" << kMaxRoughness;
    throw Error(msg.str());
  }
  if (o.threads < 0) throw Error("thread count " + std::to_string(o.threads) + " is negative");
}

}  // namespace

Shape ShapeFromName(const std::string& name) {
  if (name == "sphere") return Shape::kSphere;
  if (name == "ring") return Shape::kRing;
  throw Error("unknown shape '" + name + "' (sphere, ring)");
}

std::string ShapeName(Shape shape) { return shape == Shape::kSphere ? "sphere" : "ring"; }

Background BackgroundFromName(const std::string& name) {
  if (name == "transparent") return Background::kTransparent;
  if (name == "backdrop") return Background::kBackdrop;
  throw Error("unknown background '" + name + "' (transparent, backdrop)");
}

NormalMap TraceNormals(Shape shape, int size) {
  if (size < 1 || size > kMaxTileSize) {
    throw Error("image size " + std::to_string(size) + " lies outside 1-" +
                std::to_string(kMaxTileSize) + " pixels");
  }
  const double scale = kObjectFraction * size;
  const double half = 0.5 * size;
  const Geometry geometry(shape);
  const auto intersect = [&](double px, double py) {
    return geometry.Intersect((px - half) / scale, (half - py) / scale);
  };
  NormalMap map;
  map.size = size;
  map.normal.assign(static_cast<std::size_t>(size) * size * 3, 0.0f);
  map.coverage.assign(static_cast<std::size_t>(size) * size, 0.0f);
  std::vector<CornerHit> corners(static_cast<std::size_t>(size + 1) * (size + 1));
  for (int j = 0; j <= size; ++j) {
    for (int i = 0; i <= size; ++i) {
      const Hit hit = intersect(i, j);
      corners[static_cast<std::size_t>(j) * (size + 1) + i] = {hit.hit, hit.t};
    }
  }
  for (int j = 0; j < size; ++j) {
    const CornerHit* top = &corners[static_cast<std::size_t>(j) * (size + 1)];
    const CornerHit* bottom = top + size + 1;
    for (int i = 0; i < size; ++i) {
      const std::size_t p = static_cast<std::size_t>(j) * size + i;
      const Hit centre = intersect(i + 0.5, j + 0.5);
      bool edge = false;
      for (const CornerHit* corner : {&top[i], &top[i + 1], &bottom[i], &bottom[i + 1]}) {
        if (corner->hit != centre.hit ||
            (centre.hit && std::abs(corner->t - centre.t) > kDepthJump)) {
          edge = true;
        }
      }
      Vec3 normal = centre.normal;
      double coverage = centre.hit ? 1.0 : 0.0;
      if (edge) {
        Vec3 sum{0.0, 0.0, 0.0};
        int hits = 0;
        for (int b = 0; b < kEdgeSamples; ++b) {
          for (int a = 0; a < kEdgeSamples; ++a) {
            const Hit hit = intersect(i + (a + 0.5) / kEdgeSamples, j + (b + 0.5) / kEdgeSamples);
            if (!hit.hit) continue;
            sum = sum + hit.normal;
            ++hits;
          }
        }
        coverage = static_cast<double>(hits) / (kEdgeSamples * kEdgeSamples);
        if (!centre.hit && hits > 0) normal = Normalize(sum);
      }
      if (coverage == 0.0) normal = {0.0, 0.0, 1.0};
      map.normal[3 * p] = static_cast<float>(normal.x);
      map.normal[3 * p + 1] = static_cast<float>(normal.y);
      map.normal[3 * p + 2] = static_cast<float>(std::max(0.0, normal.z));
      map.coverage[p] = static_cast<float>(coverage);
    }
  }
  return map;
}

Renderer::Renderer(const color::Colorimeter& colorimeter, const RenderOptions& options)
    : colorimeter_(colorimeter), options_(options), environment_(options.lighting) {
  CheckOptions(options_);
  if (options_.lighting == Lighting::kStudio && options_.roughness > 0.0) {
    prefiltered_ = std::make_unique<PrefilteredEnvironment>(
        environment_, options_.roughness, internal::ThreadCount(options_.threads));
  }
}

Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;

DirectReflection Renderer::Direct(const std::vector<std::complex<double>>& index) const {
  return DirectReflection(colorimeter_, index, options_.roughness);
}

ReflectionTable Renderer::Table(const std::vector<std::complex<double>>& index) const {
  return ReflectionTable(Direct(index));
}

LinearImage Renderer::Render(const ReflectionTable& table) const {
  if (table.roughness() != options_.roughness) {
    throw Error("render: the table's roughness differs from the options'");
  }
  return RenderWith(table);
}

LinearImage Renderer::Render(const DirectReflection& direct) const {
  if (direct.roughness() != options_.roughness) {
    throw Error("render: the material's roughness differs from the options'");
  }
  if (direct.roughness() > 0.0) {
    throw Error(
        "direct spectral evaluation at every pixel is offered for a smooth surface "
        "(roughness 0) only; a rough surface is shaded from its table");
  }
  return RenderWith(direct);
}

template <typename Reflection>
LinearImage Renderer::RenderWith(const Reflection& reflection) const {
  const int size = options_.size;
  const double scale = kObjectFraction * size;
  const double half = 0.5 * size;
  const Geometry geometry(options_.shape);
  const bool uniform = options_.lighting == Lighting::kUniform;
  const bool transparent = options_.background == Background::kTransparent;
  const color::XYZ white = colorimeter_.White();
  const Vec3 view{0.0, 0.0, 1.0};

  const auto intersect = [&](double px, double py) {
    return geometry.Intersect((px - half) / scale, (half - py) / scale);
  };
  // XYZ of the light the object sends toward the camera at a hit.
  const auto shade = [&](const Hit& hit) {
    const double mu = std::max(0.0, hit.normal.z);
    const color::XYZ c = reflection.At(mu);
    if (uniform) return c;
    const Vec3 r = Reflect(view, hit.normal);
    const double e = prefiltered_ ? prefiltered_->At(r) : environment_.Radiance(r);
    return color::XYZ{e * c.X, e * c.Y, e * c.Z};
  };
  const auto backdrop = [&](double px, double py) {
    const double e = environment_.Backdrop(px / size, py / size);
    return color::XYZ{e * white.X, e * white.Y, e * white.Z};
  };
  static const SRGBMatrix kMatrix;
  const auto& m = kMatrix.m;
  const auto store = [&m](float* pixel, const color::XYZ& c, double alpha) {
    pixel[0] = static_cast<float>(m[0][0] * c.X + m[0][1] * c.Y + m[0][2] * c.Z);
    pixel[1] = static_cast<float>(m[1][0] * c.X + m[1][1] * c.Y + m[1][2] * c.Z);
    pixel[2] = static_cast<float>(m[2][0] * c.X + m[2][1] * c.Y + m[2][2] * c.Z);
    pixel[3] = static_cast<float>(alpha);
  };

  LinearImage image(size, size);
  constexpr int kRowBlock = 8;
  internal::ParallelFor(
      size, kRowBlock, internal::ThreadCount(options_.threads), [&](int row_begin, int row_end) {
        // Hits at the pixel corners of rows row_begin..row_end.
        const int stride = size + 1;
        std::vector<CornerHit> corners(static_cast<std::size_t>(row_end - row_begin + 1) * stride);
        for (int j = row_begin; j <= row_end; ++j) {
          for (int i = 0; i <= size; ++i) {
            const Hit hit = intersect(i, j);
            corners[static_cast<std::size_t>(j - row_begin) * stride + i] = {hit.hit, hit.t};
          }
        }
        for (int j = row_begin; j < row_end; ++j) {
          const CornerHit* top = &corners[static_cast<std::size_t>(j - row_begin) * stride];
          const CornerHit* bottom = top + stride;
          for (int i = 0; i < size; ++i) {
            float* pixel = image.Pixel(i, j);
            const Hit centre = intersect(i + 0.5, j + 0.5);
            bool edge = false;
            for (const CornerHit* corner : {&top[i], &top[i + 1], &bottom[i], &bottom[i + 1]}) {
              if (corner->hit != centre.hit ||
                  (centre.hit && std::abs(corner->t - centre.t) > kDepthJump)) {
                edge = true;
              }
            }
            if (!edge) {
              if (centre.hit) {
                store(pixel, shade(centre), 1.0);
              } else if (transparent) {
                store(pixel, color::XYZ{0.0, 0.0, 0.0}, 0.0);
              } else {
                store(pixel, backdrop(i + 0.5, j + 0.5), 1.0);
              }
              continue;
            }
            color::XYZ object{0.0, 0.0, 0.0}, background{0.0, 0.0, 0.0};
            int hits = 0;
            for (int b = 0; b < kEdgeSamples; ++b) {
              for (int a = 0; a < kEdgeSamples; ++a) {
                const double px = i + (a + 0.5) / kEdgeSamples;
                const double py = j + (b + 0.5) / kEdgeSamples;
                const Hit hit = intersect(px, py);
                const color::XYZ c =
                    hit.hit ? shade(hit) : (transparent ? color::XYZ{0, 0, 0} : backdrop(px, py));
                color::XYZ& sum = hit.hit ? object : background;
                sum.X += c.X;
                sum.Y += c.Y;
                sum.Z += c.Z;
                hits += hit.hit;
              }
            }
            const int total = kEdgeSamples * kEdgeSamples;
            const double coverage = static_cast<double>(hits) / total;
            // The object's colour: in uniform light exactly the centre ray's when it hits.
            color::XYZ colour{0.0, 0.0, 0.0};
            if (uniform && centre.hit) {
              colour = shade(centre);
            } else if (hits > 0) {
              colour = {object.X / hits, object.Y / hits, object.Z / hits};
            }
            if (transparent) {
              store(pixel, colour, coverage);
            } else {
              const int misses = total - hits;
              const color::XYZ bg = misses > 0 ? color::XYZ{background.X / misses, background.Y / misses,
                                              background.Z / misses}
                                        : color::XYZ{0.0, 0.0, 0.0};
              store(pixel,
                    color::XYZ{coverage * colour.X + (1.0 - coverage) * bg.X,
                        coverage * colour.Y + (1.0 - coverage) * bg.Y,
                        coverage * colour.Z + (1.0 - coverage) * bg.Z},
                    1.0);
            }
          }
        }
      });
  return image;
}

}  // namespace alloycolor::render
