// Tests of data-set manifests (model/dataset.h): the bundled data sets, composition
// conversion, and every kind of bad manifest, whose error must name the culprit.
#include "alloycolor/core/dataset.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/text.h"
#include "test_util.h"

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
using testing::DataDir;
using ::testing::HasSubstr;
using testing::MakeTempDir;
using testing::RunProgram;
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

// What a path given in the wrong place holds, for the message that names it.
TEST(GuessInputKindTest, TellsDataSetsModelsAndNkFilesApart) {
  const std::string dir = MakeTempDir();
  EXPECT_EQ(GuessInputKind(DataDir() + "/Au-Ag"), InputKind::kDataset);
  EXPECT_EQ(GuessInputKind(DataDir() + "/Cu-Zn/dataset-werner-zn.json"), InputKind::kDataset);
  EXPECT_EQ(GuessInputKind(DataDir() + "/Au-Ag/Rioux-Au50Ag50.yml"), InputKind::kNkFile);
  WriteText(dir + "/lab.CSV", "lambda_nm,n,k\n400,1,2\n");
  EXPECT_EQ(GuessInputKind(dir + "/lab.CSV"), InputKind::kNkFile);
  WriteText(dir + "/m.json", R"({"format": "alloycolor-model", "version": 1})");
  EXPECT_EQ(GuessInputKind(dir + "/m.json"), InputKind::kModelFile);
  WriteText(dir + "/broken.json", "{\"samples\": [");
  EXPECT_EQ(GuessInputKind(dir + "/broken.json"), InputKind::kUnknown);
  WriteText(dir + "/list.json", "[1, 2]");
  EXPECT_EQ(GuessInputKind(dir + "/list.json"), InputKind::kUnknown);
  EXPECT_EQ(GuessInputKind(dir), InputKind::kUnknown);  // a folder without dataset.json
  EXPECT_EQ(GuessInputKind(dir + "/missing.json"), InputKind::kUnknown);
}

TEST(NearestNameTest, OneEditInThreeLettersAtMost) {
  const std::vector<std::string> sets = {"Au-Ag", "Cu-Zn", "Nb-Sn"};
  EXPECT_EQ(NearestName("AuAg", sets), "Au-Ag");
  EXPECT_EQ(NearestName("nb-sn", sets), "Nb-Sn");  // case is ignored
  EXPECT_EQ(NearestName("Pt-Ir", sets), "");
  EXPECT_EQ(NearestName("", sets), "");
  const std::vector<std::string> options = {"angle", "illuminant", "observer", "out"};
  EXPECT_EQ(NearestName("angel", options), "angle");  // two letters swapped: one edit
  EXPECT_EQ(NearestName("illuminnt", options), "illuminant");
  EXPECT_EQ(NearestName("outt", options), "out");
  EXPECT_EQ(NearestName("bogus", options), "");
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
  // KeepSamples keeps the header and the samples it is told to, in their order.
  const Dataset odd = KeepSamples(dataset, [](const Sample& s) { return s.x_atomic > 0.75; });
  ASSERT_EQ(odd.samples.size(), 3u);  // 0.8, 0.9, 1
  EXPECT_EQ(odd.samples.front().file, "Rioux-Au80Ag20.yml");
  EXPECT_EQ(odd.manifest_path, dataset.manifest_path);
  EXPECT_EQ(odd.composition, dataset.composition);
  EXPECT_EQ(odd.excluded.size(), dataset.excluded.size());
}

TEST(AmongCompositionsTest, WithinOneBillionthIsTheSameComposition) {
  EXPECT_TRUE(AmongCompositions(0.5 + 0.9e-9, {0.2, 0.5}));
  EXPECT_TRUE(AmongCompositions(0.5 - 0.9e-9, {0.2, 0.5}));
  EXPECT_FALSE(AmongCompositions(0.5 + 1.1e-9, {0.2, 0.5}));
  EXPECT_FALSE(AmongCompositions(0.5, {}));
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
           R"("samples": [{"x": 0.5, "file": "a.yml"}, {"x": 0.500000002, "file": "b.yml"}]})",
       ": samples 'a.yml' and 'b.yml' have almost the same composition, x = 0.5 and "
       "0.500000002 (closer than 1e-6)"},
      {std::string(kHead) +
           R"("samples": [{"x": 0.5, "file": "a.yml"}, {"x": 0.5, "file": "./a.yml"}]})",
       ": samples[0] and samples[1] both use './a.yml'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    const std::string path = Manifest(c.text);
    EXPECT_THAT(ErrorOf(dir_), HasSubstr(path + c.expected));
  }
}

