#include "alloycolor/core/io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "alloycolor/core/error.h"

namespace alloycolor {
namespace {

constexpr std::string_view kYamlUnsupported =
    "only tabulated nk, or tabulated n plus tabulated k, are supported";
constexpr std::string_view kCsvHeader = "lambda_nm,n,k";

// Throws Error with the message on one line (control characters, which could come from
// a damaged file or path, become '?').
[[noreturn]] void Fail(std::string message) {
  for (char& c : message) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  throw Error(message);
}

std::string ErrnoText(int error) { return std::generic_category().message(error); }

// Text from a file quoted in a message: at most 40 characters.
std::string Quote(std::string_view text) {
  constexpr std::size_t kMax = 40;
  if (text.size() <= kMax) return "'" + std::string(text) + "'";
  return "'" + std::string(text.substr(0, kMax)) + "...'";
}

std::string Number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.10g", value);
  return buffer;
}

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

std::string_view Trim(std::string_view text) {
  while (!text.empty() && IsBlank(text.front())) text.remove_prefix(1);
  while (!text.empty() && IsBlank(text.back())) text.remove_suffix(1);
  return text;
}

std::string Lower(std::string_view text) {
  std::string result(text);
  for (char& c : result) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return result;
}

// Splits text at '\n'.
std::vector<std::string_view> Lines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) {
      lines.push_back(text.substr(start));
      break;
    }
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

// A whole number in the C locale ("1.5", "-2e-3", "+4"); no trailing characters.
bool ParseDouble(std::string_view token, double* value) {
  const bool plus = !token.empty() && token.front() == '+';
  if (plus) token.remove_prefix(1);
  if (token.empty() || (plus && token.front() == '-')) return false;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
  return ec == std::errc() && ptr == end;
}

// Where a row of a table was read. CSV rows and rows of a YAML literal block know their
// file line; rows of other YAML scalars are named by their number after the `data:` line.
struct Locator {
  std::string path;
  int block_line = 0;  // line of the YAML `data:` key, 0 for CSV
  bool exact = true;   // rows carry their own file line

  std::string At(int line) const {
    return line > 0 ? path + ":" + std::to_string(line) + ": " : path + ": ";
  }
  std::string Row(int line, int index) const {
    if (exact) return At(line);
    return At(block_line) + "data row " + std::to_string(index) + ": ";
  }
};

// One row of a table: wavelength in the file's unit, then one or two values.
struct Row {
  int line = 0;   // file line, 0 when not known
  int index = 0;  // 1-based among the table's rows
  double lambda = 0;
  double values[2] = {0, 0};
};

// Column names of a table; the first is the wavelength.
struct Columns {
  std::vector<std::string> names;
  std::string Describe(char separator) const {
    std::string text;
    for (const std::string& name : names) {
      if (!text.empty()) text += separator;
      text += name;
    }
    return text;
  }
};

Row ParseRow(const std::vector<std::string_view>& fields, const Columns& columns, char separator,
             const Locator& where, int line, int index) {
  const std::string at = where.Row(line, index);
  if (fields.size() != columns.names.size()) {
    Fail(at + "expected " + std::to_string(columns.names.size()) + " columns (" +
         columns.Describe(separator) + "), found " + std::to_string(fields.size()));
  }
  double parsed[3] = {0, 0, 0};
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (!ParseDouble(fields[i], &parsed[i])) {
      Fail(at + "cannot parse number " + Quote(fields[i]) + " (" + columns.names[i] + ")");
    }
    if (!std::isfinite(parsed[i])) {
      Fail(at + columns.names[i] + " is " + Quote(fields[i]) + ", not a finite number");
    }
  }
  if (!(parsed[0] > 0)) {
    Fail(at + columns.names[0] + " = " + Number(parsed[0]) + " is not positive");
  }
  for (std::size_t i = 1; i < fields.size(); ++i) {
    if (parsed[i] < 0) {
      Fail(at + columns.names[i] + " = " + Number(parsed[i]) + " is negative");
    }
    if (parsed[i] > kMaxOpticalConstant) {
      Fail(at + columns.names[i] + " = " + Number(parsed[i]) + " is implausibly large (over " +
           Number(kMaxOpticalConstant) + ")");
    }
  }
  Row row;
  row.line = line;
  row.index = index;
  row.lambda = parsed[0];
  row.values[0] = parsed[1];
  row.values[1] = fields.size() > 2 ? parsed[2] : 0.0;
  return row;
}

