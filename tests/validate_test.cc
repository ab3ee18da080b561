// End-to-end tests of `alloycolor validate`, through the real program:
//  - report.json has the documented shape;
//  - a held-out CIEDE2000 recomputed here, independently of the report code, from the
//    measured file and from `alloycolor fit --exclude` + `alloycolor predict` output with
//    the render colorimetry functions, agrees with report.json to 1e-6 (predict writes 17
//    significant digits on the 5 nm grid the report evaluates);
//  - bad --holdout values, an unknown method and an unwritable --out exit with status 2, a
//    one-line message and no report;
//  - infrared data (Nb-Sn) give n, k, reflectance metrics and say that colour is not
//    available;
//  - report.html is self-contained and renders in headless Chromium (skipped without it).
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/core/io.h"
#include "test_util.h"

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
using testing::CountLines;
using testing::DataDir;
using testing::MakeTempDir;
using testing::ReadText;
using testing::RunProgram;
using testing::RunResult;

// One validation of Au-Ag holding out 0.3 and 0.7 together, shared by the tests below.
class AuAgHoldout : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(MakeTempDir());
    run_ = new RunResult(
        RunProgram({"validate", "--data", DataDir() + "/Au-Ag", "--holdout", "0.3,0.7", "--angles",
                    "0,45", "--out", *dir_ + "/report", "--quiet"}));
    if (run_->status == 0) {
      report_ = new nlohmann::json(nlohmann::json::parse(ReadText(*dir_ + "/report/report.json")));
    }
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete run_;
    delete report_;
  }
  void SetUp() override {
    ASSERT_EQ(run_->status, 0) << run_->err;
    ASSERT_NE(report_, nullptr);
  }
  static std::string* dir_;
  static RunResult* run_;
  static nlohmann::json* report_;
};

std::string* AuAgHoldout::dir_ = nullptr;
RunResult* AuAgHoldout::run_ = nullptr;
nlohmann::json* AuAgHoldout::report_ = nullptr;

TEST_F(AuAgHoldout, ReportJsonHasTheDocumentedShape) {
  const nlohmann::json& r = *report_;
  EXPECT_TRUE(run_->err.empty()) << "--quiet printed: " << run_->err;
  EXPECT_EQ(r["format"], "alloycolor-validation");
  EXPECT_TRUE(r["data"].is_string());
  EXPECT_NE(r["data"].get<std::string>().find("Au-Ag"), std::string::npos);
  EXPECT_EQ(r["methods"],
            nlohmann::json({"paper", "eps-linear", "eps-pchip", "eps-spline", "smooth"}));
  EXPECT_EQ(r["mode"], "holdout");
  EXPECT_TRUE(r["delta_e00_available"].get<bool>());
  ASSERT_EQ(r["holdouts"].size(), 2u);
  EXPECT_DOUBLE_EQ(r["holdouts"][0]["x"].get<double>(), 0.3);
  EXPECT_DOUBLE_EQ(r["holdouts"][1]["x"].get<double>(), 0.7);
  for (const auto& h : r["holdouts"]) {
    // Every method trained on the same split: all samples but the two held out.
    EXPECT_EQ(h["train_x"], nlohmann::json({0.0, 0.1, 0.2, 0.4, 0.5, 0.6, 0.8, 0.9, 1.0}));
    for (const std::string method : {"paper", "eps-linear", "smooth"}) {
      SCOPED_TRACE(method + " at x = " + h["x"].dump());
      const auto& m = h["results"][method];
      ASSERT_TRUE(m.is_object());
      ASSERT_TRUE(m["delta_e00"].is_object());
      for (const char* angle : {"0", "45"}) {
        ASSERT_TRUE(m["delta_e00"][angle].is_number());
        EXPECT_GE(m["delta_e00"][angle].get<double>(), 0.0);
        EXPECT_LT(m["delta_e00"][angle].get<double>(), 10.0);
      }
      for (const char* key : {"reflectance_rms", "reflectance_max", "n_max_abs", "k_max_abs"}) {
        ASSERT_TRUE(m[key].is_number()) << key;
        EXPECT_GE(m[key].get<double>(), 0.0) << key;
      }
      EXPECT_LE(m["reflectance_rms"].get<double>(), m["reflectance_max"].get<double>());
    }
    // Every method fitted with three compositions or more has a cross-validated sigma.
    for (const char* method : {"paper", "smooth"}) {
      ASSERT_TRUE(h["results"][method]["delta_e00_sigma"].is_object()) << method;
      EXPECT_GT(h["results"][method]["delta_e00_sigma"]["0"].get<double>(), 0.0) << method;
    }
  }
  for (const char* key : {"delta_e00_0", "delta_e00_45", "reflectance_rms", "reflectance_max",
                          "n_max_abs", "k_max_abs"}) {
    ASSERT_TRUE(r["summary"].contains(key)) << key;
    EXPECT_EQ(r["summary"][key]["smooth"]["count"], 2) << key;
  }
  // stdout carries the summary.
  EXPECT_NE(run_->out.find("delta_e00_0"), std::string::npos);
}

