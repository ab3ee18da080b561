// The registry is the one place that knows a method: a method registered here, by this file
// alone, is a candidate of `auto` (its score in auto's table), one of `validate`'s defaults,
// and reads back from its model file; the built-in methods' traits are what the rest asks.
#include "alloycolor/model/registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/spectrum.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/validate/validation.h"
#include "test_util.h"

namespace alloycolor {
namespace {

using testing::DataDir;

// Nearest neighbour in composition: eps of the training sample nearest to x.
class NearestModel : public AlloyModel {
 public:
  explicit NearestModel(const Dataset& dataset) : samples_(dataset.samples) {
    const WavelengthRange range = CommonRange(dataset);
    SetCommon(dataset, range.lo_nm, range.hi_nm);
  }
  NearestModel(const nlohmann::json& doc, const std::string& source) {
    ReadCommon(doc);
    set_source(source);
    for (const auto& s : doc.at("parameters").at("samples")) {
      Sample sample{};
      sample.x_atomic = s.at("x").get<double>();
      sample.nk.source = source;
      sample.nk.lambda_nm = s.at("lambda_nm").get<std::vector<double>>();
      sample.nk.n = s.at("n").get<std::vector<double>>();
      sample.nk.k = s.at("k").get<std::vector<double>>();
      samples_.push_back(std::move(sample));
    }
  }
  std::string method() const override { return "test-nearest"; }
  std::vector<std::complex<double>> Permittivity(
      double x_atomic, const std::vector<double>& lambda_nm) const override {
    CheckLambda(lambda_nm);
    const Sample* nearest = &samples_.front();
    for (const Sample& s : samples_) {
      if (std::abs(s.x_atomic - x_atomic) < std::abs(nearest->x_atomic - x_atomic)) {
        nearest = &s;
      }
    }
    std::vector<std::complex<double>> eps;
    for (double l : lambda_nm) {
      const std::complex<double> index = NkAt(nearest->nk, l);
      eps.push_back(index * index);
    }
    return eps;
  }

 protected:
  nlohmann::json ParametersJson() const override {
    nlohmann::json samples = nlohmann::json::array();
    for (const Sample& s : samples_) {
      samples.push_back(
          {{"x", s.x_atomic}, {"lambda_nm", s.nk.lambda_nm}, {"n", s.nk.n}, {"k", s.nk.k}});
    }
    return {{"samples", samples}};
  }

 private:
  std::vector<Sample> samples_;
};

std::unique_ptr<AlloyModel> ReadNearest(const nlohmann::json& doc, const std::string& source) {
  return std::make_unique<NearestModel>(doc, source);
}

std::unique_ptr<AlloyModel> BuildNearest(const Dataset& dataset, const fit::FitSettings&) {
  return std::make_unique<NearestModel>(dataset);
}

MethodInfo NearestInfo() {
  MethodInfo info;
  info.name = "test-nearest";
  info.summary = "eps of the nearest training sample (a test's own method)";
  info.read = &ReadNearest;
  info.build = &BuildNearest;
  info.traits.auto_rank = 100;
  info.traits.validate_default = true;
  return info;
}

// Registered before main, as every method is: the registry is sealed by its first read.
const MethodRegistration kNearest{NearestInfo()};

Dataset AuAgSubset(const std::vector<double>& keep) {
  Dataset data = LoadDataset(DataDir() + "/Au-Ag");
  std::vector<double> drop;
  for (const Sample& s : data.samples) {
    if (std::find(keep.begin(), keep.end(), s.x_atomic) == keep.end()) drop.push_back(s.x_atomic);
  }
  return WithoutSamples(data, drop);
}

TEST(Registry, AMethodRegisteredHereIsKnownEverywhere) {
  ASSERT_NE(FindMethod("test-nearest"), nullptr);
  EXPECT_NE(MethodNamesText().find("test-nearest"), std::string::npos);
  const std::vector<std::string> defaults = DefaultValidationMethods();
  EXPECT_NE(std::find(defaults.begin(), defaults.end(), "test-nearest"), defaults.end());
  const std::vector<const MethodInfo*> candidates = AutoCandidates();
  ASSERT_FALSE(candidates.empty());
  EXPECT_EQ(candidates.back()->name, "test-nearest");  // the highest rank comes last

  // auto scores it beside the others, in its table.
  const color::Colorimeter cm = color::Colorimeter::Load(DataDir(), "D65", 2);
  fit::FitSettings settings;
  settings.colorimeter = &cm;
  const Dataset data = AuAgSubset({0.0, 0.2, 0.5, 0.8, 1.0});
  const std::unique_ptr<AlloyModel> model = fit::BuildModel("auto", data, settings);
  const MethodSelection& selection = model->fit_summary().selection;
  const auto it = std::find_if(selection.scores.begin(), selection.scores.end(),
                               [](const MethodScore& s) { return s.method == "test-nearest"; });
  ASSERT_NE(it, selection.scores.end());
  EXPECT_TRUE(it->error.empty()) << it->error;
  EXPECT_EQ(it->folds, 3);       // three held-out compositions
  EXPECT_EQ(it->end_miss, 0.0);  // it passes through the ends' own samples

  // Built directly, with its error bars from its folds, and read back from its file.
  const std::unique_ptr<AlloyModel> nearest = fit::BuildModel("test-nearest", data, settings);
  EXPECT_TRUE(nearest->HasUncertainty());
  const std::unique_ptr<AlloyModel> back = ModelFromJson(nearest->ToJson(), "nearest.json");
  EXPECT_EQ(back->method(), "test-nearest");
  EXPECT_EQ(back->Permittivity(0.3, {550})[0], nearest->Permittivity(0.3, {550})[0]);

  // validate's default methods include it.
  validate::ValidationOptions options;
  options.build = fit::SharedFitBuilder(cm);
  options.methods = DefaultValidationMethods();
  options.angles_deg = {0.0};
  options.mode = "holdout";
  const validate::ValidationReport report = validate::ComputeValidation(
      data, {validate::SplitAtCompositions(data, {0.5})}, cm, options, {});
  ASSERT_EQ(report.holdouts.size(), 1u);
  EXPECT_EQ(report.holdouts[0].results.count("test-nearest"), 1u);
}

TEST(Registry, BuiltInTraits) {
  EXPECT_EQ(RequireMethod("eps-linear").traits.gap_exponent, 2.0);
  EXPECT_EQ(RequireMethod("paper").traits.gap_exponent, 2.0);
  EXPECT_EQ(RequireMethod("smooth").traits.gap_exponent, 1.0);
  EXPECT_TRUE(RequireMethod("physical").traits.warm_start_folds);
  EXPECT_TRUE(RequireMethod("physical").traits.chooses_degree);
  EXPECT_FALSE(RequireMethod("physical").traits.validate_default);
  EXPECT_TRUE(RequireMethod("smooth").traits.chosen_on_one_fold);
  EXPECT_NE(testing::ErrorOf([] { RequireMethod("nope"); }).find("unknown method 'nope'"),
            std::string::npos);
  EXPECT_NE(testing::ErrorOf([] {
              MethodInfo info;
              info.name = "auto";
              info.read = &ReadNearest;
              RegisterMethod(info);
            }).find("auto"),
            std::string::npos);
}

}  // namespace
}  // namespace alloycolor
