// What a delimited file's header says: its column names as quantities, units and values,
// the fields of a line, and the choice of the n,k columns (io_delimited_columns.h).
#include "io_delimited_columns.h"

#include <algorithm>
#include <cstddef>
#include <initializer_list>
#include <regex>
#include <string>
#include <string_view>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"
#include "alloycolor/core/units.h"
#include "io_internal.h"

namespace alloycolor::delimited {

using io_internal::IsNonFiniteWord;
using io_internal::SplitWhitespace;

double NmFrom(Unit unit, double value) {
  switch (unit) {
    case Unit::kNm:
      return value;
    case Unit::kUm:
      return value * 1000.0;
    case Unit::kAngstrom:
      return value * 0.1;
    case Unit::kEv:
      return LambdaNmFromOmegaEv(value);
    case Unit::kWavenumber:
      return 1e7 / value;  // 1 cm = 1e7 nm
  }
  return value;
}

// A column name in lower case, with the non-ASCII spellings of units and symbols made
// ASCII (µ, μ -> u; Å -> angstrom; ε -> eps; superscript minus and digits; subscripts)
// and every other byte that is not a letter or digit made a separator.
std::vector<std::string> NameTokens(std::string_view name) {
  static const std::pair<std::string_view, std::string_view> kSpellings[] = {
      {"\xC2\xB5", "u"},          {"\xCE\xBC", "u"},
      {"\xC3\x85", " angstrom "}, {"\xE2\x84\xAB", " angstrom "},
      {"\xC3\xA5", " angstrom "}, {"\xCE\xB5", "eps"},
      {"\xCF\xB5", "eps"},        {"\xE2\x81\xBB", "-"},
      {"\xC2\xB9", "1"},          {"\xC2\xB2", "2"},
      {"\xE2\x82\x81", "1"},      {"\xE2\x82\x82", "2"},
  };
  std::string ascii;
  for (std::size_t i = 0; i < name.size();) {
    bool replaced = false;
    for (const auto& [from, to] : kSpellings) {
      if (name.substr(i, from.size()) == from) {
        ascii += to;
        i += from.size();
        replaced = true;
        break;
      }
    }
    if (replaced) continue;
    const char c = name[i++];
    ascii += (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  }
  std::vector<std::string> tokens;
  std::string token;
  for (const char c : ascii) {
    if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9')) {
      token += c;
    } else if (!token.empty()) {
      tokens.push_back(std::move(token));
      token.clear();
    }
  }
  if (!token.empty()) tokens.push_back(std::move(token));
  return tokens;
}

bool OneOf(const std::string& token, std::initializer_list<std::string_view> words) {
  return std::find(words.begin(), words.end(), token) != words.end();
}

enum class Quantity { kNone, kWavelength, kEnergy, kWavenumber };

AbscissaName ClassifyAbscissa(std::string_view name) {
  const std::vector<std::string> tokens = NameTokens(name);
  Quantity quantity = Quantity::kNone;
  for (const std::string& t : tokens) {
    if (OneOf(t, {"wavelength", "wavelengths", "lambda", "lamda", "lam", "wl", "wave"})) {
      quantity = Quantity::kWavelength;
    } else if (OneOf(t, {"energy", "photon", "photonenergy", "e", "hv", "hnu"})) {
      quantity = Quantity::kEnergy;
    } else if (OneOf(t, {"wavenumber", "wavenumbers", "wn", "nu"})) {
      quantity = Quantity::kWavenumber;
    }
  }
  AbscissaName result;
  std::vector<std::string> others;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::string& t = tokens[i];
    const bool cm_minus_1 = (t == "cm" && i + 1 < tokens.size() && tokens[i + 1] == "1") ||
                            (t == "1" && i + 1 < tokens.size() && tokens[i + 1] == "cm");
    Unit unit = Unit::kNm;
    Quantity implied = Quantity::kNone;
    if (OneOf(t, {"nm", "nanometer", "nanometers", "nanometre", "nanometres"})) {
      unit = Unit::kNm;
      implied = Quantity::kWavelength;
    } else if (OneOf(t, {"um", "mum", "micron", "microns", "micrometer", "micrometers",
                         "micrometre", "micrometres"})) {
      unit = Unit::kUm;
      implied = Quantity::kWavelength;
    } else if (OneOf(t, {"angstrom", "angstroms", "ang", "aa"}) ||
               (t == "a" && quantity == Quantity::kWavelength)) {
      unit = Unit::kAngstrom;
      implied = Quantity::kWavelength;
    } else if (t == "ev") {
      unit = Unit::kEv;
      implied = Quantity::kEnergy;
    } else if (cm_minus_1 || OneOf(t, {"cm1", "kayser"})) {
      unit = Unit::kWavenumber;
      implied = Quantity::kWavenumber;
      if (cm_minus_1) ++i;
    } else {
      others.push_back(t);
      continue;
    }
    if (result.has_unit) {
      result.is_abscissa = true;
      result.has_unit = false;
      result.problem = "names two units";
      return result;
    }
    if (quantity != Quantity::kNone && quantity != implied) {
      result.is_abscissa = true;
      result.problem = "names a quantity and a unit that do not match";
      return result;
    }
    result.is_abscissa = true;
    result.has_unit = true;
    result.unit = unit;
  }
  if (!result.is_abscissa && quantity != Quantity::kNone) {
    result.is_abscissa = true;
    std::string unknown;
    for (const std::string& t : others) {
      if (OneOf(t, {"wavelength", "wavelengths", "lambda", "lamda", "lam", "wl", "wave", "energy",
                    "photon", "photonenergy", "e", "hv", "hnu", "wavenumber", "wavenumbers", "wn",
                    "nu"})) {
        continue;
      }
      unknown += (unknown.empty() ? "" : " ") + t;
    }
    result.problem =
        unknown.empty() ? "gives no unit" : "has the unit " + Quote(unknown) + ", not one known";
  }
  return result;
}

