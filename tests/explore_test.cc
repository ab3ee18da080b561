// The explorer page and the tables behind it:
//  - the composition table reproduces direct spectral evaluation (material_color.h) at its
//    nodes, and between them stays within its stated error at compositions and angles it
//    never saw (random, against MaterialXYZ);
//  - `alloycolor explore` writes one self-contained page of a few MB; bad input gives one
//    line and no file;
//  - in headless Chromium (skipped without it) the page shows, at several addresses, the
//    numbers of `alloycolor color` (CIEDE2000 well under 0.5, 8-bit within 1, one-sigma
//    dE00 within 15 %) and the pixels of `alloycolor render --light uniform` (sphere and
//    ring within 2 in 8-bit), and its JavaScript CIEDE2000, CIELAB and sRGB equal the
//    C++ ones (and Sharma, Wu & Dalal's published pairs);
//  - a screenshot shows the swatch and the pictures.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/render/composition_table.h"
#include "test_util.h"

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
using testing::DataDir;
using testing::MakeTempDir;
using testing::ReadText;
using testing::RunProgram;
using testing::RunResult;
using testing::WriteText;

constexpr const char* kChromium = "/usr/bin/chromium";
constexpr int kTileSize = 256;

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

std::string ChromiumCommand(const std::string& dir) {
  return std::string("timeout 120 ") + kChromium +
         " --headless --no-sandbox --disable-gpu --no-first-run "
         "--disable-background-networking --disable-component-update --disable-sync "
         "--user-data-dir=" +
         dir + "/chromium-profile ";
}

// The DOM after the page's script has run.
std::string DumpDom(const std::string& dir, const std::string& url) {
  const std::string out = dir + "/dom.html";
  const std::string command =
      ChromiumCommand(dir) + "--dump-dom '" + url + "' >" + out + " 2>" + dir + "/chromium.log";
  if (std::system(command.c_str()) != 0) return "";
  return ReadText(out);
}

// data-value of the element with this id.
std::string Value(const std::string& dom, const std::string& id) {
  const std::regex re("id=\"" + id + "\" data-value=\"([^\"]*)\"");
  std::smatch m;
  return std::regex_search(dom, m, re) ? m[1].str() : "";
}

std::vector<double> Numbers(const std::string& text) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) out.push_back(std::stod(part));
  return out;
}

std::string Attribute(const std::string& dom, const std::string& id, const std::string& name) {
  const std::regex re("id=\"" + id + "\"[^>]* " + name + "=\"([^\"]*)\"");
  std::smatch m;
  return std::regex_search(dom, m, re) ? m[1].str() : "";
}

color::Lab LabOf(const std::vector<double>& v) { return {v.at(0), v.at(1), v.at(2)}; }

// ---------------------------------------------------------------------------------------
// The table, in C++.

class PaperTable : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dataset_ = new Dataset(LoadDataset(DataDir() + "/Au-Ag"));
    model_ = new SampleModel(SampleModel::Kind::kPaper, *dataset_);
    colorimeters_ = new std::vector<color::Colorimeter>{
        color::Colorimeter::Load(DataDir(), "A", 2), color::Colorimeter::Load(DataDir(), "D65", 2)};
    render::CompositionTableOptions options;
    options.roughness = {0.0, 0.2};
    table_ = new render::CompositionTable(
        render::BuildCompositionTable(*model_, *colorimeters_, options));
  }
  static void TearDownTestSuite() {
    delete table_;
    delete colorimeters_;
    delete model_;
    delete dataset_;
  }
  static Dataset* dataset_;
  static SampleModel* model_;
  static std::vector<color::Colorimeter>* colorimeters_;
  static render::CompositionTable* table_;
};
Dataset* PaperTable::dataset_ = nullptr;
SampleModel* PaperTable::model_ = nullptr;
std::vector<color::Colorimeter>* PaperTable::colorimeters_ = nullptr;
render::CompositionTable* PaperTable::table_ = nullptr;

