// The physical model and its Ceres fit: the term forms against published references and
// analytic limits, the cost's Jacobian against finite differences, recovery of known
// parameters within their reported uncertainty, the shipped Au-Ag and Nb-Sn sets, the JSON
// round trip and damaged files, and the `params` command.
#include "alloycolor/fit/physical_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/units.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/fit/physical_costs.h"
#include "alloycolor/model/physical_model.h"
#include "test_util.h"

namespace alloycolor {
namespace {

using testing::DataDir;
using testing::MakeTempDir;
using testing::RunProgram;
using testing::WriteText;

std::complex<double> Std(const Complex<double>& z) { return {z.re, z.im}; }

// Rioux et al. 2014's own parameters for Au (their published code): drude + rioux-gap +
// rioux-edge reproduces the shipped Au sample, which is that model's output.
TEST(PhysicalModel, RiouxTermsReproduceThePublishedGoldModel) {
  const PhysicalLayout layout({TermKind::kRiouxGap, TermKind::kRiouxEdge}, 0);
  // eps_inf, wp, gamma; A, E0 (omega_0), Eg (omega_g), G; A, E0, G.
  const double gold[10] = {2.2715, 8.9234,  0.042389, 73.251, 2.3957,
                           2.6652, 0.17880, 40.007,   3.5362, 0.35467};
  const NkSpectrum au = ReadNkFile(DataDir() + "/Au-Ag/Rioux-Au100Ag0.yml");
  for (double lambda = 300; lambda <= 1000; lambda += 1) {
    const Complex<double> nk =
        IndexFromPermittivity(PhysicalPermittivity(layout, gold, OmegaEvFromLambdaNm(lambda)));
    const std::complex<double> data = NkAt(au, lambda);
    EXPECT_NEAR(nk.re, data.real(), 2e-5) << lambda;
    EXPECT_NEAR(nk.im, data.imag(), 2e-5) << lambda;
  }
}

TEST(PhysicalModel, TermsMeetTheirAnalyticLimits) {
  // Lorentz at resonance: i A E0 / G; static limit A.
  const double lorentz[3] = {1.5, 2.0, 0.25};
  const Complex<double> at_e0 = InterbandPermittivity(TermKind::kLorentz, lorentz, 2.0);
  EXPECT_NEAR(at_e0.re, 0.0, 1e-12);
  EXPECT_NEAR(at_e0.im, 1.5 * 2.0 / 0.25, 1e-12);
  EXPECT_NEAR(InterbandPermittivity(TermKind::kLorentz, lorentz, 1e-9).re, 1.5, 1e-6);
  // Etchegoin's critical point: real at w -> 0 (causality), absorbing above its centre
  // with his phase -pi/4.
  const double cp[4] = {1.27, 2.64, 0.65, -kPi / 4};
  EXPECT_NEAR(InterbandPermittivity(TermKind::kCriticalPoint, cp, 1e-9).im, 0.0, 1e-8);
  EXPECT_GT(InterbandPermittivity(TermKind::kCriticalPoint, cp, 2.64).im, 0.0);
  // Rioux's edge: eps2 -> A pi / (2 w^2) well above the onset as G -> 0, 0 below it.
  const double edge[3] = {40.0, 2.0, 1e-6};
  EXPECT_NEAR(InterbandPermittivity(TermKind::kRiouxEdge, edge, 3.0).im, 40.0 * kPi / 18.0, 1e-4);
  EXPECT_NEAR(InterbandPermittivity(TermKind::kRiouxEdge, edge, 1.0).im, 0.0, 1e-4);
  // Drude term: eq. 7.
  const double drude[3] = {1.0, 9.0, 0.07};
  const Complex<double> d = TermPermittivity(TermKind::kDrude, drude, 2.0);
  const Complex<double> expected = DrudePermittivity(2.0, 81.0, 0.07, 1.0);
  EXPECT_DOUBLE_EQ(d.re, expected.re);
  EXPECT_DOUBLE_EQ(d.im, expected.im);
}

TEST(PhysicalModel, ParametersStayPositiveAndOrderedForAnyCoefficients) {
  const PhysicalLayout layout(
      {TermKind::kCriticalPoint, TermKind::kCriticalPoint, TermKind::kRiouxGap}, 2);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uniform(-5.0, 5.0);
  const int np = layout.num_parameters();
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> coeffs(layout.num_coefficients());
    for (double& c : coeffs) c = uniform(rng);
    for (double u : {-1.0, -0.3, 0.4, 1.0}) {
      double basis[3], raw[kPhysicalMaxParameters], v[kPhysicalMaxParameters];
      LegendreBasis(u, 2, basis);
      PhysicalRawFromCoefficients(layout, coeffs.data(), basis, raw);
      PhysicalValuesFromRaw(layout, raw, v);
      for (int k = 0; k < np; ++k) {
        const PhysicalParameter& p = layout.parameters()[k];
        if (p.map != ParameterMap::kFree) EXPECT_GT(v[k], 0.0) << p.name;
      }
      EXPECT_GE(v[0], 1.0);  // eps_inf
      const int e1 = layout.Find(1, "E0_eV"), e2 = layout.Find(2, "E0_eV");
      EXPECT_GT(v[e2], v[e1]);
      EXPECT_GT(v[layout.Find(3, "Eg_eV")], v[layout.Find(3, "E0_eV")]);
    }
  }
  EXPECT_NEAR(SoftPositive(SoftPositiveInverse(0.02)), 0.02, 1e-15);
}

TEST(PhysicalCosts, JacobianMatchesFiniteDifferences) {
  const PhysicalLayout layout({TermKind::kRiouxGap, TermKind::kRiouxEdge, TermKind::kCriticalPoint,
                               TermKind::kLorentz, TermKind::kCriticalPoint},
                              2);
  std::vector<double> omega;
  std::vector<std::complex<double>> eps;
  for (double lambda = 300; lambda <= 1000; lambda += 70) {
    omega.push_back(OmegaEvFromLambdaNm(lambda));
    eps.push_back({-20.0 + lambda / 100.0, 1.5 + lambda / 1000.0});
  }
  const double basis[3] = {1.0, 0.3, -0.365};
  std::unique_ptr<ceres::CostFunction> cost(
      fit::CreatePhysicalSampleCost(layout, basis, omega, eps));
  const int nc = layout.num_coefficients();
  const int nr = 2 * static_cast<int>(omega.size());
  std::vector<double> c(nc);
  for (int k = 0; k < layout.num_parameters(); ++k) {
    c[k * 3] = 0.5 + 0.1 * k;
    c[k * 3 + 1] = 0.05 * (k % 3) - 0.04;
    c[k * 3 + 2] = 0.02;
  }
  std::vector<double> residual(nr), jacobian(nr * nc), plus(nr), minus(nr);
  const double* blocks[1] = {c.data()};
  double* jacobians[1] = {jacobian.data()};
  ASSERT_TRUE(cost->Evaluate(blocks, residual.data(), jacobians));
  // The residuals without Jacobian (double path) equal those with it (Jet path).
  ASSERT_TRUE(cost->Evaluate(blocks, plus.data(), nullptr));
  for (int r = 0; r < nr; ++r) EXPECT_NEAR(plus[r], residual[r], 1e-12);
  for (int j = 0; j < nc; ++j) {
    const double h = 1e-6;
    std::vector<double> cp = c, cm = c;
    cp[j] += h;
    cm[j] -= h;
    const double* bp[1] = {cp.data()};
    const double* bm[1] = {cm.data()};
    ASSERT_TRUE(cost->Evaluate(bp, plus.data(), nullptr));
    ASSERT_TRUE(cost->Evaluate(bm, minus.data(), nullptr));
    for (int r = 0; r < nr; ++r) {
      const double numeric = (plus[r] - minus[r]) / (2 * h);
      EXPECT_NEAR(jacobian[r * nc + j], numeric, 1e-6 * (1 + std::abs(numeric)))
          << "residual " << r << ", coefficient " << j;
    }
  }
}

// Synthetic data from known parameters: values at x = 0, 0.5, 1, quadratic in r; without
// bowing, the straight line in r between the ends (the middle values unused).
struct Truth {
  PhysicalLayout layout{{TermKind::kCriticalPoint, TermKind::kCriticalPoint}, 2};
  std::vector<double> coeffs;
  explicit Truth(bool bowing = true) {
    // eps_inf, wp, gamma; A, E0, G, phi; A, E0, G, phi at x = 0, 0.5, 1 (a metal turning
    // into Etchegoin's gold). A critical point with phi != 0 adds negative eps2 away from
    // its centre; these values keep the total eps2 > 0.
    const double values[3][11] = {
        {1.8, 9.0, 0.06, 0.6, 3.7, 0.6, -0.5, 1.0, 4.1, 0.9, -0.785},
        {1.6, 8.8, 0.12, 1.0, 3.1, 0.6, -0.65, 1.05, 3.95, 1.0, -0.785},
        {1.54, 8.55, 0.073, 1.27, 2.64, 0.65, -0.785, 1.1, 3.82, 1.17, -0.785}};
    const int np = layout.num_parameters();
    double raw[3][11];
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < np; ++k) {
        const PhysicalParameter& p = layout.parameters()[k];
        switch (p.map) {
          case ParameterMap::kPositive:
            raw[i][k] = SoftPositiveInverse(values[i][k]);
            break;
          case ParameterMap::kOnePlusPositive:
            raw[i][k] = SoftPositiveInverse(values[i][k] - 1);
            break;
          case ParameterMap::kAbove:
            raw[i][k] = SoftPositiveInverse(values[i][k] - values[i][p.reference]);
            break;
          case ParameterMap::kFree:
            raw[i][k] = values[i][k];
            break;
        }
      }
    }
    // Legendre coefficients through u = -1, 0, 1: c0 = (f- + 4 f0 + f+)/6 - ..., solved
    // directly: P0 = 1, P1 = u, P2 = (3u^2 - 1)/2.
    coeffs.resize(layout.num_coefficients());
    for (int k = 0; k < np; ++k) {
      const double fm = raw[0][k], f0 = raw[1][k], fp = raw[2][k];
      const double c2 = (fm + fp - 2 * f0) / 3.0;
      coeffs[k * 3] = f0 + c2 / 2.0;
      coeffs[k * 3 + 1] = (fp - fm) / 2.0;
      coeffs[k * 3 + 2] = c2;
      if (!bowing) {
        coeffs[k * 3] = (fm + fp) / 2.0;
        coeffs[k * 3 + 2] = 0;
      }
    }
  }
  std::vector<double> ValuesAt(double x) const {
    double basis[3], raw[kPhysicalMaxParameters];
    LegendreBasis(2 * x - 1, 2, basis);
    PhysicalRawFromCoefficients(layout, coeffs.data(), basis, raw);
    std::vector<double> v(layout.num_parameters());
    PhysicalValuesFromRaw(layout, raw, v.data());
    return v;
  }
};