// What a header column says about the values: n, k, eps1 or eps2 of a sample (tag).
enum class ValueKind { kOther, kN, kK, kEps1, kEps2 };

struct ValueName {
  ValueKind kind = ValueKind::kOther;
  std::string tag;  // "" for a lone n, "6" for n6 and n_6
};

ValueName ClassifyValue(std::string_view name) {
  std::string joined;
  for (const std::string& t : NameTokens(name)) joined += (joined.empty() ? "" : "_") + t;
  static const std::regex kN("n(?:_?([0-9]+)|_(.+))?");
  static const std::regex kK("(?:k|kappa)(?:_?([0-9]+)|_(.+))?");
  static const std::regex kEps1(
      "(?:(?:e|eps|epsilon)_?(?:1|r|re|real)|re_(?:e|eps|epsilon))(?:_(.+))?");
  static const std::regex kEps2(
      "(?:(?:e|eps|epsilon)_?(?:2|i|im|imag)|im_(?:e|eps|epsilon))(?:_(.+))?");
  std::smatch match;
  ValueName result;
  if (std::regex_match(joined, match, kN)) {
    result.kind = ValueKind::kN;
    result.tag = match[1].matched ? match[1].str() : match[2].str();
  } else if (std::regex_match(joined, match, kK)) {
    result.kind = ValueKind::kK;
    result.tag = match[1].matched ? match[1].str() : match[2].str();
  } else if (std::regex_match(joined, match, kEps1)) {
    result.kind = ValueKind::kEps1;
    result.tag = match[1].str();
  } else if (std::regex_match(joined, match, kEps2)) {
    result.kind = ValueKind::kEps2;
    result.tag = match[1].str();
  }
  return result;
}

// The fields of a line: split at delimiter (' ' meaning runs of blanks), each trimmed;
// trailing empty fields (a trailing delimiter) dropped.
std::vector<std::string_view> SplitFields(std::string_view line, char delimiter) {
  std::vector<std::string_view> fields;
  if (delimiter == ' ') {
    fields = SplitWhitespace(line);
  } else {
    std::size_t start = 0;
    while (true) {
      const std::size_t at = line.find(delimiter, start);
      fields.push_back(
          Trim(line.substr(start, at == std::string_view::npos ? line.npos : at - start)));
      if (at == std::string_view::npos) break;
      start = at + 1;
    }
  }
  while (!fields.empty() && fields.back().empty()) fields.pop_back();
  return fields;
}

