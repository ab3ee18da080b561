// The physical model's wavelength kernel (model/physical_kernel.h) against the
// straightforward evaluation: its logarithm and arctangent against the C library, every
// term kind against the header's formulas written independently with std::complex, the
// colour of the bound model against the one-wavelength-at-a-time chain (XYZ within 1e-9),
// the covariance draws against draws made straightforwardly, the terms' hand-written
// gradients against ceres::Jet and central differences (the kernel's against the double
// path's), the grids that do not fill whole vectors, the fallback where the kernel's
// approximations do not apply, and the model file's check of its widths.
#include "alloycolor/model/physical_kernel.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <cstring>
#include <limits>
#include <random>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/color/sweep.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/units.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/physical_model.h"
#include "test_util.h"

namespace alloycolor {
namespace {

using testing::DataDir;
using testing::ErrorOf;
using Cx = std::complex<double>;

double RelativeError(double value, double reference) {
  return std::abs(value - reference) / std::max(std::abs(reference), 1e-300);
}

TEST(PhysicalKernel, LogarithmAgreesWithTheCLibrary) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> exponent(-700.0, 700.0), mantissa(1.0, 2.0);
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double x = std::ldexp(mantissa(rng), static_cast<int>(exponent(rng)));
    worst = std::max(
        worst, std::abs(kernel::LaneLog(x) - std::log(x)) / std::max(1.0, std::abs(std::log(x))));
  }
  // Near 1, where ln x is small: relative to the result.
  for (int i = -1000; i <= 1000; ++i) {
    const double x = 1.0 + i * 1e-4;
    if (x == 1.0) continue;
    worst = std::max(worst, RelativeError(kernel::LaneLog(x), std::log(x)));
  }
  EXPECT_LT(worst, 1e-15);
  EXPECT_EQ(kernel::LaneLog(1.0), 0.0);
  // Outside the normal numbers: NaN, so that the caller takes the straightforward path.
  for (double x : {0.0, -0.0, -1.0, 1e-310, std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_TRUE(std::isnan(kernel::LaneLog(x))) << x;
  }
}

TEST(PhysicalKernel, ArctangentAgreesWithTheCLibraryInEveryOctant) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> angle(-kPi, kPi), exponent(-300.0, 300.0);
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double a = angle(rng), r = std::pow(10.0, exponent(rng));
    const double y = r * std::sin(a), x = r * std::cos(a);
    worst = std::max(worst, std::abs(kernel::LaneAtan2(y, x) - std::atan2(y, x)));
  }
  EXPECT_LT(worst, 1e-15);
  // Small angles, relative to the result.
  for (double y : {1e-300, 1e-20, 1e-8, -1e-8}) {
    EXPECT_LT(RelativeError(kernel::LaneAtan2(y, 1.0), std::atan2(y, 1.0)), 1e-15) << y;
  }
  // The axes and signed zeros as the C library has them.
  for (double y : {0.0, -0.0, 1.0, -1.0}) {
    for (double x : {0.0, -0.0, 1.0, -1.0}) {
      EXPECT_EQ(kernel::LaneAtan2(y, x), std::atan2(y, x)) << y << ", " << x;
    }
  }
  EXPECT_TRUE(std::isnan(kernel::LaneAtan2(1.0, std::numeric_limits<double>::infinity())));
  EXPECT_TRUE(std::isnan(kernel::LaneAtan2(std::numeric_limits<double>::quiet_NaN(), 1.0)));
}