// The stated measurement precision: read, defaulted to 0 (not stated), and refused by name.
TEST_F(ManifestTest, PrecisionIsReadAndCheckedByName) {
  const std::string one_sample = R"("samples": [{"x": 0.5, "file": "a.yml"}])";
  Dataset dataset = LoadDataset(Manifest(std::string(kHead) + one_sample + "}"));
  EXPECT_EQ(dataset.precision_n, 0.0);
  EXPECT_EQ(dataset.precision_k, 0.0);
  dataset = LoadDataset(Manifest(std::string(kHead) + one_sample +
                                 R"(, "precision": {"n": 0.002, "k": 0.005, "x": 1}})"));
  EXPECT_EQ(dataset.precision_n, 0.002);
  EXPECT_EQ(dataset.precision_k, 0.005);
  ASSERT_EQ(dataset.warnings.size(), 1u);
  EXPECT_THAT(dataset.warnings[0], HasSubstr("precision: unknown key 'x'"));
  for (const auto& [text, expected] : std::vector<std::pair<std::string, std::string>>{
           {R"("precision": 0.002)", ": precision: '0.002' is not an object"},
           {R"("precision": {"n": -0.1})", ": precision: n: '-0.1' is not a standard deviation"},
           {R"("precision": {"k": "0.01"})", ": precision: k: '\"0.01\"' is not a standard"},
           {R"("precision": {"k": 11})", ": precision: k: '11' is not a standard deviation"}}) {
    SCOPED_TRACE(text);
    const std::string path = Manifest(std::string(kHead) + one_sample + ", " + text + "}");
    EXPECT_THAT(ErrorOf(dir_), HasSubstr(path + expected));
  }
}

// Replicates: distinct files at one composition are samples of their own, adjacent and in
// the manifest's order; the helpers see one composition with both.
TEST_F(ManifestTest, ReplicatesAreAcceptedInTheManifestsOrder) {
  const std::string rows = "DATA:\n  - type: tabulated nk\n    data: |\n";
  WriteText(dir_ + "/c.yml", rows + "        0.4 2 4\n        0.5 2 4\n        0.6 2 4\n");
  const std::string path = Manifest(std::string(kHead) + R"("samples": [
      {"x": 0.5, "file": "c.yml"}, {"x": 0.2, "file": "b.yml"}, {"x": 0.5, "file": "a.yml"}]})");
  const Dataset dataset = LoadDataset(path);
  ASSERT_EQ(dataset.samples.size(), 3u);
  EXPECT_EQ(dataset.samples[0].file, "b.yml");
  EXPECT_EQ(dataset.samples[1].file, "c.yml");
  EXPECT_EQ(dataset.samples[2].file, "a.yml");
  EXPECT_EQ(DistinctCompositions(dataset), (std::vector<double>{0.2, 0.5}));
  const std::vector<const Sample*> at = SamplesAtComposition(dataset, 0.5);
  ASSERT_EQ(at.size(), 2u);
  EXPECT_EQ(at[0]->file, "c.yml");
  EXPECT_EQ(at[1]->file, "a.yml");
  EXPECT_TRUE(SamplesAtComposition(dataset, 0.3).empty());
  EXPECT_EQ(FindSample(dataset, 0.5), at[0]);
  EXPECT_EQ(FindSampleByFile(dataset, "a.yml"), at[1]);
  EXPECT_EQ(FindSampleByFile(dataset, dir_ + "/c.yml"), at[0]);
  EXPECT_EQ(FindSampleByFile(dataset, "d.yml"), nullptr);
  EXPECT_EQ(WithoutSamples(dataset, {0.5}).samples.size(), 1u);

  // The mean: eps averaged on the union of wavelengths inside the common range (500-600
  // nm), back to n, k. a: n = 1, k = 2 (eps = -3 + 4i); c: n = 2, k = 4 (eps = -12 + 16i).
  const NkSpectrum mean = MeanSpectrum(at);
  EXPECT_EQ(mean.lambda_nm, (std::vector<double>{500, 600}));
  EXPECT_THAT(mean.source, HasSubstr("c.yml"));
  EXPECT_THAT(mean.source, HasSubstr("a.yml"));
  for (std::size_t i = 0; i < mean.lambda_nm.size(); ++i) {
    const std::complex<double> nk(mean.n[i], mean.k[i]);
    const std::complex<double> eps = nk * nk;
    EXPECT_NEAR(eps.real(), -7.5, 1e-12);
    EXPECT_NEAR(eps.imag(), 10.0, 1e-12);
    EXPECT_GE(mean.n[i], 0);
    EXPECT_GE(mean.k[i], 0);
  }
  EXPECT_EQ(MeanSpectrum({at[0]}).n, at[0]->nk.n);
}