// The measured and predicted colours recomputed here from files, as a user would: both
// over the colorimeter's whole range (360-830 nm, which the data and so the models cover).
TEST_F(AuAgHoldout, DeltaE00AgreesWithPredictOutput) {
  const color::Colorimeter colorimeter = color::Colorimeter::Load(DataDir(), "D65", 2);
  const NkSpectrum measured = ReadNkFile(DataDir() + "/Au-Ag/Rioux-Au30Ag70.yml");
  const auto measured_index = color::IndexOnGrid(colorimeter, measured);
  for (const std::string method : {"paper", "eps-linear", "smooth"}) {
    SCOPED_TRACE(method);
    const std::string model = *dir_ + "/" + method + ".json";
    const RunResult fit = RunProgram({"fit", "--data", DataDir() + "/Au-Ag", "--exclude", "0.3,0.7",
                                      "--method", method, "--out", model, "--quiet"});
    ASSERT_EQ(fit.status, 0) << fit.err;
    const RunResult predict =
        RunProgram({"predict", "--model", model, "--x", "0.3", "--lambda-from", "360",
                    "--lambda-to", "830", "--lambda-step", "1"});
    ASSERT_EQ(predict.status, 0) << predict.err;
    const std::string csv = *dir_ + "/" + method + ".csv";
    testing::WriteText(csv, predict.out);
    const auto predicted_index = color::IndexOnGrid(colorimeter, ReadNkCsv(csv));
    for (double angle : {0.0, 45.0}) {
      const color::Lab a = color::LabFromXYZ(color::MaterialXYZ(colorimeter, measured_index, angle),
                                             colorimeter.White());
      const color::Lab b = color::LabFromXYZ(
          color::MaterialXYZ(colorimeter, predicted_index, angle), colorimeter.White());
      const double expected = color::DeltaE00(a, b);
      const std::string key = angle == 0.0 ? "0" : "45";
      const double reported =
          (*report_)["holdouts"][0]["results"][method]["delta_e00"][key].get<double>();
      EXPECT_NEAR(reported, expected, 1e-6) << "angle " << angle;
    }
  }
}

TEST_F(AuAgHoldout, HtmlIsSelfContained) {
  const std::string html = ReadText(*dir_ + "/report/report.html");
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("</html>"), std::string::npos);
  EXPECT_NE(html.find("<table"), std::string::npos);
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_NE(html.find("class=\"best\""), std::string::npos);
  // Nothing is fetched: no scripts, links, images or external urls (the SVG namespace
  // name is an identifier, not a fetch).
  for (const char* bad : {"<script", "<link", "<img", "src=", "@import", "https:"}) {
    EXPECT_EQ(html.find(bad), std::string::npos) << bad;
  }
  std::string rest = html;
  for (size_t p; (p = rest.find("http://www.w3.org/2000/svg")) != std::string::npos;) {
    rest.erase(p, 26);
  }
  EXPECT_EQ(rest.find("http:"), std::string::npos);
  for (size_t p = 0; (p = html.find("url(", p)) != std::string::npos; ++p) {
    EXPECT_EQ(html.compare(p, 5, "url(#"), 0) << html.substr(p, 40);
  }
  // The measured and predicted swatch colours of the report appear in the page.
  for (const auto& h : (*report_)["holdouts"]) {
    EXPECT_NE(html.find(h["measured"]["srgb_hex"]["0"].get<std::string>()), std::string::npos);
    EXPECT_NE(html.find(h["results"]["smooth"]["srgb_hex"]["45"].get<std::string>()),
              std::string::npos);
  }
}

// RGBA pixels of a PNG file (libpng's simplified API).
std::vector<std::uint8_t> ReadPng(const std::string& path, int* width, int* height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return {};
  image.format = PNG_FORMAT_RGBA;
  std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) return {};
  *width = static_cast<int>(image.width);
  *height = static_cast<int>(image.height);
  return pixels;
}

