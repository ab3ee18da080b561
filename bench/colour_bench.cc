// Colours per second along a sweep of compositions of Au-Ag (D65, 2-degree observer, the
// 5 nm grid, normal incidence unless named), for each method: paper, eps-linear, smooth,
// eps-pchip, eps-spline, physical.
// One item is one composition taken to XYZ, CIELAB and 8-bit sRGB.
//
//  - Naive: the straightforward implementation of the chain, written here as a plain
//    per-sample loop with std::complex: the model's eps on the grid (for smooth, its
//    coefficients interpolated in wavelength and exponentiated per sample, as a first
//    implementation would; for physical, its parameters at the composition and then each
//    wavelength's terms one at a time, PhysicalPermittivity, with the C library's
//    functions), N = sqrt(eps), R = |(N - 1) / (N + 1)|^2, weighted sums.
//  - Library: what `alloycolor color` does per composition: color::IndexOnGrid,
//    color::MaterialXYZ, color::ColorFromXYZ.
//  - SweepExact: color::ColorSweep::ExactXYZ (smooth: coefficients on the grid once, no
//    allocation per composition).
//  - SweepTable: color::ColorSweep with its table of XYZ against x (error <= 1e-7).
// scripts/bench.sh runs this and prints the ratios to Naive.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/color/sweep.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/units.h"
#include "alloycolor/fit/physical_fit.h"
#include "alloycolor/fit/smooth_fit.h"
#include "alloycolor/model/interpolation.h"
#include "alloycolor/model/physical_model.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/model/smooth_model.h"

