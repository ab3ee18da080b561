// The report's opening: the data set as a whole (validation.h, DescribeWholeDataSet).
#include <cmath>

#include "alloycolor/color/material_color.h"
#include "alloycolor/color/suggest.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/validate/validation.h"

namespace alloycolor::validate {

WholeDataSet DescribeWholeDataSet(const Dataset& dataset, const color::Colorimeter& colorimeter,
                                  const ModelBuilder& fit_whole, const std::string& method,
                                  int count) {
  WholeDataSet w;
  std::unique_ptr<AlloyModel> model;
  try {
    model = fit_whole(method, dataset);
  } catch (const Error& e) {
    w.error = e.what();
    return w;
  }
  w.method = model->method();
  w.choice = model->fit_summary().selection.reason;
  w.no_error_bar = model->NoErrorBarReason();
  w.samples_checked = model->samples_checked();
  w.suspects = model->suspect_samples();
  w.excluded = model->excluded_samples();
  for (const TrainingSample& t : model->training_samples()) w.sample_x.push_back(t.x_atomic);
  color::SuggestOptions options;
  options.count = count;
  const color::SuggestResult r = color::SuggestCompositions(colorimeter, *model, options);
  w.suggestions = r.suggestions;
  w.suggest_rule = r.rule;
  w.x = r.scan_x;
  if (r.metric == "delta_e00") w.sigma = r.scan_sigma;
  if (CoversVisible(model->lambda_min_nm(), model->lambda_max_nm())) {
    for (double x : w.x) {
      const color::ColorResult c = color::ColorFromXYZ(
          colorimeter,
          color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, *model, x), 0.0));
      w.srgb8.push_back(c.srgb8);
    }
  }
  return w;
}

}  // namespace alloycolor::validate
