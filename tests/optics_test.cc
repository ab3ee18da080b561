// Analytic identities of model/optics.h, for double and for ceres::Jet.
#include "alloycolor/model/optics.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "alloycolor/core/units.h"

namespace alloycolor {
namespace {

TEST(Optics, NormalIncidenceFresnelMatchesClosedForm) {
  // R = ((n-1)^2 + k^2) / ((n+1)^2 + k^2) at 0 degrees, for metals and dielectrics.
  for (double n : {0.05, 0.27, 1.0, 1.5, 3.1}) {
    for (double k : {0.0, 0.5, 2.9, 8.0}) {
      const double expected = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
      const Reflectance<double> r = FresnelReflectance(Complex<double>{n, k}, 1.0);
      EXPECT_NEAR(r.s, expected, 1e-14) << n << " " << k;
      EXPECT_NEAR(r.p, expected, 1e-14) << n << " " << k;
      EXPECT_NEAR(NormalReflectance(Complex<double>{n, k}), expected, 1e-15);
    }
  }
}

TEST(Optics, GrazingIncidenceReflectsEverything) {
  for (double angle : {89.9, 89.99, 90.0}) {
    const double c = std::cos(angle * M_PI / 180.0);
    const Reflectance<double> r = FresnelReflectance(Complex<double>{0.3, 3.0}, std::max(c, 0.0));
    EXPECT_NEAR(r.Average(), 1.0, angle == 90.0 ? 1e-15 : 2e-2) << angle;
  }
}

TEST(Optics, FresnelAgreesWithStdComplexAtOblique) {
  // Independent evaluation of eq. 2-4 with std::complex.
  const std::complex<double> n(0.47, 2.4);
  for (double angle : {10.0, 45.0, 70.0, 85.0}) {
    const double c = std::cos(angle * M_PI / 180.0), s2 = 1 - c * c;
    const std::complex<double> root = std::sqrt(n * n - s2);
    const double rs = std::norm((c - root) / (c + root));
    const double rp = std::norm((n * n * c - root) / (n * n * c + root));
    const Reflectance<double> r = FresnelReflectance(Complex<double>{n.real(), n.imag()}, c);
    EXPECT_NEAR(r.s, rs, 1e-13);
    EXPECT_NEAR(r.p, rp, 1e-13);
    EXPECT_LT(r.p, r.s);  // p polarisation dips toward the principal angle
  }
}

TEST(Optics, DielectricBrewsterAngleHasNoPReflection) {
  const double n = 1.5, brewster = std::atan(n);
  const Reflectance<double> r = FresnelReflectance(Complex<double>{n, 0.0}, std::cos(brewster));
  EXPECT_NEAR(r.p, 0.0, 1e-15);
}

TEST(Optics, PermittivityAndIndexRoundTrip) {
  for (double n : {0.04, 0.3, 1.0, 2.5, 9.0}) {
    for (double k : {0.0, 0.01, 1.0, 3.5, 40.0}) {
      const Complex<double> eps = PermittivityFromIndex(Complex<double>{n, k});
      EXPECT_NEAR(eps.re, n * n - k * k, 1e-12 * (1 + n * n + k * k));
      EXPECT_NEAR(eps.im, 2 * n * k, 1e-12 * (1 + n * k));
      const Complex<double> back = IndexFromPermittivity(eps);
      EXPECT_NEAR(back.re, n, 1e-12 * (1 + n + k)) << n << " " << k;
      EXPECT_NEAR(back.im, k, 1e-12 * (1 + n + k)) << n << " " << k;
    }
  }
}

TEST(Optics, IndexFromPermittivityMatchesEq13And14) {
  // n^2 = (|eps| + eps1) / 2, k^2 = (|eps| - eps1) / 2.
  const Complex<double> eps{-11.4, 1.3};
  const double mod = std::hypot(eps.re, eps.im);
  const Complex<double> nk = IndexFromPermittivity(eps);
  EXPECT_NEAR(nk.re, std::sqrt((mod + eps.re) / 2), 1e-12);
  EXPECT_NEAR(nk.im, std::sqrt((mod - eps.re) / 2), 1e-12);
  EXPECT_EQ(IndexFromPermittivity(Complex<double>{0.0, 0.0}).re, 0.0);
}

TEST(Optics, DrudeInversionRoundTrip) {
  const double omega = OmegaEvFromLambdaNm(620.0);
  for (double gamma : {0.02, 0.1, 1.0, 5.0}) {
    for (double wp2 : {4.0, 81.0, 200.0}) {
      const Complex<double> eps = DrudePermittivity(omega, wp2, gamma);
      ASSERT_TRUE(DrudeInvertible(eps.re, eps.im));
      const DrudePoint p = InvertDrude(omega, eps.re, eps.im);
      EXPECT_NEAR(p.gamma_ev, gamma, 1e-12 * gamma);
      EXPECT_NEAR(p.wp2_ev2, wp2, 1e-10 * wp2);
    }
  }
}

TEST(Optics, DrudeMatchesEq7WithStdComplex) {
  const double omega = 2.0, wp2 = 81.0, gamma = 0.07;
  const std::complex<double> expected =
      1.0 - wp2 / (omega * (omega + std::complex<double>(0, gamma)));
  const Complex<double> eps = DrudePermittivity(omega, wp2, gamma);
  EXPECT_NEAR(eps.re, expected.real(), 1e-13);
  EXPECT_NEAR(eps.im, expected.imag(), 1e-13);
}

TEST(Optics, InversionUndefinedOutsideDrudeDomain) {
  EXPECT_FALSE(DrudeInvertible(1.0, 2.0));   // eps1 >= 1
  EXPECT_FALSE(DrudeInvertible(2.3, 0.5));   // transparent dielectric
  EXPECT_FALSE(DrudeInvertible(-3.0, 0.0));  // eps2 <= 0
  EXPECT_FALSE(DrudeInvertible(NAN, 1.0));
  EXPECT_TRUE(DrudeInvertible(-3.0, 0.4));
}

TEST(Optics, PlasmaConstantGivesGoldPlasmaEnergy) {
  // N_e = 5.90e28 m^-3, m* = m_e: hbar omega_p = 9.02 eV (Ashcroft & Mermin, ch. 1).
  EXPECT_NEAR(std::sqrt(kPlasmaEv2M3 * 5.90e28), 9.02, 0.01);
}

// The same code with ceres::Jet: derivatives against central finite differences.
TEST(Optics, JetDerivativesMatchFiniteDifferences) {
  using Jet = ceres::Jet<double, 2>;
  const double n0 = 0.4, k0 = 2.7, c = std::cos(0.6);
  const Jet n(n0, 0), k(k0, 1);
  const Reflectance<Jet> r = FresnelReflectance(Complex<Jet>{n, k}, Jet(c));
  const double h = 1e-6;
  auto avg = [&](double nn, double kk) {
    return FresnelReflectance(Complex<double>{nn, kk}, c).Average();
  };
  const double dn = (avg(n0 + h, k0) - avg(n0 - h, k0)) / (2 * h);
  const double dk = (avg(n0, k0 + h) - avg(n0, k0 - h)) / (2 * h);
  EXPECT_NEAR(r.Average().a, avg(n0, k0), 1e-15);
  EXPECT_NEAR(r.Average().v[0], dn, 1e-7);
  EXPECT_NEAR(r.Average().v[1], dk, 1e-7);

  const Jet gamma(0.1, 0), wp2(80.0, 1);
  const Complex<Jet> eps = DrudePermittivity(Jet(2.0), wp2, gamma);
  const Complex<Jet> index = IndexFromPermittivity(eps);
  auto k_of = [&](double g, double w) {
    return IndexFromPermittivity(DrudePermittivity(2.0, w, g)).im;
  };
  EXPECT_NEAR(index.im.v[0], (k_of(0.1 + h, 80) - k_of(0.1 - h, 80)) / (2 * h), 1e-6);
  EXPECT_NEAR(index.im.v[1], (k_of(0.1, 80 + h) - k_of(0.1, 80 - h)) / (2 * h), 1e-6);
}

}  // namespace
}  // namespace alloycolor
