#include "alloycolor/render/shading.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/units.h"
#include "alloycolor/model/optics.h"

namespace alloycolor::render {
namespace {

// Grazing incidence for the lobe integral: at mu = 0 exactly the GGX visible-normal
// distribution degenerates; the albedo is continuous there.
constexpr double kMinLobeMu = 1e-4;
// The smooth table a rough table's lobe integral reads.
constexpr int kFineTableSize = 4097;
constexpr int kPrefilterSamples = 128;
constexpr int kMaxPrefilterWidth = 512;

double RadicalInverse2(unsigned bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return bits * 2.3283064365386963e-10;  // / 2^32
}

// The Hammersley points (k + 1/2) / n, radical inverse of k.
template <int kCount>
const std::array<std::array<double, 2>, kCount>& Hammersley() {
  static const auto kPoints = [] {
    std::array<std::array<double, 2>, kCount> points;
    for (int k = 0; k < kCount; ++k) points[k] = {(k + 0.5) / kCount, RadicalInverse2(k)};
    return points;
  }();
  return kPoints;
}

// Smith's Lambda for GGX at a direction with cosine c to the normal.
double SmithLambda(double alpha, double c) {
  const double c2 = c * c;
  if (c2 <= 0.0) return 1e300;
  const double tan2 = (1.0 - c2) / c2;
  return 0.5 * (std::sqrt(1.0 + alpha * alpha * tan2) - 1.0);
}

// Heitz 2018, "Sampling the GGX distribution of visible normals": a microfacet normal
// (local frame, normal along z) for viewing direction v and uniform numbers u1, u2.
Vec3 SampleVisibleNormal(const Vec3& v, double alpha, double u1, double u2) {
  const Vec3 vh = Normalize(Vec3{alpha * v.x, alpha * v.y, v.z});
  const double lensq = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 =
      lensq > 0.0 ? (1.0 / std::sqrt(lensq)) * Vec3{-vh.y, vh.x, 0.0} : Vec3{1.0, 0.0, 0.0};
  const Vec3 t2 = Cross(vh, t1);
  const double r = std::sqrt(u1);
  const double phi = 2.0 * kPi * u2;
  const double p1 = r * std::cos(phi);
  double p2 = r * std::sin(phi);
  const double s = 0.5 * (1.0 + vh.z);
  p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * p2;
  const double p3 = std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2));
  const Vec3 nh = p1 * t1 + p2 * t2 + p3 * vh;
  return Normalize(Vec3{alpha * nh.x, alpha * nh.y, std::max(0.0, nh.z)});
}

// Directional albedo of the GGX surface: the mean over visible normals h of
// F(v.h) G2(v, l) / G1(v), l the mirror of v about h; fresnel(c) gives XYZ at cosine c.
template <typename Fresnel>
color::XYZ LobeAlbedo(double alpha, double mu, const Fresnel& fresnel) {
  mu = std::clamp(mu, kMinLobeMu, 1.0);
  const Vec3 v{std::sqrt(1.0 - mu * mu), 0.0, mu};
  const double lambda_v = SmithLambda(alpha, mu);
  color::XYZ sum{0.0, 0.0, 0.0};
  for (const auto& u : Hammersley<kLobeSamples>()) {
    const Vec3 h = SampleVisibleNormal(v, alpha, u[0], u[1]);
    const double vh = Dot(v, h);
    const double nl = 2.0 * vh * h.z - mu;  // (Reflect(v, h)).z
    if (nl <= 0.0 || vh <= 0.0) continue;
    const double weight = (1.0 + lambda_v) / (1.0 + lambda_v + SmithLambda(alpha, nl));
    const color::XYZ f = fresnel(vh);
    sum.X += weight * f.X;
    sum.Y += weight * f.Y;
    sum.Z += weight * f.Z;
  }
  const double n = kLobeSamples;
  return {sum.X / n, sum.Y / n, sum.Z / n};
}

void CheckRoughness(double alpha) {
  if (!(alpha >= 0.0 && alpha <= kMaxRoughness)) {
    std::ostringstream msg;
    msg << "roughness " << alpha << " lies outside 0-" << kMaxRoughness;
    throw Error(msg.str());
  }
}

