#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstddef>
#include <exception>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/text.h"
#include "io_internal.h"

// refractiveindex.info YAML: a DATA list holding one `tabulated nk` entry, or one `tabulated n`
// and one `tabulated k` (in one file, or a pair of files).
namespace alloycolor {
namespace {

using io_internal::CheckOpticalConstant;
using io_internal::Columns;
using io_internal::FinishRows;
using io_internal::Locator;
using io_internal::MakeSpectrum;
using io_internal::ParseField;
using io_internal::ParseYamlGuarded;
using io_internal::Row;
using io_internal::SplitWhitespace;
using io_internal::Table;

constexpr std::string_view kYamlUnsupported =
    "only tabulated nk, or tabulated n plus tabulated k, are supported";

Row ParseRow(const std::vector<std::string_view>& fields, const Columns& columns, char separator,
             const Locator& where, int line, int index) {
  const std::string at = where.Row(line, index);
  if (fields.size() != columns.names.size()) {
    Fail(at + "expected " + std::to_string(columns.names.size()) + " columns (" +
         columns.Describe(separator) + "), found " + std::to_string(fields.size()));
  }
  double parsed[3] = {0, 0, 0};
  for (std::size_t i = 0; i < fields.size(); ++i) {
    parsed[i] = ParseField(fields[i], columns.names[i], at);
  }
  if (!(parsed[0] > 0)) {
    Fail(at + columns.names[0] + " = " + FormatNumber(parsed[0]) + " is not positive");
  }
  for (std::size_t i = 1; i < fields.size(); ++i) {
    CheckOpticalConstant(parsed[i], columns.names[i], at);
  }
  Row row;
  row.line = line;
  row.index = index;
  row.lambda = parsed[0];
  row.values[0] = parsed[1];
  row.values[1] = fields.size() > 2 ? parsed[2] : 0.0;
  return row;
}

enum class EntryKind { kNk, kN, kK };

struct Entry {
  EntryKind kind;
  int number;  // 1-based position in DATA
  YAML::Node node;
};

int MarkLine(const YAML::Mark& mark) { return mark.is_null() ? 0 : mark.line + 1; }

// True when the scalar starting at mark is a literal block (`|`), whose lines are the
// file's lines from the next one on.
bool IsLiteralBlockAt(const std::string& text, const YAML::Mark& mark) {
  if (mark.is_null() || mark.line < 0 || mark.column < 0) return false;
  std::size_t start = 0;
  for (int line = 0; line < mark.line; ++line) {
    start = text.find('\n', start);
    if (start == std::string::npos) return false;
    ++start;
  }
  const std::size_t at = start + static_cast<std::size_t>(mark.column);
  const std::size_t end = text.find('\n', start);
  return at < text.size() && (end == std::string::npos || at < end) && text[at] == '|';
}

Table ReadYamlTable(const std::string& path, const std::string& text, const Entry& entry,
                    const Columns& columns, std::vector<std::string>* warnings) {
  const std::string entry_name = "DATA entry " + std::to_string(entry.number);
  const YAML::Node data = entry.node["data"];
  if (!data) {
    Fail(path + ":" + std::to_string(MarkLine(entry.node.Mark())) + ": " + entry_name +
         " has no 'data'");
  }
  Locator where;
  where.path = path;
  where.block_line = MarkLine(data.Mark());
  if (!data.IsScalar()) Fail(where.At(where.block_line) + entry_name + ": 'data' is not text");
  where.exact = IsLiteralBlockAt(text, data.Mark());

  const std::string& block = data.Scalar();
  std::vector<Row> rows;
  int index = 0;
  int offset = 0;
  for (std::string_view line : Lines(block)) {
    const int file_line = where.exact ? where.block_line + 1 + offset : 0;
    ++offset;
    if (Trim(line).empty()) continue;
    rows.push_back(ParseRow(SplitWhitespace(line), columns, ' ', where, file_line, ++index));
  }
  return FinishRows(rows, columns, where, warnings);
}

// Linear interpolation of a table of strictly increasing x; x inside the table.
double Interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  const std::size_t hi = std::upper_bound(xs.begin(), xs.end(), x) - xs.begin();
  if (hi >= xs.size()) return ys.back();
  if (hi == 0) return ys.front();
  const double t = (x - xs[hi - 1]) / (xs[hi] - xs[hi - 1]);
  return ys[hi - 1] + t * (ys[hi] - ys[hi - 1]);
}

NkSpectrum JoinNK(const std::string& path, const Table& n_table, const Table& k_table,
                  std::vector<std::string>* warnings) {
  const double k_lo = k_table.lambda.front();
  const double k_hi = k_table.lambda.back();
  std::vector<double> lambda, n, k;
  for (std::size_t i = 0; i < n_table.lambda.size(); ++i) {
    const double x = n_table.lambda[i];
    if (x < k_lo || x > k_hi) continue;
    lambda.push_back(x);
    n.push_back(n_table.values[0][i]);
    k.push_back(Interpolate(k_table.lambda, k_table.values[0], x));
  }
  const std::string ranges = "tabulated n covers " + FormatNumber(n_table.lambda.front()) + " to " +
                             FormatNumber(n_table.lambda.back()) + " um, tabulated k " +
                             FormatNumber(k_lo) + " to " + FormatNumber(k_hi) + " um";
  if (lambda.size() < 2) {
    Fail(path + ": " + ranges + "; they share fewer than two wavelengths of the n grid");
  }
  if (lambda.size() < n_table.lambda.size() && warnings != nullptr) {
    warnings->push_back(path + ": " + ranges + "; only the overlap, " +
                        FormatNumber(lambda.front()) + " to " + FormatNumber(lambda.back()) +
                        " um, is used");
  }
  return MakeSpectrum(path, lambda, n, k, 1000.0, "wavelength_um");
}

// The largest YAML file read: yaml-cpp's nodes take some 200 times the text's size.
constexpr std::size_t kMaxYamlBytes = 8u << 20;

// YAML 1.2 requires the keys of a mapping to be unique; yaml-cpp keeps both and finds the
// first. A file that gives a key twice is refused, naming the second one's line.
// *budget counts the nodes still to be visited: a file without aliases has fewer nodes than
// bytes, so a walk that runs past its size meets aliases of aliases (a "billion laughs"
// file, whose 1 KB would take minutes to walk) and is refused at once.
void RejectDuplicateYamlKeys(const std::string& path, const YAML::Node& node, int depth,
                             std::size_t* budget) {
  if (depth > 64) Fail(path + ":" + std::to_string(MarkLine(node.Mark())) + ": nested too deeply");
  if (*budget == 0) {
    Fail(path + ":" + std::to_string(MarkLine(node.Mark())) +
         ": its aliases ('*name') expand to more nodes than the file has bytes; a "
         "refractiveindex.info file needs no aliases (write the values out)");
  }
  --*budget;
  if (node.IsMap()) {
    std::set<std::string> keys;
    for (const auto& pair : node) {
      if (pair.first.IsScalar()) {
        const std::string& key = pair.first.Scalar();
        if (!keys.insert(key).second) {
          Fail(path + ":" + std::to_string(MarkLine(pair.first.Mark())) + ": duplicate key " +
               Quote(key) + " (YAML keys must be unique)");
        }
      }
      RejectDuplicateYamlKeys(path, pair.second, depth + 1, budget);
    }
  } else if (node.IsSequence()) {
    for (const auto& item : node) RejectDuplicateYamlKeys(path, item, depth + 1, budget);
  }
}

// Where a YAML stream's second document starts, and whether it holds anything (an empty
// document is a null node).
struct DocumentStarts : YAML::EventHandler {
  int documents = 0;
  YAML::Mark second;
  bool content_of_second = false;

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents == 2) second = mark;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override { Holds(); }
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {
    Holds();
  }
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    Holds();
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    Holds();
  }
  void OnMapEnd() override {}
  void Holds() { content_of_second = content_of_second || documents == 2; }
};

