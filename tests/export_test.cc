// Tests of `alloycolor export --format spd`: the spectrum files are parsed back the way
// pbrt-v4 (ReadFloatFile: numbers separated by white space, '#' to the end of the line a
// comment) and Mitsuba 3 (spectrum_from_file: '#' comment lines, two numbers per line)
// read them, and must reproduce the model's or file's n and k to 1e-6; the material
// files name them; bad input leaves no file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "alloycolor/core/dataset.h"
#include "alloycolor/core/io.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/sample_models.h"
#include "alloycolor/model/smooth_model.h"
#include "test_util.h"

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
using testing::CountLines;
using testing::DataDir;
using testing::MakeTempDir;
using testing::RunProgram;
using testing::WriteText;

constexpr double kTolerance = 1e-6;

struct Spd {
  std::vector<std::string> comments;
  std::vector<double> lambda_nm;
  std::vector<double> value;
};

// Mitsuba 3's reading: lines starting with '#' are comments, others hold exactly two
// numbers separated by spaces.
Spd ReadSpdLines(const std::string& path) {
  Spd spd;
  std::istringstream in(ReadFileText(path));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (line[0] == '#') {
      spd.comments.push_back(line);
      continue;
    }
    EXPECT_EQ(line.find('\t'), std::string::npos) << line;
    std::istringstream fields(line);
    double l = 0, v = 0;
    std::string rest;
    EXPECT_TRUE(static_cast<bool>(fields >> l >> v)) << line;
    EXPECT_FALSE(static_cast<bool>(fields >> rest)) << line;
    spd.lambda_nm.push_back(l);
    spd.value.push_back(v);
  }
  return spd;
}

// pbrt-v4's reading: every number outside '#' comments, in order; numbers are at most 31
// characters (its buffer).
std::vector<double> ReadPbrtFloats(const std::string& path) {
  std::vector<double> values;
  std::istringstream in(ReadFileText(path));
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t hash = line.find('#');
    std::istringstream tokens(line.substr(0, hash));
    std::string token;
    while (tokens >> token) {
      EXPECT_LT(token.size(), 32u);
      char* end = nullptr;
      values.push_back(std::strtod(token.c_str(), &end));
      EXPECT_EQ(*end, '\0') << token;
    }
  }
  return values;
}

// Checks the pair of files against n + i k, and the comment naming the material.
void CheckPair(const std::string& prefix, const std::vector<std::complex<double>>& index,
               const std::vector<double>& lambda_nm, const std::string& must_mention) {
  const Spd eta = ReadSpdLines(prefix + ".eta.spd");
  const Spd k = ReadSpdLines(prefix + ".k.spd");
  ASSERT_FALSE(eta.comments.empty());
  EXPECT_NE(eta.comments[0].find(must_mention), std::string::npos) << eta.comments[0];
  EXPECT_NE(k.comments[0].find(must_mention), std::string::npos) << k.comments[0];
  ASSERT_EQ(eta.lambda_nm, k.lambda_nm);
  ASSERT_EQ(eta.lambda_nm, lambda_nm);
  for (std::size_t i = 0; i < lambda_nm.size(); ++i) {
    EXPECT_NEAR(eta.value[i], index[i].real(), kTolerance) << lambda_nm[i];
    EXPECT_NEAR(k.value[i], index[i].imag(), kTolerance) << lambda_nm[i];
  }
  // pbrt sees the same pairs.
  const std::vector<double> floats = ReadPbrtFloats(prefix + ".eta.spd");
  ASSERT_EQ(floats.size(), 2 * eta.lambda_nm.size());
  for (std::size_t i = 0; i < eta.lambda_nm.size(); ++i) {
    EXPECT_EQ(floats[2 * i], eta.lambda_nm[i]);
    EXPECT_EQ(floats[2 * i + 1], eta.value[i]);
  }
}

void ExpectCovers360To830(const std::string& prefix) {
  const Spd spd = ReadSpdLines(prefix + ".eta.spd");
  ASSERT_GE(spd.lambda_nm.size(), 2u);
  EXPECT_LE(spd.lambda_nm.front(), 360.0);
  EXPECT_GE(spd.lambda_nm.back(), 830.0);
  for (std::size_t i = 1; i < spd.lambda_nm.size(); ++i) {
    EXPECT_GT(spd.lambda_nm[i], spd.lambda_nm[i - 1]);
  }
}

std::string Quote(const std::string& s) { return "\"" + s + "\""; }