double SmoothStep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// A rectangular softbox facing the origin: centre direction, its own right and up axes,
// half-extents as tangents of angles, softened at the edges. Outside the soft edges
// (tangent a >= half + soft) it is 0, found before dividing.
double SoftBox(const Vec3& w, const Vec3& centre, const Vec3& right, const Vec3& up,
               double half_width, double half_height, double soft) {
  const double d = Dot(w, centre);
  if (d <= 0.0) return 0.0;
  const double x = std::abs(Dot(w, right));
  if (x >= (half_width + soft) * d) return 0.0;
  const double y = std::abs(Dot(w, up));
  if (y >= (half_height + soft) * d) return 0.0;
  return SmoothStep(half_width + soft, half_width - soft, x / d) *
         SmoothStep(half_height + soft, half_height - soft, y / d);
}

struct StudioSet {
  Vec3 key, key_right, key_up;
  Vec3 fill, fill_right, fill_up;
  Vec3 strip, strip_right, strip_up;
  Vec3 flag, flag_right, flag_up;
};

// A softbox facing the origin from direction `centre`, its sides horizontal and vertical.
void Orient(const Vec3& centre, Vec3* c, Vec3* right, Vec3* up) {
  *c = Normalize(centre);
  *right = Normalize(Cross(Vec3{0.0, 1.0, 0.0}, *c));
  *up = Cross(*c, *right);
}

const StudioSet& Studio() {
  static const StudioSet kSet = [] {
    StudioSet s;
    Orient({-0.62, 0.55, 0.56}, &s.key, &s.key_right, &s.key_up);
    Orient({0.9, 0.15, 0.3}, &s.fill, &s.fill_right, &s.fill_up);
    Orient({0.15, 0.85, -0.5}, &s.strip, &s.strip_right, &s.strip_up);
    Orient({0.55, 0.25, 0.8}, &s.flag, &s.flag_right, &s.flag_up);
    return s;
  }();
  return kSet;
}

double StudioRadiance(const Vec3& w) {
  const StudioSet& s = Studio();
  // The tent: light walls brightening overhead, a dark gap just above the table's edge,
  // the lit table below the horizon, a black flag to the front right for contrast.
  double room = 0.42 + 0.3 * std::max(0.0, w.y);
  const double gap = SmoothStep(-0.01, 0.03, w.y) * SmoothStep(0.16, 0.08, w.y);
  room *= 1.0 - 0.85 * gap;
  room *= 1.0 - 0.9 * SoftBox(w, s.flag, s.flag_right, s.flag_up, 0.2, 0.9, 0.12);
  const double table = SmoothStep(0.0, -0.05, w.y);
  double e = (1.0 - table) * room + table * (0.35 + 0.5 * std::sqrt(std::clamp(-w.y, 0.0, 1.0)));
  e += 3.5 * SoftBox(w, s.key, s.key_right, s.key_up, 0.42, 0.32, 0.08);
  e += 1.6 * SoftBox(w, s.fill, s.fill_right, s.fill_up, 0.14, 0.5, 0.05);
  e += 2.2 * SoftBox(w, s.strip, s.strip_right, s.strip_up, 0.7, 0.07, 0.04);
  return e;
}

// Latitude-longitude parametrisation: theta from +y, phi around y from +x toward +z.
Vec3 LatLongDirection(double theta, double phi) {
  const double st = std::sin(theta);
  return {st * std::cos(phi), std::cos(theta), st * std::sin(phi)};
}

}  // namespace

DirectReflection::DirectReflection(const color::Colorimeter& colorimeter,
                                   std::vector<std::complex<double>> index, double roughness_alpha)
    : wx_(colorimeter.wx()),
      wy_(colorimeter.wy()),
      wz_(colorimeter.wz()),
      index_(std::move(index)),
      alpha_(roughness_alpha) {
  if (index_.size() != wx_.size()) {
    throw Error("shading: " + std::to_string(index_.size()) +
                " indices given for a colorimeter grid of " + std::to_string(wx_.size()) +
                " wavelengths");
  }
  CheckRoughness(alpha_);
}