TEST_F(PaperTable, BreaksAtTheTrainingCompositions) {
  // Au-Ag has 11 samples, 0..1 in steps of 0.1: ten segments.
  ASSERT_EQ(table_->segments.size(), 10u);
  for (std::size_t s = 0; s < table_->segments.size(); ++s) {
    EXPECT_NEAR(table_->segments[s].x_lo, 0.1 * s, 1e-12);
    EXPECT_NEAR(table_->segments[s].x_hi, 0.1 * (s + 1), 1e-12);
    EXPECT_GE(table_->segments[s].intervals, 3);
  }
  EXPECT_TRUE(table_->tolerance_met);
  EXPECT_LT(table_->max_de00, 0.02);
  EXPECT_LE(table_->max_srgb8_difference, 1);
}

TEST_F(PaperTable, NodesEqualDirectSpectralEvaluation) {
  for (int c = 0; c < 2; ++c) {
    for (std::size_t node = 0; node < table_->x_nodes.size(); node += 7) {
      const double x = table_->x_nodes[node];
      const auto index = color::IndexOnGrid((*colorimeters_)[c], *model_, x);
      for (int m = 0; m < table_->mu_nodes; m += 16) {
        const double mu = static_cast<double>(m) / (table_->mu_nodes - 1);
        const double angle = std::acos(mu) * 180.0 / M_PI;
        const color::XYZ exact = color::MaterialXYZ((*colorimeters_)[c], index, angle);
        const color::XYZ t = render::InterpolateCompositionTable(*table_, c, 0, x, mu);
        EXPECT_NEAR(t.X, exact.X, 1e-9) << x << " " << mu;
        EXPECT_NEAR(t.Y, exact.Y, 1e-9);
        EXPECT_NEAR(t.Z, exact.Z, 1e-9);
      }
    }
  }
}

// The error the page states is measured at midpoints; at random compositions and angles
// it is not exceeded by more than half again.
TEST_F(PaperTable, StaysWithinItsStatedErrorAtRandomPoints) {
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 300; ++trial) {
    const int c = trial % 2;
    const double x = unit(rng), angle = 89.0 * unit(rng);
    const color::Colorimeter& cm = (*colorimeters_)[c];
    const color::XYZ exact = color::MaterialXYZ(cm, color::IndexOnGrid(cm, *model_, x), angle);
    const color::XYZ t =
        render::InterpolateCompositionTable(*table_, c, 0, x, std::cos(angle * M_PI / 180.0));
    worst = std::max(worst, color::DeltaE00(color::LabFromXYZ(exact, cm.White()),
                                            color::LabFromXYZ(t, cm.White())));
  }
  EXPECT_LT(worst, 1.5 * table_->max_de00 + 1e-6);
  EXPECT_LT(worst, 0.05);
}

// A rough table interpolated in composition and angle against the renderer's own table at
// that composition.
TEST_F(PaperTable, RoughTableFollowsTheRenderersTable) {
  const color::Colorimeter& cm = (*colorimeters_)[1];
  for (double x : {0.05, 0.47, 0.83}) {
    const render::ReflectionTable reference(
        render::DirectReflection(cm, color::IndexOnGrid(cm, *model_, x), 0.2));
    for (double mu : {0.03, 0.2, 0.5, 0.77, 1.0}) {
      const color::XYZ r = reference.At(mu);
      const color::XYZ t = render::InterpolateCompositionTable(*table_, 1, 1, x, mu);
      EXPECT_LT(color::DeltaE00(color::LabFromXYZ(r, cm.White()), color::LabFromXYZ(t, cm.White())),
                0.05)
          << x << " " << mu;
    }
  }
}

// ---------------------------------------------------------------------------------------
// The program and the page.

