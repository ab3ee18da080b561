// The lab's loop (fit/suspects.h, fit/lineage.h, color/suggest.h): which sample the rest of
// a series contradicts, what a refit says of each added sample, samples set aside by the
// manifest, error bars only where something could be held out, and where to measure next.
// Against independent references: the F distribution's tail in closed form and its limit,
// the program's own `color` outputs for the figures a refit records, hand-made series with
// one sample spoilt on purpose.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/color/sample_error.h"
#include "alloycolor/color/suggest.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/error.h"
#include "alloycolor/fit/lineage.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/fit/suspects.h"
#include "alloycolor/validate/validation.h"
#include "test_util.h"

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
using testing::DataDir;
using testing::MakeTempDir;
using testing::ReadText;
using testing::RunProgram;
using testing::WriteText;

const color::Colorimeter& D65() {
  static const color::Colorimeter cm = color::Colorimeter::Load(DataDir(), "D65", 2);
  return cm;
}

fit::FitSettings Settings() {
  fit::FitSettings s;
  s.colorimeter = &D65();
  return s;
}

std::unique_ptr<AlloyModel> FitOf(const Dataset& dataset, const std::string& method = "auto") {
  return fit::FitDataSet(method, dataset, Settings(), {nullptr, "2026-12-06T00:00:00Z"});
}

// A folder with the bundled files of `from` and a manifest of these samples.
std::string DatasetOf(const std::string& from, const nlohmann::json& manifest) {
  const std::string dir = MakeTempDir();
  for (const auto& entry : fs::directory_iterator(DataDir() + "/" + from)) {
    if (entry.path().extension() == ".yml") {
      fs::copy_file(entry.path(), fs::path(dir) / entry.path().filename());
    }
  }
  WriteText(dir + "/dataset.json", manifest.dump());
  return dir;
}

nlohmann::json Manifest(const std::string& a, const std::string& b, const std::string& kind,
                        const std::vector<std::pair<double, std::string>>& samples) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& [x, file] : samples) list.push_back({{"x", x}, {"file", file}});
  return {{"system", {{"a", a}, {"b", b}}}, {"composition", kind}, {"samples", list}};
}

TEST(FTailTwo, ClosedFormAndLimit) {
  // F(2, 2) has the tail 1 / (1 + f); F(2, 2m) tends to the tail of chi^2_2 / 2, exp(-f).
  for (double f : {0.0, 0.5, 3.0, 40.0}) {
    EXPECT_NEAR(fit::FTailTwo(f, 1), 1 / (1 + f), 1e-15);
    // (1 + f / m)^-m = exp(-f) (1 + f^2 / (2 m) + ...).
    EXPECT_NEAR(fit::FTailTwo(f, 1e7), std::exp(-f), 1e-3 * std::exp(-f));
  }
  // F(2, 4) by its density integrated numerically: 2 f^0 ... pdf(f) = (1 + f / 2)^-3.
  double tail = 0;
  const double from = 2.5, step = 1e-3;
  for (double f = from; f < 4000; f += step) tail += step * std::pow(1 + (f + step / 2) / 2, -3);
  EXPECT_NEAR(fit::FTailTwo(from, 2), tail, 1e-6);
  EXPECT_EQ(fit::FTailTwo(std::numeric_limits<double>::infinity(), 3), 0);
}

TEST(MetallicFraction, CountsWavelengthsWhereNIsBelowK) {
  NkSpectrum nk;
  nk.lambda_nm = {300, 400, 500, 600, 700, 900};
  nk.n = {0.5, 2.0, 0.3, 0.3, 3.0, 0.1};
  nk.k = {2.0, 1.0, 3.0, 3.0, 2.0, 5.0};
  EXPECT_DOUBLE_EQ(fit::MetallicFraction(nk, 380, 780), 0.5);  // 400 and 700 are not
  EXPECT_TRUE(std::isnan(fit::MetallicFraction(nk, 950, 990)));
}