// The DATA entries of a refractiveindex.info file; list_at names the DATA line.
std::vector<Entry> YamlEntries(const std::string& path, const std::string& text,
                               std::string* list_at_out) {
  if (text.size() > kMaxYamlBytes) {
    Fail(path + ": " + std::to_string(text.size() >> 20) +
         " MiB is too large for a refractiveindex.info file (the limit is " +
         std::to_string(kMaxYamlBytes >> 20) + " MiB)");
  }
  // yaml-cpp reads past a NUL byte (so "0.1<NUL>5" would be 0.1): refused first.
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    const auto line = 1 + std::count(text.begin(), text.begin() + nul, '\n');
    Fail(path + ":" + std::to_string(line) +
         ": a NUL byte; a refractiveindex.info file is text (DATA cannot be read)");
  }
  YAML::Node root;
  try {
    // The first document alone: yaml-cpp 0.7's LoadAll never returns on some malformed
    // streams (a line that starts with a comma: each further document is an empty one that
    // reads nothing), so the parser is asked for the second once, not until it is done.
    root = YAML::Load(text);
    std::istringstream stream(text);
    YAML::Parser parser(stream);
    DocumentStarts starts;
    if (parser.HandleNextDocument(starts) && parser.HandleNextDocument(starts) &&
        starts.content_of_second) {
      Fail(path + ":" + std::to_string(MarkLine(starts.second)) +
           ": a second YAML document ('---'); a refractiveindex.info file holds one");
    }
  } catch (const YAML::Exception& e) {
    Fail((MarkLine(e.mark) > 0 ? path + ":" + std::to_string(MarkLine(e.mark)) : path) +
         ": invalid YAML: " + e.msg);
  }
  std::size_t budget = text.size() + 16;
  RejectDuplicateYamlKeys(path, root, 0, &budget);
  if (!root.IsMap()) Fail(path + ": not a refractiveindex.info file (no DATA list)");
  const YAML::Node list = root["DATA"];
  if (!list) Fail(path + ": not a refractiveindex.info file (no DATA list)");
  const std::string list_at = path + ":" + std::to_string(MarkLine(list.Mark())) + ": ";
  if (!list.IsSequence() || list.size() == 0) Fail(list_at + "DATA is not a non-empty list");

  std::vector<Entry> entries;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node node = list[i];
    const int number = static_cast<int>(i) + 1;
    const std::string at = path + ":" + std::to_string(MarkLine(node.Mark())) + ": DATA entry " +
                           std::to_string(number);
    const YAML::Node type = node.IsMap() ? node["type"] : YAML::Node();
    if (!type || !type.IsScalar()) Fail(at + " has no 'type'");
    const std::string& name = type.Scalar();
    if (name == "tabulated nk") {
      entries.push_back({EntryKind::kNk, number, node});
    } else if (name == "tabulated n") {
      entries.push_back({EntryKind::kN, number, node});
    } else if (name == "tabulated k") {
      entries.push_back({EntryKind::kK, number, node});
    } else {
      Fail(at + " is " + Quote(name) + "; " + std::string(kYamlUnsupported) +
           (name.rfind("formula", 0) == 0
                ? " (formulas are not evaluated: download the tabulated n, k from "
                  "refractiveindex.info instead)"
                : ""));
    }
  }
  *list_at_out = list_at;
  return entries;
}