std::string WriteSyntheticDataset(const Truth& truth, const std::vector<double>& xs, double noise) {
  std::mt19937 rng(20261122);
  std::normal_distribution<double> normal(0.0, noise);
  const auto eps = [&](double x, double lambda) {
    const std::vector<double> v = truth.ValuesAt(x);
    const Complex<double> e =
        PhysicalPermittivity(truth.layout, v.data(), OmegaEvFromLambdaNm(lambda));
    EXPECT_GT(e.im, 0.01) << "the truth absorbs at x = " << x << ", " << lambda << " nm";
    const double scale = std::sqrt(Norm2(e));
    const double d1 = scale * normal(rng), d2 = scale * normal(rng);  // in this order
    return std::complex<double>(e.re + d1, e.im + d2);
  };
  return testing::WriteSyntheticDataset(xs, eps, 300, 1000);
}

TEST(PhysicalFit, RecoversKnownParametersWithinTheirUncertainty) {
  const Truth truth;
  const Dataset data =
      LoadDataset(WriteSyntheticDataset(truth, {0.0, 0.2, 0.4, 0.6, 0.8, 1.0}, 1e-3));
  fit::PhysicalFitOptions options;
  options.terms = "cp,cp";
  const auto result = fit::FitPhysical(data, options);
  const PhysicalModel& model = *result.model;
  ASSERT_TRUE(model.fit_summary().converged);
  ASSERT_TRUE(model.HasUncertainty());
  const int nc = model.layout().num_coefficients();
  for (int j = 0; j < nc; ++j) {
    const double sigma = std::sqrt(model.covariance()[static_cast<size_t>(j) * nc + j]);
    EXPECT_GT(sigma, 0.0);
    EXPECT_LT(std::abs(model.coeffs()[j] - truth.coeffs[j]), 4 * sigma)
        << "coefficient " << j << " (" << model.layout().parameters()[j / 3].name << ")";
  }
  for (double x : {0.0, 0.3, 0.5, 0.9}) {
    const std::vector<double> v = truth.ValuesAt(x);
    const auto fitted = model.ParameterValues(x);
    for (size_t k = 0; k < v.size(); ++k) {
      EXPECT_LT(std::abs(fitted[k].value - v[k]), 4 * fitted[k].sigma)
          << fitted[k].name << " of term " << fitted[k].term << " at x = " << x;
      EXPECT_LT(fitted[k].sigma, 0.05 * std::abs(v[k]) + 0.01) << fitted[k].name;
    }
  }
}