// The material files name the spectrum files beside them: by file name alone.
void CheckMaterialFiles(const std::string& prefix) {
  const std::string base = fs::path(prefix).filename().string();
  const std::string pbrt = ReadFileText(prefix + ".pbrt");
  const std::string expected_line = "Material \"conductor\" \"spectrum eta\" " +
                                    Quote(base + ".eta.spd") + " \"spectrum k\" " +
                                    Quote(base + ".k.spd") + "\n";
  EXPECT_NE(pbrt.find(expected_line), std::string::npos) << pbrt;
  // Everything else is a comment.
  std::istringstream lines(pbrt);
  std::string line;
  int statements = 0;
  while (std::getline(lines, line)) {
    if (!line.empty() && line[0] != '#') ++statements;
  }
  EXPECT_EQ(statements, 1);
  const std::string xml = ReadFileText(prefix + ".xml");
  EXPECT_EQ(xml.rfind("<?xml version=\"1.0\"", 0), 0u);
  EXPECT_NE(xml.find("<bsdf type=\"conductor\""), std::string::npos);
  EXPECT_NE(xml.find("version=\"3.0.0\""), std::string::npos);
  EXPECT_NE(xml.find("<spectrum name=\"eta\" filename=" + Quote(base + ".eta.spd") + "/>"),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<spectrum name=\"k\" filename=" + Quote(base + ".k.spd") + "/>"),
            std::string::npos);
  EXPECT_NE(xml.find("</bsdf>"), std::string::npos);
  // Comments hold no "--" (invalid XML).
  std::size_t start = 0;
  while ((start = xml.find("<!--", start)) != std::string::npos) {
    const std::size_t end = xml.find("-->", start + 4);
    ASSERT_NE(end, std::string::npos);
    EXPECT_EQ(xml.substr(start + 4, end - start - 4).find("--"), std::string::npos);
    start = end;
  }
}

int CountFiles(const std::string& dir) {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    (void)entry;
    ++files;
  }
  return files;
}

