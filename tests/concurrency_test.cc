// The library used from several threads at once, as the Python package uses it (it
// releases the GIL around fits, colours and matches) and as `validate` and auto's folds do:
// every thread fits a model, colours a sweep of compositions and matches colours back to
// compositions, all starting together on a registry nobody has read yet, and every thread
// must get the answers one thread alone gets. scripts/tsan.sh builds this test alone under
// ThreadSanitizer (CI: .ci/run), where a data race fails it even when the answers agree.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/match.h"
#include "alloycolor/color/sweep.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/registry.h"
#include "test_util.h"

namespace alloycolor {
namespace {

using testing::DataDir;

// What one thread computes: a model's file (but for when it was fitted), colours along
// composition, matched compositions.
struct Work {
  std::string model_file;
  std::vector<std::array<double, 3>> xyz;
  std::vector<double> matched_x;
  std::string error;
};

// Au-Ag at five compositions: enough for folds (the fits' error bars) and quick.
Dataset FiveSamples() {
  Dataset data = LoadDataset(DataDir() + "/Au-Ag");
  return WithoutSamples(data, {0.1, 0.3, 0.4, 0.6, 0.7, 0.9});
}

Work DoWork(const std::string& method, const Dataset& data, const color::Colorimeter& cm) {
  Work w;
  try {
    fit::FitSettings settings;
    settings.colorimeter = &cm;
    if (FindMethod(method) == nullptr) throw Error("no method " + method);
    const std::unique_ptr<AlloyModel> model = fit::BuildModel(method, data, settings);
    nlohmann::json doc = model->ToJson();
    doc.erase("history");  // when it was fitted
    w.model_file = doc.dump();
    const color::ColorSweep sweep(cm, *model, 30.0);
    for (int i = 0; i <= 20; ++i) {
      const color::XYZ xyz = sweep.ExactXYZ(i / 20.0);
      w.xyz.push_back({xyz.X, xyz.Y, xyz.Z});
    }
    color::MatchOptions options;
    options.with_sigma = false;
    const color::ColourMatcher matcher(cm, *model, options);
    for (double x : {0.15, 0.55, 0.85}) {
      w.matched_x.push_back(matcher.Find(matcher.LabAt(x)).front().x_atomic);
    }
  } catch (const std::exception& e) {
    w.error = e.what();
  }
  return w;
}

TEST(Concurrency, FitsColoursAndMatchesFromSeveralThreadsAtOnce) {
  const color::Colorimeter cm = color::Colorimeter::Load(DataDir(), "D65", 2);
  const Dataset data = FiveSamples();
  // Two methods, each run by two threads: a Ceres fit (smooth) and an interpolation.
  const std::vector<std::string> methods = {"smooth", "eps-pchip", "smooth", "eps-pchip"};
  std::vector<Work> results(methods.size());
  std::atomic<int> ready{0};
  std::vector<std::thread> threads;
  for (size_t t = 0; t < methods.size(); ++t) {
    threads.emplace_back([&, t] {
      // All start together, so that their first reads of the registry meet.
      ++ready;
      while (ready.load() < static_cast<int>(methods.size())) std::this_thread::yield();
      results[t] = DoWork(methods[t], data, cm);
    });
  }
  for (std::thread& t : threads) t.join();
  for (size_t t = 0; t < methods.size(); ++t) {
    SCOPED_TRACE(methods[t] + " in thread " + std::to_string(t));
    ASSERT_EQ(results[t].error, "");
    const Work alone = DoWork(methods[t], data, cm);  // one thread, after the others
    EXPECT_EQ(results[t].model_file, alone.model_file);
    EXPECT_EQ(results[t].xyz, alone.xyz);
    EXPECT_EQ(results[t].matched_x, alone.matched_x);
    const std::vector<double> asked = {0.15, 0.55, 0.85};
    ASSERT_EQ(alone.matched_x.size(), asked.size());
    for (size_t i = 0; i < asked.size(); ++i) EXPECT_NEAR(alone.matched_x[i], asked[i], 1e-3);
  }
}

}  // namespace
}  // namespace alloycolor
