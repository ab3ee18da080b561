// Tests of data-set manifests (model/dataset.h): the bundled data sets, composition
// conversion, and every kind of bad manifest, whose error must name the culprit.
#include "alloycolor/core/dataset.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "test_util.h"

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
using testing::DataDir;
using ::testing::HasSubstr;
using testing::MakeTempDir;
using testing::WriteText;

void ExpectWellFormed(const Dataset& dataset) {
  ASSERT_FALSE(dataset.samples.empty());
  for (std::size_t i = 0; i < dataset.samples.size(); ++i) {
    const Sample& sample = dataset.samples[i];
    SCOPED_TRACE(sample.file);
    if (i > 0) {
      EXPECT_LT(dataset.samples[i - 1].x_atomic, sample.x_atomic);
    }
    EXPECT_GE(sample.x_atomic, 0);
    EXPECT_LE(sample.x_atomic, 1);
    EXPECT_TRUE(fs::is_regular_file(sample.path));
    EXPECT_EQ(sample.checksum, Fnv1a64Hex(ReadFileText(sample.path)));
    EXPECT_EQ(sample.checksum.size(), 16u);
    EXPECT_EQ(sample.nk.source, sample.path);
    EXPECT_GE(sample.nk.lambda_nm.size(), 2u);
  }
}

TEST(LoadDatasetTest, AuAgFolder) {
  const Dataset dataset = LoadDataset(DataDir() + "/Au-Ag");
  ExpectWellFormed(dataset);
  EXPECT_EQ(dataset.manifest_path, DataDir() + "/Au-Ag/dataset.json");
  EXPECT_EQ(dataset.name, "Au-Ag (Rioux et al. 2014 model output)");
  EXPECT_EQ(dataset.system.Name(), "Au-Ag");
  EXPECT_EQ(dataset.composition, "atomic_fraction_a");
  ASSERT_EQ(dataset.samples.size(), 11u);
  EXPECT_TRUE(dataset.warnings.empty());
  const Sample& half = dataset.samples[5];
  EXPECT_EQ(half.file, "Rioux-Au50Ag50.yml");
  EXPECT_EQ(half.path, DataDir() + "/Au-Ag/Rioux-Au50Ag50.yml");
  EXPECT_EQ(half.x_given, 0.5);
  EXPECT_EQ(half.x_atomic, 0.5);
  EXPECT_DOUBLE_EQ(half.nk.n.front(), 1.34272);
}

TEST(LoadDatasetTest, CuZnFolderAndWernerManifest) {
  const Dataset querry = LoadDataset(DataDir() + "/Cu-Zn");
  ExpectWellFormed(querry);
  ASSERT_EQ(querry.samples.size(), 5u);
  EXPECT_EQ(querry.composition, "weight_fraction_a");
  EXPECT_EQ(querry.samples.front().file, "Querry-Zn100.yml");
  // The repeated 5.102 um of Querry-Cu100.yml comes through as a warning naming the file.
  ASSERT_EQ(querry.warnings.size(), 1u);
  EXPECT_THAT(querry.warnings[0], HasSubstr("Querry-Cu100.yml:444:"));

  const Dataset werner = LoadDataset(DataDir() + "/Cu-Zn/dataset-werner-zn.json");
  ExpectWellFormed(werner);
  ASSERT_EQ(werner.samples.size(), 5u);
  EXPECT_EQ(werner.samples.front().file, "Werner-Zn100.yml");
  // Cu70Zn30 by weight: x = (0.70 / 63.546) / (0.70 / 63.546 + 0.30 / 65.38).
  const double x = (0.70 / 63.546) / (0.70 / 63.546 + 0.30 / 65.38);
  EXPECT_NEAR(werner.samples[1].x_atomic, x, 1e-14);
  EXPECT_NEAR(x, 0.70594, 1e-5);
}

