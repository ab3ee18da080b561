#include "alloycolor/core/io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"
#include "io_internal.h"

// What the n,k readers share: the table of rows and its checks, reading a file, the choice
// of reader by extension and content, and the CSV the program writes.
namespace alloycolor {
namespace {

using io_internal::ParseDelimitedGuarded;
using io_internal::ParseYamlGuarded;

constexpr std::string_view kCsvHeader = "lambda_nm,n,k";

std::string ErrnoText(int error) { return std::generic_category().message(error); }

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

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

namespace io_internal {

// "nan", "inf", "infinity" with an optional sign: numbers, but not finite ones.
bool IsNonFiniteWord(std::string_view field) {
  if (!field.empty() && (field.front() == '+' || field.front() == '-')) field.remove_prefix(1);
  const std::string lower = Lower(field);
  return lower == "nan" || lower == "inf" || lower == "infinity";
}

// A field as a finite number; the message tells a non-number from a non-finite one.
double ParseField(std::string_view field, const std::string& name, const std::string& at) {
  double value = 0;
  if (ParseFiniteDouble(field, &value)) {
    if (value != 0 && std::abs(value) < kSmallestMeasuredValue) {
      Fail(at + name + " = " + Quote(field) + " is not a measured value: nonzero but below " +
           FormatNumber(kSmallestMeasuredValue) +
           (std::abs(value) < 2.2250738585072014e-308 ? " (a denormal number)" : "") +
           "; write 0 if it is zero");
    }
    return value;
  }
  if (IsNonFiniteWord(field)) Fail(at + name + " is " + Quote(field) + ", not a finite number");
  Fail(at + "cannot parse number " + Quote(field) + " (" + name + ")");
}

// n and k within [0, kMaxOpticalConstant].
void CheckOpticalConstant(double value, const std::string& name, const std::string& at) {
  if (value < 0) Fail(at + name + " = " + FormatNumber(value) + " is negative");
  if (value > kMaxOpticalConstant) {
    Fail(at + name + " = " + FormatNumber(value) + " is implausibly large (over " +
         FormatNumber(kMaxOpticalConstant) + ")");
  }
}

// Checks the order of the rows and averages exact repeats of a wavelength (with a
// warning); refuses tables of fewer than two wavelengths and rows out of order: rows must
// ascend, or, with either_direction, may all descend instead (then the table is reversed).
Table FinishRows(const std::vector<Row>& rows, const Columns& columns, const Locator& where,
                 std::vector<std::string>* warnings, bool either_direction) {
  const std::string& unit = columns.names[0];
  if (rows.empty()) Fail(where.At(where.block_line) + "no data rows");
  Table table;
  std::vector<int> counts;
  std::vector<bool> differ;
  std::vector<const Row*> firsts;
  const Row* previous = nullptr;
  bool descending = false;
  if (either_direction) {
    for (const Row& row : rows) {
      if (row.lambda == rows.front().lambda) continue;
      descending = row.lambda < rows.front().lambda;
      break;
    }
  }
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
    if (previous != nullptr &&
        (descending ? row.lambda > previous->lambda : row.lambda < previous->lambda)) {
      Fail(where.Row(row.line, row.index) + unit + " = " + FormatNumber(row.lambda) +
           (descending ? " does not decrease like the rows before (the row before has "
                       : " does not increase (the row before has ") +
           FormatNumber(previous->lambda) + ")");
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
                          FormatNumber(table.lambda[i]) + " is given " + std::to_string(counts[i]) +
                          (differ[i] ? " times with different values; their mean is used"
                                     : " times with the same values; kept once"));
    }
  }
  if (descending) {
    std::reverse(table.lambda.begin(), table.lambda.end());
    std::reverse(table.values[0].begin(), table.values[0].end());
    std::reverse(table.values[1].begin(), table.values[1].end());
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
      Fail(path + ": " + unit + " = " + FormatNumber(lambda[i]) + " is too large");
    }
    if (i > 0 && !(lambda_nm > spectrum.lambda_nm.back())) {
      Fail(path + ": " + unit + " = " + FormatNumber(lambda[i - 1]) + " and " +
           FormatNumber(lambda[i]) + " are too close to tell apart in nm");
    }
    spectrum.lambda_nm.push_back(lambda_nm);
  }
  spectrum.n = n;
  spectrum.k = k;
  return spectrum;
}

}  // namespace io_internal

