// Adding a method is one file pair and one registration (docs/architecture.md): the toy
// method of tests/toy_method.h, registered from outside the library by toy_method.cc alone,
// is fitted, read back, listed, its option checked against its declaration, validated, and
// refused by name where auto runs, as a built-in method is; here through the library and
// through the program built with it (alloycolor_toy: app/main.cc and toy_method.cc). The
// Python module built with it is tested in tests/python/test_toy_method.py.
#include "toy_method.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/registry.h"
#include "alloycolor/validate/validation.h"
#include "test_util.h"

namespace alloycolor {
namespace {

using testing::DataDir;
using testing::ErrorOf;
using testing::MakeTempDir;
using testing::RunProgram;
using testing::RunResult;

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// stdout of the program without the toy (alloycolor itself).
std::string StockProgramOutput(const std::string& args) {
  std::string out;
  FILE* pipe = popen((std::string(ALLOYCOLOR_STOCK_BINARY) + " " + args + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return out;
  char buffer[4096];
  for (size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  pclose(pipe);
  return out;
}

class ToyMethod : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    colorimeter_ = new color::Colorimeter(color::Colorimeter::Load(DataDir(), "D65", 2));
    data_ = new Dataset(LoadDataset(DataDir() + "/Au-Ag"));
  }
  static void TearDownTestSuite() {
    delete colorimeter_;
    delete data_;
  }
  static fit::FitSettings Settings(double eps1) {
    fit::FitSettings settings;
    settings.colorimeter = colorimeter_;
    settings.options.Set(toy::kOption, eps1);
    return settings;
  }
  static color::Colorimeter* colorimeter_;
  static Dataset* data_;
};

color::Colorimeter* ToyMethod::colorimeter_ = nullptr;
Dataset* ToyMethod::data_ = nullptr;

TEST_F(ToyMethod, IsInTheRegistryWithItsOption) {
  const MethodInfo& info = RequireMethod(toy::kMethod);
  EXPECT_LT(info.traits.auto_rank, 0);
  const std::vector<DeclaredOption> options = DeclaredOptions();
  const auto it = std::find_if(options.begin(), options.end(),
                               [](const DeclaredOption& o) { return o.spec.name == toy::kOption; });
  ASSERT_NE(it, options.end());
  EXPECT_EQ(it->methods, std::vector<std::string>{toy::kMethod});
  EXPECT_TRUE(Has(MethodNamesText(), toy::kMethod));
  // `validate --methods all` runs it; its defaults do not (it says so).
  const std::vector<std::string> all = MethodList("all", "--methods");
  EXPECT_NE(std::find(all.begin(), all.end(), toy::kMethod), all.end());
  const std::vector<std::string> defaults = MethodList("", "--methods");
  EXPECT_EQ(std::find(defaults.begin(), defaults.end(), toy::kMethod), defaults.end());
}

TEST_F(ToyMethod, IsFittedWithItsOptionAndReadBack) {
  const std::vector<double> grid = {400, 550, 700};
  fit::FitSettings defaults;
  defaults.colorimeter = colorimeter_;
  const auto by_default = fit::BuildModel(toy::kMethod, *data_, defaults);
  for (const auto& eps : by_default->Permittivity(0.3, grid)) {
    EXPECT_EQ(eps, std::complex<double>(-10, toy::kEps2));  // its declared default
  }
  const auto model = fit::BuildModel(toy::kMethod, *data_, Settings(-4.5));
  EXPECT_EQ(model->method(), toy::kMethod);
  EXPECT_EQ(model->Permittivity(0.8, grid)[1], std::complex<double>(-4.5, toy::kEps2));
  EXPECT_TRUE(model->HasUncertainty());  // error bars from its folds, as any method's
  const auto back = ModelFromJson(model->ToJson(), "toy.json");
  EXPECT_EQ(back->Permittivity(0.1, grid), model->Permittivity(0.1, grid));
}

TEST_F(ToyMethod, ItsOptionIsCheckedAgainstItsDeclaration) {
  EXPECT_EQ(ErrorOf([&] { fit::BuildModel(toy::kMethod, *data_, Settings(5)); }),
            "toy_eps1: 5 is not a finite number in [-100, -0.01]");
  EXPECT_EQ(ErrorOf([&] { fit::BuildModel("smooth", *data_, Settings(-5)); }),
            "toy_eps1: an option of toy-constant; smooth does not take it");
  // It says it is not a candidate of auto, so auto refuses its option by name.
  EXPECT_EQ(ErrorOf([&] { fit::BuildModel("auto", *data_, Settings(-5)); }),
            "toy_eps1: an option of toy-constant; auto does not run it (not one of its "
            "candidates)");
  fit::FitSettings smooth;
  smooth.options.Set("smoothing", 0.5);
  EXPECT_EQ(ErrorOf([&] { fit::BuildModel(toy::kMethod, *data_, smooth); }),
            "smoothing: an option of smooth; toy-constant does not take it");
}

TEST_F(ToyMethod, IsValidated) {
  validate::ValidationOptions options;
  options.build = fit::SharedFitBuilder(*colorimeter_);
  options.methods = {toy::kMethod, "eps-linear"};
  options.angles_deg = {0.0};
  options.mode = "holdout";
  const validate::ValidationReport report = validate::ComputeValidation(
      *data_, {validate::SplitAtCompositions(*data_, {0.5})}, *colorimeter_, options, {});
  ASSERT_EQ(report.holdouts.size(), 1u);
  EXPECT_EQ(report.holdouts[0].results.count(toy::kMethod), 1u);
}

// The program built with the toy: listed by --help, fitted, its option checked with the
// same words as the library's, refused by name for auto and for another method, validated.
TEST_F(ToyMethod, TheProgramBuiltWithItRunsIt) {
  const RunResult help = RunProgram({"fit", "--help"});
  ASSERT_EQ(help.status, 0);
  EXPECT_TRUE(Has(help.out, "  toy-constant: a toy")) << help.out;
  EXPECT_TRUE(Has(help.out, "--toy-eps1")) << help.out;
  EXPECT_TRUE(Has(help.out, "toy-constant: the toy's eps1")) << help.out;
  // The program without it knows nothing of it.
  EXPECT_FALSE(Has(StockProgramOutput("fit --help"), "toy"));

  const std::string dir = MakeTempDir();
  const RunResult fitted = RunProgram({"fit", "--data", "Au-Ag", "--method", toy::kMethod,
                                       "--toy-eps1", "-3", "--out", dir + "/toy.json", "--quiet"});
  ASSERT_EQ(fitted.status, 0) << fitted.err;
  const auto model = ReadModelFile(dir + "/toy.json");
  EXPECT_EQ(model->Permittivity(0.5, {550})[0], std::complex<double>(-3, toy::kEps2));
  EXPECT_EQ(RunProgram({"color", "--model", dir + "/toy.json", "--x", "0.5"}).status, 0);

  const RunResult range = RunProgram({"fit", "--data", "Au-Ag", "--method", toy::kMethod,
                                      "--toy-eps1", "5", "--out", dir + "/no.json"});
  EXPECT_EQ(range.status, 2);
  EXPECT_TRUE(Has(range.err, "--toy-eps1: 5 is not a finite number in [-100, -0.01]")) << range.err;
  for (const char* other : {"smooth", "auto"}) {
    const RunResult refused = RunProgram({"fit", "--data", "Au-Ag", "--method", other, "--toy-eps1",
                                          "-3", "--out", dir + "/no.json"});
    EXPECT_EQ(refused.status, 2);
    EXPECT_TRUE(Has(refused.err, "--toy-eps1: an option of toy-constant;")) << refused.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/no.json"));

  const RunResult report =
      RunProgram({"validate", "--data", "Au-Ag", "--holdout", "0.5", "--methods",
                  std::string(toy::kMethod) + ",eps-linear", "--out", dir + "/report", "--quiet"});
  ASSERT_EQ(report.status, 0) << report.err;
  EXPECT_TRUE(Has(testing::ReadText(dir + "/report/report.json"), "\"toy-constant\""));
}

}  // namespace
}  // namespace alloycolor