// The header's terms (physical_model.h) as its formulas read, with std::complex and the
// C++ library's atan, atanh, log and sqrt: an implementation independent of the templated
// physics and of the kernel.
Cx HeaderTerm(TermKind kind, const double* v, double w) {
  const Cx i(0.0, 1.0);
  switch (kind) {
    case TermKind::kDrude:
      return v[0] - v[1] * v[1] / (w * (w + i * v[2]));
    case TermKind::kLorentz:
      return v[0] * v[1] * v[1] / (v[1] * v[1] - w * w - i * w * v[2]);
    case TermKind::kCriticalPoint:
      return v[0] * v[1] *
             (std::exp(i * v[3]) / (v[1] - w - i * v[2]) +
              std::exp(-i * v[3]) / (v[1] + w + i * v[2]));
    case TermKind::kRiouxGap: {
      const double e0 = v[1], eg = v[2], r = std::sqrt(eg - e0);
      const Cx c(w, v[3]);
      const Cx s1 = std::sqrt(c - eg), s2 = std::sqrt(c + eg);
      return v[0] / (c * c) *
             (-s1 * std::atan(r / s1) - s2 * std::atanh(r / s2) +
              2.0 * std::sqrt(eg) * std::atanh(r / std::sqrt(eg)) -
              0.5 * r * std::log(1.0 - c * c / (e0 * e0)));
    }
    case TermKind::kRiouxEdge: {
      const Cx c(w, v[2]);
      return -v[0] * std::log(1.0 - c * c / (v[1] * v[1])) / (2.0 * c * c);
    }
  }
  return 0.0;
}

Cx HeaderPermittivity(const PhysicalLayout& layout, const double* values, double w) {
  Cx eps = 0.0;
  for (int t = 0; t < layout.num_terms(); ++t) {
    eps += HeaderTerm(layout.term_kind(t), values + layout.term_offset(t), w);
  }
  return eps;
}

const Dataset& AuAg() {
  static const Dataset dataset = LoadDataset(DataDir() + "/Au-Ag");
  return dataset;
}

// A model with every term kind, its parameters varying with composition: each term's
// centre crosses the visible, widths from 0.02 eV (sharp) to 1.5 eV.
PhysicalModel EveryKindModel(std::vector<double> covariance = {}) {
  const PhysicalLayout layout(
      {TermKind::kLorentz, TermKind::kCriticalPoint, TermKind::kRiouxGap, TermKind::kRiouxEdge}, 2);
  // Values at x = 0, 0.5, 1 (u = -1, 0, 1) of each parameter, as r (SoftPositiveInverse
  // of the value above its reference, or the phase itself).
  const std::vector<std::array<double, 3>> r = {
      {1.2, 0.8, 1.5},    {8.6, 8.8, 8.9}, {0.02, 0.05, 0.04},                     // drude
      {3.0, 5.0, 2.0},    {2.2, 2.9, 3.6}, {0.4, 0.2, 1.5},                        // lorentz
      {1.3, 0.6, 1.0},    {2.6, 2.1, 3.0}, {0.65, 0.3, 0.9},   {-0.8, 0.3, 1.2},   // cp
      {51.0, 60.0, 73.0}, {3.9, 3.0, 2.4}, {0.13, 0.2, 0.27},  {0.02, 0.1, 0.18},  // gap
      {30.8, 35.0, 40.0}, {4.2, 3.8, 3.5}, {0.19, 0.25, 0.35}};                    // edge
  std::vector<double> coeffs;
  for (int k = 0; k < layout.num_parameters(); ++k) {
    std::array<double, 3> raw = r[k];
    if (layout.parameters()[k].map != ParameterMap::kFree) {
      for (double& v : raw) v = SoftPositiveInverse(v);
    }
    // Through u = -1, 0, 1 with P0, P1, P2: c0 - c2 / 2 = mid, c0 + c1 + c2 = hi, ...
    const double c1 = 0.5 * (raw[2] - raw[0]);
    const double c2 = (raw[0] + raw[2] - 2.0 * raw[1]) / 3.0;
    coeffs.insert(coeffs.end(), {raw[1] + 0.5 * c2, c1, c2});
  }
  return PhysicalModel(AuAg(), 300.0, 1000.0, layout, coeffs, std::move(covariance));
}

