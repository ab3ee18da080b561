#include "alloycolor/fit/lineage.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "alloycolor/color/material_color.h"
#include "alloycolor/color/sample_error.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"
#include "alloycolor/fit/suspects.h"

namespace alloycolor::fit {
namespace {

// The model against a sample it was not fitted to: its error there and its one-sigma
// (NaN where none; an extrapolation where the sample lies outside the model's range).
void ScoreAgainst(const color::Colorimeter& cm, const AlloyModel& model, const Sample& s,
                  double* delta_e00, double* sigma, double* reflectance_rms) {
  *delta_e00 = *sigma = *reflectance_rms = std::nan("");
  try {
    const color::SampleError e = color::ErrorAgainstSample(cm, model, s);
    *delta_e00 = e.delta_e00;
    *reflectance_rms = e.reflectance_rms;
    if (e.has_colour() && model.HasUncertainty()) {
      const double sd = color::DeltaE00Sigma(cm, model, s.x_atomic, 0.0);
      if (sd > 0) *sigma = sd;
    }
  } catch (const Error&) {
    // The model cannot be evaluated there: the figures stay NaN (null in the file).
  }
}

// The verdict on an added sample: its error against the old model's error bar.
std::string AddedVerdict(const AddedSample& a, const AlloyModel& previous) {
  if (!std::isfinite(a.delta_e00)) {
    return std::isfinite(a.reflectance_rms) ? "no colour to compare (reflectance RMS only)"
                                            : "the old model cannot be evaluated there";
  }
  std::string verdict = std::isfinite(a.sigma_de00) ? SigmaVerdict(a.delta_e00, a.sigma_de00)
                                                    : previous.NoErrorBarReason();
  if (a.x_atomic < previous.x_min() - 1e-9 || a.x_atomic > previous.x_max() + 1e-9) {
    verdict += " (extrapolated: outside the old model's x range)";
  }
  return verdict;
}

// The history of a model file written before models kept one: its own fit, undated.
HistoryEntry EntryOf(const AlloyModel& model) {
  HistoryEntry h;
  h.method = model.method();
  h.samples = static_cast<int>(model.training_samples().size());
  for (const TrainingSample& t : model.training_samples()) {
    AddedSample a;
    a.x_atomic = t.x_atomic;
    a.x_given = t.x_given;
    a.file = t.file;
    a.checksum = t.checksum;
    h.added.push_back(std::move(a));
  }
  return h;
}

}  // namespace

HistoryEntry LineageEntry(const Dataset& dataset, const AlloyModel& model,
                          const AlloyModel* previous, const color::Colorimeter& colorimeter,
                          const std::string& date) {
  HistoryEntry h;
  h.date = date;
  h.method = model.method();
  h.samples = static_cast<int>(dataset.samples.size());
  std::map<std::string, const TrainingSample*> before;
  if (previous != nullptr) {
    h.previous_method = previous->method();
    for (const TrainingSample& t : previous->training_samples()) before[t.file] = &t;
  }
  for (const Sample& s : dataset.samples) {
    const auto it = before.find(s.file);
    if (it != before.end()) {
      if (it->second->checksum != s.checksum) h.changed.push_back(*it->second);
      before.erase(it);
      continue;
    }
    AddedSample a;
    a.x_atomic = s.x_atomic;
    a.x_given = s.x_given;
    a.file = s.file;
    a.checksum = s.checksum;
    if (previous != nullptr) {
      ScoreAgainst(colorimeter, *previous, s, &a.delta_e00, &a.sigma_de00, &a.reflectance_rms);
      a.verdict = AddedVerdict(a, *previous);
    }
    h.added.push_back(std::move(a));
  }
  for (const auto& [file, t] : before) h.removed.push_back(*t);
  return h;
}

std::vector<SampleNote> ScoreExcluded(const Dataset& dataset, const AlloyModel& model,
                                      const color::Colorimeter& colorimeter) {
  std::vector<SampleNote> notes;
  for (const Sample& s : dataset.excluded) {
    SampleNote n;
    n.x_atomic = s.x_atomic;
    n.x_given = s.x_given;
    n.file = s.file;
    n.check = "excluded";
    n.reason = s.excluded;
    ScoreAgainst(colorimeter, model, s, &n.delta_e00, &n.sigma_de00, &n.reflectance_rms);
    notes.push_back(std::move(n));
  }
  return notes;
}

std::unique_ptr<AlloyModel> FitDataSet(const std::string& method, const Dataset& dataset,
                                       const FitSettings& settings, const FitRecord& record) {
  if (settings.colorimeter == nullptr) throw Error("a fit of a data set needs a colorimeter");
  std::unique_ptr<AlloyModel> model = BuildModel(method, dataset, settings);
  std::vector<SampleNote> suspects = CheckSamples(dataset, *model, settings);
  for (const SampleNote& n : suspects) model->AddWarning("suspect sample: " + n.reason);
  model->set_suspect_samples(std::move(suspects));
  model->set_excluded_samples(ScoreExcluded(dataset, *model, *settings.colorimeter));
  try {
    model->set_parameter_curves(ParameterCurvesJson(*model));
  } catch (const Error& e) {
    model->AddWarning("the parameter curves could not be computed: " + std::string(e.what()));
  }
  std::vector<HistoryEntry> history;
  if (record.previous != nullptr) {
    history = record.previous->history();
    if (history.empty()) history.push_back(EntryOf(*record.previous));
  }
  history.push_back(
      LineageEntry(dataset, *model, record.previous, *settings.colorimeter, record.date));
  model->set_history(std::move(history));
  return model;
}

std::function<std::unique_ptr<AlloyModel>(const std::string& method, const Dataset&)>
WholeDataSetFitter(const color::Colorimeter& colorimeter, ThreadBudget* threads,
                   CancelCheck cancel) {
  return [&colorimeter, threads, cancel](const std::string& method, const Dataset& dataset) {
    FitSettings settings;
    settings.colorimeter = &colorimeter;
    settings.threads = threads;
    settings.cancel = cancel;
    return FitDataSet(method, dataset, settings, {nullptr, NowUtcIso8601()});
  };
}

}  // namespace alloycolor::fit