// A table with strictly increasing wavelengths (file unit).
struct Table {
  std::vector<double> lambda;
  std::vector<double> values[2];
};

// Checks the order of the rows and averages exact repeats of a wavelength (with a
// warning); refuses decreasing wavelengths and tables of fewer than two wavelengths.
Table FinishRows(const std::vector<Row>& rows, const Columns& columns, const Locator& where,
                 std::vector<std::string>* warnings) {
  const std::string& unit = columns.names[0];
  if (rows.empty()) Fail(where.At(where.block_line) + "no data rows");
  Table table;
  std::vector<int> counts;
  std::vector<bool> differ;
  std::vector<const Row*> firsts;
  const Row* previous = nullptr;
  for (const Row& row : rows) {
    if (previous != nullptr && row.lambda == previous->lambda) {
      table.values[0].back() += row.values[0];
      table.values[1].back() += row.values[1];
      ++counts.back();
      if (row.values[0] != firsts.back()->values[0] || row.values[1] != firsts.back()->values[1]) {
        differ.back() = true;
      }
      continue;
    }
    if (previous != nullptr && row.lambda < previous->lambda) {
      Fail(where.Row(row.line, row.index) + unit + " = " + Number(row.lambda) +
           " does not increase (the row before has " + Number(previous->lambda) + ")");
    }
    table.lambda.push_back(row.lambda);
    table.values[0].push_back(row.values[0]);
    table.values[1].push_back(row.values[1]);
    counts.push_back(1);
    differ.push_back(false);
    firsts.push_back(&row);
    previous = &row;
  }
  for (std::size_t i = 0; i < counts.size(); ++i) {
    if (counts[i] == 1) continue;
    table.values[0][i] /= counts[i];
    table.values[1][i] /= counts[i];
    if (warnings != nullptr) {
      warnings->push_back(where.Row(firsts[i]->line, firsts[i]->index) + unit + " = " +
                          Number(table.lambda[i]) + " is given " + std::to_string(counts[i]) +
                          (differ[i] ? " times with different values; their mean is used"
                                     : " times with the same values; kept once"));
    }
  }
  if (table.lambda.size() < 2) {
    Fail(where.At(where.block_line) + "only " + std::to_string(table.lambda.size()) +
         " distinct wavelength; at least two are needed");
  }
  return table;
}

std::vector<std::string_view> SplitWhitespace(std::string_view text) {
  std::vector<std::string_view> fields;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && (IsBlank(text[i]) || text[i] == '\n')) ++i;
    const std::size_t start = i;
    while (i < text.size() && !IsBlank(text[i]) && text[i] != '\n') ++i;
    if (i > start) fields.push_back(text.substr(start, i - start));
  }
  return fields;
}

std::vector<std::string_view> SplitCommas(std::string_view text) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    if (comma == std::string_view::npos) {
      fields.push_back(Trim(text.substr(start)));
      return fields;
    }
    fields.push_back(Trim(text.substr(start, comma - start)));
    start = comma + 1;
  }
}

// Spectrum from a table whose wavelengths are in micrometres (YAML) or nanometres (CSV).
NkSpectrum MakeSpectrum(const std::string& path, const std::vector<double>& lambda,
                        const std::vector<double>& n, const std::vector<double>& k,
                        double nm_per_unit, const std::string& unit) {
  NkSpectrum spectrum;
  spectrum.source = path;
  spectrum.lambda_nm.reserve(lambda.size());
  for (std::size_t i = 0; i < lambda.size(); ++i) {
    const double lambda_nm = lambda[i] * nm_per_unit;
    if (!std::isfinite(lambda_nm)) {
      Fail(path + ": " + unit + " = " + Number(lambda[i]) + " is too large");
    }
    if (i > 0 && !(lambda_nm > spectrum.lambda_nm.back())) {
      Fail(path + ": " + unit + " = " + Number(lambda[i - 1]) + " and " + Number(lambda[i]) +
           " are too close to tell apart in nm");
    }
    spectrum.lambda_nm.push_back(lambda_nm);
  }
  spectrum.n = n;
  spectrum.k = k;
  return spectrum;
}

