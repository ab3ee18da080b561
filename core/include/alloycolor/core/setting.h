// Settings checked once, the same way by every face.
//
// Numbers: the program's options (--smoothing 2) and the Python package's keywords
// (smoothing=2) both ask NumberProblem, so that a value is refused with the same words
// wherever it is given.
//
// Options declared once (after Ceres' Solver::Options + IsValid, pbrt-v4's
// ParameterDictionary, scikit-learn's _parameter_constraints): an OptionSpec says what an
// option is called, what it takes (a whole number or a number in a range, one of a few
// words, text a check accepts, on or off), its default and one line of help. The methods'
// options are declared in their registry entries (model/registry.h) and the faces are
// generated from those declarations: the program's options and their --help, the Python
// keywords, its type stubs and the table in docs/methods.md. Values travel as
// OptionValues, a dictionary by name that the method reads where it is built.
//
// The library names an option by its name ("lambda_step_nm", also the Python keyword); the
// program by its flag ("--lambda-step"): a message names it as the caller spells it
// (OptionSpelling).
#ifndef ALLOYCOLOR_CORE_SETTING_H_
#define ALLOYCOLOR_CORE_SETTING_H_

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace alloycolor {

// A closed range of values, whole numbers only when `whole`.
struct NumberRange {
  double lo;
  double hi;
  bool whole = false;
};

// "" when `value` lies in `range` (finite; whole when asked), else what is wrong, without
// a name: "-1 is not a finite number in [0, 1e+06]".
std::string NumberProblem(double value, const NumberRange& range);
// The same for text as given (a whole token, read in the C locale; "nan" and "2.5" for a
// whole number are problems).
std::string NumberProblem(std::string_view text, const NumberRange& range);

// Throws Error "NAME: PROBLEM" when NumberProblem finds one.
void CheckNumber(const std::string& name, double value, const NumberRange& range);

// The angle of incidence, in degrees, for every face: [0, 90].
inline constexpr NumberRange kAngleDegRange{0, 90, false};
// Throws Error "NAME: 95 lies outside 0-90 degrees" for an angle outside kAngleDegRange
// (or not finite).
void CheckAngleDeg(const std::string& name, double angle_deg);

// The most nodes a fit grid may have, (to - from) / step (fit/methods.h CheckFitGrid).
inline constexpr int kMaxFitGridNodes = 20000;

// ---- options declared once ------------------------------------------------------------------

enum class OptionKind {
  kWhole,   // a whole number in `range`
  kNumber,  // a finite number in `range`
  kChoice,  // one of `choices`
  kText,    // text that `check` accepts (`values` says which)
  kFlag,    // on or off
};

// One value of an option: a number (kWhole, kNumber), text (kChoice, kText) or a flag.
struct OptionValue {
  enum class Type { kNumber, kText, kFlag };
  Type type = Type::kNumber;
  double number = 0;
  std::string text;
  bool flag = false;

  static OptionValue Number(double v) { return {Type::kNumber, v, {}, false}; }
  static OptionValue Text(std::string v) { return {Type::kText, 0, std::move(v), false}; }
  static OptionValue Flag(bool v) { return {Type::kFlag, 0, {}, v}; }
  bool operator==(const OptionValue& o) const {
    return type == o.type && number == o.number && text == o.text && flag == o.flag;
  }
};

// "2", "1e-06", "log_eps", "true".
std::string OptionValueText(const OptionValue& value);

struct OptionSpec {
  std::string name;  // the library's and Python's: "lambda_step_nm"
  // The program's: "--lambda-step"; a flag that is on by default is spelt by what turns
  // it off ("--no-covariance").
  std::string flag;
  OptionKind kind = OptionKind::kNumber;
  NumberRange range{0, 0, false};    // kWhole, kNumber
  std::vector<std::string> choices;  // kChoice
  // kText: "" when the text is acceptable, else what is wrong; `values` says what it takes.
  std::string (*check)(const std::string& text) = nullptr;
  std::string values;
  // The value a method takes when the option is not given; none: the method chooses
  // (the help says how).
  std::optional<OptionValue> default_value;
  std::string help;  // one line, without the methods, range or default
};

// How a message names an option: the library's (and Python's) name, or the program's flag.
enum class OptionSpelling { kName, kFlag };
const std::string& Spelled(const OptionSpec& spec, OptionSpelling spelling);

// What the option takes, for help and messages: "a whole number in [0, 6]",
// "one of eps, log_eps", "true or false", or the spec's `values`.
std::string OptionValuesText(const OptionSpec& spec);

// "" when `value` suits `spec`, else what is wrong, without the name
// ("7 is not a whole number in [0, 6]", "'cubic' is none of eps, log_eps").
std::string OptionProblem(const OptionSpec& spec, const OptionValue& value);

// A value given as text (the program's options): a number read in the C locale, a word,
// text, or "true"/"false" for a flag. OptionTextProblem says what is wrong ("" if
// nothing, as OptionProblem); OptionFromText throws Error "SPELLED: PROBLEM".
std::string OptionTextProblem(const OptionSpec& spec, const std::string& text);
OptionValue OptionFromText(const OptionSpec& spec, const std::string& text,
                           OptionSpelling spelling = OptionSpelling::kName);

// Whether two declarations of an option agree in all but their help.
bool SameDeclaration(const OptionSpec& a, const OptionSpec& b);

// The options given to one method, by name (pbrt's ParameterDictionary). A method reads
// what it takes; BuildModel checks them all against the method's declaration first
// (model/registry.h CheckMethodOptions), so a reader's value is always of the declared kind.
class OptionValues {
 public:
  void Set(const std::string& name, OptionValue value) { values_[name] = std::move(value); }
  void Set(const std::string& name, double v) { Set(name, OptionValue::Number(v)); }
  void Set(const std::string& name, int v) { Set(name, OptionValue::Number(v)); }
  void Set(const std::string& name, bool v) { Set(name, OptionValue::Flag(v)); }
  void Set(const std::string& name, const std::string& v) { Set(name, OptionValue::Text(v)); }
  void Set(const std::string& name, const char* v) { Set(name, OptionValue::Text(v)); }
  void Erase(const std::string& name) { values_.erase(name); }

  bool Has(const std::string& name) const { return values_.count(name) > 0; }
  // The value of `name`; throws Error when it is absent or of another type.
  double Number(const std::string& name) const;
  int Whole(const std::string& name) const;
  const std::string& Text(const std::string& name) const;
  bool Flag(const std::string& name) const;
  // The same, or `fallback` when the option was not given.
  double Number(const std::string& name, double fallback) const;
  int Whole(const std::string& name, int fallback) const;
  std::string Text(const std::string& name, const std::string& fallback) const;
  bool Flag(const std::string& name, bool fallback) const;

  const std::map<std::string, OptionValue>& all() const { return values_; }
  bool empty() const { return values_.empty(); }
  // "name=value" for each option, sorted by name, one per line: a key for memos.
  std::string Key() const;

 private:
  const OptionValue& At(const std::string& name, OptionValue::Type type) const;
  std::map<std::string, OptionValue> values_;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_SETTING_H_