// Left to the data (no --degree), the composition degree is scored by leave-one-out:
// where the truth bows (gamma 0.06, 0.12, 0.073 at x = 0, 0.5, 1, as Nordheim's rule has
// it) degree 1 misses by far (its own error on the samples exceeds degree 2's left-out
// error, so its folds are skipped) and degree 2 stays; where every parameter is a straight line
// and the six samples scatter (1 % of |eps|), degree 2 chases the scatter and degree 1 is
// more than 10 % better.
TEST(PhysicalFit, TheDataChooseTheCompositionDegree) {
  const color::Colorimeter colorimeter = color::Colorimeter::Load(DataDir(), "D65", 2);
  for (const bool bowing : {true, false}) {
    SCOPED_TRACE(bowing ? "bowing" : "straight");
    const Dataset data = LoadDataset(
        WriteSyntheticDataset(Truth(bowing), {0.0, 0.2, 0.4, 0.6, 0.8, 1.0}, bowing ? 1e-4 : 1e-2));
    fit::FitSettings settings;
    settings.options.Set("terms", "cp,cp");
    settings.colorimeter = &colorimeter;
    settings.memo = fit::MakeFitMemo();
    const auto model = fit::BuildModel("physical", data, settings);
    // Built again through the memo (as validate's physical and auto share the choice) and
    // afresh: the same model file.
    EXPECT_EQ(fit::BuildModel("physical", data, settings)->ToJson().dump(), model->ToJson().dump());
    fit::FitSettings fresh = settings;
    fresh.memo = nullptr;
    EXPECT_EQ(fit::BuildModel("physical", data, fresh)->ToJson().dump(), model->ToJson().dump());
    const nlohmann::json& details = model->fit_summary().details;
    EXPECT_EQ(model->fit_summary().degree, bowing ? 2 : 1) << details.dump();
    ASSERT_EQ(details["degree_selection"].size(), 2u);  // degrees 2 and 1
    const auto& two = details["degree_selection"][0];
    const auto& one = details["degree_selection"][1];
    EXPECT_EQ(two["degree"], 2);
    EXPECT_EQ(one["degree"], 1);
    if (bowing) {
      // The straight line misses the bowing by far more than the noise: even on the samples
      // it was fitted to, so its folds are not fitted.
      ASSERT_TRUE(one.contains("error")) << one;
      EXPECT_NE(one["error"].get<std::string>().find("its own RMS error on the samples"),
                std::string::npos)
          << one;
    } else {
      EXPECT_LT(one["rms"].get<double>(), two["rms"].get<double>() / 1.1);
    }
  }
}

