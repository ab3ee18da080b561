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
constexpr int kNewtonSteps = 2;
constexpr double kGrazingSlope = 1e-2;

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
    dir_ = ToLocal(Vec3{0.0, 0.0, -1.0});
  }

  Hit Intersect(double x, double y) const {
    Hit hit;
    Intersect(&x, &y, 1, &hit);
    return hit;
  }

  // hits[k] for the rays through (x[k], y[k]), k < n. The ring's rays are traced
  // kLanes at a time, interleaved (each exactly as on its own), so that the processor
  // overlaps their independent chains of square roots.
  void Intersect(const double* x, const double* y, int n, Hit* hits) const {
    if (shape_ == Shape::kSphere) {
      for (int k = 0; k < n; ++k) hits[k] = Sphere(x[k], y[k]);
      return;
    }
    constexpr int kLanes = 8;
    for (int first = 0; first < n; first += kLanes) {
      const int lanes = std::min(kLanes, n - first);
      RingRay rays[kLanes];
      bool active[kLanes];
      int left = 0;
      for (int k = 0; k < lanes; ++k) {
        active[k] = StartRing(x[first + k], y[first + k], &rays[k]);
        hits[first + k] = Hit{};
        left += active[k];
      }
      while (left > 0) {
        for (int k = 0; k < lanes; ++k) {
          if (!active[k]) continue;
          const int state = StepRing(&rays[k]);
          if (state == kMarching) continue;
          if (state == kHit) hits[first + k] = FinishRing(rays[k]);
          active[k] = false;
          --left;
        }
      }
    }
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

  // The outward unit normal of the torus at p (the gradient of TorusDistance).
  static Vec3 TorusNormal(const Vec3& p) {
    const double radial = std::sqrt(p.x * p.x + p.z * p.z);
    const Vec3 centre = radial > 0.0 ? (kRingMajorRadius / radial) * Vec3{p.x, 0.0, p.z}
                                     : Vec3{kRingMajorRadius, 0.0, 0.0};
    return Normalize(p - centre);
  }

  Vec3 ToLocal(const Vec3& p) const { return {Dot(p, axis_x_), Dot(p, axis_y_), Dot(p, axis_z_)}; }

  // Sphere tracing of the exact distance inside the bounding sphere (radius 1) and the
  // slab |y| <= kRingTubeRadius of the ring's frame that holds the torus, then Newton
  // steps on the distance along the ray (its slope is dir . normal), which take the hit
  // from within kTraceEpsilon of the surface to rounding unless the ray grazes.
  struct RingRay {
    Vec3 origin;    // in the ring's frame; the ray is origin + s dir_, z = -s in the world
    double s, s_hi;
    int step;
  };
  enum { kMarching, kHit, kMiss };

  bool StartRing(double x, double y, RingRay* ray) const {
    const double d2 = x * x + y * y;
    if (d2 >= 1.0) return false;
    const double half = std::sqrt(1.0 - d2);
    ray->origin = ToLocal(Vec3{x, y, 0.0});
    // dir_.y < 0: the ray crosses the slab from y = +tube to y = -tube.
    ray->s = std::max(-half, (kRingTubeRadius - ray->origin.y) / dir_.y);
    ray->s_hi = std::min(half, (-kRingTubeRadius - ray->origin.y) / dir_.y) + kTraceEpsilon;
    ray->step = 0;
    return ray->s <= ray->s_hi;
  }

  int StepRing(RingRay* ray) const {
    const double d = TorusDistance(ray->origin + ray->s * dir_);
    if (d < kTraceEpsilon) return kHit;
    ray->s += d;
    return ++ray->step < kTraceSteps && ray->s <= ray->s_hi ? kMarching : kMiss;
  }

  Hit FinishRing(RingRay ray) const {
    Vec3 n = TorusNormal(ray.origin + ray.s * dir_);
    for (int newton = 0; newton < kNewtonSteps; ++newton) {
      const double slope = Dot(dir_, n);
      if (slope > -kGrazingSlope) break;
      ray.s -= TorusDistance(ray.origin + ray.s * dir_) / slope;
      n = TorusNormal(ray.origin + ray.s * dir_);
    }
    Hit hit;
    hit.hit = true;
    hit.t = kRayStartZ + ray.s;
    hit.normal = n.x * axis_x_ + n.y * axis_y_ + n.z * axis_z_;
    return hit;
  }

  Shape shape_;
  Vec3 axis_x_{}, axis_y_{}, axis_z_{};
  Vec3 dir_{};  // the view ray's direction (0, 0, -1) in the ring's frame
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

namespace internal {

// One term of a pixel's colour (renderer.h): weight * RGB(mu), or a marker in mu.
struct PixelTerm {
  float mu;
  float weight;
};
constexpr float kBackdropMu = -1.0f;  // the backdrop (or nothing): weight * RGB(white)
constexpr float kOutlineMu = -2.0f;   // an outline pixel: the next OutlinePixel of its block

// A supersampled pixel: sum of its samples' terms plus background * RGB(white).
struct OutlinePixel {
  int first, count;  // its terms in TileBlock::samples
  float background;
  float alpha;
};

// The rows [b * TilePlan::kRows, (b + 1) * TilePlan::kRows) of the tile.
struct TileBlock {
  std::vector<OutlinePixel> outline;  // in pixel order
  std::vector<PixelTerm> samples;
};

struct TilePlan {
  static constexpr int kRows = 8;
  std::vector<PixelTerm> pixels;  // size * size, top row first
  std::vector<TileBlock> blocks;
};

}  // namespace internal

namespace {

// Traces the tile of `options` (renderer.h): the geometry, the outline's samples and the
// light E at every hit.
std::unique_ptr<internal::TilePlan> TraceTile(const RenderOptions& options,
                                              const Environment& environment,
                                              const PrefilteredEnvironment* prefiltered) {
  using internal::PixelTerm;
  const int size = options.size;
  const double scale = kObjectFraction * size;
  const double half = 0.5 * size;
  const Geometry geometry(options.shape);
  const bool uniform = options.lighting == Lighting::kUniform;
  const bool transparent = options.background == Background::kTransparent;
  const Vec3 view{0.0, 0.0, 1.0};
  const auto cosine = [](const Hit& hit) { return std::clamp(hit.normal.z, 0.0, 1.0); };
  // The light E reaching the camera by mirror reflection at a hit.
  const auto light = [&](const Hit& hit) {
    if (uniform) return 1.0;
    const Vec3 r = Reflect(view, hit.normal);
    return prefiltered != nullptr ? prefiltered->At(r) : environment.Radiance(r);
  };
  const auto backdrop = [&](double px, double py) {
    return environment.Backdrop(px / size, py / size);
  };

  // Hits of the rays through pixel positions (px[k], py[k]); world holds the positions
  // in world units.
  const auto intersect = [&](const std::vector<double>& px, const std::vector<double>& py,
                             std::vector<double> world[2], std::vector<Hit>* hits) {
    world[0].resize(px.size());
    world[1].resize(px.size());
    for (std::size_t k = 0; k < px.size(); ++k) {
      world[0][k] = (px[k] - half) / scale;
      world[1][k] = (half - py[k]) / scale;
    }
    hits->resize(px.size());
    geometry.Intersect(world[0].data(), world[1].data(), static_cast<int>(px.size()),
                       hits->data());
  };

  auto plan = std::make_unique<internal::TilePlan>();
  constexpr int kRows = internal::TilePlan::kRows;
  plan->pixels.resize(static_cast<std::size_t>(size) * size);
  plan->blocks.resize((size + kRows - 1) / kRows);
  internal::ParallelFor(
      size, kRows, internal::ThreadCount(options.threads), [&](int row_begin, int row_end) {
        internal::TileBlock& block = plan->blocks[row_begin / kRows];
        std::vector<double> px, py, world[2];
        std::vector<Hit> row;
        // Hits at the pixel corners of rows row_begin..row_end.
        const int stride = size + 1;
        std::vector<CornerHit> corners(static_cast<std::size_t>(row_end - row_begin + 1) * stride);
        for (int j = row_begin; j <= row_end; ++j) {
          px.resize(stride);
          py.assign(stride, j);
          for (int i = 0; i <= size; ++i) px[i] = i;
          intersect(px, py, world, &row);
          for (int i = 0; i <= size; ++i) {
            corners[static_cast<std::size_t>(j - row_begin) * stride + i] = {row[i].hit, row[i].t};
          }
        }
        std::vector<PixelTerm> hits;
        std::vector<Hit> centres, samples;
        for (int j = row_begin; j < row_end; ++j) {
          const CornerHit* top = &corners[static_cast<std::size_t>(j - row_begin) * stride];
          const CornerHit* bottom = top + stride;
          px.resize(size);
          py.assign(size, j + 0.5);
          for (int i = 0; i < size; ++i) px[i] = i + 0.5;
          intersect(px, py, world, &centres);
          for (int i = 0; i < size; ++i) {
            PixelTerm& pixel = plan->pixels[static_cast<std::size_t>(j) * size + i];
            const Hit& centre = centres[i];
            bool edge = false;
            for (const CornerHit* corner : {&top[i], &top[i + 1], &bottom[i], &bottom[i + 1]}) {
              if (corner->hit != centre.hit ||
                  (centre.hit && std::abs(corner->t - centre.t) > kDepthJump)) {
                edge = true;
              }
            }
            if (!edge) {
              if (centre.hit) {
                pixel = {static_cast<float>(cosine(centre)), static_cast<float>(light(centre))};
              } else {
                pixel = {internal::kBackdropMu,
                         transparent ? 0.0f : static_cast<float>(backdrop(i + 0.5, j + 0.5))};
              }
              continue;
            }
            px.clear();
            py.clear();
            for (int b = 0; b < kEdgeSamples; ++b) {
              for (int a = 0; a < kEdgeSamples; ++a) {
                px.push_back(i + (a + 0.5) / kEdgeSamples);
                py.push_back(j + (b + 0.5) / kEdgeSamples);
              }
            }
            intersect(px, py, world, &samples);
            hits.clear();
            double background = 0.0;
            for (std::size_t k = 0; k < samples.size(); ++k) {
              const Hit& hit = samples[k];
              if (hit.hit) {
                hits.push_back({static_cast<float>(cosine(hit)), static_cast<float>(light(hit))});
              } else if (!transparent) {
                background += backdrop(px[k], py[k]);
              }
            }
            const int total = kEdgeSamples * kEdgeSamples;
            const int count = static_cast<int>(hits.size());
            const double coverage = static_cast<double>(count) / total;
            // The object's colour is the mean of its samples' (in uniform light exactly the
            // centre ray's when it hits), blended with the backdrop by the coverage.
            const double share = transparent ? 1.0 : coverage;
            internal::OutlinePixel outline;
            outline.first = static_cast<int>(block.samples.size());
            if (uniform && centre.hit) {
              block.samples.push_back({static_cast<float>(cosine(centre)), static_cast<float>(share)});
            } else {
              for (const PixelTerm& hit : hits) {
                block.samples.push_back({hit.mu, static_cast<float>(share * hit.weight / count)});
              }
            }
            outline.count = static_cast<int>(block.samples.size()) - outline.first;
            const int misses = total - count;
            outline.background =
                misses > 0 ? static_cast<float>((1.0 - coverage) * background / misses) : 0.0f;
            outline.alpha = transparent ? static_cast<float>(coverage) : 1.0f;
            block.outline.push_back(outline);
            pixel = {internal::kOutlineMu, 0.0f};
          }
        }
      });
  return plan;
}

}  // namespace

Renderer::Renderer(const color::Colorimeter& colorimeter, const RenderOptions& options)
    : colorimeter_(colorimeter), options_(options), environment_(options.lighting) {
  CheckOptions(options_);
  if (options_.lighting == Lighting::kStudio && options_.roughness > 0.0) {
    prefiltered_ = std::make_unique<PrefilteredEnvironment>(
        environment_, options_.roughness, internal::ThreadCount(options_.threads));
  }
  plan_ = TraceTile(options_, environment_, prefiltered_.get());
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
  // The table in linear sRGB (a linear map of XYZ, so interpolating it is interpolating
  // XYZ and converting).
  static const SRGBMatrix kMatrix;
  const auto& m = kMatrix.m;
  const std::vector<double>& xyz = table.nodes();
  std::vector<double> rgb(xyz.size());
  for (std::size_t n = 0; n < xyz.size(); n += 3) {
    for (int c = 0; c < 3; ++c) {
      rgb[n + c] = m[c][0] * xyz[n] + m[c][1] * xyz[n + 1] + m[c][2] * xyz[n + 2];
    }
  }
  const int last = table.size() - 1;
  const double* nodes = rgb.data();
  return Shade([nodes, last](double mu, double* out) {
    const double t = mu * last;
    int i = static_cast<int>(t);
    if (i >= last) i = last - 1;
    const double f = t - i;
    const double* a = nodes + 3 * i;
    out[0] = a[0] + f * (a[3] - a[0]);
    out[1] = a[1] + f * (a[4] - a[1]);
    out[2] = a[2] + f * (a[5] - a[2]);
  });
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
  static const SRGBMatrix kMatrix;
  const auto& m = kMatrix.m;
  return Shade([&direct, &m](double mu, double* out) {
    const color::XYZ c = direct.At(mu);
    for (int k = 0; k < 3; ++k) out[k] = m[k][0] * c.X + m[k][1] * c.Y + m[k][2] * c.Z;
  });
}

template <typename ColourAt>
LinearImage Renderer::Shade(const ColourAt& rgb) const {
  const int size = options_.size;
  const internal::TilePlan& plan = *plan_;
  const color::RGB white = color::LinearSRGBFromXYZ(colorimeter_.White());
  const float backdrop_alpha = options_.background == Background::kTransparent ? 0.0f : 1.0f;
  LinearImage image(size, size);
  constexpr int kRows = internal::TilePlan::kRows;
  internal::ParallelFor(
      size, kRows, internal::ThreadCount(options_.threads), [&](int row_begin, int row_end) {
        const internal::TileBlock& block = plan.blocks[row_begin / kRows];
        const internal::OutlinePixel* outline = block.outline.data();
        const std::size_t begin = static_cast<std::size_t>(row_begin) * size;
        const std::size_t end = static_cast<std::size_t>(row_end) * size;
        float* pixel = &image.rgba[4 * begin];
        for (std::size_t p = begin; p < end; ++p, pixel += 4) {
          const internal::PixelTerm term = plan.pixels[p];
          double c[3];
          if (term.mu >= 0.0f) {
            rgb(term.mu, c);
            pixel[0] = static_cast<float>(term.weight * c[0]);
            pixel[1] = static_cast<float>(term.weight * c[1]);
            pixel[2] = static_cast<float>(term.weight * c[2]);
            pixel[3] = 1.0f;
          } else if (term.mu == internal::kBackdropMu) {
            pixel[0] = static_cast<float>(term.weight * white.r);
            pixel[1] = static_cast<float>(term.weight * white.g);
            pixel[2] = static_cast<float>(term.weight * white.b);
            pixel[3] = backdrop_alpha;
          } else {
            const internal::OutlinePixel& o = *outline++;
            double sum[3] = {o.background * white.r, o.background * white.g,
                             o.background * white.b};
            for (int s = o.first; s < o.first + o.count; ++s) {
              const internal::PixelTerm& sample = block.samples[s];
              rgb(sample.mu, c);
              for (int k = 0; k < 3; ++k) sum[k] += sample.weight * c[k];
            }
            for (int k = 0; k < 3; ++k) pixel[k] = static_cast<float>(sum[k]);
            pixel[3] = o.alpha;
          }
        }
      });
  return image;
}

}  // namespace alloycolor::render