// ---- refractiveindex.info YAML ----

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
  const std::string ranges = "tabulated n covers " + Number(n_table.lambda.front()) + " to " +
                             Number(n_table.lambda.back()) + " um, tabulated k " + Number(k_lo) +
                             " to " + Number(k_hi) + " um";
  if (lambda.size() < 2) {
    Fail(path + ": " + ranges + "; they share fewer than two wavelengths of the n grid");
  }
  if (lambda.size() < n_table.lambda.size() && warnings != nullptr) {
    warnings->push_back(path + ": " + ranges + "; only the overlap, " + Number(lambda.front()) +
                        " to " + Number(lambda.back()) + " um, is used");
  }
  return MakeSpectrum(path, lambda, n, k, 1000.0, "wavelength_um");
}

NkSpectrum ParseYaml(const std::string& path, const std::string& text,
                     std::vector<std::string>* warnings) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    Fail((MarkLine(e.mark) > 0 ? path + ":" + std::to_string(MarkLine(e.mark)) : path) +
         ": invalid YAML: " + e.msg);
  }
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
      Fail(at + " is " + Quote(name) + "; " + std::string(kYamlUnsupported));
    }
  }
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
  std::string held;
  for (const Entry& entry : entries) {
    if (!held.empty()) held += ", ";
    held += entry.kind == EntryKind::kNk  ? "'tabulated nk'"
            : entry.kind == EntryKind::kN ? "'tabulated n'"
                                          : "'tabulated k'";
  }
  Fail(list_at + "DATA holds " + held + "; " + std::string(kYamlUnsupported));
}

// Any exception from yaml-cpp or the standard library becomes an Error naming the file.
NkSpectrum ParseYamlGuarded(const std::string& path, const std::string& text,
                            std::vector<std::string>* warnings) {
  try {
    return ParseYaml(path, text, warnings);
  } catch (const Error&) {
    throw;
  } catch (const YAML::Exception& e) {
    Fail((MarkLine(e.mark) > 0 ? path + ":" + std::to_string(MarkLine(e.mark)) : path) +
         ": invalid YAML: " + e.msg);
  } catch (const std::exception& e) {
    Fail(path + ": cannot read: " + e.what());
  }
}

// ---- CSV ----

NkSpectrum ParseCsv(const std::string& path, std::string_view text,
                    std::vector<std::string>* warnings) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte order mark
  const Columns columns{{"lambda_nm", "n", "k"}};
  Locator where;
  where.path = path;
  std::vector<Row> rows;
  bool header_seen = false;
  int line_number = 0;
  int index = 0;
  for (std::string_view line : Lines(text)) {
    ++line_number;
    const std::string_view trimmed = Trim(line);
    if (trimmed.empty() || trimmed.front() == '#') continue;
    if (!header_seen) {
      std::string header;
      for (char c : Lower(trimmed)) {
        if (!IsBlank(c)) header += c;
      }
      if (header != kCsvHeader) {
        Fail(where.At(line_number) + "expected the header '" + std::string(kCsvHeader) +
             "', found " + Quote(trimmed));
      }
      header_seen = true;
      where.block_line = line_number;
      continue;
    }
    rows.push_back(ParseRow(SplitCommas(trimmed), columns, ',', where, line_number, ++index));
  }
  if (!header_seen) Fail(path + ": no data");
  const Table table = FinishRows(rows, columns, where, warnings);
  return MakeSpectrum(path, table.lambda, table.values[0], table.values[1], 1.0, "lambda_nm");
}

// True when text looks like a refractiveindex.info YAML file: a line starting "DATA:".
bool LooksLikeRefractiveIndexYaml(std::string_view text) {
  for (std::string_view line : Lines(text)) {
    if (line.substr(0, 5) == "DATA:") return true;
  }
  return false;
}

std::string Extension(const std::string& path) {
  return Lower(std::filesystem::path(path).extension().string());
}

}  // namespace

NkSpectrum ReadNkFile(const std::string& path, std::vector<std::string>* warnings) {
  const std::string extension = Extension(path);
  if (extension == ".yml" || extension == ".yaml") {
    return ReadRefractiveIndexYaml(path, warnings);
  }
  if (extension == ".csv") return ReadNkCsv(path, warnings);
  const std::string text = ReadFileText(path);
  if (LooksLikeRefractiveIndexYaml(text)) return ParseYamlGuarded(path, text, warnings);
  Fail(path + ": cannot tell the format from the extension " +
       (extension.empty() ? std::string("(none)") : Quote(extension)) +
       "; expected .yml, .yaml or .csv");
}

