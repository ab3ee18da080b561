// Shading speed of 1024 x 1024 tiles of gold (D65): the sphere in uniform and studio light
// and the ring in studio light, each
//  - Table: Renderer::Render from the XYZ table, with the Renderer (its traced tile) made
//    beforehand, as for every further image of a contact sheet or a session;
//  - First: the Renderer made and the image rendered, as for a single picture;
//  - Reference: the straightforward renderer of tests/reference_renderer.h, every pixel
//    traced, lit and coloured on its own (one thread), from the same table;
//  - Direct: spectral evaluation of the Fresnel equations at every sample;
// on one thread and on all of them; plus building the table and the 8-bit sRGB encoding.
// Counter "Mpixel/s": megapixels shaded per second of wall time.
#include <benchmark/benchmark.h>

#include <complex>
#include <string>
#include <thread>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/core/io.h"
#include "alloycolor/render/image.h"
#include "alloycolor/render/renderer.h"
#include "alloycolor/render/shading.h"
#include "reference_renderer.h"

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

// The three scenes of the table: 0 sphere uniform, 1 sphere studio, 2 ring studio.
RenderOptions Scene(int scene, int threads) {
  return Options(scene == 0 ? Lighting::kUniform : Lighting::kStudio,
                 scene == 2 ? Shape::kRing : Shape::kSphere, threads);
}

// args: scene, threads.
void BM_Table(benchmark::State& state) {
  const Renderer renderer(D65(), Scene(state.range(0), state.range(1)));
  const ReflectionTable table = renderer.Table(Gold());
  for (auto _ : state) benchmark::DoNotOptimize(renderer.Render(table));
  SetPixelRate(state, double(kSize) * kSize);
}

void BM_First(benchmark::State& state) {
  const RenderOptions options = Scene(state.range(0), state.range(1));
  const ReflectionTable table = Renderer(D65(), options).Table(Gold());
  for (auto _ : state) {
    const Renderer renderer(D65(), options);
    benchmark::DoNotOptimize(renderer.Render(table));
  }
  SetPixelRate(state, double(kSize) * kSize);
}

void BM_Reference(benchmark::State& state) {
  const RenderOptions options = Scene(state.range(0), 1);
  const ReflectionTable table = Renderer(D65(), options).Table(Gold());
  for (auto _ : state) {
    benchmark::DoNotOptimize(alloycolor::testing::ReferenceRender(
        D65(), options, [&table](double mu) { return table.At(mu); }));
  }
  SetPixelRate(state, double(kSize) * kSize);
}

void BM_Direct(benchmark::State& state) {
  const Renderer renderer(D65(), Scene(state.range(0), state.range(1)));
  const DirectReflection direct = renderer.Direct(Gold());
  for (auto _ : state) benchmark::DoNotOptimize(renderer.Render(direct));
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

void SceneArgs(benchmark::internal::Benchmark* b) {
  for (int scene = 0; scene < 3; ++scene) {
    b->Args({scene, 1});
    if (kAllThreads > 1) b->Args({scene, kAllThreads});
  }
}

BENCHMARK(BM_Table)->Apply(SceneArgs)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_First)->Apply(SceneArgs)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Reference)
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Direct)
    ->Args({0, kAllThreads})
    ->Args({1, kAllThreads})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_BuildTable)->Arg(0)->Arg(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EncodeSRGB8)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace alloycolor::render

BENCHMARK_MAIN();