TEST(ExportTest, PaperModelReproducesTheModelsIndex) {
  const std::string dir = MakeTempDir();
  const std::string prefix = dir + "/auag75";
  const auto run = RunProgram({"export", "--data", "Au-Ag", "--method", "paper", "--x", "0.75",
                               "--format", "spd", "--out", prefix, "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  const SampleModel model(SampleModel::Kind::kPaper, LoadDataset(DataDir() + "/Au-Ag"));
  // Every 5 nm of the model's range, and its ends.
  std::vector<double> grid{model.lambda_min_nm()};
  for (double l = 5.0 * std::ceil(model.lambda_min_nm() / 5.0); l < model.lambda_max_nm();
       l += 5.0) {
    if (l > grid.back()) grid.push_back(l);
  }
  if (model.lambda_max_nm() > grid.back()) grid.push_back(model.lambda_max_nm());
  CheckPair(prefix, model.Index(0.75, grid), grid, "Au-Ag at x = 0.75");
  ExpectCovers360To830(prefix);
  CheckMaterialFiles(prefix);
  EXPECT_EQ(CountFiles(dir), 4);
  fs::remove_all(dir);
}

TEST(ExportTest, SmoothModelIsExportedAtItsOwnGrid) {
  const std::string dir = MakeTempDir();
  const std::string model_path = dir + "/auag.json";
  ASSERT_EQ(
      RunProgram({"fit", "--data", "Au-Ag", "--method", "smooth", "--out", model_path, "--quiet"})
          .status,
      0);
  const std::string prefix = dir + "/s";
  const auto run =
      RunProgram({"export", "--model", model_path, "--x", "18k", "--out", prefix, "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto model = ReadModelFile(model_path);
  const auto* smooth = dynamic_cast<const SmoothModel*>(model.get());
  ASSERT_NE(smooth, nullptr);
  const double x = AtomicFromWeightFraction(0.75, model->system());
  CheckPair(prefix, model->Index(x, smooth->grid_nm()), smooth->grid_nm(), "Au-Ag at x = ");
  ExpectCovers360To830(prefix);
  CheckMaterialFiles(prefix);
  fs::remove_all(dir);
}

TEST(ExportTest, MeasuredFileIsExportedAtItsOwnWavelengths) {
  const std::string dir = MakeTempDir();
  const std::string file = DataDir() + "/pure/Ag-Johnson.yml";
  const std::string prefix = dir + "/silver";
  const auto run = RunProgram({"export", "--nk", file, "--out", prefix});
  ASSERT_EQ(run.status, 0) << run.err;
  const NkSpectrum nk = ReadNkFile(file);
  std::vector<std::complex<double>> index;
  for (std::size_t i = 0; i < nk.n.size(); ++i) index.emplace_back(nk.n[i], nk.k[i]);
  CheckPair(prefix, index, nk.lambda_nm, "Ag-Johnson.yml");
  ExpectCovers360To830(prefix);
  CheckMaterialFiles(prefix);
  fs::remove_all(dir);
}

TEST(ExportTest, ShortDataAreHeldToTheEndsAndSaySo) {
  const std::string dir = MakeTempDir();
  const std::string csv = dir + "/short.csv";
  std::string text = "lambda_nm,n,k\n";
  for (int l = 370; l <= 800; l += 10) {
    text += std::to_string(l) + "," + std::to_string(0.2 + l / 1000.0) + "," +
            std::to_string(l / 100.0) + "\n";
  }
  WriteText(csv, text);
  const std::string prefix = dir + "/short";
  const auto run = RunProgram({"export", "--nk", csv, "--out", prefix});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.err.find("held"), std::string::npos) << run.err;
  const Spd eta = ReadSpdLines(prefix + ".eta.spd");
  const Spd k = ReadSpdLines(prefix + ".k.spd");
  ASSERT_EQ(eta.lambda_nm.size(), 44u + 2u);
  EXPECT_EQ(eta.lambda_nm.front(), 360.0);
  EXPECT_EQ(eta.lambda_nm[1], 370.0);
  EXPECT_EQ(eta.lambda_nm.back(), 830.0);
  EXPECT_EQ(eta.lambda_nm[eta.lambda_nm.size() - 2], 800.0);
  EXPECT_NEAR(eta.value.front(), 0.2 + 0.37, kTolerance);
  EXPECT_NEAR(eta.value.back(), 0.2 + 0.8, kTolerance);
  EXPECT_NEAR(k.value.front(), 3.7, kTolerance);
  EXPECT_NEAR(k.value.back(), 8.0, kTolerance);
  std::string comments;
  for (const auto& c : eta.comments) comments += c + "\n";
  EXPECT_NE(comments.find("below 370 nm"), std::string::npos) << comments;
  EXPECT_NE(comments.find("above 800 nm"), std::string::npos) << comments;
  EXPECT_NE(ReadFileText(prefix + ".pbrt").find("held"), std::string::npos);
  fs::remove_all(dir);
}

TEST(ExportTest, BadInputIsRefusedWithOneLineAndNoFile) {
  const std::string dir = MakeTempDir();
  const std::string narrow = dir + "/narrow.csv";
  WriteText(narrow, "lambda_nm,n,k\n400,0.5,2\n500,0.6,3\n700,0.7,4\n");
  const std::string prefix = dir + "/out";
  const std::string gold = DataDir() + "/pure/Au-Johnson.yml";
  const std::vector<std::vector<std::string>> cases = {
      {"export", "--nk", gold},  // no --out
      {"export", "--nk", gold, "--format", "csv", "--out", prefix},
      {"export", "--nk", dir + "/missing.yml", "--out", prefix},
      {"export", "--nk", narrow, "--out", prefix},
      {"export", "--data", "Au-Ag", "--x", "0.5,0.7", "--out", prefix},
      {"export", "--data", "Au-Ag", "--x", "1.5", "--out", prefix},
      {"export", "--data", "Au-Ag", "--out", prefix},
      {"export", "--nk", gold, "--x", "0.5", "--out", prefix},
      {"export", "--nk", gold, "--out", dir + "/no/such/folder/p"},
  };
  for (const auto& args : cases) {
    const auto run = RunProgram(args);
    std::string joined;
    for (const auto& a : args) joined += a + " ";
    EXPECT_EQ(run.status, 2) << joined;
    EXPECT_EQ(CountLines(run.err), 1) << joined << "\n" << run.err;
    EXPECT_EQ(run.err.rfind("alloycolor: error: ", 0), 0u) << run.err;
  }
  const auto narrow_run = RunProgram({"export", "--nk", narrow, "--out", prefix});
  EXPECT_NE(narrow_run.err.find("380-780"), std::string::npos) << narrow_run.err;
  EXPECT_EQ(CountFiles(dir), 1);  // narrow.csv only
  fs::remove_all(dir);
}

}  // namespace
}  // namespace alloycolor