TEST(CheckSamples, QuerrysZincIsNamedAndTheOtherSeriesAreNot) {
  const Dataset querry = LoadDataset(DataDir() + "/Cu-Zn");
  const auto model = FitOf(querry);
  ASSERT_TRUE(model->samples_checked());
  ASSERT_EQ(model->suspect_samples().size(), 1u);
  const SampleNote& zinc = model->suspect_samples()[0];
  EXPECT_EQ(zinc.file, "Querry-Zn100.yml");
  EXPECT_EQ(zinc.check, "not metallic");
  EXPECT_EQ(zinc.figure, 0.0);
  EXPECT_NE(zinc.reason.find("exclude"), std::string::npos) << zinc.reason;
  // The fit without it predicts it (an extrapolation to x = 0), with an error bar there.
  EXPECT_GT(zinc.delta_e00, 5);
  EXPECT_GT(zinc.sigma_de00, 0);
  // One warning line names it.
  int named = 0;
  for (const std::string& w : model->warnings()) named += w.find("Querry-Zn100.yml") != w.npos;
  EXPECT_EQ(named, 1);
  for (const std::string set : {"Cu-Zn/dataset-werner-zn.json", "Au-Ag", "Nb-Sn"}) {
    const auto other = FitOf(LoadDataset(DataDir() + "/" + set));
    EXPECT_TRUE(other->samples_checked()) << set;
    for (const SampleNote& n : other->suspect_samples()) ADD_FAILURE() << set << ": " << n.reason;
  }
}

// Two metals with eps linear in composition, one sample's n and k scaled to make it a
// different film.
TEST(CheckSamples, ASpoiltInteriorFilmIsHeldOutOfLine) {
  const std::vector<double> xs = {0, 0.15, 0.3, 0.45, 0.6, 0.75, 0.9, 1};
  const auto spoilt = [](double x, double l) {
    const std::complex<double> e = testing::LinearEps(x, l);
    // A 40 % brighter-and-bluer film at x = 0.45: a mislabelled composition or another metal.
    return std::abs(x - 0.45) < 1e-9 ? std::complex<double>(e.real() * 1.6, e.imag() * 0.4) : e;
  };
  const Dataset bad = LoadDataset(testing::WriteSyntheticDataset(xs, spoilt));
  const auto model = FitOf(bad, "eps-linear");
  ASSERT_EQ(model->suspect_samples().size(), 1u);
  EXPECT_EQ(model->suspect_samples()[0].check, "held out");
  EXPECT_NEAR(model->suspect_samples()[0].x_atomic, 0.45, 1e-12);
  EXPECT_GT(model->suspect_samples()[0].figure, 3);
  // The same series unspoilt: nothing.
  const Dataset good = LoadDataset(testing::WriteSyntheticDataset(xs, testing::LinearEps));
  EXPECT_TRUE(FitOf(good, "eps-linear")->suspect_samples().empty());
}