color::XYZ DirectReflection::FresnelXYZ(double c) const {
  c = std::clamp(c, 0.0, 1.0);
  color::XYZ xyz{0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < index_.size(); ++i) {
    const Complex<double> nk{index_[i].real(), index_[i].imag()};
    const double r = FresnelReflectance(nk, c).Average();
    xyz.X += wx_[i] * r;
    xyz.Y += wy_[i] * r;
    xyz.Z += wz_[i] * r;
  }
  return xyz;
}

DirectReflection DirectReflection::WithRoughness(double roughness_alpha) const {
  CheckRoughness(roughness_alpha);
  DirectReflection copy = *this;
  copy.alpha_ = roughness_alpha;
  return copy;
}

color::XYZ DirectReflection::At(double mu) const {
  if (alpha_ == 0.0) return FresnelXYZ(mu);
  return LobeAlbedo(alpha_, mu, [this](double c) { return FresnelXYZ(c); });
}

ReflectionTable::ReflectionTable(const DirectReflection& direct, int size)
    : last_(std::max(size, 2) - 1), alpha_(direct.roughness()) {
  xyz_.resize(3 * static_cast<std::size_t>(last_ + 1));
  const auto store = [this](int i, const color::XYZ& v) {
    xyz_[3 * i] = v.X;
    xyz_[3 * i + 1] = v.Y;
    xyz_[3 * i + 2] = v.Z;
  };
  if (alpha_ == 0.0) {
    for (int i = 0; i <= last_; ++i) store(i, direct.FresnelXYZ(static_cast<double>(i) / last_));
    return;
  }
  const ReflectionTable fine(direct.WithRoughness(0.0), kFineTableSize);
  for (int i = 0; i <= last_; ++i) {
    store(i, LobeAlbedo(alpha_, static_cast<double>(i) / last_,
                        [&fine](double c) { return fine.At(c); }));
  }
}

double ReflectionTableError(const ReflectionTable& table, const DirectReflection& direct,
                            int samples) {
  double worst = 0.0;
  const int nodes = table.size() - 1;
  for (int s = 0; s < samples; ++s) {
    // Irrational offsets keep the samples off the nodes, where the error is largest.
    const double mu = std::fmod((s + 0.5) / samples + 0.5 * 0.6180339887498949 / nodes, 1.0);
    const color::XYZ t = table.At(mu);
    const color::XYZ d = direct.At(mu);
    const double dx[3] = {t.X - d.X, t.Y - d.Y, t.Z - d.Z};
    const double ref[3] = {d.X, d.Y, d.Z};
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(dx[c]) / std::max(std::abs(ref[c]), 1e-12));
    }
  }
  return worst;
}

CheckedTable GuardedTable(const DirectReflection& direct, const std::string& what) {
  const int samples = direct.roughness() > 0.0 ? kRoughTableCheckSamples : kTableCheckSamples;
  int size = kReflectionTableSize;
  CheckedTable checked{ReflectionTable(direct, size), 0.0};
  checked.error = ReflectionTableError(checked.table, direct, samples);
  while (checked.error > kTableErrorLimit && size < kMaxReflectionTableSize) {
    size = 4 * (size - 1) + 1;
    checked.table = ReflectionTable(direct, size);
    checked.error = ReflectionTableError(checked.table, direct, samples);
  }
  if (checked.error > kTableErrorLimit) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%.3g (relative), above the limit %g", checked.error,
                  kTableErrorLimit);
    throw Error(what + ": the XYZ table differs from direct spectral evaluation by " + buf +
                "; render it by direct spectral evaluation");
  }
  return checked;
}

Lighting LightingFromName(const std::string& name) {
  if (name == "uniform") return Lighting::kUniform;
  if (name == "studio") return Lighting::kStudio;
  throw Error("unknown lighting '" + name + "' (uniform, studio)");
}

std::string LightingName(Lighting lighting) {
  return lighting == Lighting::kUniform ? "uniform" : "studio";
}

double Environment::Radiance(const Vec3& w) const {
  if (lighting_ == Lighting::kUniform) return 1.0;
  return StudioRadiance(w);
}