NkSpectrum ReadNkFile(const std::string& path, std::vector<std::string>* warnings) {
  return ReadNkFile(path, NkColumns{}, warnings);
}

NkSpectrum ReadNkFile(const std::string& path, const NkColumns& columns,
                      std::vector<std::string>* warnings) {
  const std::string extension = Extension(path);
  const bool yaml_extension = extension == ".yml" || extension == ".yaml";
  const bool text_extension =
      extension == ".csv" || extension == ".txt" || extension == ".dat" || extension == ".tsv";
  const std::string text = ReadFileText(path);
  const bool yaml = yaml_extension || (extension != ".csv" && LooksLikeRefractiveIndexYaml(text));
  if (yaml) {
    if (!columns.empty()) {
      Fail(path + ": a column choice (" + columns.n + "," + columns.k +
           ") applies to delimited text files, not to refractiveindex.info YAML");
    }
    return ParseYamlGuarded(path, text, warnings);
  }
  if (text_extension) return ParseDelimitedGuarded(path, text, columns, warnings);
  Fail(path + ": cannot tell the format from the extension " +
       (extension.empty() ? std::string("(none)") : Quote(extension)) +
       "; expected .yml or .yaml (refractiveindex.info), or .csv, .txt, .dat or .tsv "
       "(delimited text)");
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
  if (info.st_size > kMaxInputFileBytes) {
    close(fd);
    Fail(cannot + "the file is " + std::to_string(info.st_size / (1 << 20)) + " MiB, over the " +
         std::to_string(kMaxInputFileBytes >> 20) + " MiB an input may have");
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
    if (text.size() + static_cast<std::size_t>(got) >
        static_cast<std::size_t>(kMaxInputFileBytes)) {
      close(fd);
      Fail(cannot + "the file grew past the " + std::to_string(kMaxInputFileBytes >> 20) +
           " MiB an input may have");
    }
    text.append(buffer, static_cast<std::size_t>(got));
  }
  close(fd);
  CheckTextEncoding(path, text);
  return text;
}

void CheckTextEncoding(const std::string& path, std::string_view text) {
  const auto starts = [&](std::string_view prefix) {
    return text.substr(0, prefix.size()) == prefix;
  };
  const auto nul = [&](std::size_t i) { return i < text.size() && text[i] == '\0'; };
  const auto text_byte = [&](std::size_t i) { return i < text.size() && text[i] != '\0'; };
  std::string encoding;
  if (starts(std::string_view("\xFF\xFE\0\0", 4)) || starts(std::string_view("\0\0\xFE\xFF", 4))) {
    encoding = "UTF-32 text (it begins with a UTF-32 byte order mark)";
  } else if (starts("\xFF\xFE") || starts("\xFE\xFF")) {
    encoding = std::string("UTF-16 text (") + (starts("\xFF\xFE") ? "little" : "big") +
               "-endian: it begins with a UTF-16 byte order mark)";
  } else if (text_byte(0) && nul(1) && text_byte(2) && nul(3)) {
    // Without a mark: ASCII in UTF-16 has a NUL in every other byte.
    encoding = "UTF-16 text (little-endian, without a byte order mark)";
  } else if (nul(0) && text_byte(1) && nul(2) && text_byte(3)) {
    encoding = "UTF-16 text (big-endian, without a byte order mark)";
  }
  if (!encoding.empty()) {
    Fail(path + ":1: the file is " + encoding +
         "; save it as UTF-8 (or ASCII) text so that its header and values can be read");
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
