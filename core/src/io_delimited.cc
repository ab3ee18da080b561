
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <initializer_list>
#include <regex>
#include <string>
#include <string_view>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/permittivity.h"
#include "alloycolor/core/text.h"
#include "alloycolor/core/units.h"
#include "io_delimited_columns.h"
#include "io_internal.h"

// Delimited text (CSV, TXT, DAT, TSV): the layout and delimiter, the header's names and units,
// the choice of columns, and eps1, eps2 turned into n, k.
namespace alloycolor {
namespace {

using namespace delimited;  // NOLINT: this file's own vocabulary (io_delimited_columns.h)
using io_internal::CheckOpticalConstant;
using io_internal::Columns;
using io_internal::FinishRows;
using io_internal::IsNonFiniteWord;
using io_internal::Locator;
using io_internal::MakeSpectrum;
using io_internal::ParseDelimitedGuarded;
using io_internal::ParseField;
using io_internal::Row;
using io_internal::SplitWhitespace;
using io_internal::Table;

// A delimited file's lines, its first row of numbers, the header above it and the
// delimiter: the layout every delimited table shares (n,k files, reflectance spectra).
struct DelimitedText {
  std::vector<std::string_view> lines;
  std::size_t first_row = 0;
  int header_line = 0;
  char delimiter = ',';
  std::vector<std::string> names;
};

bool IsComment(std::string_view t) { return !t.empty() && t.front() == '#'; }

// Refuses wavelengths that are plainly in the other unit than their header says: under
// nm, all below 20 (visible light in um reads 0.38-0.78); under um, all above 100 (in nm,
// 380-780). The message names the file, the header line and the fix.
void CheckWavelengthUnit(const std::string& path, int header_line, Unit unit,
                         const std::string& unit_name, const std::vector<double>& lambda) {
  if (lambda.empty() || (unit != Unit::kNm && unit != Unit::kUm)) return;
  const auto [lo, hi] = std::minmax_element(lambda.begin(), lambda.end());
  const bool nm = unit == Unit::kNm;
  if (nm ? *hi >= 20 : *lo <= 100) return;
  Fail(path + ":" + std::to_string(header_line) + ": the wavelengths run " + FormatNumber(*lo) +
       "-" + FormatNumber(*hi) + " under the header " + Quote(unit_name) + ", which says " +
       (nm ? "nm" : "um") + ": they look like " + (nm ? "micrometres" : "nanometres") +
       "; name the column " + (nm ? "'wavelength_um'" : "'wavelength_nm'") + " (or " +
       (nm ? "multiply them by 1000" : "divide them by 1000") + ")");
}

DelimitedText ScanDelimited(const std::string& path, std::string_view text) {
  if (text.substr(0, 2) == "\xFF\xFE" || text.substr(0, 2) == "\xFE\xFF") {
    Fail(path +
         ":1: the file is UTF-16 text; save it as UTF-8 (or ASCII) so that its header "
         "and rows can be read");
  }
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte order mark
  DelimitedText scan;
  scan.lines = Lines(text);
  const std::vector<std::string_view>& lines = scan.lines;
  const auto is_comment = IsComment;

  // The first row of numbers, and the header above it.
  std::size_t first_row = lines.size();
  int first_text = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string_view t = Trim(lines[i]);
    if (t.empty() || is_comment(t)) continue;
    if (first_text == 0) first_text = static_cast<int>(i) + 1;
    if (IsNumberRow(t)) {
      first_row = i;
      break;
    }
  }
  if (first_text == 0) Fail(path + ": no data");
  if (first_row == lines.size()) {
    Fail(path + ":" + std::to_string(first_text) + ": no data rows (no line of numbers under a " +
         "header; the first line is " + Quote(Trim(lines[first_text - 1])) + ")");
  }
  const int row_line = static_cast<int>(first_row) + 1;
  const char delimiter = DelimiterOf(Trim(lines[first_row]));
  const std::size_t width = SplitFields(Trim(lines[first_row]), delimiter).size();
  int header_line = 0;
  std::vector<std::string> names;
  for (std::size_t i = first_row; i-- > 0;) {
    std::string_view t = Trim(lines[i]);
    if (t.empty()) continue;
    const bool comment = is_comment(t);
    while (!t.empty() && t.front() == '#') t.remove_prefix(1);
    std::vector<std::string> candidate = SplitHeader(Trim(t), delimiter);
    const bool names_abscissa =
        std::any_of(candidate.begin(), candidate.end(),
                    [](const std::string& name) { return ClassifyAbscissa(name).is_abscissa; });
    if (!comment || names_abscissa) {
      header_line = static_cast<int>(i) + 1;
      names = std::move(candidate);
      break;
    }
  }
  if (header_line == 0) {
    Fail(path + ":" + std::to_string(row_line) +
         ": no header line above the first row of numbers; add one naming the columns, "
         "e.g. 'wavelength_nm,n,k' or 'energy_eV,e1,e2' (" +
         std::string(kHeaderAdvice) + ")");
  }
  if (names.size() != width) {
    Fail(path + ":" + std::to_string(row_line) + ": expected " + std::to_string(names.size()) +
         " columns (" + JoinNames(names, delimiter) + ", " + DelimiterName(delimiter) +
         "-separated, as the header on line " + std::to_string(header_line) + "), found " +
         std::to_string(width));
  }
  scan.first_row = first_row;
  scan.header_line = header_line;
  scan.delimiter = delimiter;
  scan.names = std::move(names);
  return scan;
}

NkSpectrum ParseDelimited(const std::string& path, std::string_view text, const NkColumns& columns,
                          std::vector<std::string>* warnings) {
  const DelimitedText scan = ScanDelimited(path, text);
  const std::vector<std::string_view>& lines = scan.lines;
  const auto is_comment = IsComment;
  const std::size_t first_row = scan.first_row;
  const int header_line = scan.header_line;
  const char delimiter = scan.delimiter;
  const std::vector<std::string>& names = scan.names;
  const Layout layout = ChooseColumns(path, names, header_line, delimiter, columns);

  const std::string unit_name = names[layout.abscissa];
  const std::string n_name = names[layout.value[0]];
  const std::string k_name = names[layout.value[1]];
  const Columns described{{unit_name, n_name, k_name}};
  Locator where;
  where.path = path;
  where.block_line = header_line;
  std::vector<Row> rows;
  int index = 0;
  for (std::size_t i = first_row; i < lines.size(); ++i) {
    const std::string_view t = Trim(lines[i]);
    if (t.empty() || is_comment(t)) continue;
    const int line = static_cast<int>(i) + 1;
    const std::string at = where.At(line);
    const std::vector<std::string_view> fields = SplitFields(t, delimiter);
    if (fields.size() != names.size()) {
      Fail(at + "expected " + std::to_string(names.size()) + " columns (" +
           JoinNames(names, delimiter == ' ' ? ' ' : delimiter) + "), found " +
           std::to_string(fields.size()));
    }
    Row row;
    row.line = line;
    row.index = ++index;
    const auto field = [&](std::size_t column) { return DecimalPoint(fields[column], delimiter); };
    row.lambda = ParseField(field(layout.abscissa), unit_name, at);
    if (!(row.lambda > 0)) {
      Fail(at + unit_name + " = " + FormatNumber(row.lambda) + " is not positive");
    }
    const double a = ParseField(field(layout.value[0]), n_name, at);
    const double b = ParseField(field(layout.value[1]), k_name, at);
    if (layout.eps) {
      if (b < 0) {
        Fail(at + k_name + " = " + FormatNumber(b) +
             " is negative (an absorbing medium has eps2 >= 0)");
      }
      if (!(std::abs(a) <= kMaxOpticalConstant * kMaxOpticalConstant &&
            b <= kMaxOpticalConstant * kMaxOpticalConstant)) {
        Fail(at + "eps = " + FormatNumber(a) + " + " + FormatNumber(b) + "i is implausibly large");
      }
      const Complex<double> nk = IndexFromPermittivity(Complex<double>{a, b});
      row.values[0] = nk.re;
      row.values[1] = nk.im;
    } else {
      row.values[0] = a;
      row.values[1] = b;
    }
    CheckOpticalConstant(row.values[0], layout.eps ? "n (from eps)" : n_name, at);
    CheckOpticalConstant(row.values[1], layout.eps ? "k (from eps)" : k_name, at);
    rows.push_back(row);
  }
  const Table table = FinishRows(rows, described, where, warnings, /*either_direction=*/true);
  CheckWavelengthUnit(path, header_line, layout.unit, unit_name, table.lambda);

  // To nm; energy and wavenumber run against wavelength.
  const bool reversed = layout.unit == Unit::kEv || layout.unit == Unit::kWavenumber;
  const std::size_t count = table.lambda.size();
  std::vector<double> lambda_nm(count), n(count), k(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t from = reversed ? count - 1 - i : i;
    lambda_nm[i] = NmFrom(layout.unit, table.lambda[from]);
    n[i] = table.values[0][from];
    k[i] = table.values[1][from];
  }
  return MakeSpectrum(path, lambda_nm, n, k, 1.0, "wavelength_nm");
}

// A reflectance spectrum: the abscissa and one column of R, as a fraction or, where its
// header says so ('R (%)', 'reflectance_percent'), in percent.
MeasuredReflectance ParseReflectance(const std::string& path, std::string_view text,
                                     std::vector<std::string>* warnings) {
  const DelimitedText scan = ScanDelimited(path, text);
  const std::string at = path + ":" + std::to_string(scan.header_line) + ": ";
  const std::string header = Quote(JoinNames(scan.names, scan.delimiter == ' ' ? ' ' : ','), 120);
  std::size_t abscissa = scan.names.size();
  Unit unit = Unit::kNm;
  for (std::size_t i = 0; i < scan.names.size() && abscissa == scan.names.size(); ++i) {
    const AbscissaName name = ClassifyAbscissa(scan.names[i]);
    if (!name.is_abscissa) continue;
    if (!name.has_unit) {
      Fail(at + "header column " + Quote(scan.names[i]) + " " + name.problem + "; " +
           std::string(kHeaderAdvice));
    }
    abscissa = i;
    unit = name.unit;
  }
  if (abscissa == scan.names.size()) {
    Fail(at + "the header " + header + " names no wavelength, energy or wavenumber column; " +
         std::string(kHeaderAdvice));
  }
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < scan.names.size(); ++i) {
    if (i == abscissa) continue;
    const std::vector<std::string> tokens = NameTokens(scan.names[i]);
    if (std::any_of(tokens.begin(), tokens.end(), [](const std::string& t) {
          return OneOf(t, {"r", "refl", "reflectance", "reflectivity"});
        })) {
      candidates.push_back(i);
    }
  }
  if (candidates.empty() && scan.names.size() == 2) candidates.push_back(1 - abscissa);
  if (candidates.size() != 1) {
    Fail(at + "the header " + header + (candidates.empty() ? " names no" : " names several") +
         " reflectance column; name one column 'R' or 'reflectance' (add '(%)' for percent)");
  }
  const std::string& r_name = scan.names[candidates.front()];
  const std::vector<std::string> r_tokens = NameTokens(r_name);
  const bool percent = r_name.find('%') != std::string::npos ||
                       std::any_of(r_tokens.begin(), r_tokens.end(), [](const std::string& t) {
                         return OneOf(t, {"percent", "pct"});
                       });
  const std::string& unit_name = scan.names[abscissa];
  const Columns described{{unit_name, r_name}};
  Locator where;
  where.path = path;
  where.block_line = scan.header_line;
  std::vector<Row> rows;
  int index = 0;
  for (std::size_t i = scan.first_row; i < scan.lines.size(); ++i) {
    const std::string_view t = Trim(scan.lines[i]);
    if (t.empty() || IsComment(t)) continue;
    const int line = static_cast<int>(i) + 1;
    const std::string row_at = where.At(line);
    const std::vector<std::string_view> fields = SplitFields(t, scan.delimiter);
    if (fields.size() != scan.names.size()) {
      Fail(row_at + "expected " + std::to_string(scan.names.size()) + " columns (" +
           JoinNames(scan.names, scan.delimiter == ' ' ? ' ' : scan.delimiter) + "), found " +
           std::to_string(fields.size()));
    }
    Row row;
    row.line = line;
    row.index = ++index;
    row.lambda = ParseField(DecimalPoint(fields[abscissa], scan.delimiter), unit_name, row_at);
    if (!(row.lambda > 0)) {
      Fail(row_at + unit_name + " = " + FormatNumber(row.lambda) + " is not positive");
    }
    const double r =
        ParseField(DecimalPoint(fields[candidates.front()], scan.delimiter), r_name, row_at);
    row.values[0] = percent ? r / 100.0 : r;
    if (row.values[0] < 0 || row.values[0] > 1) {
      Fail(row_at + r_name + " = " + FormatNumber(r) + " lies outside " +
           (percent ? "0-100 %" : "0-1 (for percent, name the column 'R (%)')"));
    }
    rows.push_back(row);
  }
  const Table table = FinishRows(rows, described, where, warnings, /*either_direction=*/true);
  CheckWavelengthUnit(path, scan.header_line, unit, unit_name, table.lambda);
  const bool reversed = unit == Unit::kEv || unit == Unit::kWavenumber;
  const std::size_t count = table.lambda.size();
  MeasuredReflectance spectrum;
  spectrum.source = path;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t from = reversed ? count - 1 - i : i;
    const double lambda_nm = NmFrom(unit, table.lambda[from]);
    if (!std::isfinite(lambda_nm) ||
        (!spectrum.lambda_nm.empty() && !(lambda_nm > spectrum.lambda_nm.back()))) {
      Fail(path + ": " + unit_name + " = " + FormatNumber(table.lambda[from]) +
           " cannot be told apart from its neighbour in nm");
    }
    spectrum.lambda_nm.push_back(lambda_nm);
    spectrum.reflectance.push_back(table.values[0][from]);
  }
  return spectrum;
}

}  // namespace