// Header fields; with whitespace between fields, a unit in brackets ("Wavelength (nm)")
// stays with the name before it.
std::vector<std::string> SplitHeader(std::string_view line, char delimiter) {
  std::vector<std::string> names;
  for (std::string_view field : SplitFields(line, delimiter)) {
    if (delimiter == ' ' && !names.empty() && (field.front() == '(' || field.front() == '[')) {
      names.back() += " " + std::string(field);
    } else {
      names.emplace_back(field);
    }
  }
  return names;
}

char DelimiterOf(std::string_view line) {
  if (line.find('\t') != std::string_view::npos) return '\t';
  if (line.find(';') != std::string_view::npos) return ';';
  if (line.find(',') != std::string_view::npos) return ',';
  return ' ';
}

std::string DelimiterName(char delimiter) {
  switch (delimiter) {
    case '\t':
      return "tab";
    case ';':
      return "semicolon";
    case ',':
      return "comma";
  }
  return "whitespace";
}

// A field with a decimal comma ("0,5", "-1,25e-3") written with '.'; other fields as they
// are. Only applied where the delimiter is not a comma, so the comma cannot be one.
std::string DecimalPoint(std::string_view field, char delimiter) {
  std::string text(field);
  if (delimiter == ',' || text.find('.') != std::string::npos) return text;
  static const std::regex kDecimalComma("[+-]?[0-9]+,[0-9]+([eE][+-]?[0-9]+)?");
  if (std::regex_match(text, kDecimalComma)) text[text.find(',')] = '.';
  return text;
}

// True when the line is at least two numbers and nothing else.
bool IsNumberRow(std::string_view line) {
  const char delimiter = DelimiterOf(line);
  const std::vector<std::string_view> fields = SplitFields(line, delimiter);
  if (fields.size() < 2) return false;
  double value = 0;
  for (std::string_view field : fields) {
    if (!ParseFiniteDouble(DecimalPoint(field, delimiter), &value) && !IsNonFiniteWord(field)) {
      return false;
    }
  }
  return true;
}

std::string JoinNames(const std::vector<std::string>& names, char delimiter) {
  std::string text;
  for (const std::string& name : names) {
    if (!text.empty()) text += delimiter == ' ' ? ' ' : delimiter;
    text += name;
  }
  return text;
}

constexpr std::string_view kColumnsAdvice =
    "choose the columns with --columns N,K (a data set sample: \"columns\": [\"n6\", "
    "\"k6\"]), by header name or 1-based column number";

// The column chosen by spec (a header name or a 1-based number), 0-based.
std::size_t ResolveColumn(const std::string& spec, const std::vector<std::string>& names,
                          const std::string& at) {
  const std::string_view trimmed = Trim(spec);
  if (!trimmed.empty() &&
      std::all_of(trimmed.begin(), trimmed.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    const std::size_t number = trimmed.size() > 6 ? 0 : std::stoul(std::string(trimmed));
    if (number < 1 || number > names.size()) {
      Fail(at + "column " + Quote(trimmed) + " does not exist: the header has " +
           std::to_string(names.size()) + " columns");
    }
    return number - 1;
  }
  for (const bool ignore_case : {false, true}) {
    std::vector<std::size_t> found;
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (ignore_case ? Lower(names[i]) == Lower(trimmed) : names[i] == trimmed) {
        found.push_back(i);
      }
    }
    if (found.size() == 1) return found.front();
    if (found.size() > 1) {
      Fail(at + "the header has " + std::to_string(found.size()) + " columns named " +
           Quote(trimmed) + "; choose by 1-based column number");
    }
  }
  Fail(at + "no column named " + Quote(trimmed) + " in the header " +
       Quote(JoinNames(names, ','), 120));
}

