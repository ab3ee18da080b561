// Every method of the registry built on every bundled data set stays physical inside the
// range it was fitted on: eps2 >= 0 (passive) and n, k no larger than 50 or, at a
// wavelength where the measured samples themselves go beyond (the far infrared: Querry's
// brasses reach n = 297 at 55 um), 10 % above their largest n, k there (the paper's Drude
// interpolation and the natural spline are not bounded by the samples exactly: measured
// 0.01 % and 5 % above them), at 201 compositions and every 5 nm (at most 1000 wavelengths). The
// physical model may refuse a data set (it does on Querry's zinc), and then must say so.
#include "alloycolor/fit/methods.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <map>
#include <string>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/io.h"
#include "alloycolor/model/registry.h"
#include "alloycolor/model/smooth_model.h"
#include "test_util.h"

namespace alloycolor {
namespace {

using testing::DataDir;

TEST(EveryMethod, StaysPassiveAndBoundedOnEveryBundledSet) {
  const color::Colorimeter colorimeter = color::Colorimeter::Load(DataDir(), "D65", 2);
  for (const std::string set : {"Au-Ag", "Cu-Zn", "Cu-Zn/dataset-werner-zn.json", "Nb-Sn"}) {
    const Dataset data = LoadDataset(DataDir() + "/" + set);
    for (const MethodInfo& method : Methods()) {
      if (method.name == fit::kAutoMethod) continue;  // one of the others
      SCOPED_TRACE(set + " " + method.name);
      fit::FitSettings settings;
      settings.calibrate = false;
      settings.colorimeter = &colorimeter;
      std::unique_ptr<AlloyModel> model;
      try {
        model = fit::BuildModel(method.name, data, settings);
      } catch (const Error& e) {
        EXPECT_EQ(method.name, "physical") << e.what();
        const std::string m = e.what();  // refused as unphysical, whichever check first
        EXPECT_TRUE(m.find("not passive") != std::string::npos ||
                    m.find("has a resonance") != std::string::npos)
            << m;
        continue;
      }
      // Every 5 nm, or 1000 wavelengths over a wider range (Querry's reach 55 um).
      const double step = std::max(5.0, (model->lambda_max_nm() - model->lambda_min_nm()) / 1000);
      const std::vector<double> grid =
          UniformGrid(std::ceil(model->lambda_min_nm() / 5) * 5, model->lambda_max_nm(), step);
      std::vector<double> bound(grid.size(), 50.0);
      for (const Sample& s : data.samples) {
        for (size_t j = 0; j < grid.size(); ++j) {
          const std::complex<double> nk = NkAt(s.nk, grid[j]);
          bound[j] = std::max({bound[j], 1.1 * nk.real(), 1.1 * nk.imag()});
        }
      }
      for (int i = 0; i <= 200; ++i) {
        const double x = model->x_min() + (model->x_max() - model->x_min()) * i / 200.0;
        const auto eps = model->Permittivity(x, grid);
        const auto nk = model->Index(x, grid);
        for (size_t j = 0; j < grid.size(); ++j) {
          ASSERT_GE(eps[j].imag(), 0.0) << "x " << x << " at " << grid[j] << " nm";
          ASSERT_LE(std::max(nk[j].real(), nk[j].imag()), bound[j])
              << "x " << x << " at " << grid[j] << " nm";
        }
      }
    }
  }
}

// Three compositions of a series whose ln eps is linear in composition: the smooth model
// chooses ln eps by its one fold (the middle from the ends), and auto's fold of it, which
// has no interior composition to choose by, scores that space too (before, it scored the
// eps line, the same as eps-pchip's, and auto took eps-pchip).
TEST(AutoMethod, ScoresTheSmoothModelInTheSpaceItDelivers) {
  const color::Colorimeter colorimeter = color::Colorimeter::Load(DataDir(), "D65", 2);
  const Dataset data =
      LoadDataset(testing::WriteSyntheticDataset({0.0, 0.5, 1.0}, testing::Geometric));
  fit::FitSettings settings;
  settings.colorimeter = &colorimeter;
  const auto model = fit::BuildModel("auto", data, settings);
  ASSERT_EQ(model->method(), "smooth");
  EXPECT_EQ(dynamic_cast<const SmoothModel&>(*model).space(), SmoothSpace::kLogEps);
  std::map<std::string, double> mean;
  for (const MethodScore& m : model->fit_summary().selection.scores) mean[m.method] = m.mean;
  EXPECT_LT(mean["smooth"], 0.01 * mean["eps-pchip"]) << mean["smooth"] << " " << mean["eps-pchip"];
}

// The physical model's degree is chosen by colour: without a colorimeter it says so.
TEST(EveryMethod, ThePhysicalDegreeChoiceWithoutAColorimeterIsAClearError) {
  const Dataset data = LoadDataset(DataDir() + "/Au-Ag");
  try {
    fit::BuildModel("physical", data, fit::FitSettings{});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("colorimeter"), std::string::npos) << e.what();
  }
  fit::FitSettings fixed;
  fixed.options.Set("degree", 1);
  fixed.calibrate = false;
  EXPECT_NO_THROW(fit::BuildModel("physical", data, fixed));
}

}  // namespace
}  // namespace alloycolor