TEST_F(ManifestTest, ReplicatesAfterWeightConversion) {
  const std::string path = Manifest(
      R"({"system": {"a": "Cu", "b": "Zn"}, "composition": "weight_fraction_a", "samples": [
      {"x": 1, "file": "a.yml"}, {"x": 1.0, "file": "b.yml"}]})");
  const Dataset dataset = LoadDataset(path);
  EXPECT_EQ(DistinctCompositions(dataset).size(), 1u);
  EXPECT_EQ(SamplesAtComposition(dataset, 1.0).size(), 2u);
}

// The same measurement twice is still refused, at one composition as at two.
TEST_F(ManifestTest, TheSameFileOrTheSameSpectrumTwiceIsRefused) {
  std::string path =
      Manifest(std::string(kHead) +
               R"("samples": [{"x": 0.5, "file": "a.yml"}, {"x": 0.5, "file": "a.yml"}]})");
  EXPECT_THAT(ErrorOf(path), HasSubstr("both use 'a.yml'"));
  fs::copy_file(dir_ + "/a.yml", dir_ + "/copy.yml");
  path = Manifest(std::string(kHead) +
                  R"("samples": [{"x": 0.5, "file": "a.yml"}, {"x": 0.5, "file": "copy.yml"}]})");
  EXPECT_THAT(ErrorOf(path), HasSubstr("hold the same n, k at every wavelength"));
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

TEST_F(ManifestTest, ElementOverridesAndTheirErrors) {
  const std::string two =
      R"("samples": [{"x": 0.2, "file": "a.yml"}, {"x": 0.7, "file": "b.yml"}])";
  const std::string head =
      R"({"system": {"a": "Au", "b": "Pd"}, "composition": "weight_fraction_a", )";
  const Dataset plain = LoadDataset(Manifest(head + two + "}"));
  EXPECT_STREQ(plain.system.b.symbol, "Pd");
  EXPECT_EQ(plain.system.b.atomic_mass, 106.42);
  EXPECT_TRUE(plain.system.b.valence_conventional);
  EXPECT_FALSE(plain.system.a.valence_conventional);
  // wt% -> at% with the IUPAC masses, by hand.
  const double w = 0.2;
  EXPECT_NEAR(plain.samples[0].x_atomic, (w / 196.966570) / (w / 196.966570 + (1 - w) / 106.42),
              1e-14);

  const Dataset custom = LoadDataset(Manifest(
      head +
      R"("elements": {"Pd": {"valence": 0.36, "density_g_cm3": 12.0, "atomic_mass": 100}},)" + two +
      "}"));
  EXPECT_EQ(custom.system.b.valence, 0.36);
  EXPECT_FALSE(custom.system.b.valence_conventional);
  EXPECT_EQ(custom.system.b.density_g_cm3, 12.0);
  EXPECT_EQ(custom.system.b.atomic_mass, 100);
  EXPECT_NEAR(custom.samples[0].x_atomic, (w / 196.966570) / (w / 196.966570 + (1 - w) / 100),
              1e-14);
  EXPECT_TRUE(custom.warnings.empty());

  const std::vector<std::pair<std::string, std::string>> bad = {
      {R"("elements": [1],)", ": elements: not an object"},
      {R"("elements": {"Ag": {"valence": 1}},)", ": elements.Ag: 'Ag' is not an element of Au-Pd"},
      {R"("elements": {"Pd": 3},)", ": elements.Pd: not an object"},
      {R"("elements": {"Pd": {"valency": 1}},)", ": elements.Pd.valency: unknown key"},
      {R"("elements": {"Pd": {"valence": "1"}},)",
       ": elements.Pd.valence: '\"1\"' is not a positive"},
      {R"("elements": {"Pd": {"valence": -1}},)", ": elements.Pd.valence: '-1' is not a positive"},
      {R"("elements": {"Pd": {"density_g_cm3": 0}},)", ": elements.Pd.density_g_cm3: '0'"},
      {R"("elements": {"Pd": {"atomic_mass": 1e300}},)", ": elements.Pd.atomic_mass: '1e+300'"},
  };
  for (const auto& [text, expected] : bad) {
    SCOPED_TRACE(text);
    const std::string path = Manifest(head + text + two + "}");
    EXPECT_THAT(ErrorOf(path), HasSubstr(path + expected));
  }
}

TEST_F(ManifestTest, FurtherMetalsLoadWithTheirWeightConversion) {
  // Standard atomic weights typed from the CIAAW 2021 table, independently of the library.
  const std::vector<std::pair<std::string, double>> metals = {
      {"Pd", 106.42},    {"Pt", 195.084},   {"Ni", 58.6934},   {"Ti", 47.867},    {"Cr", 51.9961},
      {"Co", 58.933194}, {"Rh", 102.90549}, {"Ir", 192.217},   {"Ta", 180.94788}, {"W", 183.84},
      {"Mo", 95.95},     {"V", 50.9415},    {"Ru", 101.07},    {"Os", 190.23},    {"Re", 186.207},
      {"Zr", 91.224},    {"Hf", 178.486},   {"Mn", 54.938043}, {"Cd", 112.414},   {"Si", 28.085},
      {"Ge", 72.630},    {"Sb", 121.760},   {"Bi", 208.98040}, {"Li", 6.94},      {"Be", 9.0121831},
      {"Y", 88.905838},  {"Sc", 44.955907}, {"La", 138.90547}, {"Te", 127.60},    {"B", 10.81},
  };
  ASSERT_GE(metals.size(), 26u);
  for (const auto& [symbol, mass] : metals) {
    SCOPED_TRACE(symbol);
    const std::string path = Manifest(R"({"system": {"a": "Au", "b": ")" + symbol +
                                      R"("}, "composition": "weight_fraction_a", "samples": [
        {"x": 0.75, "file": "a.yml"}, {"x": 0.3, "file": "b.yml"}]})");
    const Dataset dataset = LoadDataset(path);
    ASSERT_EQ(dataset.samples.size(), 2u);
    EXPECT_EQ(dataset.name, "Au-" + symbol);
    const auto by_hand = [&mass = mass](double w) {
      return (w / 196.966570) / (w / 196.966570 + (1 - w) / mass);
    };
    EXPECT_NEAR(dataset.samples[0].x_atomic, by_hand(0.3), 1e-13);
    EXPECT_NEAR(dataset.samples[1].x_atomic, by_hand(0.75), 1e-13);
    EXPECT_NEAR(ParseComposition("18k", dataset.system), by_hand(0.75), 1e-13);
  }
}