class ExplorePages : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { dir_ = new std::string(MakeTempDir()); }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete paper_;
    delete fit_;
    delete smooth_;
    paper_ = fit_ = smooth_ = nullptr;
  }
  // The pages, written on first use (ctest runs every test in a process of its own).
  static const RunResult& Paper() {
    if (!paper_) {
      paper_ = new RunResult(
          RunProgram({"explore", "--data", DataDir() + "/Au-Ag", "--method", "paper", "--size",
                      std::to_string(kTileSize), "--out", *dir_ + "/paper.html"}));
    }
    return *paper_;
  }
  static const RunResult& Smooth() {
    if (!smooth_) {
      fit_ = new RunResult(RunProgram({"fit", "--data", DataDir() + "/Au-Ag", "--degree", "3",
                                       "--out", *dir_ + "/smooth.json", "--quiet"}));
      EXPECT_EQ(fit_->status, 0) << fit_->err;
      smooth_ = new RunResult(RunProgram({"explore", "--model", *dir_ + "/smooth.json", "--size",
                                          std::to_string(kTileSize), "--roughness", "0", "--out",
                                          *dir_ + "/smooth.html", "--quiet"}));
    }
    return *smooth_;
  }
  static bool HaveChromium() { return fs::exists(kChromium); }

  // `alloycolor color --json` for one composition.
  static nlohmann::json Color(const std::vector<std::string>& source, const std::string& x,
                              const std::string& ill, double angle) {
    std::vector<std::string> args = {"color"};
    args.insert(args.end(), source.begin(), source.end());
    for (const std::string& a :
         {std::string("--x"), x, std::string("--illuminant"), ill, std::string("--angle"),
          std::to_string(angle), std::string("--json"), std::string("--quiet")}) {
      args.push_back(a);
    }
    const RunResult r = RunProgram(args);
    EXPECT_EQ(r.status, 0) << r.err;
    return r.status == 0 ? nlohmann::json::parse(r.out) : nlohmann::json();
  }

  // Pixels of `alloycolor render --light uniform`.
  static std::vector<std::uint8_t> Render(const std::vector<std::string>& source,
                                          const std::string& x, const std::string& ill,
                                          const std::string& shape) {
    const std::string png = *dir_ + "/render.png";
    std::vector<std::string> args = {"render"};
    args.insert(args.end(), source.begin(), source.end());
    for (const std::string& a :
         {std::string("--x"), x, std::string("--illuminant"), ill, std::string("--light"),
          std::string("uniform"), std::string("--shape"), shape, std::string("--size"),
          std::to_string(kTileSize), std::string("--out"), png, std::string("--quiet")}) {
      args.push_back(a);
    }
    const RunResult r = RunProgram(args);
    EXPECT_EQ(r.status, 0) << r.err;
    int w = 0, h = 0;
    std::vector<std::uint8_t> px = ReadPng(png, &w, &h);
    EXPECT_EQ(w, kTileSize);
    return px;
  }

  // Opens the page at `hash` and compares metal A and B with the program.
  void CheckAddress(const std::string& page, const std::vector<std::string>& source,
                    const std::string& x, const std::string& x2, const std::string& ill,
                    double angle, bool sigma) {
    const std::string hash = "#x=" + x + "&x2=" + x2 + "&ill=" + ill +
                             "&angle=" + std::to_string(angle) + "&light=uniform&rough=0";
    const std::string dom = DumpDom(*dir_, "file://" + page + hash);
    ASSERT_NE(dom.find("data-ready=\"true\""), std::string::npos)
        << hash << "\n"
        << ReadText(*dir_ + "/chromium.log");
    EXPECT_NE(dom.find("data-bad-parameters=\"\""), std::string::npos) << hash;
    // The composition chart is drawn, with its band where the model has error bars and the
    // three places to measure next.
    EXPECT_NE(dom.find("data-suggestions=\"3\""), std::string::npos) << hash;
    EXPECT_EQ(dom.find("class=\"band\"") != std::string::npos, sigma) << hash;
    color::Lab labs[2];
    for (int m = 0; m < 2; ++m) {
      const std::string key = m == 0 ? "a" : "b";
      const nlohmann::json c = Color(source, m == 0 ? x : x2, ill, angle);
      ASSERT_FALSE(c.is_null());
      const color::Lab expected{c["Lab"][0], c["Lab"][1], c["Lab"][2]};
      labs[m] = expected;
      const color::Lab shown = LabOf(Numbers(Value(dom, key + "-lab")));
      EXPECT_LT(color::DeltaE00(expected, shown), 0.05) << hash << " metal " << key;
      const std::vector<double> rgb8 = Numbers(Value(dom, key + "-srgb8"));
      ASSERT_EQ(rgb8.size(), 3u);
      for (int ch = 0; ch < 3; ++ch) {
        EXPECT_NEAR(rgb8[ch], c["srgb8"][ch].get<double>(), 1.0) << hash << " " << key;
      }
      const std::vector<double> linear = Numbers(Value(dom, key + "-linear"));
      for (int ch = 0; ch < 3; ++ch) {
        EXPECT_NEAR(linear.at(ch), c["linear_srgb"][ch].get<double>(), 2e-3) << hash;
      }
      if (sigma) {
        const double s = std::stod(Value(dom, key + "-sigma"));
        const double expected_sigma = c["delta_e00_sigma"];
        // The page interpolates sigma between its table's compositions, and sigma is
        // concave between training compositions (PredictionError::Bump): within 25 %.
        EXPECT_NEAR(s, expected_sigma, 0.25 * expected_sigma) << hash << " " << key;
      } else {
        EXPECT_EQ(Value(dom, key + "-sigma"), "none");
        EXPECT_FALSE(c.contains("delta_e00_sigma"));
      }
      // The sphere and the ring against the renderer, at the page's sample points.
      for (const std::string shape : {"sphere", "ring"}) {
        const auto samples =
            nlohmann::json::parse(Attribute(dom, shape + "-" + key, "data-samples"));
        const std::vector<std::uint8_t> px = Render(source, m == 0 ? x : x2, ill, shape);
        ASSERT_EQ(px.size(), static_cast<std::size_t>(kTileSize) * kTileSize * 4);
        for (const auto& s : samples) {
          const int i = s[0], j = s[1];
          const std::uint8_t* p = &px[(static_cast<std::size_t>(j) * kTileSize + i) * 4];
          if (p[3] != 255 || s[5].get<int>() != 255) {
            EXPECT_EQ(p[3] == 0, s[5].get<int>() == 0) << shape << " " << i << "," << j;
            continue;  // the ring's hole, or an outline
          }
          for (int ch = 0; ch < 3; ++ch) {
            EXPECT_NEAR(s[2 + ch].get<int>(), p[ch], 2)
                << hash << " " << shape << " " << key << " pixel " << i << "," << j;
          }
        }
      }
    }
    const double de = std::stod(Value(dom, "de00"));
    EXPECT_NEAR(de, color::DeltaE00(labs[0], labs[1]), 0.05) << hash;
    // The window drawn on slider A: `alloycolor tolerance --de 1` at the page's light and
    // angle (the page walks its tables, the program the model).
    std::vector<std::string> args = {"tolerance"};
    args.insert(args.end(), source.begin(), source.end());
    for (const std::string& a :
         {std::string("--x"), x, std::string("--de"), std::string("1"), std::string("--angles"),
          std::to_string(angle), std::string("--illuminants"), ill, std::string("--json"),
          std::string("--quiet")}) {
      args.push_back(a);
    }
    const RunResult t = RunProgram(args);
    ASSERT_EQ(t.status, 0) << t.err;
    const nlohmann::json window = nlohmann::json::parse(t.out);
    EXPECT_NEAR(std::stod(Attribute(dom, "window-a", "data-lo")), window["x_low"].get<double>(),
                2e-3)
        << hash;
    EXPECT_NEAR(std::stod(Attribute(dom, "window-a", "data-hi")), window["x_high"].get<double>(),
                2e-3)
        << hash;
  }

  // Types `target` into the page's match box and presses Find (a script added after the
  // page's own); returns the matches the box lists.
  static nlohmann::json MatchBox(const std::string& page, const std::string& target) {
    std::string html = ReadText(page);
    const std::size_t end = html.rfind("</body>");
    html.insert(end, "<script>document.getElementById('match-target').value = " +
                         nlohmann::json(target).dump() +
                         "; document.getElementById('match-go').click();</script>");
    WriteText(*dir_ + "/match.html", html);
    const std::string dom = DumpDom(*dir_, "file://" + *dir_ + "/match.html");
    const std::string matches = Attribute(dom, "match-result", "data-matches");
    if (matches.empty()) return nlohmann::json();
    std::string text = matches;  // the DOM serialises '"' in attributes as &quot;
    for (std::size_t at; (at = text.find("&quot;")) != std::string::npos;) {
      text.replace(at, 6, "\"");
    }
    return nlohmann::json::parse(text);
  }

  static std::string* dir_;
  static RunResult* paper_;
  static RunResult* fit_;
  static RunResult* smooth_;
};
std::string* ExplorePages::dir_ = nullptr;
RunResult* ExplorePages::paper_ = nullptr;
RunResult* ExplorePages::fit_ = nullptr;
RunResult* ExplorePages::smooth_ = nullptr;