TEST_F(AuAgHoldout, RendersInHeadlessChromium) {
  if (!fs::exists("/usr/bin/chromium")) {
    GTEST_SKIP() << "/usr/bin/chromium is absent (Debian package chromium)";
  }
  const std::string shot = *dir_ + "/shot.png";
  const std::string command =
      "timeout 120 /usr/bin/chromium --headless --no-sandbox --disable-gpu --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync "
      "--user-data-dir=" +
      *dir_ + "/chromium-profile --screenshot=" + shot + " --window-size=1200,4000 file://" +
      *dir_ + "/report/report.html >" + *dir_ + "/chromium.log 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << ReadText(*dir_ + "/chromium.log");
  int width = 0, height = 0;
  const std::vector<std::uint8_t> px = ReadPng(shot, &width, &height);
  ASSERT_FALSE(px.empty()) << "cannot read " << shot;
  EXPECT_EQ(width, 1200);
  EXPECT_EQ(height, 4000);
  // Not blank: a fair share of non-white pixels and many distinct colours.
  long non_white = 0;
  std::set<std::uint32_t> colours;
  std::map<std::uint32_t, long> counts;
  for (size_t i = 0; i + 3 < px.size(); i += 4) {
    const std::uint32_t c = (px[i] << 16) | (px[i + 1] << 8) | px[i + 2];
    non_white += c != 0xffffff;
    colours.insert(c);
    ++counts[c];
  }
  EXPECT_GT(non_white, static_cast<long>(width) * height / 50);
  EXPECT_GT(colours.size(), 100u);
  // The measured swatch of x = 0.3 is painted (a 96 x 64 chip, less its border).
  const std::string hex = (*report_)["holdouts"][0]["measured"]["srgb_hex"]["0"];
  const std::uint32_t swatch = std::stoul(hex.substr(1), nullptr, 16);
  EXPECT_GT(counts[swatch], 3000) << "swatch " << hex << " not found in the screenshot";
}