TEST(PhysicalKernel, EveryTermKindAgreesWithTheHeadersFormulas) {
  const PhysicalModel model = EveryKindModel();
  std::vector<double> grid;
  for (double l = 300; l <= 1000; l += 0.7) grid.push_back(l);
  double worst = 0;
  for (int i = 0; i <= 40; ++i) {
    const double x = i / 40.0;
    const std::vector<Cx> eps = model.Permittivity(x, grid);
    std::vector<double> values(model.layout().num_parameters());
    model.ValuesAt(x, model.coeffs().data(), values.data());
    for (size_t j = 0; j < grid.size(); ++j) {
      const Cx expected =
          HeaderPermittivity(model.layout(), values.data(), OmegaEvFromLambdaNm(grid[j]));
      worst = std::max(worst, std::abs(eps[j] - expected) / std::abs(expected));
    }
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(PhysicalKernel, EachTermAloneAgreesWithTheHeadersFormulas) {
  // One term at a time on the kernel's own grid function, wavelength counts that fill no
  // whole vector among them.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (TermKind kind :
       {TermKind::kLorentz, TermKind::kCriticalPoint, TermKind::kRiouxGap, TermKind::kRiouxEdge}) {
    const PhysicalLayout layout({kind}, 0);
    for (int trial = 0; trial < 50; ++trial) {
      std::vector<double> v = {1.0 + unit(rng), 5.0 + 5.0 * unit(rng), 0.01 + unit(rng)};
      const double a = 0.5 + 50.0 * unit(rng), e0 = 1.0 + 4.0 * unit(rng);
      const double g = 0.005 + 1.5 * unit(rng) * unit(rng);
      if (kind == TermKind::kRiouxGap) {
        v.insert(v.end(), {a, e0, e0 + 0.01 + unit(rng), g});
      } else if (kind == TermKind::kCriticalPoint) {
        v.insert(v.end(), {a, e0, g, kPi * (2.0 * unit(rng) - 1.0)});
      } else {
        v.insert(v.end(), {a, e0, g});
      }
      const size_t m = 1 + static_cast<size_t>(40 * unit(rng));
      std::vector<double> omega(m), eps1(m), eps2(m);
      for (double& w : omega) w = 0.5 + 5.0 * unit(rng);
      kernel::PhysicalPermittivityOnGrid(layout, v.data(), m, omega.data(), eps1.data(),
                                         eps2.data());
      for (size_t i = 0; i < m; ++i) {
        const Cx expected = HeaderPermittivity(layout, v.data(), omega[i]);
        EXPECT_LT(std::abs(Cx(eps1[i], eps2[i]) - expected), 1e-12 * std::abs(expected))
            << TermKindName(kind) << " at " << omega[i] << " eV, " << m << " energies";
      }
    }
  }
}

// XYZ the straightforward way: eps one wavelength at a time (PhysicalPermittivity, the
// templated physics on double), n + ik, Fresnel, the colorimeter's sums.
color::XYZ StraightforwardXYZ(const color::Colorimeter& colorimeter, const PhysicalModel& model,
                              double x, double angle_deg) {
  const std::vector<double> grid =
      color::EvaluationGrid(colorimeter, model.lambda_min_nm(), model.lambda_max_nm(), "");
  std::vector<double> values(model.layout().num_parameters());
  model.ValuesAt(x, model.coeffs().data(), values.data());
  std::vector<Cx> index;
  for (double l : grid) {
    const Complex<double> eps =
        PhysicalPermittivity(model.layout(), values.data(), OmegaEvFromLambdaNm(l));
    const Complex<double> nk = IndexFromPermittivity(eps);
    index.push_back({nk.re, nk.im});
  }
  return color::MaterialXYZ(colorimeter, index, angle_deg);
}

void ExpectSameColour(const PhysicalModel& model, double tolerance, double* worst_seen) {
  const color::Colorimeter colorimeter = color::Colorimeter::Load(DataDir(), "D65", 2);
  for (double angle : {0.0, 60.0}) {
    const color::ColorSweep sweep(colorimeter, model, angle);
    for (int i = 0; i <= 1000; ++i) {
      const double x = model.x_min() + (model.x_max() - model.x_min()) * i / 1000.0;
      const color::XYZ fast = sweep.ExactXYZ(x);
      const color::XYZ plain = StraightforwardXYZ(colorimeter, model, x, angle);
      const double d = std::max(
          {std::abs(fast.X - plain.X), std::abs(fast.Y - plain.Y), std::abs(fast.Z - plain.Z)});
      *worst_seen = std::max(*worst_seen, d);
      ASSERT_LT(d, tolerance) << "x = " << x << ", " << angle << " deg";
    }
  }
}

TEST(PhysicalKernel, ColourOfEveryTermKindEqualsTheStraightforwardChain) {
  double worst = 0;
  ExpectSameColour(EveryKindModel(), 1e-9, &worst);
  EXPECT_LT(worst, 1e-12);  // in fact: rounding
}

TEST(PhysicalKernel, ColourOfTheAuAgDefaultModelEqualsTheStraightforwardChain) {
  const color::Colorimeter d65 = color::Colorimeter::Load(DataDir(), "D65", 2);
  fit::FitSettings settings;
  settings.colorimeter = &d65;
  const std::unique_ptr<AlloyModel> model = fit::BuildModel("auto", AuAg(), settings);
  const PhysicalModel* physical = PhysicalModel::From(model.get());
  ASSERT_NE(physical, nullptr) << "auto chose " << model->method();
  double worst = 0;
  ExpectSameColour(*physical, 1e-9, &worst);
  EXPECT_LT(worst, 1e-12);
}

TEST(PhysicalKernel, BoundModelEqualsPermittivityOnGridsOfAnyLength) {
  const PhysicalModel model = EveryKindModel();
  for (size_t m : {1u, 7u, 8u, 9u, 95u, 300u}) {
    std::vector<double> grid;
    for (size_t j = 0; j < m; ++j) grid.push_back(350.0 + 600.0 * j / std::max<size_t>(m, 2));
    const std::unique_ptr<BoundModel> bound = model.Bind(grid);
    for (double x : {0.0, 0.37, 1.0}) {
      const std::vector<Complex<double>> fast = bound->Permittivity(x);
      const std::vector<Cx> plain = model.Permittivity(x, grid);
      for (size_t j = 0; j < m; ++j) {
        EXPECT_EQ(fast[j].re, plain[j].real()) << m << " " << j;
        EXPECT_EQ(fast[j].im, plain[j].imag()) << m << " " << j;
      }
    }
  }
}

TEST(PhysicalKernel, CovarianceDrawsGoThroughTheKernelAsStraightforwardDrawsWould) {
  // A covariance over every coefficient; the draws' coefficients made here as the model
  // makes them (eigen-decomposition, one normal vector per draw from the seed), eps the
  // straightforward way.
  const PhysicalModel base = EveryKindModel();
  const int nc = base.layout().num_coefficients();
  std::vector<double> covariance(static_cast<size_t>(nc) * nc, 0.0);
  for (int i = 0; i < nc; ++i) {
    for (int j = 0; j < nc; ++j) {
      covariance[i * nc + j] = 1e-4 * std::exp(-std::abs(i - j)) * (1.0 + 0.1 * (i % 3));
    }
  }
  const PhysicalModel model = EveryKindModel(covariance);
  const std::vector<double> grid = {380, 455, 530, 605, 680, 755, 830};
  const double x = 0.4;
  const auto draws = model.PermittivityDraws(x, grid, 16, 7u);
  ASSERT_EQ(draws.size(), 16u);
  Eigen::Map<const Eigen::MatrixXd> c(covariance.data(), nc, nc);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (c + c.transpose()));
  const Eigen::MatrixXd root =
      eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
  std::mt19937 rng(7u);
  std::normal_distribution<double> normal;
  for (const auto& draw : draws) {
    Eigen::VectorXd z(nc);
    for (int d = 0; d < nc; ++d) z[d] = normal(rng);
    const Eigen::VectorXd delta = root * z;
    std::vector<double> coeffs(nc), values(model.layout().num_parameters());
    for (int d = 0; d < nc; ++d) coeffs[d] = model.coeffs()[d] + delta[d];
    model.ValuesAt(x, coeffs.data(), values.data());
    for (size_t j = 0; j < grid.size(); ++j) {
      const Cx expected =
          HeaderPermittivity(model.layout(), values.data(), OmegaEvFromLambdaNm(grid[j]));
      EXPECT_LT(std::abs(draw[j] - expected), 1e-12 * std::abs(expected));
    }
  }
}