double Environment::Backdrop(double u, double v) const {
  if (lighting_ == Lighting::kUniform) return 1.0;
  // Seamless paper lit from above: lighter at the top, a soft pool of light behind the
  // object, darker toward the corners.
  const double du = u - 0.5;
  const double dv = v - 0.42;
  const double pool = std::exp(-(du * du + dv * dv) / (2.0 * 0.3 * 0.3));
  return 0.22 + 0.2 * (1.0 - v) + 0.2 * pool;
}

PrefilteredEnvironment::PrefilteredEnvironment(const Environment& environment,
                                               double roughness_alpha, int threads) {
  if (!(roughness_alpha > 0.0 && roughness_alpha <= kMaxRoughness)) {
    CheckRoughness(roughness_alpha);
    throw Error("prefiltered environment: roughness must be above 0");
  }
  const double alpha = roughness_alpha;
  width_ = std::clamp(static_cast<int>(std::ceil(4.0 * kPi / alpha)), 32, kMaxPrefilterWidth);
  width_ += width_ % 2;
  height_ = width_ / 2;
  texels_.assign(static_cast<std::size_t>(width_) * height_, 0.0f);
  const auto& points = Hammersley<kPrefilterSamples>();
  ParallelFor(height_, 4, threads, [&](int row_begin, int row_end) {
    for (int j = row_begin; j < row_end; ++j) {
      const double theta = (j + 0.5) * kPi / height_;
      for (int i = 0; i < width_; ++i) {
        const double phi = (i + 0.5) * 2.0 * kPi / width_;
        const Vec3 r = LatLongDirection(theta, phi);
        const Vec3 up = std::abs(r.y) < 0.9 ? Vec3{0.0, 1.0, 0.0} : Vec3{1.0, 0.0, 0.0};
        const Vec3 t = Normalize(Cross(up, r));
        const Vec3 b = Cross(r, t);
        double sum = 0.0, weight = 0.0;
        for (const auto& u : points) {
          // GGX normal distribution: cos^2 theta_h = (1 - u) / (1 + (alpha^2 - 1) u).
          const double c2 = (1.0 - u[0]) / (1.0 + (alpha * alpha - 1.0) * u[0]);
          const double ch = std::sqrt(c2);
          const double sh = std::sqrt(std::max(0.0, 1.0 - c2));
          const double ph = 2.0 * kPi * u[1];
          const Vec3 h = (sh * std::cos(ph)) * t + (sh * std::sin(ph)) * b + ch * r;
          const Vec3 l = Reflect(r, h);
          const double nl = Dot(r, l);
          if (nl <= 0.0) continue;
          sum += environment.Radiance(l) * nl;
          weight += nl;
        }
        texels_[static_cast<std::size_t>(j) * width_ + i] =
            static_cast<float>(weight > 0.0 ? sum / weight : environment.Radiance(r));
      }
    }
  });
}

double PrefilteredEnvironment::At(const Vec3& r) const {
  const double theta = std::acos(std::clamp(r.y, -1.0, 1.0));
  double phi = std::atan2(r.z, r.x);
  if (phi < 0.0) phi += 2.0 * kPi;
  const double fy = std::clamp(theta * height_ / kPi - 0.5, 0.0, height_ - 1.0);
  const double fx = phi * width_ / (2.0 * kPi) - 0.5;
  const int j0 = std::min(static_cast<int>(fy), height_ - 1);
  const int j1 = std::min(j0 + 1, height_ - 1);
  const double ty = fy - j0;
  const double fx_floor = std::floor(fx);
  const double tx = fx - fx_floor;
  const int i0 = (static_cast<int>(fx_floor) % width_ + width_) % width_;
  const int i1 = (i0 + 1) % width_;
  const auto at = [this](int i, int j) {
    return static_cast<double>(texels_[static_cast<std::size_t>(j) * width_ + i]);
  };
  const double top = at(i0, j0) + tx * (at(i1, j0) - at(i0, j0));
  const double bottom = at(i0, j1) + tx * (at(i1, j1) - at(i0, j1));
  return top + ty * (bottom - top);
}

}  // namespace alloycolor::render