std::string EntriesHeld(const std::vector<Entry>& entries) {
  std::string held;
  for (const Entry& entry : entries) {
    if (!held.empty()) held += ", ";
    held += entry.kind == EntryKind::kNk  ? "'tabulated nk'"
            : entry.kind == EntryKind::kN ? "'tabulated n'"
                                          : "'tabulated k'";
  }
  return held;
}

NkSpectrum ParseYaml(const std::string& path, const std::string& text,
                     std::vector<std::string>* warnings) {
  std::string list_at;
  const std::vector<Entry> entries = YamlEntries(path, text, &list_at);
  const auto count = [&entries](EntryKind kind) {
    return std::count_if(entries.begin(), entries.end(),
                         [kind](const Entry& e) { return e.kind == kind; });
  };
  const auto find = [&entries](EntryKind kind) -> const Entry& {
    return *std::find_if(entries.begin(), entries.end(),
                         [kind](const Entry& e) { return e.kind == kind; });
  };
  const auto nk = count(EntryKind::kNk), n = count(EntryKind::kN), k = count(EntryKind::kK);
  if (nk == 1 && n == 0 && k == 0) {
    const Table table = ReadYamlTable(path, text, find(EntryKind::kNk),
                                      Columns{{"wavelength_um", "n", "k"}}, warnings);
    return MakeSpectrum(path, table.lambda, table.values[0], table.values[1], 1000.0,
                        "wavelength_um");
  }
  if (nk == 0 && n == 1 && k == 1) {
    const Table n_table =
        ReadYamlTable(path, text, find(EntryKind::kN), Columns{{"wavelength_um", "n"}}, warnings);
    const Table k_table =
        ReadYamlTable(path, text, find(EntryKind::kK), Columns{{"wavelength_um", "k"}}, warnings);
    return JoinNK(path, n_table, k_table, warnings);
  }
  Fail(list_at + "DATA holds " + EntriesHeld(entries) + "; " + std::string(kYamlUnsupported) +
       (entries.size() == 1 && entries[0].kind != EntryKind::kNk
            ? " (a file with one of them alone pairs with one holding the other: "
              "\"n_file\" and \"k_file\" of a data set sample)"
            : ""));
}

