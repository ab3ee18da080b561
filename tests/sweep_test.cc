// Sweeps (render/sweep.h, `alloycolor sweep`): the fast exact path equals the chain of
// material_color.h for every model and angle; the table's error, measured and at random
// compositions, stays within its tolerance; the command's rows agree with `color`.
#include "alloycolor/color/sweep.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "alloycolor/color/material_color.h"
#include "alloycolor/color/reflectance_arrays.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/fit/physical_fit.h"
#include "alloycolor/fit/smooth_fit.h"
#include "alloycolor/model/optics.h"
#include "alloycolor/model/sample_models.h"
#include "test_util.h"

namespace alloycolor {
namespace {

using testing::DataDir;
using testing::MakeTempDir;
using testing::RunProgram;
using testing::RunResult;

struct Models {
  color::Colorimeter colorimeter = color::Colorimeter::Load(DataDir(), "D65", 2);
  Dataset dataset = LoadDataset(DataDir() + "/Au-Ag");
  std::vector<std::unique_ptr<AlloyModel>> all;
  Models() {
    all.push_back(std::make_unique<SampleModel>(SampleModel::Kind::kPaper, dataset));
    all.push_back(std::make_unique<SampleModel>(SampleModel::Kind::kEpsLinear, dataset));
    fit::SmoothFitOptions options;
    all.push_back(std::move(fit::FitSmooth(dataset, options).model));
  }
};

const Models& Shared() {
  static const Models models;
  return models;
}

double MaxDiff(const color::XYZ& a, const color::XYZ& b) {
  return std::max({std::abs(a.X - b.X), std::abs(a.Y - b.Y), std::abs(a.Z - b.Z)});
}

TEST(ColorSweep, ExactEqualsTheMaterialColourChain) {
  const Models& m = Shared();
  for (const auto& model : m.all) {
    for (double angle : {0.0, 45.0, 89.9, 90.0}) {
      const color::ColorSweep sweep(m.colorimeter, *model, angle);
      for (double x : {0.0, 0.13, 0.5, 0.77, 1.0}) {
        SCOPED_TRACE(model->method() + " angle " + std::to_string(angle) + " x " +
                     std::to_string(x));
        const color::XYZ expected =
            color::MaterialXYZ(m.colorimeter, color::IndexOnGrid(m.colorimeter, *model, x), angle);
        EXPECT_LT(MaxDiff(sweep.ExactXYZ(x), expected), 1e-12);
      }
    }
  }
}

// |a - b| relative to |b| (or absolute below 1e-300).
double RelDiff(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

// The fast paths (a model bound to the grid, the colour chain on arrays) equal the scalar
// path, AlloyModel::Permittivity and MaterialXYZ(IndexOnGrid(...)), to 1e-12 relative for
// every method and several angles; Cu-Zn brings a non-metallic zinc, so the paper model's
// skipped samples and its fallback are exercised too.
TEST(ColorSweep, FastPathsEqualTheScalarPathRelatively) {
  const color::Colorimeter colorimeter = color::Colorimeter::Load(DataDir(), "D65", 2);
  for (const std::string set : {"Au-Ag", "Cu-Zn"}) {
    const Dataset dataset = LoadDataset(DataDir() + "/" + set);
    std::vector<std::unique_ptr<AlloyModel>> models;
    models.push_back(std::make_unique<SampleModel>(SampleModel::Kind::kPaper, dataset));
    models.push_back(std::make_unique<SampleModel>(SampleModel::Kind::kEpsLinear, dataset));
    models.push_back(std::make_unique<SampleModel>(SampleModel::Kind::kEpsPchip, dataset));
    models.push_back(std::make_unique<SampleModel>(SampleModel::Kind::kEpsSpline, dataset));
    fit::SmoothFitOptions smooth;
    for (const SmoothSpace space : {SmoothSpace::kEps, SmoothSpace::kLogEps}) {
      smooth.space = space;  // the logarithm's sums are ln|eps| and arg eps
      models.push_back(std::move(fit::FitSmooth(dataset, smooth).model));
    }
    // The physical fit refuses Querry's zinc (not passive between the samples): it takes
    // Werner's.
    fit::PhysicalFitOptions physical;
    const Dataset metallic =
        set == "Au-Ag" ? dataset : LoadDataset(DataDir() + "/Cu-Zn/dataset-werner-zn.json");
    models.push_back(std::move(fit::FitPhysical(metallic, physical).model));
    for (const auto& model : models) {
      for (double angle : {0.0, 20.0, 45.0, 70.0, 85.0, 89.9}) {
        const color::ColorSweep sweep(colorimeter, *model, angle);
        for (double x : {0.0, 0.05, 0.13, 0.5, 0.77, 0.9, 1.0}) {
          SCOPED_TRACE(set + " " + model->method() + " angle " + std::to_string(angle) + " x " +
                       std::to_string(x));
          const color::XYZ expected =
              color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, *model, x), angle);
          const color::XYZ fast = sweep.ExactXYZ(x);
          EXPECT_LT(RelDiff(fast.X, expected.X), 1e-12);
          EXPECT_LT(RelDiff(fast.Y, expected.Y), 1e-12);
          EXPECT_LT(RelDiff(fast.Z, expected.Z), 1e-12);
        }
      }
      const std::vector<double> grid = {380, 402.5, 455, 600, 707.3, 780};
      const std::unique_ptr<BoundModel> bound = model->Bind(grid);
      for (double x : {0.0, 0.1, 0.33, 0.7, 1.0}) {
        const std::vector<Complex<double>> eps = bound->Permittivity(x);
        const std::vector<std::complex<double>> expected = model->Permittivity(x, grid);
        for (size_t i = 0; i < grid.size(); ++i) {
          SCOPED_TRACE(set + " " + model->method() + " x " + std::to_string(x) + " at " +
                       std::to_string(grid[i]) + " nm");
          EXPECT_LE(std::abs(std::complex<double>(eps[i].re, eps[i].im) - expected[i]),
                    1e-12 * std::abs(expected[i]));
        }
      }
    }
  }
}

// The array form of the Fresnel step, rearranged to save divisions, equals
// FresnelReflectance of IndexFromPermittivity (optics.h) at every kind of eps: metals,
// dielectrics, eps2 < 0, eps = 0 (N = 0) and eps = sin^2 (S = 0, a 0/0 limit), |eps|
// up to 1e24; on runs of 1 to 9 wavelengths (the SIMD body and its remainder), one
// weight 1 at a time so each sum is one R.
TEST(ReflectanceSums, EqualFresnelReflectanceOfTheIndex) {
  std::vector<Complex<double>> eps = {{-30, 1.5},   {-1.2, 5.8}, {2.25, 0},     {2.25, 1e-9},
                                      {0.5, 0.1},   {0, 0},      {0, 3},        {-4, 0},
                                      {1, 0},       {-11, -0.7}, {1e-300, 0},   {-1e12, 3e11},
                                      {1e24, 1e23}, {0.75, 0},   {0.75, 1e-12}, {0.25, 0}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> e1(-60, 10), e2(0, 20);
  for (int i = 0; i < 200; ++i) eps.push_back({e1(rng), e2(rng)});
  for (double angle : {0.0, 30.0, 60.0, 89.0, 90.0}) {
    const double c = std::max(std::cos(angle * M_PI / 180.0), 0.0);
    // eps = sin^2 at this angle too.
    std::vector<Complex<double>> all = eps;
    all.push_back({1 - c * c, 0});
    for (size_t run = 1; run <= 9; ++run) {
      for (size_t start = 0; start + run <= all.size(); start += run) {
        std::vector<double> e1s, e2s;
        for (size_t i = start; i < start + run; ++i) {
          e1s.push_back(all[i].re);
          e2s.push_back(all[i].im);
        }
        for (size_t one = 0; one < run; ++one) {
          std::vector<double> w(run, 0.0), zero(run, 0.0);
          w[one] = 1.0;
          double sums[3];
          color::ReflectanceSums(run, e1s.data(), e2s.data(), c, angle == 0.0, w.data(),
                                 zero.data(), w.data(), sums);
          const Complex<double> e = all[start + one];
          const double expected = FresnelReflectance(IndexFromPermittivity(e), c).Average();
          SCOPED_TRACE("eps " + std::to_string(e.re) + " + " + std::to_string(e.im) + "i at " +
                       std::to_string(angle) + " degrees");
          // At eps = sin^2 (S = 0) dR/deps diverges: the reference's N^2, one rounding
          // away from eps, gives S ~ 1e-8 and moves R by about 2 S / cos there; both meet
          // the limit R = 1.
          const double off = std::hypot(e.re - (1 - c * c), e.im);
          EXPECT_NEAR(sums[0], expected, off < 1e-6 ? 1e-7 / c : 1e-12 * expected + 1e-15);
          EXPECT_EQ(sums[1], 0.0);
          EXPECT_EQ(sums[2], sums[0]);
        }
      }
    }
  }
}

TEST(ColorSweep, TableErrorIsMeasuredAndHolds) {
  const Models& m = Shared();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (const auto& model : m.all) {
    SCOPED_TRACE(model->method());
    color::ColorSweep sweep(m.colorimeter, *model, 0.0);
    ASSERT_TRUE(sweep.BuildTable(0.0, 1.0));
    EXPECT_LE(sweep.table_error(), color::kSweepTableTolerance);
    EXPECT_GT(sweep.table_nodes(), 11);
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const double x = uniform(rng);
      worst = std::max(worst, MaxDiff(sweep.XYZAt(x), sweep.ExactXYZ(x)));
    }
    // The midpoints are where cubic interpolation errs most; allow a little beyond.
    EXPECT_LT(worst, 2 * color::kSweepTableTolerance);
    // At the nodes (the ends, the training compositions) the table is exact.
    for (double x : {0.0, 0.3, 1.0}) EXPECT_LT(MaxDiff(sweep.XYZAt(x), sweep.ExactXYZ(x)), 1e-15);
  }
}

TEST(ColorSweep, RefusesWhatItCannotDo) {
  const Models& m = Shared();
  EXPECT_THROW(color::ColorSweep(m.colorimeter, *m.all[0], 95.0), Error);
  EXPECT_THROW(color::ColorSweep(m.colorimeter, *m.all[0], std::nan("")), Error);
  color::ColorSweep sweep(m.colorimeter, *m.all[0], 0.0);
  EXPECT_FALSE(sweep.BuildTable(0.5, 0.5));  // nothing to tabulate
  EXPECT_FALSE(sweep.has_table());
  EXPECT_TRUE(sweep.BuildTable(1.0, 0.0));  // either order
}

// Parsed CSV rows of `alloycolor sweep`.
std::vector<std::vector<double>> Rows(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x,X,Y,Z,L,a,b,srgb8_r,srgb8_g,srgb8_b");
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) row.push_back(std::stod(field));
    EXPECT_EQ(row.size(), 10u) << line;
    rows.push_back(row);
  }
  return rows;
}

