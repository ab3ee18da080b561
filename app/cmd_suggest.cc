// alloycolor suggest: where to measure next (color/suggest.h): the compositions where one
// more sample would shrink the model's error bars most, chosen jointly, each with the
// one-sigma there now and what measuring it would leave of the largest and the mean
// one-sigma over the model's range.
#include <cmath>
#include <cstdio>
#include <string>

#include "alloycolor/color/suggest.h"
#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/text.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct SuggestCommandOptions {
  ModelSource source;
  int count = 1;
  std::string rule = "largest-sigma";
  std::string illuminant = "D65";
  int observer = 2;
  bool json = false;
  bool quiet = false;
  int threads = 0;
};

// The composition in the data set's own units: its weight fraction for a manifest in
// weight fractions, else the atomic fraction.
double GivenComposition(const AlloyModel& model, double x_atomic) {
  return model.composition() == "weight_fraction_a"
             ? WeightFromAtomicFraction(x_atomic, model.system())
             : x_atomic;
}

void Run(const SuggestCommandOptions& o) {
  color::SuggestOptions options;
  options.count = o.count;
  options.rule = color::ParseSuggestRule(o.rule);
  const color::Colorimeter colorimeter = LoadColorimeter(o.illuminant, o.observer);
  const auto model = o.source.Load(o.quiet);
  ThreadBudget threads(o.threads);
  options.threads = &threads;
  const color::SuggestResult r = color::SuggestCompositions(colorimeter, *model, options);
  const std::string sigma_key = r.metric == "relative_eps" ? "sigma_relative_eps" : "sigma_de00";
  if (o.json) {
    nlohmann::json list = nlohmann::json::array();
    for (const color::Suggestion& s : r.suggestions) {
      nlohmann::json row = {{"x", s.x_atomic}, {"x_given", GivenComposition(*model, s.x_atomic)}};
      row.update(CompositionJson(s.x_atomic, model->system()));
      row.erase("x_atomic");  // "x" already
      row[sigma_key] = NumberOrNull(s.sigma);
      row["max_sigma_before"] = NumberOrNull(s.max_sigma_before);
      row["max_sigma_after"] = NumberOrNull(s.max_sigma_after);
      row["mean_sigma_before"] = NumberOrNull(s.mean_sigma_before);
      row["mean_sigma_after"] = NumberOrNull(s.mean_sigma_after);
      row["rule"] = r.rule;
      list.push_back(row);
    }
    PrintOutput(JsonText(list, 2) + "\n");
    return;
  }
  std::string text;
  char line[400];
  const std::string what =
      r.metric == "delta_e00" ? "one-sigma dE00 at normal incidence, " + colorimeter.illuminant() +
                                    ", " + std::to_string(o.observer) + "-degree observer"
      : r.metric == "relative_eps" ? "one-sigma relative eps error (no colour: "
                                     "the data do not cover the visible)"
                                   : model->NoErrorBarReason();
  std::snprintf(line, sizeof line, "%s, %s model (%d compositions); %s\n",
                model->system().Name().c_str(), model->method().c_str(),
                model->TrainingCompositions(), what.c_str());
  text += line;
  if (r.suggestions.empty()) {
    text += "nothing to suggest: every composition of the range lies within " +
            FormatNumber(options.min_distance) + " of a measured one\n";
  } else if (r.metric != "none") {
    std::snprintf(line, sizeof line, "now: largest one-sigma %.3g, mean %.3g over x = %g-%g\n",
                  r.suggestions.front().max_sigma_before, r.suggestions.front().mean_sigma_before,
                  model->x_min(), model->x_max());
    text += line;
  }
  for (size_t i = 0; i < r.suggestions.size(); ++i) {
    const color::Suggestion& s = r.suggestions[i];
    std::string row =
        std::to_string(i + 1) + ". measure x = " + DescribeComposition(s.x_atomic, model->system());
    if (std::isfinite(s.sigma)) {
      std::snprintf(line, sizeof line,
                    ": one-sigma there now %.3g; with it%s measured, the largest %.3g and the "
                    "mean %.3g",
                    s.sigma, i == 0 ? "" : " and the above", s.max_sigma_after, s.mean_sigma_after);
      row += line;
    }
    text += row + "\n";
  }
  text += "rule: " + r.rule + "\n";
  PrintOutput(text);
}

}  // namespace

void RegisterSuggest(CLI::App& app) {
  auto o = std::make_shared<SuggestCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "suggest", "Where to measure next: the compositions that would shrink the error bars most");
  cmd->footer(
      "Scans the model's one-sigma colour uncertainty (as `alloycolor color` gives it: "
      "CIEDE2000 at normal incidence) over its composition range and proposes the next "
      "compositions to measure, chosen jointly: the second is the best once the first has been "
      "measured. Each comes with its one-sigma now, and the largest and the mean one-sigma "
      "over the range once it is measured (the model's error scale kept as it is). No "
      "suggestion lies within 0.02 of a measured composition. A model without error bars (two "
      "compositions) gets the middle of the widest gap. docs/usage.md tells how the rule was "
      "judged.");
  o->source.AddOptions(cmd, true, false);
  cmd->add_option("--count", o->count, "How many compositions to propose (1-20)")
      ->capture_default_str()
      ->check(NumberIn(color::kSuggestCountRange));
  cmd->add_option("--rule", o->rule,
                  "largest-sigma (the composition of largest one-sigma) or widest-gap (the "
                  "middle of the widest gap between measured compositions)")
      ->capture_default_str()
      ->check(CLI::IsMember({"largest-sigma", "widest-gap"}));
  AddColorimetryOptions(cmd, &o->illuminant, &o->observer);
  cmd->add_option("--threads", o->threads, "Threads for the scan (0: all the hardware's)")
      ->capture_default_str()
      ->check(NumberIn(0, 1024, true));
  cmd->add_flag("--json", o->json,
                "Print a JSON list: x (atomic fraction), x_given (the data set's units), "
                "sigma_de00, and the largest and mean one-sigma before and after");
  cmd->add_flag("--quiet", o->quiet, "No warnings or progress on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