// Any exception from the standard library becomes an Error naming the file.
NkSpectrum io_internal::ParseDelimitedGuarded(const std::string& path, std::string_view text,
                                              const NkColumns& columns,
                                              std::vector<std::string>* warnings) {
  try {
    return ParseDelimited(path, text, columns, warnings);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    Fail(path + ": cannot read: " + e.what());
  }
}

NkColumns ParseNkColumns(const std::string& text) {
  const std::size_t comma = text.find(',');
  NkColumns columns;
  if (comma != std::string::npos && text.find(',', comma + 1) == std::string::npos) {
    columns.n = std::string(Trim(std::string_view(text).substr(0, comma)));
    columns.k = std::string(Trim(std::string_view(text).substr(comma + 1)));
  }
  if (columns.n.empty() || columns.k.empty()) {
    Fail("columns " + Quote(text) +
         ": expected N,K, the n and k (or eps1 and eps2) columns by header name or 1-based "
         "number, e.g. 'n6,k6' or '2,3'");
  }
  return columns;
}

NkSpectrum ReadNkDelimited(const std::string& path, const NkColumns& columns,
                           std::vector<std::string>* warnings) {
  return ParseDelimitedGuarded(path, ReadFileText(path), columns, warnings);
}

MeasuredReflectance ReadReflectanceDelimited(const std::string& path,
                                             std::vector<std::string>* warnings) {
  const std::string text = ReadFileText(path);
  try {
    return ParseReflectance(path, text, warnings);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    Fail(path + ": cannot read: " + e.what());
  }
}

NkSpectrum ReadNkCsv(const std::string& path, std::vector<std::string>* warnings) {
  return ReadNkDelimited(path, NkColumns{}, warnings);
}

}  // namespace alloycolor
