// Fits and leave-one-out validation against the number of samples, on a composition-spread
// library as a co-sputtered wafer mapped by an ellipsometer gives one: N compositions
// spread over 0-1 (evenly, each moved by up to a fifth of the spacing; the two ends pure),
// n and k on 300-1000 nm in 5 nm steps from the physical model fitted to the bundled Au-Ag
// set (Rioux et al.), each sample's n and k tilted by its own scatter (a level and a slope
// across the range, each 1 % standard deviation: a film's thickness and roughness).
//
//   spread_bench --write DIR N [SEED]   writes such a set (DIR/dataset.json, DIR/s*.csv)
//   spread_bench [benchmark flags]      the benchmarks below, side by side:
//  - BM_Fit/method/N: fit::BuildModel as `alloycolor fit --method M` runs it (the method and
//    its prediction error from its folds), for eps-linear, smooth, physical and auto;
//  - BM_ValidateLoo/N: validate::ComputeValidation of every leave-one-out split with
//    eps-linear, as `alloycolor validate --loo --methods eps-linear` runs it (one thread).
// scripts/bench.sh runs it and prints the times and their ratios against the samples'.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/units.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/fit/physical_fit.h"
#include "alloycolor/validate/validation.h"

namespace alloycolor {
namespace {

// The truth: the physical model of the bundled Au-Ag set.
const PhysicalModel& Truth() {
  static const std::unique_ptr<PhysicalModel> model = [] {
    fit::PhysicalFitOptions options;
    options.terms = "rioux-gap,rioux-edge";
    options.covariance = false;
    return std::move(
        fit::FitPhysical(LoadDataset(std::string(ALLOYCOLOR_DATA_DIR) + "/Au-Ag"), options).model);
  }();
  return *model;
}

// Writes the set of n samples into dir (created); returns the manifest's path.
std::string WriteSpread(const std::string& dir, int n, unsigned seed) {
  std::filesystem::create_directories(dir);
  std::mt19937 rng(seed);
  std::normal_distribution<double> scatter(0.0, 0.01);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  std::vector<double> grid;
  for (double l = 300; l <= 1000 + 1e-9; l += 5) grid.push_back(l);
  std::ofstream manifest(dir + "/dataset.json");
  manifest << "{\"name\": \"Au-Ag composition spread, " << n
           << " samples (generated)\", \"system\": {\"a\": \"Au\", \"b\": \"Ag\"},\n"
           << " \"composition\": \"atomic_fraction_a\", \"samples\": [\n";
  for (int i = 0; i < n; ++i) {
    double x = static_cast<double>(i) / (n - 1);
    if (i > 0 && i + 1 < n) x += jitter(rng) / (n - 1);
    const double level = scatter(rng), slope = scatter(rng);
    const std::vector<std::complex<double>> nk = Truth().Index(x, grid);
    char name[32];
    std::snprintf(name, sizeof name, "s%04d.csv", i);
    std::ofstream csv(dir + "/" + name);
    csv << "lambda_nm,n,k\n";
    csv.precision(7);
    for (size_t j = 0; j < grid.size(); ++j) {
      const double tilt = 1.0 + level + slope * (grid[j] - 650.0) / 350.0;
      csv << grid[j] << "," << nk[j].real() * tilt << "," << nk[j].imag() * tilt << "\n";
    }
    char x_text[32];
    std::snprintf(x_text, sizeof x_text, "%.6f", x);
    manifest << "  {\"x\": " << x_text << ", \"file\": \"" << name << "\"}"
             << (i + 1 < n ? ",\n" : "\n");
  }
  manifest << "]}\n";
  return dir + "/dataset.json";
}

// The set of n samples (written once per size into the temporary folder).
const Dataset& Spread(int n) {
  static std::map<int, Dataset> sets;
  auto it = sets.find(n);
  if (it == sets.end()) {
    const std::string dir =
        (std::filesystem::temp_directory_path() / ("alloycolor-spread-" + std::to_string(n)))
            .string();
    it = sets.emplace(n, LoadDataset(WriteSpread(dir, n, 1))).first;
  }
  return it->second;
}

const color::Colorimeter& D65() {
  static const color::Colorimeter d65 = color::Colorimeter::Load(ALLOYCOLOR_DATA_DIR, "D65", 2);
  return d65;
}

const char* const kMethods[] = {"eps-linear", "smooth", "physical", "auto"};

// range(0): method (kMethods), range(1): samples.
void BM_Fit(benchmark::State& state) {
  const char* method = kMethods[state.range(0)];
  const Dataset& data = Spread(static_cast<int>(state.range(1)));
  fit::FitSettings settings;
  settings.colorimeter = &D65();
  for (auto _ : state) benchmark::DoNotOptimize(fit::BuildModel(method, data, settings));
  state.SetLabel(method);
  state.counters["samples"] = static_cast<double>(state.range(1));
}

// range(0): samples.
void BM_ValidateLoo(benchmark::State& state) {
  const Dataset& data = Spread(static_cast<int>(state.range(0)));
  validate::ValidationOptions options;
  options.methods = {"eps-linear"};
  options.angles_deg = {0.0, 45.0};
  options.mode = "loo";
  options.build = fit::SharedFitBuilder(D65());
  const std::vector<validate::SampleSplit> splits = validate::LeaveOneOutSplits(data);
  for (auto _ : state) {
    benchmark::DoNotOptimize(validate::ComputeValidation(data, splits, D65(), options, {}));
  }
  state.counters["samples"] = static_cast<double>(state.range(0));
}

BENCHMARK(BM_Fit)
    ->ArgNames({"method", "samples"})
    ->ArgsProduct({{0}, {50, 100, 300, 1000}})
    ->ArgsProduct({{1, 2, 3}, {100, 300}})
    ->Args({3, 1000})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(BM_ValidateLoo)  // a second or so each: the median of three runs
    ->ArgName("samples")
    ->Arg(50)
    ->Arg(100)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);

}  // namespace
}  // namespace alloycolor

int main(int argc, char** argv) {
  if (argc >= 4 && std::string(argv[1]) == "--write") {
    const unsigned seed = argc >= 5 ? static_cast<unsigned>(std::stoul(argv[4])) : 1u;
    std::printf("%s\n", alloycolor::WriteSpread(argv[2], std::stoi(argv[3]), seed).c_str());
    return 0;
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