TEST(PhysicalKernel, WhereTheApproximationsStopTheStraightforwardPathAnswers) {
  // Rioux's edge with G = 0 exactly at its onset: ln(1 - c^2 / E0^2) of 0. The kernel
  // gives NaN there; the model's grid evaluation then answers as PhysicalPermittivity does,
  // at every wavelength, bit for bit.
  const PhysicalLayout layout({TermKind::kRiouxEdge}, 0);
  const double values[6] = {1.0, 9.0, 0.05, 40.0, 2.0, 0.0};
  const std::vector<double> omega = {1.5, 1.8, 2.0, 2.5, 3.0};
  std::vector<double> eps1(omega.size()), eps2(omega.size());
  kernel::PhysicalPermittivityOnGrid(layout, values, omega.size(), omega.data(), eps1.data(),
                                     eps2.data());
  EXPECT_FALSE(kernel::AllUsable(omega.size(), eps1.data(), eps2.data()));
  const PhysicalModel edge(AuAg(), 300.0, 1000.0, layout, std::vector<double>(6, 1.0), {});
  edge.PermittivityOnGrid(values, omega.size(), omega.data(), eps1.data(), eps2.data());
  for (size_t i = 0; i < omega.size(); ++i) {
    const Complex<double> expected = PhysicalPermittivity(layout, values, omega[i]);
    EXPECT_TRUE(std::memcmp(&eps1[i], &expected.re, sizeof(double)) == 0) << omega[i];
    EXPECT_TRUE(std::memcmp(&eps2[i], &expected.im, sizeof(double)) == 0) << omega[i];
  }
  EXPECT_FALSE(std::isfinite(eps1[2]) && std::isfinite(eps2[2]));
}

