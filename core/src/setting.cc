#include "alloycolor/core/setting.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

std::string Joined(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& w : words) text += (text.empty() ? "" : ", ") + w;
  return text;
}

const char* TypeName(OptionValue::Type type) {
  switch (type) {
    case OptionValue::Type::kNumber:
      return "a number";
    case OptionValue::Type::kText:
      return "text";
    case OptionValue::Type::kFlag:
      return "true or false";
  }
  return "?";
}

OptionValue::Type TypeOf(OptionKind kind) {
  switch (kind) {
    case OptionKind::kWhole:
    case OptionKind::kNumber:
      return OptionValue::Type::kNumber;
    case OptionKind::kChoice:
    case OptionKind::kText:
      return OptionValue::Type::kText;
    case OptionKind::kFlag:
      return OptionValue::Type::kFlag;
  }
  return OptionValue::Type::kNumber;
}

}  // namespace

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

void CheckAngleDeg(const std::string& name, double angle_deg) {
  if (!(angle_deg >= kAngleDegRange.lo && angle_deg <= kAngleDegRange.hi)) {
    throw Error(name + ": " + FormatNumber(angle_deg) + " lies outside 0-90 degrees");
  }
}

// ---- options ----------------------------------------------------------------------------------

std::string OptionValueText(const OptionValue& value) {
  switch (value.type) {
    case OptionValue::Type::kNumber:
      return FormatNumber(value.number);
    case OptionValue::Type::kText:
      return value.text;
    case OptionValue::Type::kFlag:
      return value.flag ? "true" : "false";
  }
  return "";
}

const std::string& Spelled(const OptionSpec& spec, OptionSpelling spelling) {
  return spelling == OptionSpelling::kFlag ? spec.flag : spec.name;
}

std::string OptionValuesText(const OptionSpec& spec) {
  switch (spec.kind) {
    case OptionKind::kWhole:
    case OptionKind::kNumber:
      return RangeText(spec.range);
    case OptionKind::kChoice:
      return "one of " + Joined(spec.choices);
    case OptionKind::kText:
      return spec.values;
    case OptionKind::kFlag:
      return "true or false";
  }
  return "";
}

std::string OptionProblem(const OptionSpec& spec, const OptionValue& value) {
  if (value.type != TypeOf(spec.kind)) {
    return Quote(MessageLine(OptionValueText(value), 40)) + " is " + TypeName(value.type) +
           ", not " + OptionValuesText(spec);
  }
  switch (spec.kind) {
    case OptionKind::kWhole:
    case OptionKind::kNumber:
      return NumberProblem(value.number, spec.range);
    case OptionKind::kChoice:
      if (std::find(spec.choices.begin(), spec.choices.end(), value.text) == spec.choices.end()) {
        return Quote(MessageLine(value.text, 40)) + " is none of " + Joined(spec.choices);
      }
      return "";
    case OptionKind::kText:
      return spec.check != nullptr ? spec.check(value.text) : "";
    case OptionKind::kFlag:
      return "";
  }
  return "";
}

namespace {

// The value of `text` for `spec`, read as far as its kind allows (a number that does not
// read is 0: OptionTextProblem refuses it first).
OptionValue ValueFromText(const OptionSpec& spec, const std::string& text) {
  switch (spec.kind) {
    case OptionKind::kWhole:
    case OptionKind::kNumber: {
      double number = 0;
      ParseFiniteDouble(Trim(text), &number);
      return OptionValue::Number(number);
    }
    case OptionKind::kFlag:
      return OptionValue::Flag(text == "true");
    case OptionKind::kChoice:
    case OptionKind::kText:
      break;
  }
  return OptionValue::Text(text);
}

}  // namespace

std::string OptionTextProblem(const OptionSpec& spec, const std::string& text) {
  switch (spec.kind) {
    case OptionKind::kWhole:
    case OptionKind::kNumber: {
      // A number that reads is named as the library names it ("7 is not ..."), so that the
      // program and the Python package refuse a value in the same words.
      double number = 0;
      return ParseFiniteDouble(Trim(text), &number) ? NumberProblem(number, spec.range)
                                                    : NumberProblem(text, spec.range);
    }
    case OptionKind::kFlag:
      return text == "true" || text == "false"
                 ? ""
                 : Quote(MessageLine(text, 40)) + " is not true or false";
    case OptionKind::kChoice:
    case OptionKind::kText:
      break;
  }
  return OptionProblem(spec, OptionValue::Text(text));
}

OptionValue OptionFromText(const OptionSpec& spec, const std::string& text,
                           OptionSpelling spelling) {
  if (const std::string problem = OptionTextProblem(spec, text); !problem.empty()) {
    throw Error(Spelled(spec, spelling) + ": " + problem);
  }
  return ValueFromText(spec, text);
}

bool SameDeclaration(const OptionSpec& a, const OptionSpec& b) {
  return a.name == b.name && a.flag == b.flag && a.kind == b.kind && a.range.lo == b.range.lo &&
         a.range.hi == b.range.hi && a.range.whole == b.range.whole && a.choices == b.choices &&
         a.check == b.check && a.values == b.values && a.default_value == b.default_value;
}

const OptionValue& OptionValues::At(const std::string& name, OptionValue::Type type) const {
  const auto it = values_.find(name);
  if (it == values_.end()) throw Error("option " + Quote(name) + " was not given");
  if (it->second.type != type) {
    throw Error("option " + Quote(name) + " is " + TypeName(it->second.type) + ", not " +
                TypeName(type));
  }
  return it->second;
}

double OptionValues::Number(const std::string& name) const {
  return At(name, OptionValue::Type::kNumber).number;
}

int OptionValues::Whole(const std::string& name) const {
  return static_cast<int>(std::lround(Number(name)));
}

const std::string& OptionValues::Text(const std::string& name) const {
  return At(name, OptionValue::Type::kText).text;
}

bool OptionValues::Flag(const std::string& name) const {
  return At(name, OptionValue::Type::kFlag).flag;
}

double OptionValues::Number(const std::string& name, double fallback) const {
  return Has(name) ? Number(name) : fallback;
}

int OptionValues::Whole(const std::string& name, int fallback) const {
  return Has(name) ? Whole(name) : fallback;
}

std::string OptionValues::Text(const std::string& name, const std::string& fallback) const {
  return Has(name) ? Text(name) : fallback;
}

bool OptionValues::Flag(const std::string& name, bool fallback) const {
  return Has(name) ? Flag(name) : fallback;
}

std::string OptionValues::Key() const {
  std::string key;
  for (const auto& [name, value] : values_) {
    // Numbers exactly (17 digits), so that two values never share a key.
    char number[32];
    std::snprintf(number, sizeof number, "%.17g", value.number);
    key += name + "=" + std::to_string(static_cast<int>(value.type)) + ":" + number + ":" +
           value.text + ":" + (value.flag ? "1" : "0") + "\n";
  }
  return key;
}

}  // namespace alloycolor