// The shipped Au-Ag set, fitted once for several tests.
class AuAg : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dataset_ = new Dataset(LoadDataset(DataDir() + "/Au-Ag"));
    model_ = fit::FitPhysical(*dataset_, fit::PhysicalFitOptions{}).model.release();
  }
  static void TearDownTestSuite() {
    delete model_;
    delete dataset_;
  }
  static Dataset* dataset_;
  static PhysicalModel* model_;
};
Dataset* AuAg::dataset_ = nullptr;
PhysicalModel* AuAg::model_ = nullptr;

// Checked here on a dense grid apart from the fit's own check: passive, n and k bounded.
TEST_F(AuAg, StaysPassiveAndBoundedEverywhereInItsRange) {
  const std::vector<double> grid = UniformGrid(300, 1000, 2.5);
  for (int i = 0; i <= 400; ++i) {
    const double x = i / 400.0;
    const auto eps = model_->Permittivity(x, grid);
    for (size_t j = 0; j < grid.size(); ++j) {
      ASSERT_GE(eps[j].imag(), 0.0) << x << " " << grid[j];
      const std::complex<double> nk = std::sqrt(eps[j]);
      ASSERT_LE(std::max(nk.real(), nk.imag()), 50.0) << x << " " << grid[j];
    }
  }
}