TEST(SweepCommand, RowsAgreeWithColor) {
  const RunResult r = RunProgram({"sweep", "--data", "Au-Ag", "--steps", "11", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const auto rows = Rows(r.out);
  ASSERT_EQ(rows.size(), 11u);
  for (size_t i = 0; i < rows.size(); ++i) EXPECT_NEAR(rows[i][0], i / 10.0, 1e-12);
  const RunResult c = RunProgram({"color", "--data", "Au-Ag", "--x", "0.3", "--json", "--quiet"});
  ASSERT_EQ(c.status, 0) << c.err;
  const nlohmann::json color = nlohmann::json::parse(c.out);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(rows[3][1 + k], color["XYZ"][k].get<double>(), 5.1e-8);
    EXPECT_NEAR(rows[3][4 + k], color["Lab"][k].get<double>(), 5.1e-5);
    EXPECT_EQ(rows[3][7 + k], color["srgb8"][k].get<int>());
  }
}

TEST(SweepCommand, TableAgreesWithExactAndSaysSo) {
  const std::vector<std::string> args = {"sweep",      "--data",  "Au-Ag", "--method",
                                         "eps-linear", "--steps", "1001"};
  RunResult table = RunProgram(args);
  ASSERT_EQ(table.status, 0) << table.err;
  EXPECT_NE(table.err.find("interpolated from a table"), std::string::npos) << table.err;
  std::vector<std::string> exact_args = args;
  exact_args.push_back("--exact");
  const RunResult exact = RunProgram(exact_args);
  ASSERT_EQ(exact.status, 0) << exact.err;
  EXPECT_TRUE(exact.err.empty()) << exact.err;
  const auto a = Rows(table.out), b = Rows(exact.out);
  ASSERT_EQ(a.size(), 1001u);
  ASSERT_EQ(b.size(), 1001u);
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i][0], b[i][0]);
    for (int k = 1; k <= 3; ++k) worst = std::max(worst, std::abs(a[i][k] - b[i][k]));
  }
  // Table error (<= 1e-7, a little more off the midpoints) plus the 7-decimal rounding.
  EXPECT_LT(worst, 3.1e-7);
}