TEST_F(ManifestTest, ColumnsAndPairedFiles) {
  WriteText(dir_ + "/multi.csv",
            "Export\r\nWavelength(nm),n6,k6,n12,k12,\r\n500,1,2,1,3,\r\n600,1,2,1,3,\r\n");
  WriteText(dir_ + "/n.yml",
            "DATA:\n  - type: tabulated n\n    data: |\n        0.5 1\n        0.6 1\n");
  WriteText(dir_ + "/k.yml",
            "DATA:\n  - type: tabulated k\n    data: |\n        0.5 4\n        0.6 4\n");
  const std::string path = Manifest(std::string(kHead) + R"("samples": [
      {"x": 0.2, "file": "multi.csv", "columns": ["n6", "k6"]},
      {"x": 0.4, "file": "multi.csv", "columns": [4, 5]},
      {"x": 0.6, "n_file": "n.yml", "k_file": "k.yml"}]})");
  const Dataset dataset = LoadDataset(path);
  ASSERT_EQ(dataset.samples.size(), 3u);
  EXPECT_EQ(dataset.samples[0].nk.k[0], 2);
  EXPECT_EQ(dataset.samples[1].nk.k[0], 3);
  EXPECT_EQ(dataset.samples[2].nk.k[0], 4);
  EXPECT_EQ(dataset.samples[0].file, "multi.csv (columns n6,k6)");
  EXPECT_EQ(dataset.samples[1].file, "multi.csv (columns 4,5)");
  EXPECT_EQ(dataset.samples[2].file, "n.yml + k.yml");
  EXPECT_EQ(dataset.samples[2].k_path, dir_ + "/k.yml");
  EXPECT_EQ(dataset.samples[2].checksum,
            Fnv1a64Hex(ReadFileText(dir_ + "/n.yml") + ReadFileText(dir_ + "/k.yml")));

  const std::vector<std::pair<std::string, std::string>> bad = {
      {R"({"x": 0.2, "file": "multi.csv"})", "the header holds 2 column pairs"},
      {R"({"x": 0.2, "file": "multi.csv", "columns": "n6,k6"})",
       ": samples[0].columns: not a list"},
      {R"({"x": 0.2, "file": "multi.csv", "columns": ["n6"]})", ": samples[0].columns: not a list"},
      {R"({"x": 0.2, "file": "multi.csv", "columns": [0, 1]})", "neither a header name nor"},
      {R"({"x": 0.2, "file": "multi.csv", "columns": ["n7", "k7"]})", "no column named 'n7'"},
      {R"({"x": 0.2, "n_file": "n.yml"})", ": samples[0]: give either \"file\" or both"},
      {R"({"x": 0.2, "file": "a.yml", "k_file": "k.yml"})", ": samples[0]: give either"},
      {R"({"x": 0.2, "n_file": "n.yml", "k_file": "k.yml", "columns": [2, 3]})",
       "columns: applies to \"file\""},
      {R"({"x": 0.2, "n_file": "k.yml", "k_file": "n.yml"})", "expected 'tabulated n' alone"},
  };
  for (const auto& [sample, expected] : bad) {
    SCOPED_TRACE(sample);
    const std::string bad_path = Manifest(std::string(kHead) + R"("samples": [)" + sample + "]}");
    EXPECT_THAT(ErrorOf(bad_path), HasSubstr(expected));
  }
}

