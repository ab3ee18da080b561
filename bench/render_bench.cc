// Shading speed of a 1024 x 1024 sphere (gold, D65): from the XYZ table against cos(theta)
// and from direct spectral evaluation of the Fresnel equations at every pixel, on one
// thread and on all of them; plus building the table, the studio set, the ring, and the
// 8-bit sRGB encoding. Counter "Mpixel/s": megapixels shaded per second of wall time.
#include <benchmark/benchmark.h>

#include <complex>
#include <string>
#include <thread>
#include <vector>

#include "alloycolor/core/io.h"
#include "alloycolor/color/colorimetry.h"
#include "alloycolor/render/image.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/render/renderer.h"
#include "alloycolor/render/shading.h"

namespace alloycolor::render {
using namespace alloycolor::color;  // NOLINT(build/namespaces): colour types throughout
namespace {

constexpr int kSize = 1024;

const Colorimeter& D65() {
  static const Colorimeter kColorimeter = Colorimeter::Load(ALLOYCOLOR_DATA_DIR, "D65", 2);
  return kColorimeter;
}

const std::vector<std::complex<double>>& Gold() {
  static const auto kIndex =
      IndexOnGrid(D65(), ReadNkFile(std::string(ALLOYCOLOR_DATA_DIR) + "/pure/Au-Johnson.yml"));
  return kIndex;
}

RenderOptions Options(Lighting lighting, Shape shape, int threads, double roughness = 0.0) {
  RenderOptions options;
  options.shape = shape;
  options.size = kSize;
  options.lighting = lighting;
  options.roughness = roughness;
  options.background = Background::kTransparent;
  options.threads = threads;
  return options;
}

void SetPixelRate(benchmark::State& state, double pixels) {
  state.counters["Mpixel/s"] =
      benchmark::Counter(pixels * state.iterations() / 1e6, benchmark::Counter::kIsRate);
}

int Threads(const benchmark::State& state) { return static_cast<int>(state.range(0)); }

void BM_SphereUniformTable(benchmark::State& state) {
  const Renderer renderer(D65(), Options(Lighting::kUniform, Shape::kSphere, Threads(state)));
  const ReflectionTable table = renderer.Table(Gold());
  for (auto _ : state) benchmark::DoNotOptimize(renderer.Render(table));
  SetPixelRate(state, double(kSize) * kSize);
}

void BM_SphereUniformDirect(benchmark::State& state) {
  const Renderer renderer(D65(), Options(Lighting::kUniform, Shape::kSphere, Threads(state)));
  const DirectReflection direct = renderer.Direct(Gold());
  for (auto _ : state) benchmark::DoNotOptimize(renderer.Render(direct));
  SetPixelRate(state, double(kSize) * kSize);
}

void BM_SphereStudioTable(benchmark::State& state) {
  const Renderer renderer(D65(), Options(Lighting::kStudio, Shape::kSphere, Threads(state)));
  const ReflectionTable table = renderer.Table(Gold());
  for (auto _ : state) benchmark::DoNotOptimize(renderer.Render(table));
  SetPixelRate(state, double(kSize) * kSize);
}

void BM_SphereStudioDirect(benchmark::State& state) {
  const Renderer renderer(D65(), Options(Lighting::kStudio, Shape::kSphere, Threads(state)));
  const DirectReflection direct = renderer.Direct(Gold());
  for (auto _ : state) benchmark::DoNotOptimize(renderer.Render(direct));
  SetPixelRate(state, double(kSize) * kSize);
}

void BM_RingStudioTable(benchmark::State& state) {
  const Renderer renderer(D65(), Options(Lighting::kStudio, Shape::kRing, Threads(state)));
  const ReflectionTable table = renderer.Table(Gold());
  for (auto _ : state) benchmark::DoNotOptimize(renderer.Render(table));
  SetPixelRate(state, double(kSize) * kSize);
}

void BM_BuildTable(benchmark::State& state) {
  const double alpha = state.range(0) / 100.0;
  const DirectReflection direct(D65(), Gold(), alpha);
  for (auto _ : state) benchmark::DoNotOptimize(ReflectionTable(direct));
  const ReflectionTable table(direct);
  state.counters["rel_error"] = ReflectionTableError(table, direct, alpha > 0 ? 32 : 4000);
}

void BM_EncodeSRGB8(benchmark::State& state) {
  const Renderer renderer(D65(), Options(Lighting::kStudio, Shape::kSphere, 0));
  const LinearImage image = renderer.Render(renderer.Table(Gold()));
  for (auto _ : state) benchmark::DoNotOptimize(EncodeSRGB8(image));
  SetPixelRate(state, double(kSize) * kSize);
}

const int kAllThreads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

BENCHMARK(BM_SphereUniformTable)
    ->Arg(1)
    ->Arg(kAllThreads)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SphereUniformDirect)
    ->Arg(1)
    ->Arg(kAllThreads)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SphereStudioTable)
    ->Arg(1)
    ->Arg(kAllThreads)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SphereStudioDirect)->Arg(kAllThreads)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RingStudioTable)->Arg(kAllThreads)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BuildTable)->Arg(0)->Arg(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EncodeSRGB8)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace alloycolor::render

BENCHMARK_MAIN();