TEST(Exclude, ASampleSetAsideIsKeptWithItsReasonAndScoredAsHeldOut) {
  nlohmann::json manifest = Manifest("Cu", "Zn", "weight_fraction_a",
                                     {{0.0, "Querry-Zn100.yml"},
                                      {0.70, "Querry-Cu70Zn30.yml"},
                                      {0.85, "Querry-Cu85Zn15.yml"},
                                      {0.90, "Querry-Cu90Zn10.yml"},
                                      {1.0, "Querry-Cu100.yml"}});
  manifest["samples"][0]["exclude"] = "not metallic: an oxidised film";
  const std::string dir = DatasetOf("Cu-Zn", manifest);
  const Dataset dataset = LoadDataset(dir);
  ASSERT_EQ(dataset.samples.size(), 4u);
  ASSERT_EQ(dataset.excluded.size(), 1u);
  EXPECT_EQ(dataset.excluded[0].excluded, "not metallic: an oxidised film");
  const auto model = FitOf(dataset);
  EXPECT_EQ(model->x_min(), dataset.samples.front().x_atomic);
  ASSERT_EQ(model->excluded_samples().size(), 1u);
  const SampleNote& zinc = model->excluded_samples()[0];
  EXPECT_EQ(zinc.reason, "not metallic: an oxidised film");
  // Held out: the model never saw it, and its error there is what ErrorAgainstSample says.
  const double expected = color::ErrorAgainstSample(D65(), *model, dataset.excluded[0]).delta_e00;
  EXPECT_DOUBLE_EQ(zinc.delta_e00, expected);
  // Through the model file and back.
  const auto back = ModelFromJson(model->ToJson(), "m.json");
  ASSERT_EQ(back->excluded_samples().size(), 1u);
  EXPECT_EQ(back->excluded_samples()[0].reason, zinc.reason);
  // The validation report holds it out of every split and scores it in a split of its own,
  // trained on every sample in use; the summaries leave it out.
  validate::ValidationOptions v;
  v.build = fit::SharedFitBuilder(D65());
  v.methods = {"eps-linear"};
  v.angles_deg = {0.0};
  v.mode = "loo";
  const validate::ValidationReport report =
      validate::ComputeValidation(dataset, validate::LeaveOneOutSplits(dataset), D65(), v, nullptr);
  int aside = 0;
  for (const validate::HoldoutResult& h : report.holdouts) {
    if (h.excluded.empty()) continue;
    ++aside;
    EXPECT_EQ(h.file, "Querry-Zn100.yml");
    EXPECT_EQ(report.splits[h.split].train_x.size(), dataset.samples.size());
    EXPECT_GT(h.results.at("eps-linear").delta_e00.at(0), 5);
  }
  EXPECT_EQ(aside, 1);
  for (const validate::SplitResult& split : report.splits) {
    for (double x : split.train_x) EXPECT_NE(x, 0.0) << "a split trained on the zinc set aside";
  }
  EXPECT_EQ(validate::Coverage(report, "eps-linear", 0).count, 2);  // the two interior folds
  // A reason must be text.
  manifest["samples"][0]["exclude"] = true;
  WriteText(dir + "/dataset.json", manifest.dump());
  const std::string message = testing::ErrorOf([&] { LoadDataset(dir); });
  EXPECT_NE(message.find("samples[0]"), std::string::npos) << message;
  EXPECT_NE(message.find("exclude"), std::string::npos) << message;
}

TEST(ErrorBars, TwoCompositionsClaimNone) {
  const Dataset all = LoadDataset(DataDir() + "/Cu-Zn");
  Dataset two = all;
  two.samples = {all.samples[1], all.samples[4]};
  for (const std::string method : {"auto", "smooth", "physical", "eps-linear"}) {
    const auto model = fit::BuildModel(method, two, Settings());
    EXPECT_FALSE(model->HasUncertainty()) << method;
    EXPECT_LT(color::DeltaE00Sigma(D65(), *model, 0.85, 0.0), 0) << method;
    EXPECT_NE(model->NoErrorBarReason().find("no error bar: 2 compositions"), std::string::npos);
  }
}