// The end samples' fits are remembered for the process: a second fit of the same data
// takes them from memory and must give the very file the first gave, and a fit of other
// data in between (other ends, other terms) must not disturb it.
TEST_F(AuAg, ARepeatedFitGivesTheSameBytes) {
  fit::PhysicalFitOptions other;
  other.terms = "lorentz,lorentz,lorentz";
  fit::FitPhysical(WithoutSamples(*dataset_, {0.0}), other);
  const auto again = fit::FitPhysical(*dataset_, fit::PhysicalFitOptions{});
  EXPECT_EQ(ModelFileText(*again.model), ModelFileText(*model_));
  // Each candidate's terms fitted its own end samples (what is remembered is per terms).
  const nlohmann::json& candidates = model_->fit_summary().details.at("terms_candidates");
  ASSERT_EQ(candidates.size(), 3u);
  for (size_t i = 0; i < candidates.size(); ++i) {
    for (size_t j = i + 1; j < candidates.size(); ++j) {
      EXPECT_NE(candidates[i]["end_costs"], candidates[j]["end_costs"]) << candidates.dump();
    }
  }
}

// A leave-one-out fold started from the model fitted to all samples (as the prediction
// error's folds are) reaches the fit a cold start reaches on the fold's data: the same
// terms, and predictions at the held-out composition equal to 1e-3 relative (both fits
// reproduce the data to about 1e-5). A start of another degree is
// ignored (a cold fit).
TEST_F(AuAg, AWarmFoldReachesTheColdFit) {
  const Dataset fold = WithoutSamples(*dataset_, {0.5});
  fit::PhysicalFitOptions cold_options;
  const auto cold = fit::FitPhysical(fold, cold_options);
  fit::PhysicalFitOptions warm_options;
  warm_options.start = model_;
  const auto warm = fit::FitPhysical(fold, warm_options);
  EXPECT_EQ(warm.terms, cold.terms);
  EXPECT_NE(warm.model->fit_summary().details.value("terms_chosen_by", "").find("warm start"),
            std::string::npos);
  // Fewer iterations is the usual case but not a law (Ceres's path depends on the
  // machine's floating point: 10 against 6 on the machine this was last run on): it converges.
  EXPECT_TRUE(warm.model->fit_summary().converged);
  const std::vector<double> grid = UniformGrid(300, 1000, 5);
  const auto a = warm.model->Permittivity(0.5, grid), b = cold.model->Permittivity(0.5, grid);
  for (size_t j = 0; j < grid.size(); ++j) {
    EXPECT_LE(std::abs(a[j] - b[j]), 1e-3 * std::abs(b[j])) << grid[j] << " nm";
  }
  fit::PhysicalFitOptions other_degree;
  other_degree.start = model_;
  other_degree.degree = 1;
  const auto ignored = fit::FitPhysical(fold, other_degree);
  EXPECT_EQ(ignored.model->fit_summary().details.value("terms_chosen_by", "").find("warm start"),
            std::string::npos);
}

// Querry's zinc (eps1 > 1 across the visible) drives every degree's fit out of physics
// between the samples: refused, naming the data set and where. Which check it fails first
// (eps2 < 0, or n beyond the limit) rests on rounding, so on the build the machine runs
// (core/simd.h): one of our machines meets a resonance where another meets eps2 < 0.
TEST(PhysicalFit, AnUnphysicalFitIsRefusedNamingWhere) {
  try {
    fit::FitPhysical(LoadDataset(DataDir() + "/Cu-Zn"), fit::PhysicalFitOptions{});
    FAIL() << "the fit was accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("Cu-Zn/dataset.json"), std::string::npos) << m;
    EXPECT_TRUE(m.find("is not passive (eps2 = ") != std::string::npos ||
                m.find("has a resonance (n = ") != std::string::npos)
        << m;
    EXPECT_NE(m.find(" at x = "), std::string::npos) << m;
    EXPECT_NE(m.find("lower degrees tried too"), std::string::npos) << m;
  }
}

