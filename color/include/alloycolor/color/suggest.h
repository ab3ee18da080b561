// Where to measure next: the compositions where one more sample would shrink the model's
// error bars most, in the spirit of integrated-variance acquisition (BoTorch's
// qNegIntegratedPosteriorVariance) and of CAMEO's choice of the next film.
//
// The one-sigma a model gives at x (DeltaE00Sigma, material_color.h; for data without
// colour, the relative eps one-sigma of its prediction error, calibration * mean scale *
// B(x)) is scanned at kSuggestGrid compositions evenly over the model's range. A sample
// measured at x0 puts x0 among the prediction error's compositions (model/alloy_model.h:
// B = 0 there, and the gaps beside it shrink), which is what the model would carry after
// the measurement if the method's error scale stayed as it is. The rule (SuggestRule):
//  - kLargestSigma, the default: the scanned composition where the one-sigma a measurement
//    can remove is largest (the interpolation's, scale * B; the misfit, the replicates'
//    scatter and the data's precision stay whatever is measured), at least min_distance
//    from every training composition and every earlier suggestion;
//  - kWidestGap: the middle of the widest gap between those compositions (the ends of the
//    range count as compositions), the obvious alternative, and the only one for a model
//    without error bars.
// Suggestions are chosen jointly: the second is the best given that the first will have
// been measured. Each carries the one-sigma at its composition now (as `color` gives it),
// and the largest and the mean one-sigma over the scan before any suggestion is measured
// and after this one and the earlier ones are. scripts/suggest_table.py measures the
// rules on real series (docs/accuracy.md).
#ifndef ALLOYCOLOR_COLOR_SUGGEST_H_
#define ALLOYCOLOR_COLOR_SUGGEST_H_

#include <limits>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/core/setting.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::color {

inline constexpr int kSuggestGrid = 201;
// No composition closer than this to a measured one is suggested (atomic fraction).
inline constexpr double kSuggestMinDistance = 0.02;

enum class SuggestRule { kLargestSigma, kWidestGap };

// "largest-sigma" or "widest-gap"; ParseSuggestRule throws Error naming the choices.
std::string SuggestRuleName(SuggestRule rule);
SuggestRule ParseSuggestRule(const std::string& name);

// How many compositions every face lets suggest propose (--count, count).
inline constexpr NumberRange kSuggestCountRange{1, 20, true};

struct SuggestOptions {
  int count = 1;  // kSuggestCountRange
  SuggestRule rule = SuggestRule::kLargestSigma;
  double min_distance = kSuggestMinDistance;
  ThreadBudget* threads = nullptr;
  CancelCheck cancel;  // called at every point of each scan (core/progress.h)
};

struct Suggestion {
  double x_atomic = 0;
  // The one-sigma there now: CIEDE2000 (normal incidence, the colorimeter's illuminant and
  // observer) or, for data without colour, the relative eps error; NaN without error bars.
  double sigma = std::numeric_limits<double>::quiet_NaN();
  // Over the scanned range: before any suggestion is measured, and after this one and the
  // earlier ones are (NaN without error bars).
  double max_sigma_before = std::numeric_limits<double>::quiet_NaN();
  double max_sigma_after = std::numeric_limits<double>::quiet_NaN();
  double mean_sigma_before = std::numeric_limits<double>::quiet_NaN();
  double mean_sigma_after = std::numeric_limits<double>::quiet_NaN();
};

struct SuggestResult {
  std::string metric;  // "delta_e00", "relative_eps" or "none" (no error bars)
  std::string rule;    // the rule used (SuggestRuleName), with why where it fell back
  std::vector<Suggestion> suggestions;
  // The scan before any suggestion: compositions and their one-sigma (for plots).
  std::vector<double> scan_x, scan_sigma;
};

// Throws Error for a count outside 1..20; returns fewer suggestions where the range has no
// room left (every composition within min_distance of a measured or suggested one).
SuggestResult SuggestCompositions(const Colorimeter& colorimeter, const AlloyModel& model,
                                  const SuggestOptions& options);

}  // namespace alloycolor::color

#endif  // ALLOYCOLOR_COLOR_SUGGEST_H_
