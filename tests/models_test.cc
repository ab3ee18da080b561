// The paper baseline and eps-linear models, and the JSON model file, against hand
// calculations of eq. 7, 11, 12 and the shipped data.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>

#include "alloycolor/core/composition.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/units.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/interpolation.h"
#include "alloycolor/model/sample_models.h"
#include "test_util.h"

namespace alloycolor {
namespace {

using testing::DataDir;
using testing::MakeTempDir;
using testing::WriteText;

// eq. 7 with tau in fs and m* in electron masses, written independently with std::complex.
std::complex<double> DrudeEps(double lambda_nm, double tau_fs, double mass, double ne_m3) {
  const double hbar_ev_s = 6.582119569e-16, e = 1.602176634e-19, eps0 = 8.8541878128e-12,
               me = 9.1093837015e-31;
  const double omega = 2 * M_PI * 299792458.0 / (lambda_nm * 1e-9);  // rad/s
  const double wp2 = ne_m3 * e * e / (eps0 * me * mass);             // rad^2/s^2
  const double gamma = 1.0 / (tau_fs * 1e-15);
  (void)hbar_ev_s;
  return 1.0 - wp2 / (omega * (omega + std::complex<double>(0, gamma)));
}

// Writes a CSV sample of a Drude metal with the given tau and m*.
std::string WriteDrudeSample(const std::string& dir, const std::string& name, double x,
                             double tau_fs, double mass, const AlloySystem& system) {
  std::vector<double> l, n, k;
  for (double lambda = 300; lambda <= 900; lambda += 10) {
    const std::complex<double> nk =
        std::sqrt(DrudeEps(lambda, tau_fs, mass, FreeElectronDensityM3(x, system)));
    l.push_back(lambda);
    n.push_back(nk.real());
    k.push_back(nk.imag());
  }
  const std::string path = dir + "/" + name;
  WriteText(path, NkCsvText(l, n, k));
  return path;
}

TEST(PaperModel, InterpolatesTauAndMassLinearly) {
  const std::string dir = MakeTempDir();
  const AlloySystem system{FindElement("Au"), FindElement("Ag")};
  WriteDrudeSample(dir, "a.csv", 0.0, 30.0, 1.0, system);
  WriteDrudeSample(dir, "b.csv", 1.0, 10.0, 1.4, system);
  WriteText(dir + "/dataset.json",
            R"({"system": {"a": "Au", "b": "Ag"}, "composition": "atomic_fraction_a",
                "samples": [{"x": 0, "file": "a.csv"}, {"x": 1, "file": "b.csv"}]})");
  const Dataset data = LoadDataset(dir);
  const SampleModel paper(SampleModel::Kind::kPaper, data);
  const double x = 0.25;
  for (double lambda : {400.0, 550.0, 700.0}) {
    // Hand calculation: tau and m* linear in x, N_e(x) from the composition.
    const std::complex<double> expected =
        DrudeEps(lambda, 30.0 + (10.0 - 30.0) * x, 1.0 + 0.4 * x, FreeElectronDensityM3(x, system));
    const std::complex<double> got = paper.Permittivity(x, {lambda})[0];
    EXPECT_NEAR(got.real(), expected.real(), 1e-6 * std::abs(expected)) << lambda;
    EXPECT_NEAR(got.imag(), expected.imag(), 1e-6 * std::abs(expected)) << lambda;
    SampleModel::TauMass tm;
    ASSERT_TRUE(paper.PaperTauMass(x, lambda, &tm));
    EXPECT_NEAR(tm.tau_fs, 25.0, 1e-6);
    EXPECT_NEAR(tm.mass_ratio, 1.1, 1e-6);
  }
  // eps-linear is the straight line between the samples' eps.
  const SampleModel linear(SampleModel::Kind::kEpsLinear, data);
  const std::complex<double> e0 = linear.Permittivity(0.0, {500.0})[0];
  const std::complex<double> e1 = linear.Permittivity(1.0, {500.0})[0];
  const std::complex<double> mid = linear.Permittivity(x, {500.0})[0];
  EXPECT_NEAR(std::abs(mid - (e0 + (e1 - e0) * x)), 0.0, 1e-12);
}

TEST(PaperModel, ReproducesItsKnownSamples) {
  const Dataset data = LoadDataset(DataDir() + "/Au-Ag");
  const SampleModel paper(SampleModel::Kind::kPaper, data);
  for (const Sample& s : data.samples) {
    for (double lambda : {360.0, 450.5, 550.0, 633.0, 800.0}) {
      const std::complex<double> nk = NkAt(s.nk, lambda);
      const std::complex<double> got = paper.Index(s.x_atomic, {lambda})[0];
      EXPECT_NEAR(got.real(), nk.real(), 1e-9) << s.file << " " << lambda;
      EXPECT_NEAR(got.imag(), nk.imag(), 1e-9) << s.file << " " << lambda;
    }
  }
}

TEST(PaperModel, NamesSamplesWhereTheInversionIsUndefinedAndStaysFinite) {
  const Dataset data = LoadDataset(DataDir() + "/Cu-Zn");
  const SampleModel paper(SampleModel::Kind::kPaper, data);
  bool named = false;
  for (const std::string& w : paper.warnings()) {
    named |=
        w.find("Querry-Zn100") != std::string::npos && w.find("eps1 >= 1") != std::string::npos;
  }
  EXPECT_TRUE(named);
  for (double x = 0; x <= 1.0; x += 0.05) {
    for (const auto& nk : paper.Index(x, UniformGrid(360, 830, 5))) {
      ASSERT_TRUE(std::isfinite(nk.real()) && std::isfinite(nk.imag())) << x;
      ASSERT_GE(nk.imag(), 0.0);
    }
  }
}

TEST(ModelFile, RoundTripGivesIdenticalPredictionsAndBytes) {
  const Dataset data = LoadDataset(DataDir() + "/Au-Ag");
  for (auto kind : {SampleModel::Kind::kPaper, SampleModel::Kind::kEpsLinear}) {
    const SampleModel model(kind, data);
    const std::string text = ModelFileText(model);
    const auto back = ModelFromJson(nlohmann::json::parse(text), "mem");
    EXPECT_EQ(ModelFileText(*back), text);
    const std::vector<double> grid = UniformGrid(380, 780, 7);
    for (double x : {0.05, 0.33, 0.75}) {
      EXPECT_EQ(back->Permittivity(x, grid), model.Permittivity(x, grid));
    }
  }
}

TEST(ModelFile, DamagedFilesNameTheCulprit) {
  const Dataset data = LoadDataset(DataDir() + "/Au-Ag");
  const nlohmann::json good = SampleModel(SampleModel::Kind::kPaper, data).ToJson();
  nlohmann::json doc = good;
  doc["version"] = 99;
  testing::ExpectModelFileError(doc, "version");
  doc = good;
  doc["format"] = "something";
  testing::ExpectModelFileError(doc, "format");
  doc = good;
  doc.erase("system");
  testing::ExpectModelFileError(doc, "system");
  doc = good;
  doc["method"] = "magic";
  testing::ExpectModelFileError(doc, "magic");
  doc = good;
  doc["x_range"] = "wide";
  testing::ExpectModelFileError(doc, "x_range");
  doc = good;
  doc["parameters"]["samples"][0]["n"] = "oops";
  testing::ExpectModelFileError(doc, "parameters.samples[0]");
}

TEST(DefaultGrid, VisibleForAuAgAndInfraredForNbSn) {
  const std::vector<double> visible = DefaultGrid(LoadDataset(DataDir() + "/Au-Ag"));
  EXPECT_DOUBLE_EQ(visible.front(), 360.0);
  EXPECT_DOUBLE_EQ(visible.back(), 830.0);
  EXPECT_EQ(visible.size(), 95u);
  const std::vector<double> infrared = DefaultGrid(LoadDataset(DataDir() + "/Nb-Sn"));
  EXPECT_GE(infrared.front(), 1000.0);
  EXPECT_EQ(infrared.size(), 101u);
}

}  // namespace
}  // namespace alloycolor

