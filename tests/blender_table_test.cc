// The Blender add-on's table (export/blender_table.h): its samples against direct
// spectral evaluation, the measured error of Blender's bilinear lookup on the bundled
// systems, the files `alloycolor export --format blender-table` writes and what it refuses.
#include "alloycolor/export/blender_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/export/export_files.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/render/shading.h"
#include "test_util.h"

namespace alloycolor::exports {
namespace {

using testing::DataDir;
using testing::MakeTempDir;
using testing::ReadText;
using testing::RunProgram;

const color::Colorimeter& D65() {
  static const color::Colorimeter d65 = color::Colorimeter::Load(DataDir(), "D65", 2);
  return d65;
}

SampleModel EpsLinear(const std::string& set) {
  return SampleModel(SampleModel::Kind::kEpsLinear, LoadDataset(DataDir() + "/" + set));
}

color::RGB DirectRGB(const AlloyModel& model, double x, double mu) {
  const render::DirectReflection direct(D65(), color::IndexOnGrid(D65(), model, x), 0.0);
  const color::RGB c = color::LinearSRGBFromXYZ(direct.FresnelXYZ(mu));
  return {std::clamp(c.r, 0.0, 1.0), std::clamp(c.g, 0.0, 1.0), std::clamp(c.b, 0.0, 1.0)};
}

// Every sample at its node is the spectral colour there (within the table's tolerance and
// the 16-bit step), for a few columns and rows.
TEST(BlenderTableTest, SamplesAreTheSpectralColourAtTheirNodes) {
  const SampleModel model = EpsLinear("Au-Ag");
  const BlenderTable t = BuildBlenderTable(D65(), model, {});
  ASSERT_EQ(t.columns, kBlenderTableColumns);
  ASSERT_EQ(t.rows, kBlenderTableRows);
  EXPECT_DOUBLE_EQ(t.x_min, model.x_min());
  EXPECT_DOUBLE_EQ(t.x_max, model.x_max());
  for (int i : {0, 37, 128, t.columns - 1}) {
    const double x = t.x_min + i * (t.x_max - t.x_min) / (t.columns - 1);
    for (int m : {0, 5, 64, t.rows - 1}) {
      const double mu = static_cast<double>(m) / (t.rows - 1);
      const color::RGB want = DirectRGB(model, x, mu);
      const double* got = &t.rgb[(m * t.columns + i) * 3];
      EXPECT_NEAR(got[0], want.r, 2e-3) << "column " << i << " row " << m;
      EXPECT_NEAR(got[1], want.g, 2e-3) << "column " << i << " row " << m;
      EXPECT_NEAR(got[2], want.b, 2e-3) << "column " << i << " row " << m;
    }
    // F0 is the top row (before clamping and rounding).
    EXPECT_NEAR(std::min(t.f0[i].g, 1.0), t.rgb[((t.rows - 1) * t.columns + i) * 3 + 1], 1e-4);
  }
}

// The figure the JSON states: Blender's lookup within 1 of 8-bit sRGB on the bundled
// Au-Ag and Cu-Zn data (Cu-Zn's Zn end has the sharpest change near grazing incidence).
TEST(BlenderTableTest, LookupIsWithinOneOfEightBitSrgbOnBundledSystems) {
  for (const char* set : {"Au-Ag", "Cu-Zn"}) {
    const BlenderTable t = BuildBlenderTable(D65(), EpsLinear(set), {});
    EXPECT_LE(t.max_srgb8_difference, 1) << set;
    EXPECT_LT(t.max_de00, 0.5) << set;
    EXPECT_EQ(t.check_points, (2 * t.columns - 1) * (2 * t.rows - 1) - t.columns * t.rows) << set;
  }
}

// Too coarse an image is measured as such: the figure is not a constant.
TEST(BlenderTableTest, CoarseImageReportsALargerError) {
  const BlenderTable t = BuildBlenderTable(D65(), EpsLinear("Cu-Zn"), {16, 8, 0});
  EXPECT_GT(t.max_srgb8_difference, 3);
  EXPECT_THROW(BuildBlenderTable(D65(), EpsLinear("Cu-Zn"), {1, 8, 0}), Error);
}

TEST(BlenderTableTest, ExportWritesTheImageAndTheDescription) {
  const SampleModel model = EpsLinear("Au-Ag");
  const ExportMaterial material = AlloyExportMaterial(D65(), model, 0.5, "built from data Au-Ag");
  ExportSettings settings;
  settings.format = "blender-table";
  const ExportFiles e = BuildExport(D65(), material, "/tmp/au", settings);
  ASSERT_EQ(e.files.size(), 2u);
  EXPECT_EQ(e.files[0].path, "/tmp/au.alloy-table.png");
  EXPECT_EQ(e.files[1].path, "/tmp/au.alloy-table.json");
  const std::string& png = e.files[0].contents;
  ASSERT_GT(png.size(), 33u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  const auto be32 = [&png](int at) {
    return (static_cast<unsigned char>(png[at]) << 24) |
           (static_cast<unsigned char>(png[at + 1]) << 16) |
           (static_cast<unsigned char>(png[at + 2]) << 8) | static_cast<unsigned char>(png[at + 3]);
  };
  EXPECT_EQ(be32(16), kBlenderTableColumns);
  EXPECT_EQ(be32(20), kBlenderTableRows);
  EXPECT_EQ(png[24], 16);                                                  // bit depth
  EXPECT_EQ(png.find(std::string("\0\0\0\1sRGB", 8)), std::string::npos);  // data, no sRGB chunk
  const nlohmann::json doc = nlohmann::json::parse(e.files[1].contents);
  EXPECT_EQ(doc["system"], "Au-Ag");
  EXPECT_EQ(doc["elements"][0], "Au");
  EXPECT_NEAR(doc["molar_masses_g_mol"][0].get<double>(), 196.97, 0.01);
  EXPECT_NEAR(doc["molar_masses_g_mol"][1].get<double>(), 107.87, 0.01);
  EXPECT_EQ(doc["image"], "au.alloy-table.png");
  EXPECT_TRUE(doc["karat"].get<bool>());
  EXPECT_EQ(doc["gold_element"], 0);
  EXPECT_EQ(doc["f0"].size(), static_cast<std::size_t>(kBlenderTableColumns));
  EXPECT_LE(doc["lookup_error"]["max_srgb8_difference"].get<int>(), 1);
  for (const char* field : {"max_delta_e00", "max_srgb8_difference", "check_points"}) {
    EXPECT_EQ(e.summary["lookup_error"][field], doc["lookup_error"][field]) << field;
  }
  EXPECT_NE(doc["material"].get<std::string>().find("eps-linear model built from data Au-Ag"),
            std::string::npos);
}

TEST(BlenderTableTest, MeasuredMetalIsRefused) {
  const ExportMaterial material =
      MeasuredExportMaterial(D65(), ReadNkFile(DataDir() + "/pure/Cu-Johnson.yml"));
  ExportSettings settings;
  settings.format = "blender-table";
  const std::string message =
      testing::ErrorOf([&] { BuildExport(D65(), material, "/tmp/cu", settings); });
  EXPECT_NE(message.find("blender-table"), std::string::npos) << message;
}

// The program: no --x needed, both files written, the error on stderr; not part of "all".
TEST(BlenderTableTest, ProgramExportsWithoutAComposition) {
  const std::string dir = MakeTempDir();
  const auto run = RunProgram({"export", "--data", "Cu-Zn", "--method", "eps-linear", "--format",
                               "blender-table", "--out", dir + "/brass", "--json"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.err.find("largest 8-bit sRGB difference"), std::string::npos) << run.err;
  const nlohmann::json doc = nlohmann::json::parse(ReadText(dir + "/brass.alloy-table.json"));
  EXPECT_FALSE(doc["karat"].get<bool>());
  EXPECT_EQ(nlohmann::json::parse(run.out)["files"].size(), 2u);
  const auto all = RunProgram({"export", "--data", "Cu-Zn", "--method", "eps-linear", "--x", "0.7",
                               "--format", "all", "--out", dir + "/all", "--json", "--quiet"});
  ASSERT_EQ(all.status, 0) << all.err;
  EXPECT_EQ(all.out.find("alloy-table"), std::string::npos);
}

}  // namespace
}  // namespace alloycolor::exports