namespace alloycolor {
namespace {

constexpr int kSweepSteps = 1001;  // compositions 0, 0.001, ..., 1, cycled

struct Fixture {
  color::Colorimeter colorimeter = color::Colorimeter::Load(ALLOYCOLOR_DATA_DIR, "D65", 2);
  Dataset dataset = LoadDataset(std::string(ALLOYCOLOR_DATA_DIR) + "/Au-Ag");
  // 0 paper, 1 eps-linear, 2 smooth, 3 eps-pchip, 4 eps-spline, 5 physical.
  std::vector<std::unique_ptr<AlloyModel>> models;
  Fixture() {
    models.push_back(std::make_unique<SampleModel>(SampleModel::Kind::kPaper, dataset));
    models.push_back(std::make_unique<SampleModel>(SampleModel::Kind::kEpsLinear, dataset));
    fit::SmoothFitOptions options;  // the default fit: smoothing by cross-validation
    models.push_back(std::move(fit::FitSmooth(dataset, options).model));
    models.push_back(std::make_unique<SampleModel>(SampleModel::Kind::kEpsPchip, dataset));
    models.push_back(std::make_unique<SampleModel>(SampleModel::Kind::kEpsSpline, dataset));
    fit::PhysicalFitOptions physical;
    models.push_back(std::move(fit::FitPhysical(dataset, physical).model));
  }
  const AlloyModel& Model(int which) const { return *models[which]; }
};

const Fixture& Shared() {
  static const Fixture fixture;
  return fixture;
}

double SweepX(int64_t i) { return static_cast<double>(i % kSweepSteps) / (kSweepSteps - 1); }

// CIELAB and 8-bit sRGB of XYZ: the same for every variant.
struct Colour {
  color::XYZ xyz;
  color::Lab lab;
  std::array<std::uint8_t, 3> srgb8;
};
Colour Finish(const color::Colorimeter& colorimeter, const color::XYZ& xyz) {
  return {xyz, color::LabFromXYZ(xyz, colorimeter.White()),
          color::SRGB8FromLinear(color::LinearSRGBFromXYZ(xyz))};
}

// ---- the straightforward implementation ----

// The colorimeter's grid held inside the model's range.
std::vector<double> HeldGrid(const color::Colorimeter& colorimeter, const AlloyModel& model) {
  std::vector<double> grid = colorimeter.lambda_nm();
  for (double& l : grid) l = std::clamp(l, model.lambda_min_nm(), model.lambda_max_nm());
  return grid;
}

color::XYZ NaiveXYZFromEps(const color::Colorimeter& colorimeter,
                           const std::vector<std::complex<double>>& eps) {
  color::XYZ xyz{0, 0, 0};
  for (size_t i = 0; i < eps.size(); ++i) {
    const std::complex<double> n = std::sqrt(eps[i]);
    const double r = std::norm((n - 1.0) / (n + 1.0));
    xyz.X += colorimeter.wx()[i] * r;
    xyz.Y += colorimeter.wy()[i] * r;
    xyz.Z += colorimeter.wz()[i] * r;
  }
  return xyz;
}

// The smooth model evaluated straightforwardly from its knots, with std::complex: at each
// wavelength both neighbouring nodes' PCHIP curves (slopes recomputed), the blend, and eps
// from it.
std::vector<std::complex<double>> NaiveSmoothEps(const SmoothModel& model, double x,
                                                 const std::vector<double>& grid) {
  const std::vector<double>& nodes = model.grid_nm();
  const std::vector<double>& knots = model.knots_x();
  std::vector<std::complex<double>> eps;
  for (double l : grid) {
    size_t hi = std::upper_bound(nodes.begin(), nodes.end(), l) - nodes.begin();
    hi = std::clamp<size_t>(hi, 1, nodes.size() - 1);
    const double t = (l - nodes[hi - 1]) / (nodes[hi] - nodes[hi - 1]);
    std::complex<double> e[2];
    for (int side = 0; side < 2; ++side) {
      const size_t j = hi - 1 + side;
      const Interpolant e1(Interpolation::kPchip, knots, model.part1()[j]);
      const Interpolant e2(Interpolation::kPchip, knots, model.part2()[j]);
      e[side] = {e1(x), e2(x)};
    }
    const std::complex<double> parts = e[0] * (1 - t) + e[1] * t;
    eps.push_back(EpsFromParts(model.space(), parts.real(), parts.imag()));
  }
  return eps;
}

// The physical model one wavelength at a time: its parameter values at x, then each term.
std::vector<std::complex<double>> NaivePhysicalEps(const PhysicalModel& model, double x,
                                                   const std::vector<double>& grid) {
  std::vector<double> values(model.layout().num_parameters());
  model.ValuesAt(x, model.coeffs().data(), values.data());
  std::vector<std::complex<double>> eps;
  for (double l : grid) {
    const Complex<double> e =
        PhysicalPermittivity(model.layout(), values.data(), OmegaEvFromLambdaNm(l));
    eps.push_back({e.re, e.im});
  }
  return eps;
}

void BM_Naive(benchmark::State& state) {
  const Fixture& f = Shared();
  const AlloyModel& model = f.Model(state.range(0));
  const auto* smooth = dynamic_cast<const SmoothModel*>(&model);
  const PhysicalModel* physical = PhysicalModel::From(&model);
  const std::vector<double> grid = HeldGrid(f.colorimeter, model);
  int64_t i = 0;
  for (auto _ : state) {
    const double x = SweepX(i++);
    const std::vector<std::complex<double>> eps = smooth     ? NaiveSmoothEps(*smooth, x, grid)
                                                  : physical ? NaivePhysicalEps(*physical, x, grid)
                                                             : model.Permittivity(x, grid);
    benchmark::DoNotOptimize(Finish(f.colorimeter, NaiveXYZFromEps(f.colorimeter, eps)));
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_Library(benchmark::State& state) {
  const Fixture& f = Shared();
  const AlloyModel& model = f.Model(state.range(0));
  int64_t i = 0;
  for (auto _ : state) {
    const double x = SweepX(i++);
    const color::XYZ xyz =
        color::MaterialXYZ(f.colorimeter, color::IndexOnGrid(f.colorimeter, model, x), 0.0);
    benchmark::DoNotOptimize(color::ColorFromXYZ(f.colorimeter, xyz));
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_SweepExact(benchmark::State& state) {
  const Fixture& f = Shared();
  const color::ColorSweep sweep(f.colorimeter, f.Model(state.range(0)),
                                static_cast<double>(state.range(1)));
  int64_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(Finish(f.colorimeter, sweep.ExactXYZ(SweepX(i++))));
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_SweepTable(benchmark::State& state) {
  const Fixture& f = Shared();
  color::ColorSweep sweep(f.colorimeter, f.Model(state.range(0)),
                          static_cast<double>(state.range(1)));
  if (!sweep.BuildTable(0.0, 1.0)) {
    state.SkipWithError("no table within the tolerance");
    return;
  }
  state.counters["table_nodes"] = sweep.table_nodes();
  state.counters["table_error"] = sweep.table_error();
  int64_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(Finish(f.colorimeter, sweep.XYZAt(SweepX(i++))));
  }
  state.SetItemsProcessed(state.iterations());
}

// Building the table, once per sweep.
void BM_SweepTableBuild(benchmark::State& state) {
  const Fixture& f = Shared();
  color::ColorSweep sweep(f.colorimeter, f.Model(state.range(0)), 0.0);
  for (auto _ : state) benchmark::DoNotOptimize(sweep.BuildTable(0.0, 1.0));
}

constexpr int kModels = 6;
void ModelNames(benchmark::internal::Benchmark* b) {
  b->ArgNames({"model"});
  for (int m = 0; m < kModels; ++m) b->Args({m});
}
void ModelAngleNames(benchmark::internal::Benchmark* b) {
  b->ArgNames({"model", "angle"});
  for (int m = 0; m < kModels; ++m) b->Args({m, 0});
  b->Args({0, 60});
  b->Args({2, 60});
}

// model: 0 paper, 1 eps-linear, 2 smooth, 3 eps-pchip, 4 eps-spline, 5 physical.
BENCHMARK(BM_Naive)->Apply(ModelNames);
BENCHMARK(BM_Library)->Apply(ModelNames);
BENCHMARK(BM_SweepExact)->Apply(ModelAngleNames);
BENCHMARK(BM_SweepTable)->Apply(ModelAngleNames);
BENCHMARK(BM_SweepTableBuild)->Apply(ModelNames)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace alloycolor

BENCHMARK_MAIN();