namespace alloycolor {
namespace {

// Hand calculations for (0, 0), (1, 1), (2, 0). Natural spline: the middle second derivative
// m solves 2 (1 + 1) m = 6 ((0 - 1) - (1 - 0)), m = -3, so on [0, 1]
// S(x) = (m / 6) x^3 + (1 - m / 6) x and S(0.5) = 0.6875. PCHIP: the middle slope is 0
// (the secants change sign), the end slope ((2 h0 + h1) d0 - h0 d1) / (h0 + h1) = 2, so the
// Hermite cubic on [0, 1] gives 0.125 * 2 + 0.5 * 1 = 0.75 at 0.5.
TEST(Interpolation, MatchHandCalculations) {
  const std::vector<double> xs = {0, 1, 2}, ys = {0, 1, 0};
  const Interpolant spline(Interpolation::kNaturalSpline, xs, ys);
  const Interpolant pchip(Interpolation::kPchip, xs, ys);
  const Interpolant linear(Interpolation::kLinear, xs, ys);
  EXPECT_NEAR(spline(0.5), 0.6875, 1e-12);
  EXPECT_NEAR(spline(1.5), 0.6875, 1e-12);
  EXPECT_NEAR(pchip(0.5), 0.75, 1e-12);
  EXPECT_NEAR(linear(0.5), 0.5, 1e-12);
  for (double x : {0.0, 1.0, 2.0}) {
    EXPECT_DOUBLE_EQ(spline(x), ys[static_cast<int>(x)]);
    EXPECT_DOUBLE_EQ(pchip(x), ys[static_cast<int>(x)]);
  }
  // On (0, 0), (1, 1), (2, 1) PCHIP stays within the data; the spline overshoots past x = 1
  // (its slope there is (1 - 1) - (2 m) / 6 = 0.5 with m = -1.5).
  const Interpolant flat_pchip(Interpolation::kPchip, xs, {0, 1, 1});
  const Interpolant flat_spline(Interpolation::kNaturalSpline, xs, {0, 1, 1});
  double pchip_max = 0, spline_max = 0;
  for (int i = 0; i <= 200; ++i) {
    pchip_max = std::max(pchip_max, flat_pchip(i / 100.0));
    spline_max = std::max(spline_max, flat_spline(i / 100.0));
  }
  EXPECT_LE(pchip_max, 1.0 + 1e-12);
  EXPECT_GT(spline_max, 1.0);
  // Beyond the ends: the straight line with the end slope (spline: S'(0) = 1 - m / 6 = 1.5).
  EXPECT_NEAR(spline(-1.0), -1.5, 1e-12);
  EXPECT_NEAR(pchip(-0.5), -1.0, 1e-12);
  // Monotone data stay monotone under PCHIP (Fritsch-Carlson).
  const Interpolant mono(Interpolation::kPchip, {0, 0.2, 0.5, 1}, {0, 0.9, 1.0, 5.0});
  double last = -1;
  for (int i = 0; i <= 100; ++i) {
    const double v = mono(i / 100.0);
    EXPECT_GE(v, last - 1e-12) << i;
    last = v;
  }
  // With two points every scheme is the straight line.
  EXPECT_NEAR(Interpolant(Interpolation::kNaturalSpline, {0, 1}, {2, 4})(0.25), 2.5, 1e-12);
  EXPECT_NEAR(Interpolant(Interpolation::kPchip, {0, 1}, {2, 4})(0.25), 2.5, 1e-12);
}

// The eps-pchip and eps-spline models are those interpolants applied to eps1 and eps2 of the
// samples at each wavelength, and reproduce the samples.
TEST(SampleModels, CubicBaselinesInterpolateEps) {
  const Dataset data = LoadDataset(DataDir() + "/Au-Ag");
  const Dataset train = WithoutSamples(data, {0.1, 0.2, 0.3, 0.4, 0.6, 0.7, 0.8, 0.9});
  const SampleModel pchip(SampleModel::Kind::kEpsPchip, train);
  const SampleModel spline(SampleModel::Kind::kEpsSpline, train);
  EXPECT_EQ(pchip.method(), "eps-pchip");
  EXPECT_EQ(spline.method(), "eps-spline");
  for (double lambda : {450.0, 550.0, 650.0}) {
    std::vector<double> xs, e1, e2;
    for (const Sample& s : train.samples) {
      const std::complex<double> n = NkAt(s.nk, lambda);
      xs.push_back(s.x_atomic);
      e1.push_back((n * n).real());
      e2.push_back((n * n).imag());
    }
    for (double x : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      const std::complex<double> got = pchip.Permittivity(x, {lambda})[0];
      EXPECT_NEAR(got.real(), Interpolant(Interpolation::kPchip, xs, e1)(x), 1e-12);
      EXPECT_NEAR(got.imag(), Interpolant(Interpolation::kPchip, xs, e2)(x), 1e-12);
      const std::complex<double> s = spline.Permittivity(x, {lambda})[0];
      EXPECT_NEAR(s.real(), Interpolant(Interpolation::kNaturalSpline, xs, e1)(x), 1e-12);
    }
  }
  // A model file round trip keeps the method.
  EXPECT_EQ(ModelFromJson(pchip.ToJson(), "pchip")->method(), "eps-pchip");
  EXPECT_EQ(ModelFromJson(spline.ToJson(), "spline")->method(), "eps-spline");
}

}  // namespace
}  // namespace alloycolor
