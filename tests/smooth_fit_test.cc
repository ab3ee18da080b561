// The smooth Ceres fit: cost functor derivatives, recovery of known curves, determinism,
// JSON round trip, refit, and the accuracy figure of the issue on the shipped Au-Ag data.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "alloycolor/fit/smooth_costs.h"
#include "alloycolor/fit/smooth_fit.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/core/units.h"
#include "alloycolor/color/material_color.h"
#include "test_util.h"

namespace alloycolor {
namespace {

using testing::DataDir;
using testing::MakeTempDir;
using testing::WriteText;

TEST(SmoothCosts, EpsResidualJacobianMatchesFiniteDifferences) {
  const double basis[3] = {1.0, 0.3, -0.365};
  std::unique_ptr<ceres::CostFunction> cost(
      fit::EpsResidual<3>::Create(basis, 2.1, std::complex<double>(-12.0, 1.5)));
  double params[6] = {-2.0, 0.3, -0.1, 4.3, 0.2, 0.05};
  const double* blocks[1] = {params};
  double residual[2], jacobian[12];
  double* jacobians[1] = {jacobian};
  ASSERT_TRUE(cost->Evaluate(blocks, residual, jacobians));
  for (int p = 0; p < 6; ++p) {
    const double h = 1e-6;
    double plus[6], minus[6], rp[2], rm[2];
    std::copy(params, params + 6, plus);
    std::copy(params, params + 6, minus);
    plus[p] += h;
    minus[p] -= h;
    const double* bp[1] = {plus};
    const double* bm[1] = {minus};
    cost->Evaluate(bp, rp, nullptr);
    cost->Evaluate(bm, rm, nullptr);
    for (int r = 0; r < 2; ++r) {
      EXPECT_NEAR(jacobian[r * 6 + p], (rp[r] - rm[r]) / (2 * h), 1e-6) << r << " " << p;
    }
  }
}

TEST(SmoothCosts, CurvatureIsTheSecondDifference) {
  std::unique_ptr<ceres::CostFunction> cost(fit::CurvatureResidual<1>::Create(2.0));
  double a[2] = {1.0, 5.0}, b[2] = {2.0, 4.0}, c[2] = {4.0, 4.0};
  const double* blocks[3] = {a, b, c};
  double residual[2];
  ASSERT_TRUE(cost->Evaluate(blocks, residual, nullptr));
  EXPECT_DOUBLE_EQ(residual[0], 2.0 * (1 - 4 + 4));
  EXPECT_DOUBLE_EQ(residual[1], 2.0 * (5 - 8 + 4));
}

// Truth: ln gamma and ln wp^2 quadratic in x at every wavelength.
double TrueLnGamma(double x, double lambda) { return std::log(0.05 + 0.002 * lambda / 100) + 0.8 * x - 0.5 * x * x; }
double TrueLnWp2(double x, double lambda) { return std::log(80.0) - 0.3 * x + 0.2 * x * x + 1e-4 * (lambda - 500); }

std::string WriteSyntheticDataset(const std::vector<double>& xs) {
  const std::string dir = MakeTempDir();
  std::string samples;
  for (size_t i = 0; i < xs.size(); ++i) {
    std::vector<double> l, n, k;
    for (double lambda = 380; lambda <= 800; lambda += 5) {
      const Complex<double> eps = DrudePermittivity(OmegaEvFromLambdaNm(lambda),
                                                    std::exp(TrueLnWp2(xs[i], lambda)),
                                                    std::exp(TrueLnGamma(xs[i], lambda)));
      const Complex<double> nk = IndexFromPermittivity(eps);
      l.push_back(lambda);
      n.push_back(nk.re);
      k.push_back(nk.im);
    }
    const std::string file = "s" + std::to_string(i) + ".csv";
    WriteText(dir + "/" + file, NkCsvText(l, n, k));
    samples += (i ? "," : "") + std::string("{\"x\": ") + std::to_string(xs[i]) +
               ", \"file\": \"" + file + "\"}";
  }
  WriteText(dir + "/dataset.json",
            "{\"system\": {\"a\": \"Au\", \"b\": \"Ag\"}, \"composition\": \"atomic_fraction_a\", "
            "\"samples\": [" + samples + "]}");
  return dir;
}

TEST(SmoothFit, RecoversKnownCurves) {
  const Dataset data = LoadDataset(WriteSyntheticDataset({0.0, 0.2, 0.45, 0.6, 0.8, 1.0}));
  fit::SmoothFitOptions options;
  options.degree = 2;
  options.smoothing = 0;  // the truth is not smooth in wavelength by construction
  options.ridge = 0;
  const auto result = fit::FitSmooth(data, options);
  ASSERT_TRUE(result.model->fit_summary().converged);
  for (double x : {0.1, 0.33, 0.7, 0.95}) {
    for (double lambda : {380.0, 500.0, 640.0, 800.0}) {
      const std::complex<double> e = result.model->Permittivity(x, {lambda})[0];
      const DrudePoint p = InvertDrude(OmegaEvFromLambdaNm(lambda), e.real(), e.imag());
      EXPECT_NEAR(std::log(p.gamma_ev), TrueLnGamma(x, lambda), 1e-6) << x << " " << lambda;
      EXPECT_NEAR(std::log(p.wp2_ev2), TrueLnWp2(x, lambda), 1e-6) << x << " " << lambda;
    }
  }
  // Cross-validation finds a degree that represents the truth.
  const auto cv = fit::FitSmooth(data, fit::SmoothFitOptions{});
  EXPECT_GE(cv.model->degree(), 2);
  EXPECT_FALSE(cv.cross_validation.empty());
  const std::complex<double> e = cv.model->Permittivity(0.33, {550.0})[0];
  const DrudePoint p = InvertDrude(OmegaEvFromLambdaNm(550), e.real(), e.imag());
  EXPECT_NEAR(std::log(p.gamma_ev), TrueLnGamma(0.33, 550), 1e-4);
}

size_t FirstDifference(const std::string& a, const std::string& b) {
  size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  return i;
}

TEST(SmoothFit, SameInputsGiveTheSameBytesAndTheFileReadsBack) {
  const Dataset data = LoadDataset(DataDir() + "/Au-Ag");
  fit::SmoothFitOptions options;
  options.degree = 4;
  const std::string a = ModelFileText(*fit::FitSmooth(data, options).model);
  const std::string b = ModelFileText(*fit::FitSmooth(data, options).model);
  EXPECT_TRUE(a == b) << "first difference at byte " << FirstDifference(a, b) << ": "
                      << a.substr(FirstDifference(a, b) > 300 ? FirstDifference(a, b) - 300 : 0, 400);
  const auto back = ModelFromJson(nlohmann::json::parse(a), "mem");
  const std::string c = ModelFileText(*back);
  EXPECT_TRUE(c == a) << "first difference at byte " << FirstDifference(a, c) << ": "
                      << a.substr(FirstDifference(a, c) > 80 ? FirstDifference(a, c) - 80 : 0, 160);
  const auto fitted = fit::FitSmooth(data, options).model;
  const std::vector<double> grid = UniformGrid(360, 830, 2.5);
  for (double x : {0.0, 0.37, 1.0}) EXPECT_EQ(back->Permittivity(x, grid), fitted->Permittivity(x, grid));
}

TEST(SmoothFit, RefitFromAnEarlierModelConvergesToTheSameFit) {
  const Dataset all = LoadDataset(DataDir() + "/Au-Ag");
  fit::SmoothFitOptions options;
  options.degree = 3;
  const auto old_model = fit::FitSmooth(WithoutSamples(all, {0.3, 0.7}), options).model;
  const auto fresh = fit::FitSmooth(all, options).model;
  options.start = old_model.get();
  const auto refit = fit::FitSmooth(all, options).model;
  const std::vector<double> grid = UniformGrid(380, 780, 20);
  for (double x : {0.15, 0.5, 0.85}) {
    const auto a = fresh->Index(x, grid), b = refit->Index(x, grid);
    for (size_t i = 0; i < grid.size(); ++i) EXPECT_NEAR(std::abs(a[i] - b[i]), 0.0, 1e-6);
  }
}

TEST(SmoothFit, LeavesOutSamplesThatContradictDrudeAndSaysSo) {
  const auto result = fit::FitSmooth(LoadDataset(DataDir() + "/Cu-Zn"), fit::SmoothFitOptions{});
  bool named = false;
  for (const auto& w : result.model->warnings()) {
    named |= w.find("Querry-Zn100") != std::string::npos && w.find("left out") != std::string::npos;
  }
  EXPECT_TRUE(named);
  for (const auto& nk : result.model->Index(0.5, UniformGrid(360, 830, 5))) {
    EXPECT_TRUE(std::isfinite(nk.real()) && std::isfinite(nk.imag()));
  }
}

TEST(SmoothFit, NothingUsableIsAClearError) {
  const std::string dir = MakeTempDir();
  // Two transparent dielectrics: eps1 > 1 everywhere.
  WriteText(dir + "/a.csv", "lambda_nm,n,k\n300,1.5,0\n900,1.5,0\n");
  WriteText(dir + "/b.csv", "lambda_nm,n,k\n300,1.6,0\n900,1.6,0\n");
  WriteText(dir + "/dataset.json",
            R"({"system": {"a": "Au", "b": "Ag"}, "composition": "atomic_fraction_a",
                "samples": [{"x": 0, "file": "a.csv"}, {"x": 1, "file": "b.csv"}]})");
  EXPECT_THROW(fit::FitSmooth(LoadDataset(dir), fit::SmoothFitOptions{}), Error);
}

// The issue's figure: train on the paper's known compositions, predict the others.
TEST(SmoothFit, AuAgPaperSplitColourErrorIsSmall) {
  const Dataset all = LoadDataset(DataDir() + "/Au-Ag");
  const std::vector<double> held_out = {0.1, 0.3, 0.4, 0.7, 0.9};
  const Dataset train = WithoutSamples(all, held_out);
  ASSERT_EQ(train.samples.size(), 6u);
  const auto smooth = fit::FitSmooth(train, fit::SmoothFitOptions{}).model;
  const SampleModel paper(SampleModel::Kind::kPaper, train);
  const color::Colorimeter cm = color::Colorimeter::Load(DataDir(), "D65", 2);
  double worst_smooth = 0, worst_paper = 0;
  for (const Sample& s : all.samples) {
    bool is_held = false;
    for (double x : held_out) is_held |= std::abs(s.x_atomic - x) < 1e-9;
    if (!is_held) continue;
    const color::Lab truth =
        color::LabFromXYZ(color::MaterialXYZ(cm, color::IndexOnGrid(cm, s.nk), 0.0), cm.White());
    auto de = [&](const AlloyModel& m) {
      return color::DeltaE00(
          truth, color::LabFromXYZ(
                     color::MaterialXYZ(cm, color::IndexOnGrid(cm, m, s.x_atomic), 0.0),
                     cm.White()));
    };
    worst_smooth = std::max(worst_smooth, de(*smooth));
    worst_paper = std::max(worst_paper, de(paper));
    const double sigma = color::DeltaE00Sigma(cm, *smooth, s.x_atomic, 0.0);
    EXPECT_TRUE(std::isfinite(sigma) && sigma > 0) << sigma;
  }
  EXPECT_LE(worst_smooth, 0.2);
  EXPECT_GT(worst_paper, 2 * worst_smooth);
}

}  // namespace
}  // namespace alloycolor