TEST_F(ExplorePages, WritesOneSelfContainedPageOfAFewMegabytes) {
  ASSERT_EQ(Paper().status, 0) << Paper().err;
  EXPECT_NE(Paper().err.find("largest error"), std::string::npos);
  const std::string html = ReadText(*dir_ + "/paper.html");
  EXPECT_GT(html.size(), 100000u);
  EXPECT_LT(html.size(), 4000000u);
  for (const char* bad : {"<link", "<img", "src=", "@import", "http:", "https:", "url("}) {
    EXPECT_EQ(html.find(bad), std::string::npos) << bad;
  }
  // The data block is JSON without a non-finite number (which nlohmann writes as null).
  const std::string open = "<script type=\"application/json\" id=\"explorer-data\">";
  const std::size_t begin = html.find(open);
  ASSERT_NE(begin, std::string::npos);
  const std::string data =
      html.substr(begin + open.size(), html.find("</script>", begin) - begin - open.size());
  EXPECT_EQ(data.find("null"), std::string::npos);
  const auto doc = nlohmann::json::parse(data);
  EXPECT_EQ(doc["format"], "alloycolor-explorer");
  EXPECT_EQ(doc["training"].size(), 11u);
  EXPECT_EQ(doc["samples"].size(), 11u);
  EXPECT_TRUE(doc["samples"][0]["measured"].get<bool>());
  // Where to measure next, for the composition chart: three compositions inside the range,
  // none within 0.02 of a training sample.
  ASSERT_EQ(doc["suggestions"].size(), 3u);
  for (const auto& s : doc["suggestions"]) {
    const double x = s["x"].get<double>();
    EXPECT_GE(x, 0.0);
    EXPECT_LE(x, 1.0);
    for (const auto& t : doc["training"])
      EXPECT_GE(std::abs(x - t["x"].get<double>()), 0.02 - 1e-12);
  }
  EXPECT_TRUE(doc["suspects"].is_array());
}