TEST(LoadDatasetTest, NbSnWeightFractionsBecomeAtomic) {
  const Dataset dataset = LoadDataset(DataDir() + "/Nb-Sn/dataset.json");
  ExpectWellFormed(dataset);
  ASSERT_EQ(dataset.samples.size(), 9u);
  EXPECT_EQ(dataset.system.Name(), "Sn-Nb");
  const Sample& sn06 = dataset.samples[1];
  EXPECT_EQ(sn06.file, "Golovashkin-06.yml");
  EXPECT_EQ(sn06.x_given, 0.06);
  // By hand: (0.06 / 118.710) / (0.06 / 118.710 + 0.94 / 92.90637) = 0.0475785.
  EXPECT_NEAR(sn06.x_atomic, 0.0475785, 1e-7);
  // 55 wt% Sn: (0.55 / 118.710) / (0.55 / 118.710 + 0.45 / 92.90637) = 0.488907.
  const Sample& sn55 = dataset.samples[7];
  EXPECT_EQ(sn55.file, "Golovashkin-55.yml");
  EXPECT_NEAR(sn55.x_atomic, (0.55 / 118.710) / (0.55 / 118.710 + 0.45 / 92.90637), 1e-14);
  EXPECT_EQ(dataset.samples.front().x_atomic, 0.0);
  EXPECT_EQ(dataset.samples.back().x_atomic, 1.0);
}

TEST(WithoutSamplesTest, DropsTheNamedCompositions) {
  const Dataset dataset = LoadDataset(DataDir() + "/Au-Ag");
  const Dataset fewer = WithoutSamples(dataset, {0.5, 0.9 + 1e-12, 0.55});
  ASSERT_EQ(fewer.samples.size(), 9u);
  for (const Sample& sample : fewer.samples) {
    EXPECT_NE(sample.file, "Rioux-Au50Ag50.yml");
    EXPECT_NE(sample.file, "Rioux-Au90Ag10.yml");
  }
  EXPECT_EQ(fewer.name, dataset.name);
  EXPECT_EQ(WithoutSamples(dataset, {}).samples.size(), 11u);
}

// A folder with two small spectra and a manifest written by each test.
class ManifestTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string rows = "DATA:\n  - type: tabulated nk\n    data: |\n";
    WriteText(dir_ + "/a.yml", rows + "        0.5 1 2\n        0.6 1 2\n");
    WriteText(dir_ + "/b.yml", rows + "        0.5 1 3\n        0.6 1 3\n");
    WriteText(dir_ + "/bad.yml", rows + "        0.5 1 2\n        0.6 1 oops\n");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Manifest(const std::string& text, const std::string& name = "dataset.json") {
    WriteText(dir_ + "/" + name, text);
    return dir_ + "/" + name;
  }
  // The Error of loading the manifest, checked to be on one line.
  std::string ErrorOf(const std::string& path) {
    try {
      LoadDataset(path);
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      return message;
    }
    ADD_FAILURE() << "no Error for " << path;
    return "";
  }

  std::string dir_ = MakeTempDir();
};

constexpr char kHead[] =
    R"({"system": {"a": "Au", "b": "Ag"}, "composition": "atomic_fraction_a", )";

TEST_F(ManifestTest, RelativeAndAbsoluteFilesAndUnknownKeys) {
  const std::string path = Manifest(std::string(kHead) + R"("samples": [
    {"x": 0.7, "file": "a.yml"}, {"x": 0.2, "file": ")" +
                                        dir_ + R"(/b.yml", "note": 1}],
    "colour": "green"})",
                                    "mine.json");
  const Dataset dataset = LoadDataset(path);
  ASSERT_EQ(dataset.samples.size(), 2u);
  EXPECT_EQ(dataset.samples[0].file, dir_ + "/b.yml");
  EXPECT_EQ(dataset.samples[1].path, dir_ + "/a.yml");
  EXPECT_EQ(dataset.name, "Au-Ag");
  ASSERT_EQ(dataset.warnings.size(), 2u);
  EXPECT_THAT(dataset.warnings[0], HasSubstr("mine.json: unknown key 'colour'"));
  EXPECT_THAT(dataset.warnings[1], HasSubstr("mine.json: samples[1]: unknown key 'note'"));
}

