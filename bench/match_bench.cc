// From colour to composition on the Au-Ag smooth model (D65, 2-degree observer, normal
// incidence): one item is one target colour (the model's own colour at one of 19
// compositions 0.05, 0.10, ..., 0.95, cycled) taken to its best composition.
//
//  - BruteForce: the straightforward implementation, written here: the colour chain of
//    material_color.h (IndexOnGrid, MaterialXYZ, LabFromXYZ) at 2001 evenly spaced
//    compositions and the smallest CIEDE2000 taken (resolution 0.025 at%, the round trip's
//    0.05 at% bar; no error bar, no other minima).
//  - MatchColour: color::MatchColour, one call per target as `alloycolor match` makes it
//    (sweep table built, 1001-point scan, Brent refinement to 1e-10, every local
//    minimum), with the one-sigma (64 uncertainty draws) and without.
//  - MatcherFind: one color::ColourMatcher prepared once, Find per target without the
//    one-sigma (as Python's model.match(labs, sigma=False) runs for many targets); /0 the
//    targets above, /1 each moved off the colour curve by 0.4 in L*, a* and b* (a measured
//    colour rarely lies on the model's curve, and more of the scan then lies within reach).
// No timed assertions; scripts/bench.sh-style figures: compare items per second.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "alloycolor/color/match.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/fit/methods.h"

namespace alloycolor {
namespace {

struct Fixture {
  color::Colorimeter colorimeter = color::Colorimeter::Load(ALLOYCOLOR_DATA_DIR, "D65", 2);
  Dataset dataset = LoadDataset(std::string(ALLOYCOLOR_DATA_DIR) + "/Au-Ag");
  std::unique_ptr<AlloyModel> model;
  std::vector<color::Lab> targets, off_curve;
  Fixture() {
    model = fit::SharedFitBuilder(colorimeter)("smooth", dataset);
    for (int i = 1; i <= 19; ++i) targets.push_back(Lab(i * 0.05));
    for (const color::Lab& t : targets) off_curve.push_back({t.L + 0.4, t.a + 0.4, t.b + 0.4});
  }
  color::Lab Lab(double x) const {
    return color::LabFromXYZ(
        color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, *model, x), 0.0),
        colorimeter.White());
  }
};

const Fixture& Shared() {
  static const Fixture fixture;
  return fixture;
}

void BM_BruteForce(benchmark::State& state) {
  const Fixture& f = Shared();
  size_t t = 0;
  for (auto _ : state) {
    const color::Lab& target = f.targets[t++ % f.targets.size()];
    double best_x = 0, best_d = 1e300;
    for (int i = 0; i <= 2000; ++i) {
      const double x = i / 2000.0;
      const double d = color::DeltaE00(target, f.Lab(x));
      if (d < best_d) best_d = d, best_x = x;
    }
    benchmark::DoNotOptimize(best_x);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BruteForce)->Unit(benchmark::kMillisecond);

void BM_MatchColour(benchmark::State& state) {
  const Fixture& f = Shared();
  color::MatchOptions options;
  options.with_sigma = state.range(0) != 0;
  size_t t = 0;
  for (auto _ : state) {
    const auto matches =
        color::MatchColour(f.colorimeter, *f.model, f.targets[t++ % f.targets.size()], options);
    benchmark::DoNotOptimize(matches.front().x_atomic);
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(options.with_sigma ? "with one-sigma" : "without one-sigma");
}
BENCHMARK(BM_MatchColour)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

void BM_MatcherFind(benchmark::State& state) {
  const Fixture& f = Shared();
  color::MatchOptions options;
  options.with_sigma = false;
  const color::ColourMatcher matcher(f.colorimeter, *f.model, options);
  const std::vector<color::Lab>& targets = state.range(0) == 0 ? f.targets : f.off_curve;
  size_t t = 0;
  for (auto _ : state) {
    const auto matches = matcher.Find(targets[t++ % targets.size()]);
    benchmark::DoNotOptimize(matches.front().x_atomic);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MatcherFind)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace alloycolor

BENCHMARK_MAIN();
