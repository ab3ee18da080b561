#include "alloycolor/fit/methods.h"

#include <memory>
#include <utility>

#include "alloycolor/core/dataset.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"
#include "alloycolor/model/registry.h"
#include "folds.h"

namespace alloycolor::fit {

std::shared_ptr<FitMemo> MakeFitMemo() { return std::make_shared<FitMemo>(); }

std::unique_ptr<AlloyModel> BuildModel(const std::string& method, const Dataset& dataset,
                                       const FitSettings& settings) {
  if (!settings.memo) {
    // One memo for this fit, its candidates and its folds.
    FitSettings with_memo = settings;
    with_memo.memo = MakeFitMemo();
    return BuildModel(method, dataset, with_memo);
  }
  if (!settings.options_checked) {
    // Once, before any work: the options against the method's declarations.
    FitSettings checked = settings;
    checked.options = CheckFitOptions(method, settings.options, dataset);
    checked.options_checked = true;
    return BuildModel(method, dataset, checked);
  }
  if (DistinctCompositions(dataset).size() < 2) {
    std::string files;
    for (const Sample& s : dataset.samples) files += (files.empty() ? "" : ", ") + s.file;
    throw Error(dataset.manifest_path + ": a model needs samples at two compositions at least; " +
                (dataset.samples.empty()
                     ? std::string("there are none")
                     : "every sample is at x = " + FormatNumber(dataset.samples.front().x_given) +
                           " (" + files + ")"));
  }
  if (method == kAutoMethod) return BuildAuto(dataset, settings);
  if (!BuiltInBuildersAttached()) throw Error("the built-in methods have no builders");
  const MethodInfo& info = RequireMethod(method);
  if (ChoosesDegree(info, settings)) {
    if (settings.colorimeter == nullptr) {
      throw Error(info.name +
                  ": the composition degree is chosen by the colour error of leave-one-out "
                  "folds, which needs a colorimeter (FitSettings::colorimeter); or give the "
                  "degree");
    }
    Scored r = RememberedDegreeChoice(info, dataset, settings);
    if (!r.model) throw Error(r.score.error);
    return std::move(r.model);
  }
  if (settings.calibrate && settings.colorimeter != nullptr) {
    // Through the job's memo: `validate` builds each method on a split as `auto` scores it
    // there as a candidate.
    Scored r = RememberedBuild(info, dataset, settings);
    if (!r.model) throw Error(r.score.error);
    return std::move(r.model);
  }
  return BuildWithFolds(info, dataset, settings, nullptr);
}

std::function<std::unique_ptr<AlloyModel>(const std::string& method, const Dataset& training)>
SharedFitBuilder(const color::Colorimeter& colorimeter, ThreadBudget* threads, CancelCheck cancel) {
  FitSettings settings;
  settings.colorimeter = &colorimeter;
  settings.threads = threads;
  settings.cancel = std::move(cancel);
  settings.memo = MakeFitMemo();
  return [settings](const std::string& method, const Dataset& training) {
    return BuildModel(method, training, settings);
  };
}

}  // namespace alloycolor::fit