// The judge's check of a refit: the recorded error and one-sigma of the added sample equal
// what `alloycolor color` gives for the old model at the sample's composition and for the
// sample's own file.
TEST(Refit, TheAddedSampleIsJudgedAsColorWouldJudgeIt) {
  const std::vector<std::pair<double, std::string>> first = {{0.0, "Werner-Zn100.yml"},
                                                             {0.70, "Querry-Cu70Zn30.yml"},
                                                             {0.85, "Querry-Cu85Zn15.yml"},
                                                             {1.0, "Querry-Cu100.yml"}};
  std::vector<std::pair<double, std::string>> second = first;
  second.push_back({0.90, "Querry-Cu90Zn10.yml"});
  const std::string dir = DatasetOf("Cu-Zn", Manifest("Cu", "Zn", "weight_fraction_a", first));
  const std::string old_path = dir + "/old.json", new_path = dir + "/new.json";
  ASSERT_EQ(RunProgram({"fit", "--data", dir, "--out", old_path, "--quiet"}).status, 0);
  WriteText(dir + "/dataset.json", Manifest("Cu", "Zn", "weight_fraction_a", second).dump());
  const testing::RunResult refit =
      RunProgram({"fit", "--data", dir, "--refit", old_path, "--out", new_path, "--quiet"});
  ASSERT_EQ(refit.status, 0) << refit.err;
  EXPECT_NE(refit.err.find("refit: added Querry-Cu90Zn10.yml"), std::string::npos) << refit.err;
  const nlohmann::json model = nlohmann::json::parse(ReadText(new_path));
  ASSERT_EQ(model["history"].size(), 2u);
  const nlohmann::json& added = model["history"][1]["added"];
  ASSERT_EQ(added.size(), 1u);
  const double x = added[0]["x"].get<double>();
  char x_text[40];
  std::snprintf(x_text, sizeof x_text, "%.17g", x);
  const auto old_colour = nlohmann::json::parse(
      RunProgram({"color", "--model", old_path, "--x", x_text, "--json"}).out);
  const auto measured = nlohmann::json::parse(
      RunProgram({"color", "--nk", dir + "/Querry-Cu90Zn10.yml", "--json"}).out);
  const auto lab = [](const nlohmann::json& c) {
    return color::Lab{c["Lab"][0].get<double>(), c["Lab"][1].get<double>(),
                      c["Lab"][2].get<double>()};
  };
  EXPECT_NEAR(added[0]["delta_e00"].get<double>(), color::DeltaE00(lab(old_colour), lab(measured)),
              0.02);
  EXPECT_NEAR(added[0]["sigma_de00"].get<double>(), old_colour["delta_e00_sigma"].get<double>(),
              0.02);
  EXPECT_FALSE(added[0]["verdict"].get<std::string>().empty());
  EXPECT_EQ(model["history"][1]["previous_method"],
            nlohmann::json::parse(ReadText(old_path))["method"]);
}

TEST(Suggest, KeepsAwayFromSamplesInsideTheRangeAndPrintsColorsSigma) {
  const Dataset dataset = LoadDataset(DataDir() + "/Cu-Zn/dataset-werner-zn.json");
  const auto model = fit::BuildModel("smooth", dataset, Settings());
  color::SuggestOptions options;
  options.count = 3;
  const color::SuggestResult r = color::SuggestCompositions(D65(), *model, options);
  ASSERT_EQ(r.suggestions.size(), 3u);
  std::vector<double> taken;
  for (const TrainingSample& t : model->training_samples()) taken.push_back(t.x_atomic);
  double previous_max = INFINITY;
  for (const color::Suggestion& s : r.suggestions) {
    EXPECT_GE(s.x_atomic, model->x_min());
    EXPECT_LE(s.x_atomic, model->x_max());
    for (double t : taken) EXPECT_GE(std::abs(s.x_atomic - t), 0.02 - 1e-12) << s.x_atomic;
    taken.push_back(s.x_atomic);
    EXPECT_DOUBLE_EQ(s.sigma, color::DeltaE00Sigma(D65(), *model, s.x_atomic, 0.0));
    // Measuring more never widens the largest error bar.
    EXPECT_LE(s.max_sigma_after, previous_max + 1e-12);
    EXPECT_LE(s.mean_sigma_after, s.mean_sigma_before);
    previous_max = s.max_sigma_after;
  }
  // Measuring the suggestions lowers the mean one-sigma over the range.
  EXPECT_LT(r.suggestions.back().mean_sigma_after, 0.9 * r.suggestions[0].mean_sigma_before);
  // The widest gap's rule: the middle of the widest gap, the range's ends counted.
  options.rule = color::SuggestRule::kWidestGap;
  options.count = 1;
  const color::SuggestResult widest = color::SuggestCompositions(D65(), *model, options);
  std::vector<double> xs;
  for (const TrainingSample& t : model->training_samples()) xs.push_back(t.x_atomic);
  double width = 0, middle = 0;
  for (size_t i = 1; i < xs.size(); ++i) {
    if (xs[i] - xs[i - 1] > width) width = xs[i] - xs[i - 1], middle = (xs[i] + xs[i - 1]) / 2;
  }
  ASSERT_EQ(widest.suggestions.size(), 1u);
  EXPECT_DOUBLE_EQ(widest.suggestions[0].x_atomic, middle);
  // Without error bars, the middle of the widest gap.
  Dataset two = dataset;
  two.samples = {dataset.samples[1], dataset.samples[4]};
  const auto line = fit::BuildModel("smooth", two, Settings());
  const color::SuggestResult gap = color::SuggestCompositions(D65(), *line, {});
  ASSERT_EQ(gap.suggestions.size(), 1u);
  EXPECT_NEAR(gap.suggestions[0].x_atomic, 0.5 * (line->x_min() + line->x_max()), 1e-12);
  EXPECT_TRUE(std::isnan(gap.suggestions[0].sigma));
}

