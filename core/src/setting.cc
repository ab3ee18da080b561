#include "alloycolor/core/setting.h"

#include <cmath>
#include <string>
#include <string_view>

#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"

namespace alloycolor {
namespace {

std::string RangeText(const NumberRange& range) {
  return std::string(range.whole ? "a whole number in [" : "a finite number in [") +
         FormatNumber(range.lo) + ", " + FormatNumber(range.hi) + "]";
}

}  // namespace

const NumberRange& FitSettingRange(std::string_view name) {
  if (name == "degree") return kDegreeRange;
  if (name == "smoothing") return kSmoothingRange;
  if (name == "lambda_from_nm" || name == "lambda_to_nm") return kLambdaNmRange;
  if (name == "lambda_step_nm") return kLambdaStepNmRange;
  throw Error("no fit setting is named " + Quote(name));
}

std::string NumberProblem(double value, const NumberRange& range) {
  if (std::isfinite(value) && value >= range.lo && value <= range.hi &&
      (!range.whole || value == std::floor(value))) {
    return std::string();
  }
  return FormatNumber(value) + " is not " + RangeText(range);
}

std::string NumberProblem(std::string_view text, const NumberRange& range) {
  double value = 0;
  if (!ParseFiniteDouble(Trim(text), &value)) {
    return Quote(MessageLine(std::string(text), 40)) + " is not " + RangeText(range);
  }
  const std::string problem = NumberProblem(value, range);
  return problem.empty()
             ? problem
             : Quote(MessageLine(std::string(text), 40)) + " is not " + RangeText(range);
}

void CheckNumber(const std::string& name, double value, const NumberRange& range) {
  if (const std::string problem = NumberProblem(value, range); !problem.empty()) {
    throw Error(name + ": " + problem);
  }
}

}  // namespace alloycolor
