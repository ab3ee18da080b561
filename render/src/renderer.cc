#include "alloycolor/render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "alloycolor/core/error.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/units.h"

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

// Whether pixel i, whose centre ray gave `centre`, straddles an edge: a corner of it (rows
// top and bottom of the corner grid) hits where the centre misses or the reverse, or lies
// more than kDepthJump deeper or shallower.
bool StraddlesEdge(const CornerHit* top, const CornerHit* bottom, int i, const Hit& centre) {
  for (const CornerHit* corner : {&top[i], &top[i + 1], &bottom[i], &bottom[i + 1]}) {
    if (corner->hit != centre.hit || (centre.hit && std::abs(corner->t - centre.t) > kDepthJump)) {
      return true;
    }
  }
  return false;
}

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

  // hits[k] for the rays through (x[k], y[k]), k < n.
  void Intersect(const double* x, const double* y, int n, Hit* hits) const {
    if (shape_ == Shape::kSphere) {
      for (int k = 0; k < n; ++k) hits[k] = Sphere(x[k], y[k]);
    } else {
      IntersectRing(x, y, n, hits);
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
  // slab |y| <= kRingTubeRadius of the ring's frame that holds the torus, then a Newton
  // step on the distance along the ray (its slope is dir . normal), which takes the hit
  // from within kTraceEpsilon of the surface to about kTraceEpsilon^2 / kRingTubeRadius
  // unless the ray grazes.
  struct RingRay {
    Vec3 origin;  // in the ring's frame; the ray is origin + s dir_, z = -s in the world
    double s, s_hi;
    int step;
  };

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

  // The ring's rays kLanes at a time, each traced exactly as on its own: the distances of
  // all lanes are computed together (independent square roots, which the processor
  // overlaps and the compiler may vectorise), and a lane whose ray has ended takes the
  // next one.
  void IntersectRing(const double* x, const double* y, int n, Hit* hits) const {
    constexpr int kLanes = 8;
    int ray_of[kLanes];  // -1: idle
    double ox[kLanes], oy[kLanes], oz[kLanes], s[kLanes], s_hi[kLanes];
    int steps[kLanes];
    int next = 0;
    // Gives the lane the next ray that enters the slab (the others miss at once).
    const auto load = [&](int lane) {
      while (next < n) {
        const int k = next++;
        hits[k] = Hit{};
        RingRay ray;
        if (!StartRing(x[k], y[k], &ray)) continue;
        ray_of[lane] = k;
        ox[lane] = ray.origin.x;
        oy[lane] = ray.origin.y;
        oz[lane] = ray.origin.z;
        s[lane] = ray.s;
        s_hi[lane] = ray.s_hi;
        steps[lane] = 0;
        return true;
      }
      ray_of[lane] = -1;
      ox[lane] = oy[lane] = oz[lane] = s[lane] = s_hi[lane] = 0.0;
      return false;
    };
    int busy = 0;
    for (int lane = 0; lane < kLanes; ++lane) busy += load(lane);
    while (busy > 0) {
      double d[kLanes];
      for (int lane = 0; lane < kLanes; ++lane) {
        d[lane] = TorusDistance(Vec3{ox[lane], oy[lane], oz[lane]} + s[lane] * dir_);
      }
      for (int lane = 0; lane < kLanes; ++lane) {
        if (ray_of[lane] < 0) continue;
        const bool hit = d[lane] < kTraceEpsilon;
        if (!hit) {
          s[lane] += d[lane];
          if (++steps[lane] < kTraceSteps && s[lane] <= s_hi[lane]) continue;
        } else {
          hits[ray_of[lane]] = FinishRing(
              RingRay{{ox[lane], oy[lane], oz[lane]}, s[lane], s_hi[lane], steps[lane]}, d[lane]);
        }
        busy -= !load(lane);
      }
    }
  }

  // The hit of a ray whose distance to the torus at ray.s is `distance` (below
  // kTraceEpsilon), polished by the Newton step.
  Hit FinishRing(RingRay ray, double distance) const {
    Vec3 n = TorusNormal(ray.origin + ray.s * dir_);
    const double slope = Dot(dir_, n);
    if (slope < -kGrazingSlope) {
      ray.s -= distance / slope;
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

// The rays of a size x size tile through pixel positions (renderer.h), traced in batches.
class TileTracer {
 public:
  TileTracer(Shape shape, int size)
      : geometry_(shape), scale_(kObjectFraction * size), half_(0.5 * size) {}

  // The rays through (px0 + i, py), i < count: a row of pixel corners (px0 = 0) or centres
  // (px0 = 1/2).
  const std::vector<Hit>& Row(double px0, double py, int count) {
    px_.resize(count);
    py_.assign(count, py);
    for (int i = 0; i < count; ++i) px_[i] = px0 + i;
    return Trace();
  }

  // The kEdgeSamples x kEdgeSamples sample rays of pixel (i, j), row by row; Px(k), Py(k)
  // give their positions.
  const std::vector<Hit>& Samples(int i, int j) {
    px_.clear();
    py_.clear();
    for (int b = 0; b < kEdgeSamples; ++b) {
      for (int a = 0; a < kEdgeSamples; ++a) {
        px_.push_back(i + (a + 0.5) / kEdgeSamples);
        py_.push_back(j + (b + 0.5) / kEdgeSamples);
      }
    }
    return Trace();
  }
  double Px(int k) const { return px_[k]; }
  double Py(int k) const { return py_[k]; }

 private:
  const std::vector<Hit>& Trace() {
    const std::size_t n = px_.size();
    x_.resize(n);
    y_.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      x_[k] = (px_[k] - half_) / scale_;
      y_[k] = (half_ - py_[k]) / scale_;
    }
    hits_.resize(n);
    geometry_.Intersect(x_.data(), y_.data(), static_cast<int>(n), hits_.data());
    return hits_;
  }

  Geometry geometry_;
  double scale_, half_;
  std::vector<double> px_, py_, x_, y_;  // pixel and world positions
  std::vector<Hit> hits_;
};

}  // namespace

void CheckRenderOptions(const RenderOptions& o, bool direct, OptionSpelling spelling) {
  const auto named = [spelling](const char* name) {
    return (spelling == OptionSpelling::kFlag ? "--" : "") + std::string(name);
  };
  const auto number = [](double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", value);
    return std::string(text);
  };
  if (o.size < 1 || o.size > kMaxTileSize) {
    throw Error(named("size") + ": " + std::to_string(o.size) + " lies outside 1-" +
                std::to_string(kMaxTileSize) + " pixels");
  }
  if (!(o.roughness >= 0.0 && o.roughness <= kMaxRoughness)) {
    throw Error(named("roughness") + ": " + number(o.roughness) + " lies outside 0-" +
                number(kMaxRoughness) + " (GGX alpha)");
  }
  if (o.threads < 0) {
    throw Error(named("threads") + ": " + std::to_string(o.threads) + " is negative");
  }
  if (direct && o.roughness > 0.0) {
    throw Error(named("direct") + ": direct spectral evaluation at every pixel needs " +
                named("roughness") + " 0");
  }
}

Shape ShapeFromName(const std::string& name) {
  if (name == "sphere") return Shape::kSphere;
  if (name == "ring") return Shape::kRing;
  throw Error("unknown shape '" + name + "' (sphere, ring)");
}

std::string ShapeName(Shape shape) { return shape == Shape::kSphere ? "sphere" : "ring"; }

std::string AlloyLabel(const AlloyModel& model, double x_atomic) {
  char x[32];
  std::snprintf(x, sizeof x, "%.4g", x_atomic);
  return model.system().Name() + " x=" + x;
}

Background BackgroundFromName(const std::string& name) {
  if (name == "transparent") return Background::kTransparent;
  if (name == "backdrop") return Background::kBackdrop;
  throw Error("unknown background '" + name + "' (transparent, backdrop)");
}

Background DefaultBackground(Lighting lighting) {
  return lighting == Lighting::kUniform ? Background::kTransparent : Background::kBackdrop;
}

NormalMap TraceNormals(Shape shape, int size) {
  if (size < 1 || size > kMaxTileSize) {
    throw Error("image size " + std::to_string(size) + " lies outside 1-" +
                std::to_string(kMaxTileSize) + " pixels");
  }
  TileTracer tracer(shape, size);
  NormalMap map;
  map.size = size;
  map.normal.assign(static_cast<std::size_t>(size) * size * 3, 0.0f);
  map.coverage.assign(static_cast<std::size_t>(size) * size, 0.0f);
  std::vector<CornerHit> corners(static_cast<std::size_t>(size + 1) * (size + 1));
  for (int j = 0; j <= size; ++j) {
    const std::vector<Hit>& row = tracer.Row(0.0, j, size + 1);
    for (int i = 0; i <= size; ++i) {
      corners[static_cast<std::size_t>(j) * (size + 1) + i] = {row[i].hit, row[i].t};
    }
  }
  std::vector<Hit> centres;
  for (int j = 0; j < size; ++j) {
    const CornerHit* top = &corners[static_cast<std::size_t>(j) * (size + 1)];
    const CornerHit* bottom = top + size + 1;
    centres = tracer.Row(0.5, j + 0.5, size);
    for (int i = 0; i < size; ++i) {
      const std::size_t p = static_cast<std::size_t>(j) * size + i;
      const Hit& centre = centres[i];
      const bool edge = StraddlesEdge(top, bottom, i, centre);
      Vec3 normal = centre.normal;
      double coverage = centre.hit ? 1.0 : 0.0;
      if (edge) {
        Vec3 sum{0.0, 0.0, 0.0};
        int hits = 0;
        for (const Hit& hit : tracer.Samples(i, j)) {
          if (!hit.hit) continue;
          sum = sum + hit.normal;
          ++hits;
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

  auto plan = std::make_unique<internal::TilePlan>();
  constexpr int kRows = internal::TilePlan::kRows;
  plan->pixels.resize(static_cast<std::size_t>(size) * size);
  plan->blocks.resize((size + kRows - 1) / kRows);
  ParallelFor(size, kRows, ThreadCount(options.threads), [&](int row_begin, int row_end) {
    CheckCancel(options.cancel);
    internal::TileBlock& block = plan->blocks[row_begin / kRows];
    TileTracer tracer(options.shape, size);
    // Hits at the pixel corners of rows row_begin..row_end.
    const int stride = size + 1;
    std::vector<CornerHit> corners(static_cast<std::size_t>(row_end - row_begin + 1) * stride);
    for (int j = row_begin; j <= row_end; ++j) {
      const std::vector<Hit>& row = tracer.Row(0.0, j, stride);
      for (int i = 0; i <= size; ++i) {
        corners[static_cast<std::size_t>(j - row_begin) * stride + i] = {row[i].hit, row[i].t};
      }
    }
    std::vector<PixelTerm> hits;
    std::vector<Hit> centres;
    for (int j = row_begin; j < row_end; ++j) {
      const CornerHit* top = &corners[static_cast<std::size_t>(j - row_begin) * stride];
      const CornerHit* bottom = top + stride;
      centres = tracer.Row(0.5, j + 0.5, size);
      for (int i = 0; i < size; ++i) {
        PixelTerm& pixel = plan->pixels[static_cast<std::size_t>(j) * size + i];
        const Hit& centre = centres[i];
        const bool edge = StraddlesEdge(top, bottom, i, centre);
        if (!edge) {
          if (centre.hit) {
            pixel = {static_cast<float>(cosine(centre)), static_cast<float>(light(centre))};
          } else {
            pixel = {internal::kBackdropMu,
                     transparent ? 0.0f : static_cast<float>(backdrop(i + 0.5, j + 0.5))};
          }
          continue;
        }
        const std::vector<Hit>& samples = tracer.Samples(i, j);
        hits.clear();
        double background = 0.0;
        for (std::size_t k = 0; k < samples.size(); ++k) {
          const Hit& hit = samples[k];
          if (hit.hit) {
            hits.push_back({static_cast<float>(cosine(hit)), static_cast<float>(light(hit))});
          } else if (!transparent) {
            background += backdrop(tracer.Px(k), tracer.Py(k));
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
  CheckRenderOptions(options_, false);
  if (options_.lighting == Lighting::kStudio && options_.roughness > 0.0) {
    prefiltered_ = std::make_unique<PrefilteredEnvironment>(environment_, options_.roughness,
                                                            ThreadCount(options_.threads));
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
  ParallelFor(size, kRows, ThreadCount(options_.threads), [&](int row_begin, int row_end) {
    CheckCancel(options_.cancel);
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
        double sum[3] = {o.background * white.r, o.background * white.g, o.background * white.b};
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
