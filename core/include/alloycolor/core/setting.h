// Numeric settings checked once, the same way by every face: the program's options
// (--smoothing 2) and the Python package's keywords (smoothing=2) both ask
// NumberProblem, so that a value is refused with the same words wherever it is given.
// The library names a setting by its own name ("smoothing", "lambda_step_nm"); each face
// puts its own spelling in front (CLI11 the option, Python the keyword).
// The ranges of the fit's settings live here until fit/ carries its own table
// (fit::FitSettings holds the values; these are their bounds).
#ifndef ALLOYCOLOR_CORE_SETTING_H_
#define ALLOYCOLOR_CORE_SETTING_H_

#include <string>
#include <string_view>

namespace alloycolor {

// A closed range of values, whole numbers only when `whole`.
struct NumberRange {
  double lo;
  double hi;
  bool whole = false;
};

// The fit's numeric settings: physical's composition degree, smooth's roughness weight,
// and the fit grid in nm (from, to: 1 nm to 1 mm; step: 0.01 nm to 100 um).
inline constexpr NumberRange kDegreeRange{0, 20, true};
inline constexpr NumberRange kSmoothingRange{0, 1e6, false};
inline constexpr NumberRange kLambdaNmRange{1, 1e6, false};
inline constexpr NumberRange kLambdaStepNmRange{0.01, 1e5, false};
// The most nodes a fit grid may have ((to - from) / step).
inline constexpr int kMaxFitGridNodes = 20000;

// The range of a fit setting by its library name ("degree", "smoothing",
// "lambda_from_nm", "lambda_to_nm", "lambda_step_nm"); throws Error for another name.
const NumberRange& FitSettingRange(std::string_view name);

// "" when `value` lies in `range` (finite; whole when asked), else what is wrong, without
// a name: "-1 is not a finite number in [0, 1e+06]".
std::string NumberProblem(double value, const NumberRange& range);
// The same for text as given (a whole token, read in the C locale; "nan" and "2.5" for a
// whole number are problems).
std::string NumberProblem(std::string_view text, const NumberRange& range);

// Throws Error "NAME: PROBLEM" when NumberProblem finds one.
void CheckNumber(const std::string& name, double value, const NumberRange& range);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_SETTING_H_