NkSpectrum ReadRefractiveIndexYaml(const std::string& path, std::vector<std::string>* warnings) {
  return ParseYamlGuarded(path, ReadFileText(path), warnings);
}

NkSpectrum ReadNkCsv(const std::string& path, std::vector<std::string>* warnings) {
  const std::string text = ReadFileText(path);
  return ParseCsv(path, text, warnings);
}

std::string NkCsvText(const std::vector<double>& lambda_nm, const std::vector<double>& n,
                      const std::vector<double>& k) {
  if (n.size() != lambda_nm.size() || k.size() != lambda_nm.size()) {
    throw Error("NkCsvText: lambda_nm, n and k differ in length (" +
                std::to_string(lambda_nm.size()) + ", " + std::to_string(n.size()) + ", " +
                std::to_string(k.size()) + ")");
  }
  std::string text = std::string(kCsvHeader) + "\n";
  char buffer[96];
  for (std::size_t i = 0; i < lambda_nm.size(); ++i) {
    std::snprintf(buffer, sizeof(buffer), "%.17g,%.17g,%.17g\n", lambda_nm[i], n[i], k[i]);
    text += buffer;
  }
  return text;
}

std::string ReadFileText(const std::string& path) {
  const std::string cannot = "cannot read '" + path + "': ";
  // O_NONBLOCK so that a FIFO cannot hang the open; only regular files are read.
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) Fail(cannot + ErrnoText(errno));
  struct stat info;
  if (fstat(fd, &info) != 0) {
    const int error = errno;
    close(fd);
    Fail(cannot + ErrnoText(error));
  }
  if (!S_ISREG(info.st_mode)) {
    close(fd);
    Fail(cannot + (S_ISDIR(info.st_mode) ? ErrnoText(EISDIR) : "not a regular file"));
  }
  std::string text;
  char buffer[65536];
  while (true) {
    const ssize_t got = read(fd, buffer, sizeof(buffer));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      const int error = errno;
      close(fd);
      Fail(cannot + ErrnoText(error));
    }
    if (got == 0) break;
    text.append(buffer, static_cast<std::size_t>(got));
  }
  close(fd);
  return text;
}

void WriteFileAtomic(const std::string& path, const std::string& contents) {
  const std::string temp = path + ".tmp." + std::to_string(getpid());
  const std::string cannot = "cannot write '" + path + "': ";
  const int fd = open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0666);
  if (fd < 0) Fail(cannot + ErrnoText(errno));
  const auto fail = [&](int error, bool is_open) {
    if (is_open) close(fd);
    unlink(temp.c_str());
    Fail(cannot + ErrnoText(error));
  };
  // A replaced file keeps its permissions.
  struct stat old_info;
  if (stat(path.c_str(), &old_info) == 0 && S_ISREG(old_info.st_mode)) {
    fchmod(fd, old_info.st_mode & 07777);
  }
  std::size_t written = 0;
  while (written < contents.size()) {
    const ssize_t put = write(fd, contents.data() + written, contents.size() - written);
    if (put < 0 && errno == EINTR) continue;
    if (put < 0) fail(errno, true);
    written += static_cast<std::size_t>(put);
  }
  if (fsync(fd) != 0) fail(errno, true);
  if (close(fd) != 0) fail(errno, false);
  if (rename(temp.c_str(), path.c_str()) != 0) fail(errno, false);
  // Make the rename itself durable; a failure here leaves a complete file, so it is ignored.
  const std::string folder = std::filesystem::path(path).parent_path().string();
  const int dir_fd =
      open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    fsync(dir_fd);
    close(dir_fd);
  }
}

std::string Fnv1a64Hex(const std::string& bytes) {
  std::uint64_t hash = 14695981039346656037ULL;
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 1099511628211ULL;
  }
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string hex(16, '0');
  for (int i = 15; i >= 0; --i) {
    hex[static_cast<std::size_t>(i)] = kDigits[hash & 0xf];
    hash >>= 4;
  }
  return hex;
}

}  // namespace alloycolor