TEST_F(AuAg, ReproducesEverySampleFrom300To1000nm) {
  EXPECT_EQ(model_->fit_summary().details["terms"], "rioux-gap,rioux-edge");
  EXPECT_EQ(model_->lambda_min_nm(), 300.0);
  EXPECT_EQ(model_->lambda_max_nm(), 1000.0);
  ASSERT_EQ(dataset_->samples.size(), 11u);
  for (const Sample& s : dataset_->samples) {
    std::vector<double> grid;
    for (double l : s.nk.lambda_nm) {
      if (l >= 300 - 1e-9 && l <= 1000 + 1e-9) grid.push_back(l);
    }
    const auto index = model_->Index(s.x_atomic, grid);
    double dn = 0, dk = 0;
    for (size_t i = 0; i < grid.size(); ++i) {
      const std::complex<double> data = NkAt(s.nk, grid[i]);
      dn = std::max(dn, std::abs(index[i].real() - data.real()));
      dk = std::max(dk, std::abs(index[i].imag() - data.imag()));
    }
    EXPECT_LT(dn, 0.01) << s.file;
    EXPECT_LT(dk, 0.01) << s.file;
  }
  // Physical and finite, with uncertainties, everywhere in between.
  for (double x = 0; x <= 1.0 + 1e-9; x += 0.05) {
    for (const auto& v : model_->ParameterValues(x)) {
      EXPECT_TRUE(std::isfinite(v.value) && std::isfinite(v.sigma)) << v.name;
      if (v.name != "phi_rad") EXPECT_GT(v.value, 0.0) << v.name << " at x = " << x;
    }
  }
}

TEST_F(AuAg, FileReadsBackWithIdenticalPredictionsAndBytes) {
  const std::string text = ModelFileText(*model_);
  const auto back = ModelFromJson(nlohmann::json::parse(text), "mem");
  EXPECT_EQ(back->method(), "physical");
  EXPECT_TRUE(ModelFileText(*back) == text);
  const std::vector<double> grid = UniformGrid(300, 1000, 2.5);
  for (double x : {0.0, 0.37, 1.0}) {
    EXPECT_EQ(back->Permittivity(x, grid), model_->Permittivity(x, grid));
    EXPECT_EQ(back->PermittivityDraws(x, grid, 4, 7u), model_->PermittivityDraws(x, grid, 4, 7u));
  }
  // The same inputs give the same bytes.
  EXPECT_TRUE(ModelFileText(*fit::FitPhysical(*dataset_, fit::PhysicalFitOptions{}).model) == text);
}

// Expects ModelFromJson to refuse the document with a message naming `field`.
void ExpectRefused(const nlohmann::json& doc, const std::string& field) {
  try {
    ModelFromJson(doc, "mem");
    ADD_FAILURE() << "accepted a damaged " << field;
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("mem: ", 0), 0u) << what;
    EXPECT_NE(what.find(field), std::string::npos) << what;
  }
}

TEST_F(AuAg, DamagedFieldsAreNamed) {
  const nlohmann::json doc = nlohmann::json::parse(ModelFileText(*model_));
  nlohmann::json d = doc;
  d["parameters"]["terms"][1]["kind"] = "quadrupole";
  ExpectRefused(d, "parameters.terms[1].kind");
  d = doc;
  d["parameters"]["terms"][0]["parameters"][1]["coefficients"] = {1.0, 2.0};
  ExpectRefused(d, "parameters.terms[0].parameters[1].coefficients");
  d = doc;
  d["parameters"]["terms"][2]["parameters"][0]["coefficients"][0] = "many";
  ExpectRefused(d, "parameters.terms[2].parameters[0].coefficients[0]");
  d = doc;
  d["parameters"]["terms"][1]["parameters"][1]["name"] = "E1_eV";
  ExpectRefused(d, "parameters.terms[1].parameters[1].name");
  d = doc;
  d["parameters"].erase("degree");
  ExpectRefused(d, "parameters: missing field 'degree'");
  d = doc;
  d["parameters"]["covariance"] = {1.0, 2.0, 3.0};
  ExpectRefused(d, "parameters.covariance");
  d = doc;
  d["parameters"]["terms"][0]["kind"] = "cp";
  ExpectRefused(d, "parameters.terms[0].kind");
}

