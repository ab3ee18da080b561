// A fit of a user's data set as the program's `fit` and Python's fit make it: the model
// BuildModel gives, then what the lab's loop asks of it between measurements
// (docs/model-format.md):
//  - the samples checked against the rest of the series (suspects.h), each suspect also a
//    warning of the model;
//  - the samples the manifest sets aside ("exclude"), each scored as held out: the model
//    (which never saw it) against it, with its one-sigma there;
//  - the design's parameter curves, tau(x) and m*(x) with their one-sigma (the model
//    file's parameters.curves, as `alloycolor params --format json` computes them);
//  - its lineage: the previous model's history (a refit) and an entry for this fit, which
//    for each sample added since the previous model records that model's prediction
//    there: its CIEDE2000 error at normal incidence (the colorimeter of the settings,
//    D65 and 2 degrees in the program), its reflectance RMS, its one-sigma and the verdict
//    (SigmaVerdict): whether the new measurement was inside the old model's error bar.
#ifndef ALLOYCOLOR_FIT_LINEAGE_H_
#define ALLOYCOLOR_FIT_LINEAGE_H_

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/core/dataset.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::fit {

struct FitRecord {
  const AlloyModel* previous = nullptr;  // a refit: the model it follows
  std::string date;                      // of this fit: ISO 8601, UTC (NowUtcIso8601)
};

// BuildModel, then the checks, the set-aside samples, the parameter curves and the lineage
// above. Needs settings.colorimeter. Throws Error as BuildModel does.
std::unique_ptr<AlloyModel> FitDataSet(const std::string& method, const Dataset& dataset,
                                       const FitSettings& settings, const FitRecord& record);

// FitDataSet with the default options, dated now, as a function of the method and the
// data set: what a validation report describes the whole data set by
// (validate::ValidationOptions::fit_whole). `colorimeter` (and `threads`, if given) must
// outlive it; `cancel` is checked in the fit (FitSettings::cancel).
std::function<std::unique_ptr<AlloyModel>(const std::string& method, const Dataset&)>
WholeDataSetFitter(const color::Colorimeter& colorimeter, ThreadBudget* threads = nullptr,
                   CancelCheck cancel = {});

// The entry FitDataSet adds to the history of `model`, fitted to `dataset`, after
// `previous` (null for a first fit).
HistoryEntry LineageEntry(const Dataset& dataset, const AlloyModel& model,
                          const AlloyModel* previous, const color::Colorimeter& colorimeter,
                          const std::string& date);

// The samples the manifest set aside (Dataset::excluded), each scored against `model`.
std::vector<SampleNote> ScoreExcluded(const Dataset& dataset, const AlloyModel& model,
                                      const color::Colorimeter& colorimeter);

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_LINEAGE_H_
