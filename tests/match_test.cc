// From colour to composition (color/match.h, `alloycolor match`, `alloycolor tolerance`),
// against independent references: the model's own colour through the material-colour
// chain (MaterialXYZ of IndexOnGrid) on a fine grid (round trip, every composition of equal
// colour), a brute-force walk for the tolerance window, and measured held-out samples
// recovered by leave-one-out.
#include "alloycolor/color/match.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/composition.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/units.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/sample_models.h"
#include "test_util.h"

namespace alloycolor {
namespace {

using testing::DataDir;
using testing::MakeTempDir;
using testing::RunProgram;
using testing::RunResult;

struct AuAg {
  color::Colorimeter colorimeter = color::Colorimeter::Load(DataDir(), "D65", 2);
  Dataset dataset = LoadDataset(DataDir() + "/Au-Ag");
  std::unique_ptr<AlloyModel> model;
  std::string model_path;
  AuAg() {
    model = fit::SharedFitBuilder(colorimeter)("smooth", dataset);
    model_path = MakeTempDir() + "/auag.json";
    testing::WriteText(model_path, model->ToJson().dump());
  }
};

const AuAg& Shared() {
  static const AuAg shared;
  return shared;
}

// The reference colour: the material-colour chain, not the sweep the matcher uses.
color::Lab ChainLab(const color::Colorimeter& c, const AlloyModel& model, double x, double angle) {
  return color::LabFromXYZ(color::MaterialXYZ(c, color::IndexOnGrid(c, model, x), angle),
                           c.White());
}

// Round trip: the model's own colour at compositions 0.0025 apart comes back within
// 0.05 at% wherever colour changes by more than 0.2 dE00 per at%.
TEST(Match, RoundTripRecoversTheComposition) {
  const AuAg& m = Shared();
  const color::ColourMatcher matcher(m.colorimeter, *m.model, {});
  double worst = 0, sum = 0;
  int counted = 0;
  for (int i = 0; i <= 400; ++i) {
    const double x0 = i / 400.0;
    const double h = 1e-3;
    const double speed_per_at =
        color::DeltaE00(ChainLab(m.colorimeter, *m.model, std::max(0.0, x0 - h), 0),
                        ChainLab(m.colorimeter, *m.model, std::min(1.0, x0 + h), 0)) /
        (100 * (std::min(1.0, x0 + h) - std::max(0.0, x0 - h)));
    const std::vector<color::Match> matches =
        matcher.Find(ChainLab(m.colorimeter, *m.model, x0, 0));
    ASSERT_FALSE(matches.empty());
    EXPECT_LT(matches.front().de00, 1e-6) << "x0 " << x0;
    for (size_t j = 1; j < matches.size(); ++j) {
      EXPECT_LE(matches[j - 1].de00, matches[j].de00);
    }
    if (speed_per_at <= 0.2) continue;
    double nearest = 1;
    for (const color::Match& match : matches) {
      nearest = std::min(nearest, std::abs(match.x_atomic - x0));
    }
    EXPECT_LT(100 * nearest, 0.05) << "x0 " << x0 << " speed " << speed_per_at;
    worst = std::max(worst, 100 * nearest);
    sum += 100 * nearest;
    ++counted;
  }
  std::printf(
      "round trip: %d compositions where colour changes > 0.2 dE00/at%%; "
      "max error %.2e at%%, mean %.2e at%%\n",
      counted, worst, sum / counted);
  EXPECT_GT(counted, 300);
}

// Every composition of equal colour is listed: a brute-force exact scan of DeltaE00 to the
// target (chain colour, 2001 points) finds its local minima under 0.05; each is matched.
TEST(Match, ListsEveryCompositionOfEqualColour) {
  const AuAg& m = Shared();
  const color::ColourMatcher matcher(m.colorimeter, *m.model, {});
  std::vector<color::Lab> grid(2001);
  for (int i = 0; i <= 2000; ++i) grid[i] = ChainLab(m.colorimeter, *m.model, i / 2000.0, 0);
  int minima = 0;
  for (int t = 0; t <= 20; ++t) {
    const color::Lab target = ChainLab(m.colorimeter, *m.model, t / 20.0 + 0.013 * (t < 20), 0);
    const std::vector<color::Match> matches = matcher.Find(target);
    std::vector<double> d(grid.size());
    for (size_t i = 0; i < grid.size(); ++i) d[i] = color::DeltaE00(target, grid[i]);
    for (size_t i = 0; i < d.size(); ++i) {
      const bool left = i == 0 || d[i] < d[i - 1];
      const bool right = i + 1 == d.size() || d[i] <= d[i + 1];
      if (!(left && right && d[i] < 0.05)) continue;
      ++minima;
      const double x = i / 2000.0;
      const bool found = std::any_of(matches.begin(), matches.end(), [&](const color::Match& mm) {
        return std::abs(mm.x_atomic - x) <= 1e-3;
      });
      EXPECT_TRUE(found) << "target " << t << ": brute-force minimum at " << x << " not listed";
    }
  }
  EXPECT_GE(minima, 21);
}

// Colour that is not monotone in composition: eps = LinearEps(g(x)) with g rising from 0
// to 0.95 at x = 0.5 and falling to 0.1 at x = 1, interpolated by PCHIP (affine in the
// samples' values, so the model's colour depends on its interpolated g alone): every
// colour between g = 0.1 and 0.95 is reached twice. Both are listed with de00 ~ 0 (checked
// on the material-colour chain), the first at x0, the other beyond the peak.
TEST(Match, ListsBothCompositionsOfARisingAndFallingColour) {
  const std::string dir =
      testing::WriteSyntheticDataset({0.0, 0.25, 0.5, 0.75, 1.0}, [](double x, double lambda_nm) {
        return testing::LinearEps(0.95 * std::sin(kPi * x) + 0.1 * x, lambda_nm);
      });
  const Dataset dataset = LoadDataset(dir);
  const SampleModel model(SampleModel::Kind::kEpsPchip, dataset);
  const color::Colorimeter colorimeter = color::Colorimeter::Load(DataDir(), "D65", 2);
  for (const double x0 : {0.1, 0.3, 0.42}) {
    const color::Lab target = ChainLab(colorimeter, model, x0, 0);
    const std::vector<color::Match> matches = color::MatchColour(colorimeter, model, target);
    std::vector<double> exact;
    for (const color::Match& m : matches) {
      if (m.de00 < 1e-6) exact.push_back(m.x_atomic);
    }
    ASSERT_EQ(exact.size(), 2u) << x0;
    std::sort(exact.begin(), exact.end());
    EXPECT_NEAR(exact[0], x0, 5e-4);
    EXPECT_GT(exact[1], 0.5);
    EXPECT_LT(color::DeltaE00(target, ChainLab(colorimeter, model, exact[1], 0)), 1e-6);
  }
}

// A spectrum written as the model's reflectance at x0 (in percent, wavelength in um,
// semicolon-separated with a decimal comma) is matched back to x0.
TEST(Match, ReflectanceSpectrumRoundTrip) {
  const AuAg& m = Shared();
  const double x0 = 0.4321;
  std::vector<double> grid;
  for (double l = 380; l <= 800; l += 10) grid.push_back(l);
  const std::vector<double> r = color::ReflectanceSpectrum(m.model->Index(x0, grid), 0.0);
  std::string text = "# synthetic\nwavelength (um);R (%)\n";
  for (size_t i = 0; i < grid.size(); ++i) {
    char line[64];
    std::snprintf(line, sizeof line, "%.3f;%.10f\n", grid[i] / 1000, 100 * r[i]);
    std::string s = line;
    for (char& c : s) {
      if (c == '.') c = ',';
    }
    text += s;
  }
  const std::string path = MakeTempDir() + "/r.txt";
  testing::WriteText(path, text);
  const MeasuredReflectance spectrum = ReadReflectanceDelimited(path);
  ASSERT_EQ(spectrum.lambda_nm.size(), grid.size());
  EXPECT_NEAR(spectrum.reflectance[3], r[3], 1e-10);
  const color::ColourMatcher matcher(m.colorimeter, *m.model, {});
  const auto matches = matcher.FindReflectance(spectrum.lambda_nm, spectrum.reflectance, path);
  EXPECT_NEAR(matches.front().x_atomic, x0, 1e-6);
  EXPECT_LT(matches.front().reflectance_rms, 1e-8);
  // Its colour from R read linearly between the 10 nm samples: close, not equal.
  EXPECT_LT(matches.front().de00, 0.05);

  const RunResult run =
      RunProgram({"match", "--model", m.model_path, "--reflectance", path, "--json", "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto doc = nlohmann::json::parse(run.out);
  EXPECT_NEAR(doc["matches"][0]["x_atomic"].get<double>(), x0, 1e-6);
}

// The window against a brute-force walk with the material-colour chain in steps of
// 1e-5 (0.001 at%): within 0.01 at%, at two angles and two illuminants.
TEST(Tolerance, WindowAgreesWithBruteForce) {
  const AuAg& m = Shared();
  const std::vector<color::Colorimeter> colorimeters = {
      m.colorimeter, color::Colorimeter::Load(DataDir(), "A", 2)};
  const std::vector<double> angles = {0.0, 45.0};
  for (const double x0 : {0.2, 0.5, 0.75}) {
    for (const double de : {0.5, 1.0}) {
      color::ToleranceOptions options;
      options.de00 = de;
      options.angles_deg = angles;
      const color::ToleranceWindow w = color::Tolerance(colorimeters, *m.model, x0, options);
      double edges[2];
      for (int side = 0; side < 2; ++side) {
        const double direction = side == 0 ? -1 : 1;
        double x = x0;
        while (true) {
          const double next = x + direction * 1e-5;
          if (next < 0 || next > 1) break;
          double worst = 0;
          for (const auto& c : colorimeters) {
            for (const double a : angles) {
              worst = std::max(worst, color::DeltaE00(ChainLab(c, *m.model, x0, a),
                                                      ChainLab(c, *m.model, next, a)));
            }
          }
          if (worst > de) break;
          x = next;
        }
        edges[side] = x;
      }
      std::printf("tolerance x0 %.2f dE %.1f: window [%.6f, %.6f], brute force [%.6f, %.6f]\n", x0,
                  de, w.x_low, w.x_high, edges[0], edges[1]);
      EXPECT_NEAR(w.x_low, edges[0], 1e-4);
      EXPECT_NEAR(w.x_high, edges[1], 1e-4);
      EXPECT_FALSE(w.clipped_low);
      EXPECT_FALSE(w.clipped_high);
      EXPECT_GT(w.de00_per_x, 0);
    }
  }
}

TEST(Tolerance, ClipsAtTheModelsRange) {
  const AuAg& m = Shared();
  color::ToleranceOptions options;
  options.de00 = 5.0;
  const color::ToleranceWindow w = color::Tolerance({m.colorimeter}, *m.model, 0.99, options);
  EXPECT_TRUE(w.clipped_high);
  EXPECT_EQ(w.x_high, 1.0);
  EXPECT_FALSE(w.clipped_low);

  const RunResult run =
      RunProgram({"tolerance", "--model", m.model_path, "--x", "0.99", "--de", "5", "--json"});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto doc = nlohmann::json::parse(run.out);
  EXPECT_TRUE(doc["clipped_high"].get<bool>());
  EXPECT_NEAR(doc["x_low"].get<double>(), w.x_low, 1e-12);
  EXPECT_GT(doc["de00_per_at_percent"].get<double>(), 0);
  const RunResult text = RunProgram({"tolerance", "--model", m.model_path, "--x", "18k"});
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("dE00 per at%"), std::string::npos) << text.out;
}

// A blue no Au-G alloy has: the plain verdict, exit 0, matches sorted by de00.
TEST(MatchProgram, UnreachableBlueGetsAPlainVerdict) {
  const AuAg& m = Shared();
  const RunResult run =
      RunProgram({"match", "--model", m.model_path, "--lab", "45,5,-45", "--json"});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto doc = nlohmann::json::parse(run.out);
  EXPECT_FALSE(doc["reachable"].get<bool>());
  EXPECT_EQ(doc["verdict"].get<std::string>().rfind("not reachable with Au-Ag: the closest is", 0),
            0u);
  ASSERT_GE(doc["matches"].size(), 1u);
  for (size_t i = 1; i < doc["matches"].size(); ++i) {
    EXPECT_LE(doc["matches"][i - 1]["de00"].get<double>(), doc["matches"][i]["de00"].get<double>());
  }
  for (const auto& match : doc["matches"]) {
    EXPECT_TRUE(match.contains("x_atomic") && match.contains("x_sigma") && match.contains("de00"));
    EXPECT_GT(match["de00"].get<double>(), 1.0);
  }
  const RunResult text = RunProgram({"match", "--model", m.model_path, "--hex", "#2040c0"});
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("not reachable with Au-Ag: the closest is x = "), std::string::npos)
      << text.out;
}

TEST(MatchProgram, ReachableTargetPrintsAllUnits) {
  const AuAg& m = Shared();
  const color::Lab lab = ChainLab(m.colorimeter, *m.model, 0.75, 0);
  char text[128];
  std::snprintf(text, sizeof text, "%.10f,%.10f,%.10f", lab.L, lab.a, lab.b);
  const RunResult run =
      RunProgram({"match", "--model", m.model_path, "--lab", text, "--target-sigma", "0.5"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("75.00 at% Au"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("wt% Au"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find(" k)"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("+-"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("not reachable"), std::string::npos) << run.out;
}

TEST(MatchProgram, BadInputsGiveOneLineNamingTheCulprit) {
  const AuAg& m = Shared();
  const struct {
    std::vector<std::string> args;
    std::string needle;
  } cases[] = {
      {{"--lab", "80,5"}, "--lab"},
      {{"--lab", "80,x,5"}, "--lab"},
      {{"--hex", "#12345g"}, "#12345g"},
      {{"--xyz", "0.5,-1,0.2"}, "XYZ"},
      {{"--reflectance", "/nonexistent/r.csv"}, "/nonexistent/r.csv"},
      {{"--nk", "/nonexistent/nk.csv"}, "/nonexistent/nk.csv"},
      {{"--lab", "80,5,30", "--hex", "#ffffff"}, "exactly one target"},
      {{"--lab", "80,5,30", "--angle", "95"}, "--angle"},
  };
  for (const auto& c : cases) {
    std::vector<std::string> args = {"match", "--model", m.model_path};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const RunResult run = RunProgram(args);
    EXPECT_EQ(run.status, 2) << c.needle;
    EXPECT_EQ(testing::CountLines(run.err), 1) << run.err;
    EXPECT_NE(run.err.find(c.needle), std::string::npos) << run.err;
    EXPECT_TRUE(run.out.empty());
  }
  const std::string dir = MakeTempDir();
  testing::WriteText(dir + "/r.csv", "wavelength_nm,R\n500,0.5\n600,1.7\n");
  const RunResult run =
      RunProgram({"match", "--model", m.model_path, "--reflectance", dir + "/r.csv"});
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find(dir + "/r.csv:3:"), std::string::npos) << run.err;
  const RunResult tol =
      RunProgram({"tolerance", "--model", m.model_path, "--x", "0.5", "--illuminants", "D65,Q"});
  EXPECT_EQ(tol.status, 2);
  EXPECT_EQ(testing::CountLines(tol.err), 1) << tol.err;
}

// validate reports the composition recovered from each held-out sample's colour, per
// method, in report.json (per sample and summarised) and report.html.
TEST(MatchValidate, ReportsTheRecoveredComposition) {
  const std::string out = MakeTempDir() + "/report";
  const RunResult run = RunProgram({"validate", "--data", "Au-Ag", "--methods", "smooth,eps-linear",
                                    "--out", out, "--quiet", "--threads", "1"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("recovery_at%"), std::string::npos) << run.out;
  const auto doc = nlohmann::json::parse(testing::ReadText(out + "/report.json"));
  const auto& smooth = doc["composition_recovery"]["smooth"];
  EXPECT_EQ(smooth["count"].get<int>(), 9);
  EXPECT_LE(smooth["mean_abs_error_at_percent"].get<double>(), 0.3);
  EXPECT_GE(smooth["within_2_sigma"].get<int>(), 8);
  const auto& first = doc["holdouts"][0];
  const auto& recovered = first["results"]["smooth"]["recovered"];
  EXPECT_NEAR(recovered["error_at_percent"].get<double>(),
              100 * (recovered["x_atomic"].get<double>() - first["x"].get<double>()), 1e-9);
  EXPECT_NE(testing::ReadText(out + "/report.html").find("Composition recovered from colour"),
            std::string::npos);
}

// Leave-one-out recovery of measured held-out samples: each interior composition of a data
// set left out in turn, the model built on the rest, the sample's measured n,k matched on
// its colour at normal incidence. The bars: Au-Ag mean error <= 0.3 at%; Cu-Zn
// with Werner's zinc <= 4 wt%; the truth within two sigma for >= 90 % pooled.
struct Recovery {
  double mean_abs_at = 0, mean_abs_wt = 0;
  int within_two_sigma = 0, count = 0;
};

Recovery RecoverHeldOut(const std::string& manifest) {
  const color::Colorimeter colorimeter = color::Colorimeter::Load(DataDir(), "D65", 2);
  const Dataset dataset = LoadDataset(manifest);
  const auto build = fit::SharedFitBuilder(colorimeter);
  const std::vector<double> xs = DistinctCompositions(dataset);
  Recovery r;
  for (size_t i = 1; i + 1 < xs.size(); ++i) {
    const auto model = build("smooth", WithoutSamples(dataset, {xs[i]}));
    for (const Sample& s : dataset.samples) {
      if (s.x_atomic != xs[i]) continue;
      const color::Lab target = color::LabFromXYZ(
          color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, s.nk), 0.0),
          colorimeter.White());
      const color::Match best = color::MatchColour(colorimeter, *model, target).front();
      const double error = best.x_atomic - s.x_atomic;
      const double error_wt = WeightFromAtomicFraction(best.x_atomic, dataset.system) -
                              WeightFromAtomicFraction(s.x_atomic, dataset.system);
      std::printf(
          "  %s x %.4f: recovered %.4f +- %.4f (dE00 left %.2f), error %+.2f at%% "
          "%+.2f wt%%\n",
          dataset.system.Name().c_str(), s.x_atomic, best.x_atomic, best.x_sigma, best.de00,
          100 * error, 100 * error_wt);
      r.mean_abs_at += 100 * std::abs(error);
      r.mean_abs_wt += 100 * std::abs(error_wt);
      r.within_two_sigma += std::abs(error) <= 2 * best.x_sigma;
      ++r.count;
    }
  }
  r.mean_abs_at /= r.count;
  r.mean_abs_wt /= r.count;
  std::printf("%s: %d held-out samples, mean |error| %.3f at%% (%.3f wt%%), %d within 2 sigma\n",
              manifest.c_str(), r.count, r.mean_abs_at, r.mean_abs_wt, r.within_two_sigma);
  return r;
}

TEST(MatchRecovery, HeldOutSamplesByLeaveOneOut) {
  const Recovery au_ag = RecoverHeldOut(DataDir() + "/Au-Ag");
  const Recovery cu_zn = RecoverHeldOut(DataDir() + "/Cu-Zn/dataset-werner-zn.json");
  EXPECT_LE(au_ag.mean_abs_at, 0.3);
  EXPECT_LE(cu_zn.mean_abs_wt, 4.0);
  const int pooled = au_ag.count + cu_zn.count;
  const int within = au_ag.within_two_sigma + cu_zn.within_two_sigma;
  std::printf("pooled: %d of %d within two sigma (%.0f %%)\n", within, pooled,
              100.0 * within / pooled);
  EXPECT_GE(within, 0.9 * pooled);
}

}  // namespace
}  // namespace alloycolor