TEST(SweepCommand, JsonAndOptions) {
  const std::string dir = MakeTempDir();
  ASSERT_EQ(RunProgram({"fit", "--data", "Au-Ag", "--method", "smooth", "--out",
                        dir + "/smooth.json", "--quiet"})
                .status,
            0);
  const RunResult r = RunProgram({"sweep", "--model", dir + "/smooth.json", "--from", "1", "--to",
                                  "18k", "--steps", "5", "--angle", "60", "--illuminant", "A",
                                  "--observer", "10", "--format", "json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["method"], "smooth");
  EXPECT_EQ(doc["illuminant"], "A");
  EXPECT_EQ(doc["evaluation"]["method"], "exact");
  ASSERT_EQ(doc["results"].size(), 5u);
  EXPECT_EQ(doc["results"][0]["x"].get<double>(), 1.0);
  EXPECT_NEAR(doc["results"][4]["x"].get<double>(), 0.6216, 1e-3);  // 18k, descending
  for (const auto& row : doc["results"]) {
    EXPECT_EQ(row["XYZ"].size(), 3u);
    EXPECT_EQ(row["Lab"].size(), 3u);
    EXPECT_EQ(row["srgb8"].size(), 3u);
  }
  // One composition.
  const RunResult one = RunProgram(
      {"sweep", "--model", dir + "/smooth.json", "--from", "0.5", "--to", "0.5", "--steps", "1"});
  ASSERT_EQ(one.status, 0) << one.err;
  EXPECT_EQ(testing::CountLines(one.out), 2);
}

TEST(SweepCommand, BadOptionsGiveOneLine) {
  const std::vector<std::vector<std::string>> cases = {
      {"sweep", "--data", "Au-Ag", "--steps", "0"},
      {"sweep", "--data", "Au-Ag", "--steps", "-3"},
      {"sweep", "--data", "Au-Ag", "--steps", "many"},
      {"sweep", "--data", "Au-Ag", "--steps", "10000000000"},
      {"sweep", "--data", "Au-Ag", "--format", "xml"},
      {"sweep", "--data", "Au-Ag", "--from", "1.5"},
      {"sweep", "--data", "Au-Ag", "--to", "nan"},
      {"sweep", "--data", "Au-Ag", "--from", "0,1"},
      {"sweep", "--data", "Au-Ag", "--angle", "95"},
      {"sweep", "--data", "Au-Ag", "--illuminant", "D99"},
      {"sweep", "--data", "Au-Ag", "--method", "magic"},
      {"sweep", "--data", "Nb-Sn"},  // infrared data: no colour
      {"sweep"},
  };
  for (const auto& args : cases) {
    std::string cmd;
    for (const auto& a : args) cmd += a + " ";
    const RunResult r = RunProgram(args);
    EXPECT_EQ(r.status, 2) << cmd << r.err;
    EXPECT_EQ(testing::CountLines(r.err), 1) << cmd << r.err;
    EXPECT_TRUE(r.out.empty()) << cmd;
  }
}

}  // namespace
}  // namespace alloycolor
