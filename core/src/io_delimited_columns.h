// Private to the delimited-text readers (io_delimited.cc): what a header says. Its
// column names read as quantities and units (wavelength in nm, um or Angstrom, photon
// energy in eV, wavenumber in cm^-1) or as values (n, k, eps1, eps2 with a sample tag),
// the fields of a line and its delimiter, and the choice of the n,k columns
// (io_delimited_columns.cc).
#ifndef ALLOYCOLOR_CORE_SRC_IO_DELIMITED_COLUMNS_H_
#define ALLOYCOLOR_CORE_SRC_IO_DELIMITED_COLUMNS_H_

#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "alloycolor/core/io.h"

namespace alloycolor::delimited {

// The abscissa of a delimited file and how to turn it into nm.
enum class Unit { kNm, kUm, kAngstrom, kEv, kWavenumber };

// The value in nm of `value` in `unit`.
double NmFrom(Unit unit, double value);

// A column name in lower case, with the non-ASCII spellings of units and symbols made
// ASCII and every other byte that is not a letter or digit made a separator, as tokens.
std::vector<std::string> NameTokens(std::string_view name);

bool OneOf(const std::string& token, std::initializer_list<std::string_view> words);

// What a header column says about the abscissa.
struct AbscissaName {
  bool is_abscissa = false;  // a quantity or a unit is named
  bool has_unit = false;
  Unit unit = Unit::kNm;
  std::string problem;  // why it cannot be used, when is_abscissa && !has_unit
};

AbscissaName ClassifyAbscissa(std::string_view name);

// The fields of a line: split at delimiter (' ' meaning runs of blanks), each trimmed;
// trailing empty fields (a trailing delimiter) dropped.
std::vector<std::string_view> SplitFields(std::string_view line, char delimiter);
// Header fields; with whitespace between fields, a unit in brackets ("Wavelength (nm)")
// stays with the name before it.
std::vector<std::string> SplitHeader(std::string_view line, char delimiter);
char DelimiterOf(std::string_view line);
std::string DelimiterName(char delimiter);
// A field with a decimal comma ("0,5", "-1,25e-3") written with '.'; other fields as they
// are. Only applied where the delimiter is not a comma, so the comma cannot be one.
std::string DecimalPoint(std::string_view field, char delimiter);
// True when the line is at least two numbers and nothing else.
bool IsNumberRow(std::string_view line);
std::string JoinNames(const std::vector<std::string>& names, char delimiter);

inline constexpr std::string_view kHeaderAdvice =
    "the first column must name the abscissa and its unit (e.g. 'wavelength_nm', "
    "'Wavelength (nm)', 'wl_um', 'lambda (A)', 'Energy (eV)', 'wavenumber (cm-1)')";

// The header and the columns to read.
struct Layout {
  int header_line = 0;
  char delimiter = ',';
  std::vector<std::string> names;
  std::size_t abscissa = 0;
  Unit unit = Unit::kNm;
  std::size_t value[2] = {0, 0};
  bool eps = false;
};

// The abscissa and the n,k (or eps1, eps2) columns of a header: found from the names, or
// chosen by `columns`; throws Error naming the file and header line.
Layout ChooseColumns(const std::string& path, const std::vector<std::string>& names,
                     int header_line, char delimiter, const NkColumns& columns);

}  // namespace alloycolor::delimited

#endif  // ALLOYCOLOR_CORE_SRC_IO_DELIMITED_COLUMNS_H_