// The model file's new fields are read back as written, and a damaged one is named.
TEST(ModelFile, HistoryNotesAndCurvesRoundTripAndAreChecked) {
  const Dataset dataset = LoadDataset(DataDir() + "/Cu-Zn");
  const auto model = FitOf(dataset, "eps-linear");
  const nlohmann::json doc = model->ToJson();
  const auto back = ModelFromJson(doc, "m.json");
  EXPECT_EQ(back->ToJson(), doc);
  ASSERT_EQ(back->history().size(), 1u);
  EXPECT_EQ(back->history()[0].added.size(), dataset.samples.size());
  EXPECT_EQ(back->suspect_samples().size(), 1u);
  EXPECT_TRUE(doc["parameters"]["curves"]["rows"].is_array());
  nlohmann::json bad = doc;
  bad["history"][0]["samples"] = 2.5;
  testing::ExpectModelFileError(bad, "history[0].samples");
  bad = doc;
  bad["history"][0]["added"][1] = "Querry-Cu70Zn30.yml";
  testing::ExpectModelFileError(bad, "history[0].added[1]");
  bad = doc;
  bad["fit"]["suspect_samples"][0].erase("reason");
  testing::ExpectModelFileError(bad, "fit.suspect_samples[0]");
}

// sweep --sigma prints, per row, the one-sigma `color` gives at that composition.
TEST(Sweep, TheSigmaColumnIsColorsOneSigma) {
  const std::string dir = MakeTempDir();
  const std::string model = dir + "/m.json";
  ASSERT_EQ(RunProgram({"fit", "--data", DataDir() + "/Cu-Zn/dataset-werner-zn.json", "--method",
                        "smooth", "--out", model, "--quiet"})
                .status,
            0);
  const testing::RunResult sweep =
      RunProgram({"sweep", "--model", model, "--steps", "5", "--sigma", "--quiet"});
  ASSERT_EQ(sweep.status, 0) << sweep.err;
  std::istringstream rows(sweep.out);
  std::string line;
  std::getline(rows, line);
  EXPECT_EQ(line, "x,X,Y,Z,L,a,b,srgb8_r,srgb8_g,srgb8_b,sigma_de00");
  int count = 0;
  while (std::getline(rows, line)) {
    const std::string x = line.substr(0, line.find(','));
    const double sigma = std::stod(line.substr(line.rfind(',') + 1));
    const auto colour =
        nlohmann::json::parse(RunProgram({"color", "--model", model, "--x", x, "--json"}).out);
    EXPECT_NEAR(sigma, colour["delta_e00_sigma"].get<double>(), 5e-5) << line;
    ++count;
  }
  EXPECT_EQ(count, 5);
  // A model without error bars: --sigma is refused, saying why.
  nlohmann::json two = Manifest("Cu", "Zn", "weight_fraction_a",
                                {{0.70, "Querry-Cu70Zn30.yml"}, {1.0, "Querry-Cu100.yml"}});
  const std::string two_dir = DatasetOf("Cu-Zn", two);
  const testing::RunResult refused =
      RunProgram({"sweep", "--data", two_dir, "--steps", "3", "--sigma", "--quiet"});
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.err.find("--sigma: no error bar: 2 compositions"), std::string::npos)
      << refused.err;
}

}  // namespace
}  // namespace alloycolor