// Each term's hand-written gradient (physical_terms.h) against ceres::Jet through the same
// term's value and against central differences, on the double path and in the kernel.
TEST(PhysicalKernel, HandWrittenGradientsAgreeWithJetsAndFiniteDifferences) {
  using Jet = ceres::Jet<double, 4>;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (TermKind kind : {TermKind::kDrude, TermKind::kLorentz, TermKind::kCriticalPoint,
                        TermKind::kRiouxGap, TermKind::kRiouxEdge}) {
    const int n = kind == TermKind::kCriticalPoint || kind == TermKind::kRiouxGap ? 4 : 3;
    for (int trial = 0; trial < 40; ++trial) {
      double v[4];
      const double e0 = 1.0 + 3.0 * unit(rng), g = 0.02 + unit(rng);
      if (kind == TermKind::kDrude) {
        v[0] = 1.0 + unit(rng), v[1] = 5.0 + 4.0 * unit(rng), v[2] = 0.01 + 0.3 * unit(rng);
      } else if (kind == TermKind::kRiouxGap) {
        v[0] = 50.0 * unit(rng) + 1.0, v[1] = e0, v[2] = e0 + 0.05 + unit(rng), v[3] = g;
      } else {
        v[0] = 20.0 * unit(rng) + 0.5, v[1] = e0, v[2] = g, v[3] = kPi * (2 * unit(rng) - 1);
      }
      const double w = 0.5 + 4.0 * unit(rng);
      const TermGradient<double> grad = TermGradientAt(kind, v, w);
      Jet vj[4];
      for (int j = 0; j < n; ++j) vj[j] = Jet(v[j], j);
      const Complex<Jet> jet = kind == TermKind::kDrude
                                   ? DrudePermittivity(Jet(w), vj[1] * vj[1], vj[2], vj[0])
                                   : InterbandPermittivity(kind, vj, w);
      EXPECT_NEAR(grad.value.re, jet.re.a, 1e-12 * std::abs(jet.re.a) + 1e-12);
      EXPECT_NEAR(grad.value.im, jet.im.a, 1e-12 * std::abs(jet.im.a) + 1e-12);
      for (int j = 0; j < n; ++j) {
        const double scale = std::hypot(jet.re.v[j], jet.im.v[j]) + 1e-9;
        EXPECT_NEAR(grad.d[j].re, jet.re.v[j], 1e-9 * scale) << TermKindName(kind) << " " << j;
        EXPECT_NEAR(grad.d[j].im, jet.im.v[j], 1e-9 * scale) << TermKindName(kind) << " " << j;
        // Central differences, independent of both.
        double up[4], down[4];
        std::copy(v, v + 4, up);
        std::copy(v, v + 4, down);
        const double h = 1e-6 * std::max(1.0, std::abs(v[j]));
        up[j] += h;
        down[j] -= h;
        const Cx d = (HeaderTerm(kind, up, w) - HeaderTerm(kind, down, w)) / (2 * h);
        EXPECT_NEAR(grad.d[j].re, d.real(), 1e-5 * (std::abs(d) + 1.0)) << TermKindName(kind);
        EXPECT_NEAR(grad.d[j].im, d.imag(), 1e-5 * (std::abs(d) + 1.0)) << TermKindName(kind);
      }
    }
  }
}

