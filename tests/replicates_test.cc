// Replicates: two films of one alloy, distinct files at the same composition.
//  - the data set keeps both; every method fits them: the interpolating methods through
//    their mean (one node per composition), the regressions with each film an observation;
//    the prediction at their composition lies within 0.6 d of the colour of their mean
//    (d the CIEDE2000 difference between the films) and the model's own one-sigma there is
//    at least 0.25 d (the replicate scatter enters the error bar);
//  - the model's leave-one-out folds hold out both films together;
//  - validate's leave-one-out gives one row per sample, holding out a composition with all
//    its replicates; --holdout names one replicate by its file, or a composition with both;
//    the report names the replicates' files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/io.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/fit/smooth_fit.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/validate/validation.h"
#include "test_util.h"

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
using testing::DataDir;
using ::testing::HasSubstr;
using testing::MakeTempDir;
using testing::ReadText;
using testing::RunProgram;
using testing::WriteText;

// Compositions of the bundled Au-Ag set used (fewer folds: a quicker test).
const std::vector<double> kXs = {0.0, 0.2, 0.5, 0.8, 1.0};
constexpr double kKScale = 1.12;  // the second film: k of the first, 12 % higher

const color::Colorimeter& D65() {
  static const color::Colorimeter cm = color::Colorimeter::Load(DataDir(), "D65", 2);
  return cm;
}

color::Lab LabOf(const std::vector<std::complex<double>>& index) {
  return color::ColorFromXYZ(D65(), color::MaterialXYZ(D65(), index, 0.0)).lab;
}

// A folder with a manifest for kXs of the bundled Au-Ag set and, at x = 0.5, a second film
// "Au50-film2.csv" whose k is kKScale times the first's.
std::string WriteReplicateDataset() {
  const std::string dir = MakeTempDir();
  const Dataset bundled = LoadDataset(DataDir() + "/Au-Ag");
  std::string samples;
  for (double x : kXs) {
    const Sample* s = FindSample(bundled, x);
    samples += (samples.empty() ? "" : ", ") + std::string("{\"x\": ") + std::to_string(x) +
               ", \"file\": \"" + s->path + "\"}";
    if (x == 0.5) {
      std::vector<double> k = s->nk.k;
      for (double& v : k) v *= kKScale;
      WriteText(dir + "/Au50-film2.csv", NkCsvText(s->nk.lambda_nm, s->nk.n, k));
      samples += ", {\"x\": 0.5, \"file\": \"Au50-film2.csv\"}";
    }
  }
  WriteText(dir + "/dataset.json",
            "{\"system\": {\"a\": \"Au\", \"b\": \"Ag\"}, \"composition\": \"atomic_fraction_a\", "
            "\"samples\": [" +
                samples + "]}");
  return dir;
}

const std::string& ReplicateDir() {
  static const std::string dir = WriteReplicateDataset();
  return dir;
}

TEST(Replicates, TheDataSetKeepsBothFilms) {
  const Dataset data = LoadDataset(ReplicateDir());
  ASSERT_EQ(data.samples.size(), kXs.size() + 1);
  EXPECT_EQ(DistinctCompositions(data), kXs);
  const std::vector<const Sample*> films = SamplesAtComposition(data, 0.5);
  ASSERT_EQ(films.size(), 2u);
  EXPECT_EQ(films[0]->file.find("Rioux-Au50Ag50.yml") != std::string::npos, true);
  EXPECT_EQ(films[1]->file, "Au50-film2.csv");
}

// The identical file twice at one composition stays refused.
TEST(Replicates, TheSameFileTwiceIsRefused) {
  const std::string dir = MakeTempDir();
  const std::string au50 = DataDir() + "/Au-Ag/Rioux-Au50Ag50.yml";
  WriteText(dir + "/dataset.json",
            "{\"system\": {\"a\": \"Au\", \"b\": \"Ag\"}, \"composition\": \"atomic_fraction_a\", "
            "\"samples\": [{\"x\": 0, \"file\": \"" +
                DataDir() +
                "/Au-Ag/Rioux-Au0Ag100.yml\"}, "
                "{\"x\": 0.5, \"file\": \"" +
                au50 + "\"}, {\"x\": 0.5, \"file\": \"" + au50 +
                "\"}, "
                "{\"x\": 1, \"file\": \"" +
                DataDir() + "/Au-Ag/Rioux-Au100Ag0.yml\"}]}");
  EXPECT_THAT(testing::ErrorOf([&] { LoadDataset(dir); }),
              HasSubstr("one file is one composition"));
}

