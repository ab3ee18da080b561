// Time of the smooth Ceres fit (fit/smooth_fit.h) against the size of the data, on the
// bundled Au-Ag set (Rioux et al., 11 compositions, 1 nm data):
//  - wavelengths: the fit grid over 360-830 nm at 5, 2.5 and 1.25 nm (95, 189, 377 nodes:
//    1x, 2x, 4x), all 11 samples;
//  - samples: 3 (x = 0, 0.5, 1), 6 (0, 0.2, ..., 1) and all 11 compositions (1x, 2x, 3.7x)
//    on the 5 nm grid.
// Both with the smoothing fixed (1e-3), so the figure is the Ceres solve itself (its
// iteration count is reported: it varies with the data, and so does the time);
// BM_FitDefault is the smooth fit as `fit --method smooth` runs it (smoothing by leave-one-
// composition-out cross-validation over 8 candidates) on all samples and the 5 nm grid;
// BM_BuildModel is the whole of what `fit` does for a method before writing the file:
// the fit and its prediction error from 9 leave-one-out folds and 4 folds holding out two
// neighbouring compositions for its gap exponent (fit::BuildModel, the folds
// on the machine's cores: wall-clock time), for smooth, physical and auto.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/spectrum.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/fit/smooth_fit.h"

namespace alloycolor {
namespace {

const Dataset& AuAg() {
  static const Dataset dataset = LoadDataset(std::string(ALLOYCOLOR_DATA_DIR) + "/Au-Ag");
  return dataset;
}

// The Au-Ag samples at the given compositions only.
Dataset Subset(const std::vector<double>& keep) {
  std::vector<double> exclude;
  for (const Sample& s : AuAg().samples) {
    bool kept = false;
    for (double x : keep) kept |= std::abs(s.x_atomic - x) < 1e-9;
    if (!kept) exclude.push_back(s.x_atomic);
  }
  return WithoutSamples(AuAg(), exclude);
}

void Fit(benchmark::State& state, const Dataset& dataset, double step_nm) {
  fit::SmoothFitOptions options;
  options.grid_nm = UniformGrid(360.0, 830.0, step_nm);
  options.smoothing = 1e-3;
  int iterations = 0;
  for (auto _ : state) {
    const fit::SmoothFitResult result = fit::FitSmooth(dataset, options);
    iterations = result.model->fit_summary().iterations;
    benchmark::DoNotOptimize(result.model.get());
  }
  state.counters["samples"] = static_cast<double>(dataset.samples.size());
  state.counters["wavelengths"] = static_cast<double>(options.grid_nm.size());
  state.counters["ceres_iterations"] = iterations;
}

// range(0): wavelength multiple 1, 2, 4.
void BM_FitWavelengths(benchmark::State& state) {
  Fit(state, AuAg(), 5.0 / static_cast<double>(state.range(0)));
}

// range(0): 3, 6 or 11 samples.
void BM_FitSamples(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  const Dataset dataset = count == 3   ? Subset({0.0, 0.5, 1.0})
                          : count == 6 ? Subset({0.0, 0.2, 0.4, 0.6, 0.8, 1.0})
                                       : AuAg();
  Fit(state, dataset, 5.0);
}

void BM_FitDefault(benchmark::State& state) {
  fit::SmoothFitOptions options;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fit::FitSmooth(AuAg(), options).model);
  }
}

// range(0): 0 smooth, 1 physical, 2 auto.
void BM_BuildModel(benchmark::State& state) {
  static const color::Colorimeter d65 = color::Colorimeter::Load(ALLOYCOLOR_DATA_DIR, "D65", 2);
  const char* method = state.range(0) == 0 ? "smooth" : state.range(0) == 1 ? "physical" : "auto";
  fit::FitSettings settings;
  settings.colorimeter = &d65;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fit::BuildModel(method, AuAg(), settings));
  }
  state.SetLabel(method);
}

BENCHMARK(BM_FitWavelengths)
    ->ArgName("x")
    ->Arg(1)
    ->Arg(2)
    ->Arg(4)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly();
BENCHMARK(BM_FitSamples)
    ->ArgName("samples")
    ->Arg(3)
    ->Arg(6)
    ->Arg(11)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly();
BENCHMARK(BM_FitDefault)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly();
BENCHMARK(BM_BuildModel)
    ->ArgName("method")
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Repetitions(3)
    ->ReportAggregatesOnly();

}  // namespace
}  // namespace alloycolor

BENCHMARK_MAIN();