TEST_F(ExplorePages, BadInputGivesOneLineAndNoPage) {
  const std::string out = *dir_ + "/bad.html";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"explore", "--data", DataDir() + "/Nb-Sn", "--out", out},
        std::vector<std::string>{"explore", "--data", "Au-Ag", "--size", "10", "--out", out},
        std::vector<std::string>{"explore", "--data", "Au-Ag", "--roughness", "0,2", "--out", out},
        std::vector<std::string>{"explore", "--data", "Au-Ag", "--illuminants", "D65,X9", "--out",
                                 out},
        std::vector<std::string>{"explore", "--out", out}}) {
    const RunResult r = RunProgram(args);
    EXPECT_EQ(r.status, 2) << args[2];
    EXPECT_EQ(testing::CountLines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("alloycolor: error: ", 0), 0u) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST_F(ExplorePages, PaperPageShowsWhatColorAndRenderGive) {
  ASSERT_EQ(Paper().status, 0) << Paper().err;
  if (!HaveChromium()) GTEST_SKIP() << kChromium << " is absent (Debian package chromium)";
  const std::string page = *dir_ + "/paper.html";
  const std::vector<std::string> source = {"--data", DataDir() + "/Au-Ag", "--method", "paper"};
  // Training compositions, karats between them, three illuminants, several angles.
  CheckAddress(page, source, "0.75", "0.55", "D65", 0.0, true);
  CheckAddress(page, source, "18k", "14k", "A", 45.0, true);
  CheckAddress(page, source, "0.3333", "0.9137", "D50", 72.5, true);
  // The match box (D65, 0 degrees: the page's default view) finds what `match` finds.
  for (const auto& [target, option, value] :
       {std::tuple{"#f2e6b0", "--hex", "#f2e6b0"}, {"85, 2, 25", "--lab", "85,2,25"}}) {
    const nlohmann::json shown = MatchBox(page, target);
    ASSERT_TRUE(shown.is_array() && !shown.empty()) << target;
    const std::vector<std::string> args = {
        "match", "--data", DataDir() + "/Au-Ag", "--method", "paper", option, value, "--json"};
    const RunResult r = RunProgram(args);
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json expected = nlohmann::json::parse(r.out)["matches"];
    EXPECT_NEAR(shown[0]["x_atomic"].get<double>(), expected[0]["x_atomic"].get<double>(), 2e-3)
        << target;
    EXPECT_NEAR(shown[0]["de00"].get<double>(), expected[0]["de00"].get<double>(), 0.05) << target;
  }
}

TEST_F(ExplorePages, SmoothPageShowsWhatColorAndRenderGiveWithUncertainty) {
  ASSERT_EQ(Smooth().status, 0) << Smooth().err;
  if (!HaveChromium()) GTEST_SKIP() << kChromium << " is absent (Debian package chromium)";
  const std::vector<std::string> source = {"--model", *dir_ + "/smooth.json"};
  CheckAddress(*dir_ + "/smooth.html", source, "0.62", "0.071", "D65", 30.0, true);
  CheckAddress(*dir_ + "/smooth.html", source, "22k", "9k", "A", 0.0, true);
}

// The page's own colour script, run by Chromium on Sharma, Wu & Dalal's pairs
// (tests/reference/ciede2000_sharma2005.csv) and on random Lab pairs and XYZ values,
// against the C++ functions.
TEST_F(ExplorePages, JavaScriptColourEqualsTheCppColour) {
  ASSERT_EQ(Paper().status, 0) << Paper().err;
  if (!HaveChromium()) GTEST_SKIP() << kChromium << " is absent (Debian package chromium)";
  const std::string html = ReadText(*dir_ + "/paper.html");
  const std::size_t open = html.find("<script id=\"colour-js\">");
  ASSERT_NE(open, std::string::npos);
  const std::size_t begin = html.find('>', open) + 1;
  const std::string script = html.substr(begin, html.find("</script>", begin) - begin);

  std::mt19937 rng(2005);
  std::uniform_real_distribution<double> l(0.0, 100.0), ab(-90.0, 90.0), unit(0.0, 1.1);
  std::vector<std::array<double, 6>> pairs;
  const auto sharma = testing::ReadReferenceTable("ciede2000_sharma2005.csv");
  for (const auto& r : sharma) {
    pairs.push_back({r.at(1), r.at(2), r.at(3), r.at(4), r.at(5), r.at(6)});
  }
  for (int i = 0; i < 300; ++i)
    pairs.push_back({l(rng), ab(rng), ab(rng), l(rng), ab(rng), ab(rng)});
  std::vector<std::array<double, 3>> xyzs;
  for (int i = 0; i < 200; ++i) xyzs.push_back({unit(rng), unit(rng), unit(rng)});
  xyzs.push_back({0.0, 0.0, 0.0});
  xyzs.push_back({0.001, 0.002, 0.001});
  const color::XYZ white = color::Colorimeter::Load(DataDir(), "D65", 2).White();
  nlohmann::json m = nlohmann::json::array();
  const color::XYZ unit_xyz[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  double rows[3][3];
  for (int c = 0; c < 3; ++c) {
    const color::RGB col = color::LinearSRGBFromXYZ(unit_xyz[c]);
    rows[0][c] = col.r;
    rows[1][c] = col.g;
    rows[2][c] = col.b;
  }
  for (auto& r : rows) m.push_back({r[0], r[1], r[2]});
  const std::string harness =
      "<!DOCTYPE html><html><body><pre id=\"out\"></pre><script>" + script +
      "</script><script>const pairs = " + nlohmann::json(pairs).dump() +
      "; const xyzs = " + nlohmann::json(xyzs).dump() +
      "; const white = " + nlohmann::json({white.X, white.Y, white.Z}).dump() +
      "; const m = " + m.dump() +
      ";\nconst out = {de: pairs.map(p => AlloyColour.deltaE00(p.slice(0, 3), p.slice(3))),"
      " lab: xyzs.map(x => AlloyColour.labFromXYZ(x, white)),"
      " rgb8: xyzs.map(x => AlloyColour.linearSRGBFromXYZ(m, x).map(AlloyColour.srgb8))};\n"
      "document.getElementById('out').textContent = JSON.stringify(out);</script></body></html>";
  WriteText(*dir_ + "/harness.html", harness);
  const std::string dom = DumpDom(*dir_, "file://" + *dir_ + "/harness.html");
  const std::size_t a = dom.find("<pre id=\"out\">");
  ASSERT_NE(a, std::string::npos) << ReadText(*dir_ + "/chromium.log");
  const std::size_t b = dom.find("</pre>", a);
  const auto out = nlohmann::json::parse(dom.substr(a + 14, b - a - 14));
  ASSERT_EQ(out["de"].size(), pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto& p = pairs[i];
    const double cpp = color::DeltaE00({p[0], p[1], p[2]}, {p[3], p[4], p[5]});
    EXPECT_NEAR(out["de"][i].get<double>(), cpp, 1e-9) << "pair " << i;
    if (i < sharma.size()) EXPECT_NEAR(out["de"][i].get<double>(), sharma[i].at(7), 1e-4);
  }
  for (std::size_t i = 0; i < xyzs.size(); ++i) {
    const color::XYZ x{xyzs[i][0], xyzs[i][1], xyzs[i][2]};
    const color::Lab lab = color::LabFromXYZ(x, white);
    EXPECT_NEAR(out["lab"][i][0].get<double>(), lab.L, 1e-9);
    EXPECT_NEAR(out["lab"][i][1].get<double>(), lab.a, 1e-9);
    EXPECT_NEAR(out["lab"][i][2].get<double>(), lab.b, 1e-9);
    const auto rgb8 = color::SRGB8FromLinear(color::LinearSRGBFromXYZ(x));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(out["rgb8"][i][c].get<int>(), rgb8[c]) << i;
  }
}

TEST_F(ExplorePages, ScreenshotShowsTheSwatchAndThePictures) {
  ASSERT_EQ(Paper().status, 0) << Paper().err;
  if (!HaveChromium()) GTEST_SKIP() << kChromium << " is absent (Debian package chromium)";
  const std::string shot = *dir_ + "/shot.png";
  const std::string command =
      ChromiumCommand(*dir_) + "--screenshot=" + shot + " --window-size=1200,1600 'file://" +
      *dir_ + "/paper.html#x=0.75&x2=0.4&ill=D65&angle=0' >" + *dir_ + "/chromium.log 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << ReadText(*dir_ + "/chromium.log");
  int w = 0, h = 0;
  const std::vector<std::uint8_t> px = ReadPng(shot, &w, &h);
  ASSERT_EQ(w, 1200);
  const nlohmann::json c =
      Color({"--data", DataDir() + "/Au-Ag", "--method", "paper"}, "0.75", "D65", 0.0);
  const std::uint32_t swatch = std::stoul(c["srgb_hex"].get<std::string>().substr(1), nullptr, 16);
  std::map<std::uint32_t, long> counts;
  for (std::size_t i = 0; i + 3 < px.size(); i += 4) {
    ++counts[(px[i] << 16) | (px[i + 1] << 8) | px[i + 2]];
  }
  // The 96 x 96 swatch (less its border), and thousands of distinct colours in the
  // shaded sphere and ring.
  EXPECT_GT(counts[swatch], 80 * 80) << c["srgb_hex"];
  EXPECT_GT(counts.size(), 3000u);
}

}  // namespace
}  // namespace alloycolor