class ReplicateFit : public ::testing::TestWithParam<const char*> {};

TEST_P(ReplicateFit, PredictsTheMeanWithAnErrorBarThatCoversTheScatter) {
  const Dataset data = LoadDataset(ReplicateDir());
  const std::vector<const Sample*> films = SamplesAtComposition(data, 0.5);
  ASSERT_EQ(films.size(), 2u);
  const color::Lab first = LabOf(color::IndexOnGrid(D65(), films[0]->nk));
  const color::Lab second = LabOf(color::IndexOnGrid(D65(), films[1]->nk));
  const double d = color::DeltaE00(first, second);
  ASSERT_GT(d, 1.0);  // a difference the eye sees
  const color::Lab mean = LabOf(color::IndexOnGrid(D65(), MeanSpectrum(films)));

  fit::FitSettings settings;
  settings.colorimeter = &D65();
  const std::unique_ptr<AlloyModel> model = fit::BuildModel(GetParam(), data, settings);
  ASSERT_TRUE(model);
  EXPECT_EQ(model->training_samples().size(), data.samples.size());
  const double miss = color::DeltaE00(LabOf(color::IndexOnGrid(D65(), *model, 0.5)), mean);
  EXPECT_LE(miss, 0.6 * d) << GetParam() << ": d = " << d;
  ASSERT_TRUE(model->HasUncertainty()) << GetParam();
  const double sigma = color::DeltaE00Sigma(D65(), *model, 0.5, 0.0);
  EXPECT_GE(sigma, 0.25 * d) << GetParam() << ": d = " << d;
  RecordProperty("delta_e00_films", std::to_string(d));
  RecordProperty("miss_of_mean", std::to_string(miss));
  RecordProperty("sigma", std::to_string(sigma));
}

INSTANTIATE_TEST_SUITE_P(Methods, ReplicateFit,
                         ::testing::Values("paper", "eps-linear", "eps-pchip", "eps-spline",
                                           "smooth", "physical", "auto"));

// With three compositions no fold can cross-validate the smoothing; the marginal
// likelihood decides, and with the second film it has the films' scatter to weigh (three
// samples alone leave it nothing: the default, no smoothing).
TEST(Replicates, SmoothWeighsTheFilmsScatterWhenFewCompositions) {
  const Dataset all = LoadDataset(ReplicateDir());
  const Dataset three = WithoutSamples(all, {0.2, 0.8});
  ASSERT_EQ(three.samples.size(), 4u);
  const fit::SmoothFitResult with = fit::FitSmooth(three, {});
  EXPECT_FALSE(with.evidence.empty());
  EXPECT_EQ(with.smoothing_per_node.size(), with.model->grid_nm().size());
  Dataset single = three;
  single.samples.erase(single.samples.begin() + 2);  // the second film
  ASSERT_EQ(single.samples.size(), 3u);
  EXPECT_TRUE(fit::FitSmooth(single, {}).evidence.empty());
}

// Leave-one-out holds out x = 0.2, 0.5 (both films) and 0.8: one row per held-out sample.
TEST(Replicates, LeaveOneOutHoldsOutACompositionWithAllItsFilms) {
  const Dataset data = LoadDataset(ReplicateDir());
  const std::vector<validate::SampleSplit> splits = validate::LeaveOneOutSplits(data);
  ASSERT_EQ(splits.size(), 3u);
  EXPECT_EQ(splits[1], (validate::SampleSplit{2, 3}));

  validate::ValidationOptions options;
  options.build = fit::SharedFitBuilder(D65());
  options.methods = {"eps-linear", "smooth"};
  options.angles_deg = {0.0};
  options.mode = "loo";
  const validate::ValidationReport report =
      validate::ComputeValidation(data, splits, D65(), options, {});
  ASSERT_EQ(report.holdouts.size(), 4u);
  EXPECT_EQ(report.holdouts[1].split, 1);
  EXPECT_EQ(report.holdouts[2].split, 1);
  EXPECT_TRUE(report.holdouts[1].replicate);
  EXPECT_FALSE(report.holdouts[0].replicate);
  EXPECT_EQ(report.holdouts[2].file, "Au50-film2.csv");
  // Neither film is in the training of its split.
  EXPECT_EQ(report.splits[1].train_x, (std::vector<double>{0.0, 0.2, 0.8, 1.0}));
  for (const validate::HoldoutResult& h : report.holdouts) {
    for (const std::string& method : options.methods) {
      ASSERT_EQ(h.results.count(method), 1u);
      EXPECT_TRUE(h.results.at(method).error.empty()) << h.results.at(method).error;
    }
  }
}