// A white-gold data set named with its real elements, made from bundled spectra (the
// Rioux Au-Ag series relabelled Au-Pd: the optics need no Pd data to be exercised), in
// three of the layouts labs write, fitted and validated by the real program.
TEST(AuPdProgramTest, FitAndLeaveOneOutValidationRunOnAWhiteGoldDataSet) {
  const std::string dir = MakeTempDir();
  const std::vector<std::pair<int, const char*>> series = {{100, "Rioux-Au100Ag0.yml"},
                                                           {80, "Rioux-Au80Ag20.yml"},
                                                           {50, "Rioux-Au50Ag50.yml"},
                                                           {30, "Rioux-Au30Ag70.yml"},
                                                           {0, "Rioux-Au0Ag100.yml"}};
  std::string multi = "Ellipsometer export\r\nAu-Pd series\r\nWavelength(nm),n80,k80,n30,k30,\r\n";
  const NkSpectrum au80 = ReadNkFile(DataDir() + "/Au-Ag/Rioux-Au80Ag20.yml");
  const NkSpectrum au30 = ReadNkFile(DataDir() + "/Au-Ag/Rioux-Au30Ag70.yml");
  ASSERT_EQ(au80.lambda_nm, au30.lambda_nm);
  for (std::size_t i = au80.lambda_nm.size(); i-- > 0;) {
    char row[160];
    std::snprintf(row, sizeof(row), "%.9g,%.9g,%.9g,%.9g,%.9g,\r\n", au80.lambda_nm[i], au80.n[i],
                  au80.k[i], au30.n[i], au30.k[i]);
    multi += row;
  }
  WriteText(dir + "/export.csv", multi);
  const NkSpectrum au50 = ReadNkFile(DataDir() + "/Au-Ag/Rioux-Au50Ag50.yml");
  std::string eps = "# eps of the 50 % film\nEnergy (eV)\te1\te2\n";
  for (std::size_t i = 0; i < au50.lambda_nm.size(); ++i) {
    char row[160];
    const double n = au50.n[i], k = au50.k[i];
    std::snprintf(row, sizeof(row), "%.9g\t%.9g\t%.9g\n", 1239.8419843320026 / au50.lambda_nm[i],
                  n * n - k * k, 2 * n * k);
    eps += row;
  }
  WriteText(dir + "/au50-eps.txt", eps);
  WriteText(dir + "/dataset.json", R"({"name": "white gold, a test",
    "system": {"a": "Au", "b": "Pd"}, "composition": "atomic_fraction_a", "samples": [
      {"x": 1.0, "file": ")" + DataDir() +
                                       R"(/Au-Ag/Rioux-Au100Ag0.yml"},
      {"x": 0.8, "file": "export.csv", "columns": ["n80", "k80"]},
      {"x": 0.5, "file": "au50-eps.txt"},
      {"x": 0.3, "file": "export.csv", "columns": ["n30", "k30"]},
      {"x": 0.0, "file": ")" + DataDir() +
                                       R"(/Au-Ag/Rioux-Au0Ag100.yml"}]})");

  const auto fit = RunProgram({"fit", "--data", dir, "--out", dir + "/aupd.json", "--quiet"});
  ASSERT_EQ(fit.status, 0) << fit.err;
  const auto model = nlohmann::json::parse(ReadFileText(dir + "/aupd.json"));
  EXPECT_EQ(model["system"]["a"], "Au");
  EXPECT_EQ(model["system"]["b"], "Pd");

  const auto color = RunProgram({"color", "--model", dir + "/aupd.json", "--x", "18k", "--json"});
  EXPECT_EQ(color.status, 0) << color.err;

  const auto validate =
      RunProgram({"validate", "--data", dir, "--loo", "--out", dir + "/report", "--quiet"});
  ASSERT_EQ(validate.status, 0) << validate.err;
  const auto report = nlohmann::json::parse(ReadFileText(dir + "/report/report.json"));
  EXPECT_EQ(report["mode"], "loo");
  EXPECT_EQ(report["holdouts"].size(), 3u);  // the interior samples
  fs::remove_all(dir);
}

}  // namespace
}  // namespace alloycolor

namespace alloycolor {
namespace {

// Pd has no free-electron valence in Ashcroft & Mermin's table: the m* read-out says its
// valence is a convention; Au's is not flagged.
TEST(ConventionalValence, FlaggedInTheParamsReadOut) {
  const std::string dir = MakeTempDir();
  const std::string au = DataDir() + "/Au-Ag/Rioux-Au100Ag0.yml";
  const std::string ag = DataDir() + "/Au-Ag/Rioux-Au0Ag100.yml";
  WriteText(dir + "/dataset.json",
            R"({"system": {"a": "Au", "b": "Pd"}, "composition": "atomic_fraction_a",
                "samples": [{"x": 0, "file": ")" +
                ag + R"("}, {"x": 1, "file": ")" + au + R"("}]})");
  const auto r = RunProgram({"params", "--data", dir, "--method", "eps-linear", "--steps", "2"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("Pd: Z = 1 (conventional"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("Au: Z = 1 (conventional"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace alloycolor