TEST(PhysicalKernel, TheKernelsGradientEqualsTheDoublePathsOnEveryTerm) {
  const PhysicalModel model = EveryKindModel();
  const PhysicalLayout& layout = model.layout();
  const int np = layout.num_parameters();
  std::vector<double> values(np);
  model.ValuesAt(0.37, model.coeffs().data(), values.data());
  for (size_t m : {5u, 8u, 21u}) {
    std::vector<double> omega(m), e1(m), e2(m), g1(np * m), g2(np * m);
    for (size_t i = 0; i < m; ++i) omega[i] = 1.4 + 2.2 * i / m;
    kernel::PhysicalGradientOnGrid(layout, values.data(), m, omega.data(), e1.data(), e2.data(),
                                   g1.data(), g2.data());
    for (size_t i = 0; i < m; ++i) {
      Cx eps = 0.0;
      for (int t = 0; t < layout.num_terms(); ++t) {
        const int o = layout.term_offset(t);
        const TermGradient<double> g = TermGradientAt(layout.term_kind(t), &values[o], omega[i]);
        eps += Cx(g.value.re, g.value.im);
        for (int j = 0; j < layout.term_size(t); ++j) {
          const Cx d(g.d[j].re, g.d[j].im);
          EXPECT_LT(std::abs(Cx(g1[(o + j) * m + i], g2[(o + j) * m + i]) - d),
                    1e-12 * (std::abs(d) + 1e-300))
              << "term " << t << " parameter " << j;
        }
      }
      EXPECT_LT(std::abs(Cx(e1[i], e2[i]) - eps), 1e-13 * std::abs(eps));
    }
  }
}

TEST(PhysicalKernel, AModelFileWithAPoleNarrowerThanTheFloorIsRefusedNamingTheField) {
  const PhysicalModel model = EveryKindModel();
  nlohmann::json doc = model.ToJson();
  EXPECT_NO_THROW(ModelFromJson(doc, "every-kind.json"));
  // The cp term's width (terms[2], its parameters[2]) falls to about 2e-10 eV.
  doc["parameters"]["terms"][2]["parameters"][2]["coefficients"] = {-1000.0, 0.0, 0.0};
  const std::string message = ErrorOf([&] { ModelFromJson(doc, "narrow.json"); });
  EXPECT_NE(message.find("narrow.json"), std::string::npos) << message;
  EXPECT_NE(message.find("parameters.terms[2].parameters[2] (G_eV)"), std::string::npos) << message;
  double width = 0, x = 0;
  // The Lorentz line's (terms[1]): through 0.4, 0.2, 1.5 eV at u = -1, 0, 1 its width is
  // 0.2 + 0.55 u + 0.75 u^2, least at u = -11/30 (x = 19/60), 0.2 - 0.55^2 / 3 eV. Rioux's
  // terms have no pole: their 0.02 eV does not count.
  EXPECT_EQ(model.NarrowestPole(&width, &x), "parameters.terms[1].parameters[2] (G_eV)");
  EXPECT_NEAR(width, 0.2 - 0.55 * 0.55 / 3.0, 1e-4);
  EXPECT_NEAR(x, 19.0 / 60.0, 1.0 / 256);
}

}  // namespace
}  // namespace alloycolor
