// Private to the n,k readers (io.cc, io_yaml.cc, io_delimited.cc): the table of rows every
// format reads into, its checks, and each format's entry point for ReadNkFile's dispatch.
#ifndef ALLOYCOLOR_CORE_SRC_IO_INTERNAL_H_
#define ALLOYCOLOR_CORE_SRC_IO_INTERNAL_H_

#include <string>
#include <string_view>
#include <vector>

#include "alloycolor/core/io.h"

namespace alloycolor {
namespace io_internal {

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

// A field as a finite number; the message tells a non-number from a non-finite one.
double ParseField(std::string_view field, const std::string& name, const std::string& at);

// "nan", "inf", "infinity" with an optional sign: numbers, but not finite ones.
bool IsNonFiniteWord(std::string_view field);

// n and k within [0, kMaxOpticalConstant].
void CheckOpticalConstant(double value, const std::string& name, const std::string& at);

// A table with strictly increasing wavelengths (file unit).
struct Table {
  std::vector<double> lambda;
  std::vector<double> values[2];
};

// Checks the order of the rows and averages exact repeats of a wavelength (with a
// warning); refuses tables of fewer than two wavelengths and rows out of order: rows must
// ascend, or, with either_direction, may all descend instead (then the table is reversed).
Table FinishRows(const std::vector<Row>& rows, const Columns& columns, const Locator& where,
                 std::vector<std::string>* warnings, bool either_direction = false);

// The whitespace-separated fields of text (newlines separate too).
std::vector<std::string_view> SplitWhitespace(std::string_view text);

// Spectrum from a table whose wavelengths are in micrometres (YAML) or nanometres (CSV).
NkSpectrum MakeSpectrum(const std::string& path, const std::vector<double>& lambda,
                        const std::vector<double>& n, const std::vector<double>& k,
                        double nm_per_unit, const std::string& unit);

// A refractiveindex.info YAML file's text as n,k (io_yaml.cc); any failure is an Error
// naming the file.
NkSpectrum ParseYamlGuarded(const std::string& path, const std::string& text,
                            std::vector<std::string>* warnings);

// Any exception from the standard library becomes an Error naming the file.
NkSpectrum ParseDelimitedGuarded(const std::string& path, std::string_view text,
                                 const NkColumns& columns, std::vector<std::string>* warnings);

}  // namespace io_internal
}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_SRC_IO_INTERNAL_H_