TEST(PhysicalFit, NbSnInfraredDrudeGivesTauAndMassAgainstComposition) {
  const Dataset data = LoadDataset(DataDir() + "/Nb-Sn");
  const auto result = fit::FitPhysical(data, fit::PhysicalFitOptions{});
  EXPECT_EQ(result.terms, "none");
  const PhysicalModel& model = *result.model;
  EXPECT_GE(model.lambda_min_nm(), 1000.0);
  for (const Sample& s : data.samples) {
    const auto values = model.ParameterValues(s.x_atomic);
    const auto& wp = values[model.layout().Find(0, "wp_eV")];
    const auto& gamma = values[model.layout().Find(0, "gamma_eV")];
    const double tau_fs = TauFsFromGammaEv(gamma.value);
    const double mass =
        kPlasmaEv2M3 * FreeElectronDensityM3(s.x_atomic, data.system) / (wp.value * wp.value);
    EXPECT_TRUE(tau_fs > 0.1 && tau_fs < 100) << s.file << ": tau " << tau_fs << " fs";
    EXPECT_TRUE(mass > 0.05 && mass < 50) << s.file << ": m* " << mass;
    EXPECT_TRUE(std::isfinite(wp.sigma) && wp.sigma > 0) << s.file;
    EXPECT_TRUE(std::isfinite(gamma.sigma) && gamma.sigma > 0) << s.file;
  }
}

TEST(PhysicalFit, BadOptionsAreNamed) {
  const Dataset data = LoadDataset(DataDir() + "/Nb-Sn");
  fit::PhysicalFitOptions options;
  options.terms = "cp,quadrupole";
  EXPECT_THROW(fit::FitPhysical(data, options), Error);
  options.terms = "none";
  options.lambda_from_nm = 300;
  options.lambda_to_nm = 1000;
  try {
    fit::FitPhysical(data, options);
    ADD_FAILURE() << "fitted outside the data";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Golovashkin"), std::string::npos) << e.what();
  }
}

TEST_F(AuAg, ParamsCommandPrintsTheParametersAgainstComposition) {
  const std::string dir = MakeTempDir();
  WriteText(dir + "/auag.json", ModelFileText(*model_));
  const auto text = RunProgram({"params", "--model", dir + "/auag.json"});
  ASSERT_EQ(text.status, 0) << text.err;
  for (const char* column : {"wp_eV", "gamma_eV", "tau_fs", "N_e_m^-3", "m*/m_e", "eps_inf",
                             "t1:E0_eV", "t1:E0_nm", "t1:Eg_eV", "t2:G_eV"}) {
    EXPECT_NE(text.out.find(column), std::string::npos) << column;
  }
  EXPECT_NE(text.out.find("±"), std::string::npos);
  const auto json = RunProgram({"params", "--model", dir + "/auag.json", "--format", "json",
                                "--from", "0.25", "--to", "0.75", "--steps", "3"});
  ASSERT_EQ(json.status, 0) << json.err;
  const auto out = nlohmann::json::parse(json.out);
  ASSERT_EQ(out["rows"].size(), 3u);
  EXPECT_DOUBLE_EQ(out["rows"][1]["x"].get<double>(), 0.5);
  EXPECT_GT(out["rows"][1]["tau_fs"]["value"].get<double>(), 0.0);
  EXPECT_GT(out["rows"][1]["t1:E0_nm"]["value"].get<double>(), 300.0);
  // tau = hbar / gamma, by hand from the printed gamma.
  EXPECT_NEAR(out["rows"][1]["tau_fs"]["value"].get<double>(),
              kHbarEvFs / out["rows"][1]["gamma_eV"]["value"].get<double>(), 1e-9);
  // The infrared set through the command line: fit, then params.
  const auto fitted = RunProgram({"fit", "--data", DataDir() + "/Nb-Sn", "--method", "physical",
                                  "--out", dir + "/nbsn.json", "--quiet"});
  ASSERT_EQ(fitted.status, 0) << fitted.err;
  const auto nbsn = RunProgram({"params", "--model", dir + "/nbsn.json", "--steps", "5"});
  ASSERT_EQ(nbsn.status, 0) << nbsn.err;
  EXPECT_NE(nbsn.out.find("drude only"), std::string::npos) << nbsn.out;
  // A model without fitted physical parameters gives its pointwise tau and m*.
  const auto paper = RunProgram({"params", "--data", DataDir() + "/Au-Ag", "--method", "paper"});
  EXPECT_EQ(paper.status, 0) << paper.err;
  EXPECT_NE(paper.out.find("tau_fs@550nm"), std::string::npos) << paper.out;
  // Bad terms are refused with a clear message.
  const auto bad = RunProgram({"fit", "--data", DataDir() + "/Nb-Sn", "--method", "physical",
                               "--terms", "cp,quadrupole", "--out", dir + "/x.json"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("unknown term kind 'quadrupole'"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace alloycolor
