// Numerical edges of the chain from n, k to colour: k = 0, n = k, n = k = 0, the largest
// n, k the readers accept, angles 0, 89.9 and 90 degrees, compositions exactly 0 and 1,
// data that only partly cover the CIE range. Each gives a finite colour or a clear error.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/model/optics.h"
#include "test_util.h"

namespace alloycolor::testing {
namespace {

// color --json on a CSV of the given rows "lambda,n,k".
nlohmann::json ColourOf(const std::string& rows, const std::vector<std::string>& extra = {}) {
  const std::string dir = MakeTempDir();
  WriteText(dir + "/nk.csv", "lambda_nm,n,k\n" + rows);
  std::vector<std::string> args = {"color", "--json", "--quiet", "--nk", dir + "/nk.csv"};
  args.insert(args.end(), extra.begin(), extra.end());
  const RunResult r = RunProgram(args);
  EXPECT_EQ(r.status, 0) << r.err;
  if (r.status != 0) return nlohmann::json::object();
  return nlohmann::json::parse(r.out);
}

void ExpectFiniteColour(const nlohmann::json& c) {
  ASSERT_TRUE(c.contains("XYZ"));
  for (const char* key : {"XYZ", "Lab", "linear_srgb"}) {
    for (const auto& v : c[key]) {
      ASSERT_TRUE(v.is_number()) << key << " " << c.dump();
      EXPECT_TRUE(std::isfinite(v.get<double>())) << key << " " << c.dump();
    }
  }
}

// Rows covering 300-900 nm with constant n, k.
std::string Flat(double n, double k) {
  std::string rows;
  for (int l = 300; l <= 900; l += 100) {
    rows += std::to_string(l) + "," + std::to_string(n) + "," + std::to_string(k) + "\n";
  }
  return rows;
}

TEST(NumericalEdges, OpticsAtTheEdges) {
  using C = Complex<double>;
  // k = 0: a dielectric, R = ((n-1)/(n+1))^2 at normal incidence.
  EXPECT_NEAR(FresnelReflectance(C{1.5, 0.0}, 1.0).Average(), 0.04, 1e-15);
  // n = k: eps1 = 0, and eq. 13, 14 give back n = k.
  const C eps = PermittivityFromIndex(C{2.0, 2.0});
  EXPECT_EQ(eps.re, 0.0);
  const C nk = IndexFromPermittivity(eps);
  EXPECT_NEAR(nk.re, 2.0, 1e-15);
  EXPECT_NEAR(nk.im, 2.0, 1e-15);
  // eps = 0 and N = 0 (a perfect reflector).
  EXPECT_EQ(IndexFromPermittivity(C{0.0, 0.0}).re, 0.0);
  EXPECT_EQ(NormalReflectance(C{0.0, 0.0}), 1.0);
  for (double cos_psi : {1.0, 0.5, 0.0}) {  // Rp is 0/0 at normal incidence: its limit, 1
    EXPECT_EQ(FresnelReflectance(C{0.0, 0.0}, cos_psi).Average(), 1.0) << cos_psi;
  }
  // The largest n, k the readers accept (1e6): |eps| ~ 1e12, R finite and near 1.
  for (double cos_psi : {1.0, 0.5, 1e-3, 0.0}) {
    const double r = FresnelReflectance(C{1e6, 1e6}, cos_psi).Average();
    EXPECT_TRUE(std::isfinite(r)) << cos_psi;
    EXPECT_NEAR(r, 1.0, cos_psi > 0.1 ? 1e-5 : 1e-2) << cos_psi;  // Rp dips near grazing
    const C back = IndexFromPermittivity(PermittivityFromIndex(C{1e6, 1e6}));
    EXPECT_NEAR(back.re, 1e6, 1e-3);
  }
  // No interface (N = 1): R = 0 up to and including grazing incidence.
  for (double cos_psi : {1.0, 0.5, 0.0}) {
    EXPECT_EQ(FresnelReflectance(C{1.0, 0.0}, cos_psi).Average(), 0.0) << cos_psi;
  }
  // Grazing incidence on a metal goes to 1.
  EXPECT_GT(FresnelReflectance(C{0.2, 3.0}, std::cos(89.9 * M_PI / 180)).Average(), 0.99);
}

TEST(NumericalEdges, ColourOfEdgeConstants) {
  // k = 0 (glass-like): Y = R = 0.04 at normal incidence.
  nlohmann::json c = ColourOf(Flat(1.5, 0.0));
  ExpectFiniteColour(c);
  EXPECT_NEAR(c["XYZ"][1].get<double>(), 0.04, 1e-6);
  // n = k.
  ExpectFiniteColour(ColourOf(Flat(3.0, 3.0)));
  // n = k = 0 reflects everything.
  c = ColourOf(Flat(0.0, 0.0));
  ExpectFiniteColour(c);
  EXPECT_NEAR(c["XYZ"][1].get<double>(), 1.0, 1e-12);
  // The largest accepted n, k: |eps| ~ 1e12.
  for (const std::string angle : {"0", "45", "89.9", "90"}) {
    c = ColourOf(Flat(1e6, 1e6), {"--angle", angle});
    ExpectFiniteColour(c);
    EXPECT_NEAR(c["XYZ"][1].get<double>(), 1.0, angle == "89.9" ? 1e-3 : 1e-5) << angle;
  }
}

TEST(NumericalEdges, AnglesZeroAndGrazing) {
  const std::string gold = DataDir() + "/Au-Ag/Rioux-Au100Ag0.yml";
  double previous_y = 0;
  for (const std::string angle : {"0", "30", "60", "89", "89.9", "90"}) {
    const RunResult r = RunProgram({"color", "--json", "--quiet", "--nk", gold, "--angle", angle});
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json c = nlohmann::json::parse(r.out);
    ExpectFiniteColour(c);
    const double y = c["XYZ"][1].get<double>();
    EXPECT_GE(y, previous_y - 0.02) << angle;  // brighter towards grazing (after a dip)
    previous_y = y;
  }
  EXPECT_NEAR(previous_y, 1.0, 1e-9);  // 90 degrees: R = 1
}

TEST(NumericalEdges, CompositionsExactlyZeroAndOne) {
  const std::string dir = MakeTempDir();
  ASSERT_EQ(RunProgram({"fit", "--data", "Au-Ag", "--degree", "3", "--no-covariance", "--out",
                        dir + "/smooth.json", "--quiet"})
                .status,
            0);
  const std::vector<std::vector<std::string>> sources = {
      {"--data", "Au-Ag", "--method", "paper"},
      {"--data", "Au-Ag", "--method", "eps-linear"},
      {"--model", dir + "/smooth.json"}};
  for (const auto& source : sources) {
    for (const std::string x : {"0", "1", "0at%", "100wt%", "24k"}) {
      std::vector<std::string> args = {"color", "--json", "--quiet", "--x", x};
      args.insert(args.end(), source.begin(), source.end());
      const RunResult r = RunProgram(args);
      ASSERT_EQ(r.status, 0) << source[1] << " " << x << ": " << r.err;
      ExpectFiniteColour(nlohmann::json::parse(r.out));
    }
    std::vector<std::string> args = {"sweep", "--quiet", "--from",  "0",
                                     "--to",  "1",       "--steps", "2"};
    args.insert(args.end(), source.begin(), source.end());
    const RunResult r = RunProgram(args);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(CountLines(r.out), 3);
    EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  }
  // The paper model at x = 0 and 1 is the pure metals' data.
  for (const auto& [x, file] : {std::pair<std::string, std::string>{"0", "Rioux-Au0Ag100.yml"},
                                {"1", "Rioux-Au100Ag0.yml"}}) {
    const RunResult model = RunProgram(
        {"color", "--json", "--quiet", "--data", "Au-Ag", "--method", "paper", "--x", x});
    const RunResult data =
        RunProgram({"color", "--json", "--quiet", "--nk", DataDir() + "/Au-Ag/" + file});
    ASSERT_EQ(model.status, 0);
    ASSERT_EQ(data.status, 0);
    const auto a = nlohmann::json::parse(model.out), b = nlohmann::json::parse(data.out);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(a["XYZ"][k].get<double>(), b["XYZ"][k].get<double>(), 1e-12);
    }
  }
}

TEST(NumericalEdges, GridsThatPartlyCoverTheCieRange) {
  // 380-780 nm exactly: the CIE grid's 360-380 and 785-830 nm are held at the ends.
  nlohmann::json c = ColourOf("380,0.5,2\n780,0.2,4\n");
  ExpectFiniteColour(c);
  // Less than 380-780 nm: a clear error naming the range needed.
  for (const std::string rows : {"390,0.5,2\n780,0.2,4\n", "380,0.5,2\n770,0.2,4\n"}) {
    const std::string dir = MakeTempDir();
    WriteText(dir + "/short.csv", "lambda_nm,n,k\n" + rows);
    const RunResult r = RunProgram({"color", "--nk", dir + "/short.csv"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(CountLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("short.csv"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("380-780"), std::string::npos) << r.err;
  }
  // Illuminants whose tables are narrower (C: 380-780 nm) and a 10-degree observer.
  c = ColourOf("380,0.5,2\n780,0.2,4\n", {"--illuminant", "C", "--observer", "10"});
  ExpectFiniteColour(c);
}

TEST(NumericalEdges, FarExtrapolationIsFiniteOrRefused) {
  const std::string dir = MakeTempDir();
  // A smooth model fitted on the middle of the range, asked for the ends.
  ASSERT_EQ(RunProgram({"fit", "--data", "Au-Ag", "--exclude", "0,0.1,0.9,1", "--degree", "6",
                        "--no-covariance", "--out", dir + "/inner.json", "--quiet"})
                .status,
            0);
  for (const std::string x : {"0", "1"}) {
    const RunResult r = RunProgram(
        {"color", "--json", "--quiet", "--model", dir + "/inner.json", "--x", x, "--extrapolate"});
    if (r.status == 0) {
      ExpectFiniteColour(nlohmann::json::parse(r.out));
    } else {
      EXPECT_EQ(r.status, 2) << r.err;
      EXPECT_EQ(CountLines(r.err), 1) << r.err;
    }
  }
}

}  // namespace
}  // namespace alloycolor::testing
