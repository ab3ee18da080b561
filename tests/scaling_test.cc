// What keeps fits of a composition-spread library (hundreds of compositions) bounded, and
// the shortcuts taken on the way, each against the straightforward computation:
//  - the smooth fit's data residual, evaluated on the few knots its point depends on,
//    against the whole PCHIP curve differentiated by Ceres;
//  - the interpolating models evaluated from x's neighbourhood against an interpolant
//    through every sample;
//  - their folds fitted to the compositions around those they hold out (MethodTraits::
//    fold_reach) against the same folds fitted to every other sample;
//  - the physical fit of more than kPhysicalMaxCompositions compositions: fitted to that
//    many, spread by rank, saying so;
//  - the smooth fit of more than kSmoothMaxGpCompositions compositions: no Gaussian process,
//    saying so; the folds of a dense series keep the smoothing chosen on all the samples.
// No time is asserted: scripts/bench.sh measures the times (bench/spread_bench.cc).
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "../fit/src/folds.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/fit/physical_fit.h"
#include "alloycolor/fit/smooth_costs.h"
#include "alloycolor/fit/smooth_fit.h"
#include "alloycolor/model/interpolation.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/model/smooth_model.h"
#include "test_util.h"

namespace alloycolor {
namespace {

// The residual as the whole curve gives it: PCHIP through every knot.
struct WholeCurveResidual {
  std::vector<double> knots;
  double x, part, weight;
  template <typename T>
  bool operator()(T const* const* blocks, T* residual) const {
    T slopes[kSmoothMaxKnots];
    PchipSlopes(knots.data(), blocks[0], knots.size(), slopes);
    residual[0] =
        (HermiteAt(knots.data(), blocks[0], slopes, knots.size(), x) - T(part)) * T(weight);
    return true;
  }
};

TEST(Scaling, SmoothResidualFromItsWindowEqualsTheWholeCurve) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (size_t k : {2u, 3u, 4u, 7u, 24u}) {
    std::vector<double> knots(k), values(k);
    for (size_t c = 0; c < k; ++c) knots[c] = (c + 0.3 * unit(rng)) / k;
    for (double& v : values) v = -20.0 + 40.0 * unit(rng);
    for (int trial = 0; trial < 40; ++trial) {
      const double x = -0.2 + 1.4 * unit(rng);  // beyond the ends too
      const fit::SmoothDataResidual window(knots, x, 1.5, 0.7);
      ceres::DynamicAutoDiffCostFunction<WholeCurveResidual, 4> whole(
          new WholeCurveResidual{knots, x, 1.5, 0.7});
      whole.AddParameterBlock(static_cast<int>(k));
      whole.SetNumResiduals(1);
      const double* blocks[] = {values.data()};
      double r1, r2;
      std::vector<double> j1(k), j2(k);
      double* jac1[] = {j1.data()};
      double* jac2[] = {j2.data()};
      ASSERT_TRUE(window.Evaluate(blocks, &r1, jac1));
      ASSERT_TRUE(whole.Evaluate(blocks, &r2, jac2));
      EXPECT_EQ(r1, r2) << k << " knots, x = " << x;
      for (size_t c = 0; c < k; ++c) EXPECT_EQ(j1[c], j2[c]) << k << " knots, knot " << c;
    }
  }
}

TEST(Scaling, InterpolatingModelsFromTheNeighbourhoodEqualTheWholeInterpolant) {
  std::vector<double> xs;
  for (int i = 0; i <= 40; ++i) xs.push_back(i / 40.0 + (i % 3 == 1 && i < 40 ? 0.004 : 0.0));
  const Dataset data = LoadDataset(testing::WriteSyntheticDataset(xs, [](double x, double l) {
    return std::complex<double>(-10 - 20 * x * x + 0.01 * l * std::sin(9 * x),
                                2 + 3 * x + std::cos(7 * x) * l / 500);
  }));
  const std::vector<double> grid = {400, 512.5, 640, 777};
  for (SampleModel::Kind kind : {SampleModel::Kind::kEpsLinear, SampleModel::Kind::kEpsPchip}) {
    const SampleModel model(kind, data);
    for (double x : {-0.05, 0.0, 0.013, 0.5, 0.7771, 0.99, 1.0, 1.04}) {
      const std::vector<std::complex<double>> eps = model.Permittivity(x, grid);
      for (size_t j = 0; j < grid.size(); ++j) {
        std::vector<double> e1, e2;
        for (size_t i = 0; i < xs.size(); ++i) {
          const std::complex<double> nk = NkAt(data.samples[i].nk, grid[j]);
          e1.push_back((nk * nk).real());
          e2.push_back((nk * nk).imag());
        }
        const Interpolation scheme =
            kind == SampleModel::Kind::kEpsPchip ? Interpolation::kPchip : Interpolation::kLinear;
        // PCHIP from x's neighbourhood: the very arithmetic of the whole curve; the line:
        // the same to rounding (the model writes it as lo + (hi - lo) t).
        const double tolerance = kind == SampleModel::Kind::kEpsPchip ? 0.0 : 1e-13;
        const double re = Interpolant(scheme, xs, e1)(x), im = Interpolant(scheme, xs, e2)(x);
        EXPECT_NEAR(eps[j].real(), re, tolerance * std::abs(re)) << x << " " << grid[j];
        EXPECT_NEAR(eps[j].imag(), im, tolerance * std::abs(im)) << x << " " << grid[j];
      }
    }
  }
}

TEST(Scaling, FoldsOfInterpolatingMethodsFromTheirWindowEqualFoldsOfEveryOtherSample) {
  // Uneven compositions, a replicate at 0.3, and one sample (x = 0.6) measured over fewer
  // wavelengths: a fold whose window leaves it out would cover more than the rest do, so it
  // must be fitted to every other sample instead.
  std::vector<double> xs;
  for (int i = 0; i <= 16; ++i) xs.push_back(std::pow(i / 16.0, 1.3));
  xs.insert(xs.end(), {0.3, 0.6});
  std::sort(xs.begin(), xs.end());
  Dataset data = LoadDataset(testing::WriteSyntheticDataset(xs, [](double x, double l) {
    return std::complex<double>(-12 - 25 * x * x + 0.01 * l * std::sin(8 * x),
                                1.5 + 2 * x + std::cos(6 * x) * l / 600);
  }));
  for (Sample& s : data.samples) {
    if (s.x_atomic == 0.6) s.nk = Resample(s.nk, UniformGrid(420, 760, 5));
  }
  for (size_t i = 0; i < data.samples.size(); ++i) {
    if (data.samples[i].x_atomic != 0.3) continue;
    Sample replicate = data.samples[i];
    replicate.file = "replicate.csv";
    for (double& n : replicate.nk.n) n *= 1.02;
    data.samples.insert(data.samples.begin() + static_cast<std::ptrdiff_t>(i) + 1, replicate);
    break;
  }
  const std::vector<double> c = DistinctCompositions(data);  // as read (6 decimals)
  ASSERT_EQ(c.size(), 19u);
  const std::vector<std::vector<double>> held = {{c[1]},         {0.3},   {c[8], c[9]}, {0.6},
                                                 {c[10], c[16]}, {c[17]}, {1.0},        {0.0}};
  const std::vector<double> grid = {420, 500, 600, 700, 760};
  for (const char* name : {"eps-linear", "eps-pchip"}) {
    const MethodInfo& method = *FindMethod(name);
    ASSERT_GE(method.traits.fold_reach, 0) << name;
    fit::FitSettings settings;
    settings.calibrate = false;
    const std::unique_ptr<AlloyModel> whole = fit::BuildModel(name, data, settings);
    const std::vector<fit::Fold> folds = fit::FitFolds(method, data, settings, *whole, held);
    ASSERT_EQ(folds.size(), held.size());
    for (size_t k = 0; k < held.size(); ++k) {
      // The fold as it would be without the shortcut: every other sample.
      const Dataset rest = WithoutSamples(data, held[k]);
      fit::FitSettings plain = settings;
      plain.fold = true;
      const std::unique_ptr<AlloyModel> expected = fit::BuildModel(name, rest, plain);
      ASSERT_NE(folds[k].model, nullptr) << name << " " << held[k].front() << folds[k].error;
      EXPECT_EQ(folds[k].compositions, DistinctCompositions(rest));
      EXPECT_EQ(folds[k].model->lambda_min_nm(), expected->lambda_min_nm());
      EXPECT_EQ(folds[k].model->lambda_max_nm(), expected->lambda_max_nm());
      EXPECT_EQ(folds[k].held.size(), data.samples.size() - rest.samples.size());
      for (double x : held[k]) {
        const std::vector<std::complex<double>> got = folds[k].model->Permittivity(x, grid);
        const std::vector<std::complex<double>> want = expected->Permittivity(x, grid);
        for (size_t j = 0; j < grid.size(); ++j) {
          EXPECT_EQ(got[j], want[j]) << name << " held " << x << " at " << grid[j];
        }
      }
    }
  }
}

// n compositions of two Drude metals with eps linear between them (a little bowing).
Dataset Spread(int n) {
  std::vector<double> xs;
  for (int i = 0; i < n; ++i) xs.push_back(static_cast<double>(i) / (n - 1));
  return LoadDataset(testing::WriteSyntheticDataset(xs, [](double x, double lambda_nm) {
    const double w = 1239.84198 / lambda_nm, wp2 = 80 + 10 * x, gamma = 0.05 + 0.1 * x * (1 - x);
    const std::complex<double> drude = 1.0 - wp2 / (w * std::complex<double>(w, gamma));
    return drude + std::complex<double>(0.0, 0.5 + x);
  }));
}

TEST(Scaling, PhysicalFitOfASpreadTakesEvenlySpreadCompositionsAndSaysSo) {
  const Dataset data = Spread(fit::kPhysicalMaxCompositions + 1);
  fit::PhysicalFitOptions options;
  options.terms = "none";
  options.degree = 1;
  options.covariance = false;
  std::vector<std::string> progress;
  options.progress = [&](const std::string& line) { progress.push_back(line); };
  const fit::PhysicalFitResult r = fit::FitPhysical(data, options);
  ASSERT_EQ(r.model->training_samples().size(), static_cast<size_t>(fit::kPhysicalMaxCompositions));
  EXPECT_EQ(r.model->training_samples().front().x_atomic, 0.0);
  EXPECT_EQ(r.model->training_samples().back().x_atomic, 1.0);
  bool said = false;
  for (const std::string& w : r.model->warnings()) {
    said |= w.find("fitted to the samples at 100 of the " + std::to_string(data.samples.size()) +
                   " compositions") != std::string::npos;
  }
  EXPECT_TRUE(said);
  ASSERT_FALSE(progress.empty());
  EXPECT_NE(progress.front().find("spread evenly by rank"), std::string::npos);
}

TEST(Scaling, SmoothFitOfASpreadTriesNoGaussianProcessAndItsFoldsKeepItsSmoothing) {
  const Dataset data = Spread(fit::kSmoothMaxGpCompositions + 1);
  fit::SmoothFitOptions options;
  options.grid_nm = {420, 600, 780};  // three nodes: the shortcut, not the curves, is tested
  options.space = SmoothSpace::kEps;
  const fit::SmoothFitResult r = fit::FitSmooth(data, options);
  EXPECT_LT(r.gp_rms_reflectance, 0);  // not scored
  bool said = false;
  for (const std::string& w : r.model->warnings()) {
    said |= w.find("Gaussian-process form was not tried") != std::string::npos;
  }
  EXPECT_TRUE(said);
  // A fold of this dense series (all but one composition) keeps the smoothing chosen here.
  fit::FitSettings settings;
  settings.fold = true;
  settings.calibrate = false;
  settings.parent = r.model.get();
  settings.options.Set("lambda_from_nm", 420.0);
  settings.options.Set("lambda_to_nm", 780.0);
  settings.options.Set("lambda_step_nm", 180.0);
  const Dataset fold = WithoutSamples(data, {data.samples[40].x_atomic});
  const std::unique_ptr<AlloyModel> model = fit::BuildModel("smooth", fold, settings);
  const SmoothModel* folded = SmoothModel::From(model.get());
  ASSERT_NE(folded, nullptr);
  EXPECT_EQ(folded->smoothing(), r.model->smoothing());
  EXPECT_EQ(folded->space(), r.model->space());
}

}  // namespace
}  // namespace alloycolor
