// End-to-end tests of `alloycolor chart`: the SVG strip has one swatch per composition,
// each of the colour `alloycolor color` gives at that composition, labelled with the
// composition; the PNG has the same colours at the swatches' centres; bad options and
// infrared models exit with status 2 and one line.
#include <gtest/gtest.h>
#include <png.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

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

std::string ColourHex(const std::string& x) {
  const RunResult run = RunProgram(
      {"color", "--data", DataDir() + "/Au-Ag", "--method", "eps-linear", "--x", x, "--json"});
  EXPECT_EQ(run.status, 0) << run.err;
  return nlohmann::json::parse(run.out)["srgb_hex"];
}

std::vector<std::string> SwatchFills(const std::string& svg) {
  std::vector<std::string> fills;
  const std::regex rect("<rect class=\"swatch\"[^>]* fill=\"(#[0-9a-f]{6})\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), rect); it != std::sregex_iterator();
       ++it) {
    fills.push_back((*it)[1]);
  }
  return fills;
}

TEST(Chart, SvgHasOneLabelledSwatchPerComposition) {
  const std::string dir = MakeTempDir();
  const std::string out = dir + "/chart.svg";
  const RunResult run =
      RunProgram({"chart", "--data", DataDir() + "/Au-Ag", "--method", "eps-linear", "--from", "0",
                  "--to", "1", "--steps", "11", "--out", out, "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;
  const std::string svg = ReadText(out);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  const std::vector<std::string> fills = SwatchFills(svg);
  ASSERT_EQ(fills.size(), 11u);
  EXPECT_EQ(fills[0], ColourHex("0"));
  EXPECT_EQ(fills[5], ColourHex("0.5"));
  EXPECT_EQ(fills[10], ColourHex("1"));
  EXPECT_NE(fills[0], fills[10]);  // silver and gold differ
  for (const char* label :
       {">0</text>", ">50</text>", ">100</text>", ">Ag</text>", ">Au</text>", "at% Au"}) {
    EXPECT_NE(svg.find(label), std::string::npos) << label;
  }
  fs::remove_all(dir);
}

TEST(Chart, WeightManifestsAreLabelledInWeightPercent) {
  const std::string dir = MakeTempDir();
  const std::string model = dir + "/model.json";
  ASSERT_EQ(RunProgram({"fit", "--data", DataDir() + "/Cu-Zn", "--method", "paper", "--out", model,
                        "--quiet"})
                .status,
            0);
  const RunResult run =
      RunProgram({"chart", "--model", model, "--steps", "5", "--out", dir + "/c.svg", "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  const std::string svg = ReadText(dir + "/c.svg");
  EXPECT_EQ(SwatchFills(svg).size(), 5u);
  EXPECT_NE(svg.find("wt% Cu"), std::string::npos);
  // Evenly spaced in weight percent, as labelled.
  for (const char* label : {">0</text>", ">25</text>", ">50</text>", ">75</text>", ">100</text>"}) {
    EXPECT_NE(svg.find(label), std::string::npos) << label;
  }
  fs::remove_all(dir);
}

TEST(Chart, PngHasTheSwatchColours) {
  const std::string dir = MakeTempDir();
  const std::string out = dir + "/chart.png";
  const RunResult run = RunProgram({"chart", "--data", DataDir() + "/Au-Ag", "--method",
                                    "eps-linear", "--steps", "3", "--out", out, "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_file(&image, out.c_str())) << image.message;
  image.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> px(PNG_IMAGE_SIZE(image));
  ASSERT_TRUE(png_image_finish_read(&image, nullptr, px.data(), 0, nullptr)) << image.message;
  // 3 swatches of 64 px with 8 px around and between them.
  EXPECT_EQ(image.width, 3u * 64 + 4 * 8);
  EXPECT_EQ(image.height, 64u + 2 * 8);
  const char* xs[] = {"0", "0.5", "1"};
  for (int i = 0; i < 3; ++i) {
    const int x = 8 + i * 72 + 32, y = 40;
    const std::uint8_t* p = &px[(static_cast<size_t>(y) * image.width + x) * 3];
    char hex[8];
    std::snprintf(hex, sizeof hex, "#%02x%02x%02x", p[0], p[1], p[2]);
    EXPECT_EQ(hex, ColourHex(xs[i])) << "swatch " << i;
  }
  const std::uint8_t* corner = &px[0];
  EXPECT_EQ(corner[0] + corner[1] + corner[2], 3 * 255);  // white margin
  fs::remove_all(dir);
}

void ExpectRefused(const std::vector<std::string>& args, const std::string& needle) {
  const RunResult run = RunProgram(args);
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_EQ(CountLines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find(needle), std::string::npos) << run.err;
}

TEST(Chart, RefusesBadRequests) {
  const std::string dir = MakeTempDir();
  const std::string au_ag = DataDir() + "/Au-Ag";
  ExpectRefused({"chart", "--data", au_ag, "--out", dir + "/c.jpg", "--quiet"}, ".svg or .png");
  ExpectRefused({"chart", "--data", au_ag, "--steps", "1", "--out", dir + "/c.svg"}, "--steps");
  ExpectRefused({"chart", "--data", au_ag, "--to", "1.5", "--out", dir + "/c.svg"}, "--to");
  ExpectRefused({"chart", "--data", DataDir() + "/Nb-Sn", "--out", dir + "/c.svg", "--quiet"},
                "380-780 nm");
  EXPECT_FALSE(fs::exists(dir + "/c.svg"));
  EXPECT_FALSE(fs::exists(dir + "/c.jpg"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace alloycolor