Layout ChooseColumns(const std::string& path, const std::vector<std::string>& names,
                     int header_line, char delimiter, const NkColumns& columns) {
  const std::string at = path + ":" + std::to_string(header_line) + ": ";
  const std::string header = Quote(JoinNames(names, delimiter == ' ' ? ' ' : ','), 120);
  Layout layout;
  layout.header_line = header_line;
  layout.delimiter = delimiter;
  layout.names = names;
  bool found = false;
  for (std::size_t i = 0; i < names.size() && !found; ++i) {
    const AbscissaName abscissa = ClassifyAbscissa(names[i]);
    if (!abscissa.is_abscissa) continue;
    if (!abscissa.has_unit) {
      Fail(at + "header column " + Quote(names[i]) + " " + abscissa.problem + "; " +
           std::string(kHeaderAdvice));
    }
    layout.abscissa = i;
    layout.unit = abscissa.unit;
    found = true;
  }
  if (!found) {
    Fail(at + "the header " + header + " names no wavelength, energy or wavenumber column; " +
         std::string(kHeaderAdvice));
  }

  if (!columns.empty()) {
    if (columns.n.empty() || columns.k.empty()) {
      Fail(at + "a column choice needs both the n and the k column");
    }
    layout.value[0] = ResolveColumn(columns.n, names, at);
    layout.value[1] = ResolveColumn(columns.k, names, at);
    for (const std::size_t v : layout.value) {
      if (v == layout.abscissa) {
        Fail(at + "column " + Quote(names[v]) + " is the abscissa, not n or k");
      }
    }
    if (layout.value[0] == layout.value[1]) {
      Fail(at + "n and k are both column " + Quote(names[layout.value[0]]));
    }
    const ValueKind first = ClassifyValue(names[layout.value[0]]).kind;
    const ValueKind second = ClassifyValue(names[layout.value[1]]).kind;
    layout.eps = first == ValueKind::kEps1 && second == ValueKind::kEps2;
    const bool nk = (first == ValueKind::kN || first == ValueKind::kOther) &&
                    (second == ValueKind::kK || second == ValueKind::kOther);
    if (!layout.eps && !nk) {
      Fail(at + "columns " + Quote(names[layout.value[0]]) + " and " +
           Quote(names[layout.value[1]]) +
           " are neither n and k nor eps1 and eps2 (give n then k, or eps1 then eps2)");
    }
    return layout;
  }

  // Pairs of columns with the same sample tag.
  struct Pair {
    std::size_t first, second;
    bool eps;
    std::string tag;
  };
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i == layout.abscissa) continue;
    const ValueName a = ClassifyValue(names[i]);
    if (a.kind != ValueKind::kN && a.kind != ValueKind::kEps1) continue;
    const ValueKind partner = a.kind == ValueKind::kN ? ValueKind::kK : ValueKind::kEps2;
    for (std::size_t j = 0; j < names.size(); ++j) {
      const ValueName b = ClassifyValue(names[j]);
      if (j != layout.abscissa && b.kind == partner && b.tag == a.tag) {
        pairs.push_back({i, j, a.kind == ValueKind::kEps1, a.tag});
        break;
      }
    }
  }
  // n,k and eps1,eps2 of the same single sample: the same data, read as n and k.
  if (pairs.size() == 2 && pairs[0].tag == pairs[1].tag && pairs[0].eps != pairs[1].eps) {
    pairs.erase(pairs[0].eps ? pairs.begin() : pairs.begin() + 1);
  }
  if (pairs.empty()) {
    Fail(at + "the header " + header +
         " has no n,k (or eps1,eps2) column pair; name them 'n' and 'k' (or 'e1' and 'e2') "
         "in the header, or " +
         std::string(kColumnsAdvice));
  }
  if (pairs.size() > 1) {
    std::string list;
    for (std::size_t p = 0; p < pairs.size() && p < 6; ++p) {
      list += (p ? ", " : "") + names[pairs[p].first] + "/" + names[pairs[p].second];
    }
    if (pairs.size() > 6) list += ", ...";
    Fail(at + "the header holds " + std::to_string(pairs.size()) + " column pairs (" + list +
         "), one per sample; " + std::string(kColumnsAdvice));
  }
  layout.value[0] = pairs[0].first;
  layout.value[1] = pairs[0].second;
  layout.eps = pairs[0].eps;
  return layout;
}

}  // namespace alloycolor::delimited
