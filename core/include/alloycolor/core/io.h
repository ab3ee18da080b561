// Readers of optical constants:
//  - refractiveindex.info database YAML: DATA entries `tabulated nk` (rows
//    `wavelength_um n k`), or `tabulated n` plus `tabulated k` in one file (rows
//    `wavelength_um value`, joined on the n grid with k interpolated). Other entry types
//    (`formula N`, `tabulated n2`) are refused with a message naming them.
//  - CSV with a header line `lambda_nm,n,k` (lines starting with '#' are comments).
// Every error names the file, and the line where there is one. n and k must lie in
// [0, kMaxOpticalConstant]. A wavelength repeated
// with different values is averaged with a warning (real files do this).
#ifndef ALLOYCOLOR_CORE_IO_H_
#define ALLOYCOLOR_CORE_IO_H_

#include <string>
#include <vector>

#include "alloycolor/core/spectrum.h"

namespace alloycolor {

// The largest n or k a reader accepts. Metals reach k ~ 1e3 in the far infrared; above
// 1e77, |eps|^2 overflows a double and reflectance becomes NaN.
inline constexpr double kMaxOpticalConstant = 1e6;

// Chooses the reader from the extension (.yml/.yaml or .csv; another extension is read
// as YAML when a line starts with "DATA:"). warnings, if given, receive one line per
// oddity that was repaired, each beginning "file:line: " (or "file: ").
NkSpectrum ReadNkFile(const std::string& path, std::vector<std::string>* warnings = nullptr);
NkSpectrum ReadRefractiveIndexYaml(const std::string& path,
                                   std::vector<std::string>* warnings = nullptr);
NkSpectrum ReadNkCsv(const std::string& path, std::vector<std::string>* warnings = nullptr);

// Writes lambda_nm,n,k rows with full precision (17 significant digits).
std::string NkCsvText(const std::vector<double>& lambda_nm, const std::vector<double>& n,
                      const std::vector<double>& k);

// Whole file as a string; throws Error naming the file when it cannot be read.
std::string ReadFileText(const std::string& path);

// Writes through a temporary file in the same folder renamed into place, so that a
// failed or interrupted write never leaves a damaged file nor destroys the old one.
void WriteFileAtomic(const std::string& path, const std::string& contents);

// FNV-1a 64-bit checksum of bytes, as 16 hex digits.
std::string Fnv1a64Hex(const std::string& bytes);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_IO_H_