TEST(Replicates, HoldoutNamesOneFilmByItsFileOrBothByTheComposition) {
  const Dataset data = LoadDataset(ReplicateDir());
  EXPECT_EQ(validate::HoldoutSplit(data, {"Au50-film2.csv"}), (validate::SampleSplit{3}));
  EXPECT_EQ(validate::HoldoutSplit(data, {"0.5"}), (validate::SampleSplit{2, 3}));
  EXPECT_EQ(validate::HoldoutSplit(data, {"50at%", "0.2"}), (validate::SampleSplit{1, 2, 3}));
  EXPECT_THAT(testing::ErrorOf([&] { validate::HoldoutSplit(data, {"nonesuch.csv"}); }),
              HasSubstr("nonesuch.csv"));
  EXPECT_THAT(testing::ErrorOf([&] { validate::HoldoutSplit(data, {"1"}); }),
              HasSubstr("end sample"));
}

// The program: --holdout with the second film's file holds out that film alone; the first
// film stays in training; the report names the file.
TEST(Replicates, ValidateHoldsOutOneFilmByFileName) {
  const std::string out = MakeTempDir();
  const testing::RunResult run =
      RunProgram({"validate", "--data", ReplicateDir(), "--holdout", "Au50-film2.csv", "--methods",
                  "eps-linear,paper", "--angles", "0", "--out", out, "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(ReadText(out + "/report.json"));
  ASSERT_EQ(report["holdouts"].size(), 1u);
  EXPECT_EQ(report["holdouts"][0]["file"], "Au50-film2.csv");
  EXPECT_EQ(report["holdouts"][0]["replicate"], true);
  EXPECT_EQ(report["splits"][0]["train_x"], nlohmann::json({0.0, 0.2, 0.5, 0.8, 1.0}));
  EXPECT_EQ(report["splits"][0]["holdout_files"], nlohmann::json({"Au50-film2.csv"}));
  // The first film predicts its twin: the error is the films' own difference.
  const double de = report["holdouts"][0]["results"]["eps-linear"]["delta_e00"]["0"];
  EXPECT_GT(de, 0.5);
  EXPECT_THAT(ReadText(out + "/report.html"), HasSubstr("Au50-film2.csv"));

  // Leave-one-out by the program: one row per sample, both films at 0.5.
  const std::string loo = MakeTempDir();
  const testing::RunResult all =
      RunProgram({"validate", "--data", ReplicateDir(), "--methods", "eps-linear", "--angles", "0",
                  "--out", loo, "--quiet"});
  ASSERT_EQ(all.status, 0) << all.err;
  const nlohmann::json rows = nlohmann::json::parse(ReadText(loo + "/report.json"));
  ASSERT_EQ(rows["holdouts"].size(), 4u);
  EXPECT_EQ(rows["holdouts"][2]["file"], "Au50-film2.csv");
  EXPECT_EQ(rows["holdouts"][1]["split"], rows["holdouts"][2]["split"]);
}

// Every command that takes a data set takes one with replicates.
TEST(Replicates, FitCommandAcceptsTheDataSet) {
  const std::string out = MakeTempDir() + "/model.json";
  const testing::RunResult run = RunProgram(
      {"fit", "--data", ReplicateDir(), "--method", "eps-pchip", "--out", out, "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json model = nlohmann::json::parse(ReadText(out));
  EXPECT_EQ(model["training_samples"].size(), kXs.size() + 1);
}

}  // namespace
}  // namespace alloycolor