TEST(Validate, InfraredDataHaveNoColourButSpectralMetrics) {
  const std::string dir = MakeTempDir();
  const RunResult run =
      RunProgram({"validate", "--data", DataDir() + "/Nb-Sn", "--loo", "--methods",
                  "paper,eps-linear", "--out", dir + "/r", "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto r = nlohmann::json::parse(ReadText(dir + "/r/report.json"));
  EXPECT_EQ(r["mode"], "loo");
  EXPECT_FALSE(r["delta_e00_available"].get<bool>());
  EXPECT_NE(r["metric_ranges"]["delta_e00"].get<std::string>().find("not available"),
            std::string::npos);
  ASSERT_EQ(r["holdouts"].size(), 7u);  // the interior samples
  for (const auto& h : r["holdouts"]) {
    EXPECT_NE(h["metric_range"].get<std::string>().find("1000-"), std::string::npos);
    for (const char* method : {"paper", "eps-linear"}) {
      const auto& m = h["results"][method];
      EXPECT_TRUE(m["delta_e00"].is_null());
      EXPECT_TRUE(m["reflectance_rms"].is_number());
      EXPECT_TRUE(m["k_max_abs"].is_number());
    }
  }
  const std::string html = ReadText(dir + "/r/report.html");
  EXPECT_NE(html.find("not available"), std::string::npos);
  fs::remove_all(dir);
}

// A line per method by default; with --verbose, a line per split too.
TEST(Validate, LeaveOneOutReportsProgress) {
  const std::string dir = MakeTempDir();
  const RunResult quiet = RunProgram({"validate", "--data", DataDir() + "/Cu-Zn", "--loo",
                                      "--methods", "paper,eps-linear", "--out", dir});
  ASSERT_EQ(quiet.status, 0) << quiet.err;
  EXPECT_NE(quiet.err.find("validate: eps-linear on 3 splits"), std::string::npos) << quiet.err;
  EXPECT_EQ(quiet.err.find("validate [1/6]"), std::string::npos) << quiet.err;
  const RunResult run = RunProgram({"validate", "--data", DataDir() + "/Cu-Zn", "--loo",
                                    "--methods", "paper,eps-linear", "--out", dir, "--verbose"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.err.find("validate [1/6] paper"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("validate [6/6] eps-linear"), std::string::npos) << run.err;
  const auto r = nlohmann::json::parse(ReadText(dir + "/report.json"));
  ASSERT_EQ(r["holdouts"].size(), 3u);
  // A weight-fraction manifest: x is the atomic fraction, x_given the manifest's number.
  EXPECT_DOUBLE_EQ(r["holdouts"][1]["x_given"].get<double>(), 0.85);
  EXPECT_NEAR(r["holdouts"][1]["x"].get<double>(), 0.8536, 1e-4);
  fs::remove_all(dir);
}

TEST(Validate, HoldoutMatchesTheManifestNumbers) {
  const std::string dir = MakeTempDir();
  const RunResult run = RunProgram({"validate", "--data", DataDir() + "/Cu-Zn", "--holdout", "0.85",
                                    "--methods", "eps-linear", "--out", dir, "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto r = nlohmann::json::parse(ReadText(dir + "/report.json"));
  ASSERT_EQ(r["holdouts"].size(), 1u);
  EXPECT_EQ(r["holdouts"][0]["file"], "Querry-Cu85Zn15.yml");
  fs::remove_all(dir);
}

// A failing run: status 2, one line naming `needle`, no report folder.
void ExpectRefused(const std::vector<std::string>& extra, const std::string& needle) {
  const std::string dir = MakeTempDir();
  std::vector<std::string> args = {"validate", "--data",        DataDir() + "/Au-Ag",
                                   "--out",    dir + "/report", "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  const RunResult run = RunProgram(args);
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_EQ(CountLines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find(needle), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir + "/report/report.json"));
  EXPECT_FALSE(fs::exists(dir + "/report/report.html"));
  fs::remove_all(dir);
}

TEST(Validate, RefusesAHoldoutThatIsNotASample) {
  ExpectRefused({"--holdout", "0.3,0.35"}, "0.35");
}

TEST(Validate, RefusesAnEndSampleAsHoldout) {
  ExpectRefused({"--holdout", "0"}, "end sample");
  ExpectRefused({"--holdout", "0.5,1"}, "end sample");
}

TEST(Validate, RefusesBadOptions) {
  ExpectRefused({"--holdout", "0.3", "--loo"}, "not both");
  ExpectRefused({"--holdout", "0.3", "--methods", "paper,nonesuch"}, "nonesuch");
  ExpectRefused({"--holdout", "0.3", "--angles", "95"}, "--angles");
}

TEST(Validate, UnwritableOutExitsTwoWithoutAReport) {
  const std::string dir = MakeTempDir();
  testing::WriteText(dir + "/file", "not a folder\n");
  for (const std::string out : {dir + "/file", dir + "/file/report"}) {
    const RunResult run = RunProgram({"validate", "--data", DataDir() + "/Au-Ag", "--holdout",
                                      "0.5", "--methods", "paper", "--out", out, "--quiet"});
    EXPECT_EQ(run.status, 2) << run.err;
    EXPECT_EQ(CountLines(run.err), 1) << run.err;
    EXPECT_NE(run.err.find(dir + "/file"), std::string::npos) << run.err;
  }
  // Nothing but the file we made.
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.path().filename() != "file";
  EXPECT_EQ(entries, 0);
  EXPECT_EQ(ReadText(dir + "/file"), "not a folder\n");
  fs::remove_all(dir);
}

TEST(Validate, ReplacesAnOldReportWhole) {
  const std::string dir = MakeTempDir();
  testing::WriteText(dir + "/report.json", "old");
  const RunResult run = RunProgram({"validate", "--data", DataDir() + "/Au-Ag", "--holdout", "0.5",
                                    "--methods", "eps-linear", "--out", dir, "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NO_THROW(nlohmann::json::parse(ReadText(dir + "/report.json")));
  // No temporary or probe files left behind.
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename());
  EXPECT_EQ(names, (std::set<std::string>{"report.json", "report.html"}));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace alloycolor

namespace alloycolor {
namespace {

// fit --method auto: every method's leave-one-out score in the model file equals the mean
// CIEDE2000 that `validate --loo` reports for that method on its own, and the chosen method
// lies within 10 % of the lowest.
TEST(AutoMethod, ChoosesTheLowestLeaveOneOutScoreAndRecordsTheTable) {
  const std::string dir = MakeTempDir();
  const std::string data = DataDir() + "/Cu-Zn/dataset-werner-zn.json";
  const RunResult fit = RunProgram({"fit", "--data", data, "--out", dir + "/auto.json"});
  ASSERT_EQ(fit.status, 0) << fit.err;
  EXPECT_NE(fit.err.find("auto chose"), std::string::npos) << fit.err;
  std::ifstream in(dir + "/auto.json");
  const nlohmann::json model = nlohmann::json::parse(in);
  const nlohmann::json& selection = model["fit"]["selection"];
  ASSERT_TRUE(selection.is_object()) << model["fit"].dump();
  const RunResult loo =
      RunProgram({"validate", "--data", data, "--loo", "--methods",
                  "paper,eps-linear,eps-pchip,eps-spline,smooth", "--out", dir + "/v", "--quiet"});
  ASSERT_EQ(loo.status, 0) << loo.err;
  std::ifstream rin(dir + "/v/report.json");
  const nlohmann::json report = nlohmann::json::parse(rin);
  std::map<std::string, double> mean;
  for (const auto& row : selection["scores"]) {
    if (row.contains("mean")) mean[row["method"]] = row["mean"].get<double>();
  }
  for (const char* m : {"paper", "eps-linear", "eps-pchip", "eps-spline", "smooth"}) {
    ASSERT_TRUE(mean.count(m)) << m;
    EXPECT_NEAR(mean[m], report["summary"]["delta_e00_0"][m]["mean"].get<double>(), 1e-9) << m;
  }
  const std::string chosen = model["method"];
  for (const auto& [m, v] : mean) EXPECT_LE(mean[chosen], 1.10 * v + 1e-12) << m;
  EXPECT_NE(selection["reason"].get<std::string>().find(chosen), std::string::npos);
}

// Three compositions of Cu-Zn (zinc, 90 % and pure copper): the one fold holds out 90 %
// and fits the two ends, where the physical model can only be degree 1, while it is
// delivered at degree 2. That fold scores another model, so auto leaves physical unscored
// (on this fold its degree-1 fit beat the line, 1.1 against 6.0, and was taken; delivered,
// it erred 5.4 at 71 % and 85 % against eps-pchip's 2.9) and, with one fold, takes smooth.
TEST(AutoMethod, DoesNotScoreThePhysicalModelOnFoldsTooSmallForItsDegree) {
  const std::string dir = MakeTempDir();
  for (const char* f : {"Werner-Zn100.yml", "Querry-Cu90Zn10.yml", "Querry-Cu100.yml"}) {
    fs::copy_file(DataDir() + "/Cu-Zn/" + f, dir + "/" + f);
  }
  testing::WriteText(dir + "/dataset.json",
                     R"({"system": {"a": "Cu", "b": "Zn"}, "composition": "weight_fraction_a",
                         "samples": [{"x": 0.0, "file": "Werner-Zn100.yml"},
                                     {"x": 0.9, "file": "Querry-Cu90Zn10.yml"},
                                     {"x": 1.0, "file": "Querry-Cu100.yml"}]})");
  const RunResult fit = RunProgram({"fit", "--data", dir, "--quiet", "--out", dir + "/a.json"});
  ASSERT_EQ(fit.status, 0) << fit.err;
  std::ifstream in(dir + "/a.json");
  const nlohmann::json model = nlohmann::json::parse(in);
  EXPECT_EQ(model["method"], "smooth");
  bool seen = false;
  for (const auto& row : model["fit"]["selection"]["scores"]) {
    if (row["method"] != "physical") continue;
    seen = true;
    EXPECT_FALSE(row.contains("mean")) << row.dump();
    EXPECT_NE(row.dump().find("cannot fit its degree 2"), std::string::npos) << row.dump();
  }
  EXPECT_TRUE(seen);
}

// auto on `data` takes `chosen` although `lowest` has a leave-one-out mean more than 10 %
// below it (so the 10 % rule alone would not take it), and says why: checked by hand from
// `validate --loo`'s folds (the same folds) that `lowest`'s worst fold is not below
// `chosen`'s best. `folds`: how many there were.
void ExpectChoiceWithinTheFoldsScatter(const std::string& data, const std::string& chosen,
                                       const std::string& lowest, size_t* folds) {
  const std::string dir = MakeTempDir();
  const RunResult fit = RunProgram({"fit", "--data", data, "--quiet", "--out", dir + "/a.json"});
  ASSERT_EQ(fit.status, 0) << fit.err;
  std::ifstream in(dir + "/a.json");
  const nlohmann::json model = nlohmann::json::parse(in);
  const RunResult loo = RunProgram({"validate", "--data", data, "--loo", "--methods",
                                    chosen + "," + lowest, "--out", dir + "/v", "--quiet"});
  ASSERT_EQ(loo.status, 0) << loo.err;
  std::ifstream rin(dir + "/v/report.json");
  const nlohmann::json report = nlohmann::json::parse(rin);
  double taken = 0, other = 0, taken_best = 1e300, other_worst = 0;
  *folds = 0;
  for (const auto& h : report["holdouts"]) {
    const double a = h["results"][chosen]["reflectance_rms"].get<double>();
    const double b = h["results"][lowest]["reflectance_rms"].get<double>();
    taken += a;
    other += b;
    taken_best = std::min(taken_best, a);
    other_worst = std::max(other_worst, b);
    ++*folds;
  }
  ASSERT_GE(*folds, 2u);
  ASSERT_GT(taken, 1.10 * other);
  ASSERT_GE(other_worst, taken_best);
  EXPECT_EQ(model["method"], chosen);
  const std::string reason = model["fit"]["selection"]["reason"];
  EXPECT_NE(reason.find("the range of the folds"), std::string::npos) << reason;
  EXPECT_NE(reason.find(lowest), std::string::npos) << reason;
}

// Nb-Sn's leave-one-out: smooth, auto's default, scores lowest and is taken.
TEST(AutoMethod, KeepsTheDefaultWhereItScoresLowest) {
  const std::string dir = MakeTempDir();
  const RunResult fit = RunProgram({"fit", "--data", "Nb-Sn", "--quiet", "--out", dir + "/a.json"});
  ASSERT_EQ(fit.status, 0) << fit.err;
  std::ifstream in(dir + "/a.json");
  const nlohmann::json model = nlohmann::json::parse(in);
  EXPECT_EQ(model["method"], "smooth");
  const std::string reason = model["fit"]["selection"]["reason"];
  EXPECT_NE(reason.find("lowest"), std::string::npos) << reason;
  EXPECT_EQ(model["fit"]["selection"]["scores"][0]["folds"], 7);
}

// A data set of the given bundled Nb-Sn samples (x: the manifest's numbers) in a new folder.
std::string NbSnSubset(const std::vector<std::pair<double, std::string>>& samples) {
  const std::string dir = MakeTempDir();
  std::string list;
  for (const auto& [x, file] : samples) {
    fs::copy_file(DataDir() + "/Nb-Sn/" + file, dir + "/" + file);
    list += (list.empty() ? "" : ", ") + std::string("{\"x\": ") + std::to_string(x) +
            ", \"file\": \"" + file + "\"}";
  }
  testing::WriteText(dir + "/dataset.json",
                     R"({"system": {"a": "Sn", "b": "Nb"}, "composition": "weight_fraction_a",
                         "samples": [)" +
                         list + "]}");
  return dir;
}

// From two folds: Nb-Sn at 0, 6, 34 and 100 wt% Sn, where eps-spline's mean is 40 % below
// smooth's (auto's default) but the two folds disagree: eps-spline's worst is above
// smooth's best. On the five samples held back from this subset, eps-spline errs more.
TEST(AutoMethod, WeighsALeadByTheScatterOfTwoFolds) {
  const std::string dir = NbSnSubset({{0.0, "Golovashkin-Nb-293K.yml"},
                                      {0.06, "Golovashkin-06.yml"},
                                      {0.34, "Golovashkin-34.yml"},
                                      {1.0, "Golovashkin-Sn-293K.yml"}});
  size_t folds = 0;
  ExpectChoiceWithinTheFoldsScatter(dir, "smooth", "eps-spline", &folds);
  EXPECT_EQ(folds, 2u);
  const RunResult held =
      RunProgram({"validate", "--data", "Nb-Sn", "--holdout", "0.22,0.28,0.3,0.4,0.55", "--methods",
                  "smooth,eps-spline", "--out", dir + "/h", "--quiet"});
  ASSERT_EQ(held.status, 0) << held.err;
  std::ifstream hin(dir + "/h/report.json");
  const nlohmann::json h = nlohmann::json::parse(hin)["summary"];
  EXPECT_LT(h["reflectance_rms"]["smooth"]["mean"].get<double>(),
            h["reflectance_rms"]["eps-spline"]["mean"].get<double>());
}

// One fold (three compositions: Au-Ag at 0, 10 and 100 at% Au): paper's straight line scores
// lowest on it, but auto takes smooth and says why; held out, the other eight samples
// are far better predicted by smooth (auto) than by paper, and better than by eps-linear.
TEST(AutoMethod, TakesSmoothWithOneFold) {
  const std::string dir = MakeTempDir();
  const std::string held_out = "0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9";
  const RunResult fit = RunProgram(
      {"fit", "--data", "Au-Ag", "--exclude", held_out, "--quiet", "--out", dir + "/a.json"});
  ASSERT_EQ(fit.status, 0) << fit.err;
  std::ifstream in(dir + "/a.json");
  const nlohmann::json model = nlohmann::json::parse(in);
  EXPECT_EQ(model["method"], "smooth");
  std::map<std::string, double> score;
  for (const auto& row : model["fit"]["selection"]["scores"]) {
    if (row.contains("mean")) score[row["method"]] = row["mean"].get<double>();
  }
  ASSERT_LT(score["paper"] * 1.10, score["smooth"]);  // the fold alone would take paper
  const std::string reason = model["fit"]["selection"]["reason"];
  EXPECT_NE(reason.find("one fold"), std::string::npos) << reason;
  const RunResult held =
      RunProgram({"validate", "--data", "Au-Ag", "--holdout", held_out, "--methods",
                  "paper,eps-linear,auto", "--angles", "0", "--out", dir + "/h", "--quiet"});
  ASSERT_EQ(held.status, 0) << held.err;
  std::ifstream hin(dir + "/h/report.json");
  const nlohmann::json summary = nlohmann::json::parse(hin)["summary"]["delta_e00_0"];
  const double automatic = summary["auto"]["mean"], linear = summary["eps-linear"]["mean"];
  EXPECT_LT(automatic, linear);
  EXPECT_LT(5 * automatic, summary["paper"]["mean"].get<double>());
}

// Au-Ag with scatter added as a real series has it: each sample's n and k times
// 1 + c0 + c1 u + c2 sin(pi u) + c3 cos(pi u) (u the wavelength scaled to [0, 1]; the c
// drawn once from a normal law of 2 % and written below), the 70 % sample left out. The
// physical fit's degree-1 candidate stays physical but, finished, is not passive at the
// silver end. auto (the default) records physical as not scored and chooses among the
// others: before, the physical fit's error ended auto itself. The physical method alone is
// refused with that one-line error.
TEST(AutoMethod, GoesOnWhenThePhysicalFitIsRefused) {
  static const double kScatter[11][8] = {
      // per sample, x = 0, 0.1, ..., 1: c for n, for k
      {0.0069, 0.0164, 0.0066, -0.0261, 0.0181, 0.0089, -0.0107, 0.0116},
      {0.0073, 0.0059, 0.0006, 0.0109, -0.0147, -0.0033, -0.0096, 0.012},
      {0.0008, -0.0058, -0.0156, -0.0051, 0.0002, -0.0055, 0.0259, 0.0201},
      {-0.0542, -0.0378, -0.0035, -0.0084, 0.0043, 0.0043, 0.0424, -0.0222},
      {-0.0076, 0.0409, 0.0129, 0.0133, -0.0103, -0.033, 0.0033, 0.0022},
      {-0.0245, -0.0137, -0.0014, -0.0189, -0.002, 0.0019, 0.0007, -0.0101},
      {0.0119, 0.0178, 0.0064, -0.0164, 0.0146, -0.01, 0.0176, -0.0214},
      {0.0183, -0.0004, -0.025, -0.0063, 0.0011, 0.0055, -0.0196, -0.0221},
      {0.004, -0.0093, 0.0047, 0.0152, -0.033, 0.0051, 0.0245, -0.006},
      {-0.0162, 0.015, 0.0051, 0.0179, -0.0069, -0.0296, -0.0022, -0.0089},
      {0.0155, 0.0039, -0.0326, -0.0239, 0.0177, 0.0136, -0.0128, 0.0}};
  const std::string dir = MakeTempDir();
  std::string list;
  for (int i = 0; i <= 10; ++i) {
    if (i == 7) continue;
    const std::string name =
        "Rioux-Au" + std::to_string(10 * i) + "Ag" + std::to_string(100 - 10 * i) + ".yml";
    const NkSpectrum s = ReadNkFile(DataDir() + "/Au-Ag/" + name);
    const double* c = kScatter[i];
    std::string text = "DATA:\n  - type: tabulated nk\n    data: |\n";
    for (size_t j = 0; j < s.lambda_nm.size(); ++j) {
      const double u =
          (s.lambda_nm[j] - s.lambda_min_nm()) / (s.lambda_max_nm() - s.lambda_min_nm());
      const double su = std::sin(M_PI * u), cu = std::cos(M_PI * u);
      const double n = s.n[j] * (1 + (c[0] + c[1] * u + c[2] * su + c[3] * cu));
      const double k = s.k[j] * (1 + (c[4] + c[5] * u + c[6] * su + c[7] * cu));
      char line[96];
      std::snprintf(line, sizeof line, "        %.17g %.17g %.17g\n", s.lambda_nm[j] / 1000, n, k);
      text += line;
    }
    testing::WriteText(dir + "/" + name, text);
    list += (list.empty() ? "" : ", ") + std::string("{\"x\": ") + std::to_string(0.1 * i) +
            ", \"file\": \"" + name + "\"}";
  }
  testing::WriteText(dir + "/dataset.json",
                     R"({"system": {"a": "Au", "b": "Ag"}, "composition": "atomic_fraction_a",
                         "samples": [)" +
                         list + "]}");
  const RunResult fit =
      RunProgram({"fit", "--data", dir, "--no-covariance", "--quiet", "--out", dir + "/a.json"});
  ASSERT_EQ(fit.status, 0) << fit.err;
  std::ifstream in(dir + "/a.json");
  const nlohmann::json model = nlohmann::json::parse(in);
  EXPECT_NE(model["method"], "physical");
  bool refused = false;
  for (const auto& row : model["fit"]["selection"]["scores"]) {
    if (row["method"] != "physical") continue;
    EXPECT_FALSE(row.contains("mean")) << row.dump();
    refused = row.value("error", "").find("the physical fit") != std::string::npos;
  }
  EXPECT_TRUE(refused) << model["fit"]["selection"].dump();
  const RunResult physical = RunProgram({"fit", "--data", dir, "--method", "physical",
                                         "--no-covariance", "--quiet", "--out", dir + "/p.json"});
  EXPECT_EQ(physical.status, 2);
  EXPECT_EQ(CountLines(physical.err), 1) << physical.err;
  EXPECT_NE(physical.err.find("the physical fit"), std::string::npos) << physical.err;
  EXPECT_FALSE(fs::exists(dir + "/p.json"));
}

// A method that fails on every split (the physical fit refuses Querry's zinc) is reported
// failed beside the others; the printed coverage counts agree with report.json.
TEST(Validate, AMethodFailingEverywhereIsReportedBesideTheOthers) {
  const std::string out = MakeTempDir() + "/r";
  const RunResult r = RunProgram({"validate", "--data", DataDir() + "/Cu-Zn", "--methods",
                                  "eps-linear,physical", "--angles", "0", "--quiet", "--out", out});
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  for (const auto& h : report["holdouts"]) {
    EXPECT_TRUE(h["results"]["eps-linear"]["delta_e00"]["0"].is_number());
  }
  bool physical_error = false;
  for (const auto& s : report["splits"]) {
    physical_error |= s.contains("errors") && s["errors"].contains("physical");
  }
  EXPECT_TRUE(physical_error) << report["splits"].dump();
  const auto& cell = report["sigma_honesty"]["eps-linear"]["0"];
  const std::string expected = std::to_string(cell["within_1_sigma"].get<int>()) + "/" +
                               std::to_string(cell["count"].get<int>());
  const size_t row = r.out.find("in_1sigma_0");
  ASSERT_NE(row, std::string::npos) << r.out;
  EXPECT_NE(r.out.substr(row, r.out.find('\n', row) - row).find(expected), std::string::npos)
      << r.out;
}

// Issue 11's test of honest error bars: pooled over every leave-one-out fold of the bundled
// colour sets (Au-Ag, Cu-Zn with Querry's and with Werner's zinc) and over the methods, the
// held-out CIEDE2000 falls within one sigma 55-80 % of the time and within two 90 % or more
// (measured 55/75 and 73/75; the calibration before the geometric mean and the linear
// methods' squared gap gave 65/75). Held-out data against each method's own claim; the same
// counts `validate` prints. Physical (8/11 and 10/11) is left out: its joint fits take five
// times the others' time, minutes under the sanitizers.
TEST(Validate, PooledLeaveOneOutCoverageOfTheBundledSetsIsInTheIssuesBand) {
  const std::string dir = MakeTempDir();
  const std::vector<std::string> sets = {DataDir() + "/Au-Ag", DataDir() + "/Cu-Zn",
                                         DataDir() + "/Cu-Zn/dataset-werner-zn.json"};
  int count = 0, within_1 = 0, within_2 = 0;
  for (size_t i = 0; i < sets.size(); ++i) {
    const std::string out = dir + "/r" + std::to_string(i);
    const RunResult r = RunProgram({"validate", "--data", sets[i], "--loo", "--methods",
                                    "paper,eps-linear,eps-pchip,eps-spline,smooth", "--angles", "0",
                                    "--quiet", "--out", out});
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json report = nlohmann::json::parse(ReadText(out + "/report.json"));
    for (const auto& [method, angles] : report["sigma_honesty"].items()) {
      count += angles["0"]["count"].get<int>();
      within_1 += angles["0"]["within_1_sigma"].get<int>();
      within_2 += angles["0"]["within_2_sigma"].get<int>();
    }
  }
  ASSERT_EQ(count, 75);  // 15 folds for each of five methods
  EXPECT_GE(within_1, 0.55 * count) << within_1 << "/" << count;
  EXPECT_LE(within_1, 0.80 * count) << within_1 << "/" << count;
  EXPECT_GE(within_2, 0.90 * count) << within_2 << "/" << count;
}

// The folds and splits run on several threads or on one: the report is the same to the
// byte (each task writes its own result; nothing depends on which finishes first), and
// so is a fitted model file with its prediction error.
TEST(Validate, TheSameOnOneThreadAsOnSeveral) {
  // The model files' history records when they were fitted: one date for both runs.
  setenv("SOURCE_DATE_EPOCH", "1765000000", 1);
  const std::string dir = MakeTempDir();
  std::string reports[2], models[2];
  for (int run = 0; run < 2; ++run) {
    const std::string threads = run == 0 ? "1" : "3";
    const std::string out = dir + "/r" + threads;
    const RunResult v =
        RunProgram({"validate", "--data", DataDir() + "/Au-Ag", "--methods", "eps-pchip,smooth",
                    "--angles", "0", "--threads", threads, "--quiet", "--out", out});
    ASSERT_EQ(v.status, 0) << v.err;
    reports[run] = ReadText(out + "/report.json");
    const std::string model = dir + "/m" + threads + ".json";
    const RunResult f = RunProgram({"fit", "--data", DataDir() + "/Au-Ag", "--method", "physical",
                                    "--threads", threads, "--quiet", "--out", model});
    ASSERT_EQ(f.status, 0) << f.err;
    models[run] = ReadText(model);
  }
  EXPECT_FALSE(reports[0].empty());
  EXPECT_EQ(reports[0], reports[1]);
  EXPECT_NE(models[0].find("\"uncertainty\""), std::string::npos);
  EXPECT_EQ(models[0], models[1]);
  EXPECT_EQ(RunProgram({"fit", "--data", DataDir() + "/Au-Ag", "--threads", "-2", "--out",
                        dir + "/bad.json"})
                .status,
            2);
}

}  // namespace
}  // namespace alloycolor