TEST_F(ManifestTest, ErrorsNameTheManifestAndTheField) {
  struct Case {
    std::string text;
    std::string expected;  // after "<dir>/dataset.json"
  };
  const std::string one_sample = R"("samples": [{"x": 0.5, "file": "a.yml"}]})";
  const std::vector<Case> cases = {
      {"", ":1: invalid JSON"},
      {"{\"system\": {\"a\": \"Au\",\n \"b\": \"Ag\"},\n \"composition\": ,\n}",
       ":3: invalid JSON"},
      {"[1, 2]", ": the manifest is not a JSON object"},
      {R"({"composition": "atomic_fraction_a", )" + one_sample, ": system: missing"},
      {R"({"system": {"a": "Xx", "b": "Ag"}, "composition": "atomic_fraction_a", )" + one_sample,
       ": system.a: unknown element 'Xx'"},
      {R"({"system": {"a": "Au"}, "composition": "atomic_fraction_a", )" + one_sample,
       ": system.b: missing"},
      {R"({"system": {"a": "Au", "b": 3}, "composition": "atomic_fraction_a", )" + one_sample,
       ": system.b: not a string"},
      {R"({"system": {"a": "Au", "b": "Au"}, "composition": "atomic_fraction_a", )" + one_sample,
       ": system: a and b are both 'Au'"},
      {R"({"system": {"a": "Au", "b": "Ag"}, )" + one_sample, ": composition: missing"},
      {R"({"system": {"a": "Au", "b": "Ag"}, "composition": "percent", )" + one_sample,
       ": composition: '\"percent\"' is neither"},
      {R"({"system": {"a": "Au", "b": "Ag"}, "composition": "atomic_fraction_a", "name": 3, )" +
           one_sample,
       ": name: not a string"},
      {std::string(kHead) + R"("samples": []})", ": samples: missing or not a non-empty list"},
      {std::string(kHead) + R"("samples": {}})", ": samples: missing or not a non-empty list"},
      {std::string(kHead) + R"("samples": [3]})", ": samples[0]: not an object"},
      {std::string(kHead) + R"("samples": [{"x": 0.5}]})", ": samples[0].file: missing"},
      {std::string(kHead) + R"("samples": [{"x": 0.5, "file": ""}]})", ": samples[0].file"},
      {std::string(kHead) + R"("samples": [{"file": "a.yml"}]})",
       ": samples[0] ('a.yml'): x: missing or not a number"},
      {std::string(kHead) + R"("samples": [{"x": "0.5", "file": "a.yml"}]})",
       ": samples[0] ('a.yml'): x: missing or not a number"},
      {std::string(kHead) +
           R"("samples": [{"x": 0.1, "file": "b.yml"}, {"x": 1.5, "file": "a.yml"}]})",
       ": samples[1] ('a.yml'): x = 1.5 lies outside [0, 1]"},
      {std::string(kHead) + R"("samples": [{"x": -0.5, "file": "a.yml"}]})",
       ": samples[0] ('a.yml'): x = -0.5 lies outside [0, 1]"},
      {std::string(kHead) + R"("samples": [{"x": 0.5, "file": "dataset.json"}]})",
       ": samples[0] ('dataset.json'): the sample file is the manifest itself"},
      {std::string(kHead) + R"("samples": [{"x": 0.5, "file": "./dataset.json"}]})",
       ": samples[0] ('./dataset.json'): the sample file is the manifest itself"},
      {std::string(kHead) +
           R"("samples": [{"x": 0.5, "file": "a.yml"}, {"x": 0.5, "file": "b.yml"}]})",
       ": samples 'a.yml' and 'b.yml' have the same composition, x = 0.5"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    const std::string path = Manifest(c.text);
    EXPECT_THAT(ErrorOf(dir_), HasSubstr(path + c.expected));
  }
}

TEST_F(ManifestTest, SameCompositionAfterWeightConversion) {
  const std::string path = Manifest(
      R"({"system": {"a": "Cu", "b": "Zn"}, "composition": "weight_fraction_a", "samples": [
      {"x": 1, "file": "a.yml"}, {"x": 1.0, "file": "b.yml"}]})");
  EXPECT_THAT(ErrorOf(path), HasSubstr(path + ": samples 'a.yml' and 'b.yml' have the same"));
}

TEST_F(ManifestTest, SampleErrorsNameTheSampleFile) {
  Manifest(std::string(kHead) + R"("samples": [{"x": 0.5, "file": "missing.yml"}]})");
  EXPECT_THAT(ErrorOf(dir_), HasSubstr("cannot read '" + dir_ + "/missing.yml'"));
  Manifest(std::string(kHead) +
           R"("samples": [{"x": 0.5, "file": "a.yml"}, {"x": 0.6, "file": "bad.yml"}]})");
  EXPECT_THAT(ErrorOf(dir_), HasSubstr(dir_ + "/bad.yml:5: cannot parse number 'oops'"));
}

TEST_F(ManifestTest, MissingManifestOrFolder) {
  EXPECT_THAT(ErrorOf(dir_), HasSubstr("cannot read '" + dir_ + "/dataset.json'"));
  EXPECT_THAT(ErrorOf(dir_ + "/nothing.json"),
              HasSubstr("cannot read '" + dir_ + "/nothing.json'"));
}

}  // namespace
}  // namespace alloycolor