// f(), with any exception from yaml-cpp or the standard library turned into an Error naming
// the file (and the line, where yaml-cpp knows it).
template <typename F>
auto YamlGuarded(const std::string& path, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const Error&) {
    throw;
  } catch (const YAML::Exception& e) {
    Fail((MarkLine(e.mark) > 0 ? path + ":" + std::to_string(MarkLine(e.mark)) : path) +
         ": invalid YAML: " + e.msg);
  } catch (const std::exception& e) {
    Fail(path + ": cannot read: " + e.what());
  }
}

// The table of a file holding one `tabulated n` (or `tabulated k`) entry and nothing else.
Table ReadSingleTabulated(const std::string& path, EntryKind kind,
                          std::vector<std::string>* warnings) {
  const std::string text = ReadFileText(path);
  const char* wanted = kind == EntryKind::kN ? "'tabulated n'" : "'tabulated k'";
  return YamlGuarded(path, [&]() {
    std::string list_at;
    const std::vector<Entry> entries = YamlEntries(path, text, &list_at);
    if (entries.size() != 1 || entries[0].kind != kind) {
      Fail(list_at + "DATA holds " + EntriesHeld(entries) + "; expected " + wanted +
           " alone (this file is the " + (kind == EntryKind::kN ? "n" : "k") + " file of a pair)");
    }
    return ReadYamlTable(path, text, entries[0],
                         Columns{{"wavelength_um", kind == EntryKind::kN ? "n" : "k"}}, warnings);
  });
}

}  // namespace

NkSpectrum io_internal::ParseYamlGuarded(const std::string& path, const std::string& text,
                                         std::vector<std::string>* warnings) {
  return YamlGuarded(path, [&]() { return ParseYaml(path, text, warnings); });
}

NkSpectrum ReadRefractiveIndexYaml(const std::string& path, std::vector<std::string>* warnings) {
  return ParseYamlGuarded(path, ReadFileText(path), warnings);
}

NkSpectrum ReadNkPair(const std::string& n_path, const std::string& k_path,
                      std::vector<std::string>* warnings) {
  const Table n_table = ReadSingleTabulated(n_path, EntryKind::kN, warnings);
  const Table k_table = ReadSingleTabulated(k_path, EntryKind::kK, warnings);
  NkSpectrum spectrum = JoinNK(n_path + " and " + k_path, n_table, k_table, warnings);
  spectrum.source = n_path;
  return spectrum;
}

}  // namespace alloycolor
