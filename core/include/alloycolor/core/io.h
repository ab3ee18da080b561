// Readers of optical constants, each layout detected from the file, never guessed:
//  - refractiveindex.info database YAML: DATA entries `tabulated nk` (rows
//    `wavelength_um n k`), or `tabulated n` plus `tabulated k` in one file (rows
//    `wavelength_um value`, joined on the n grid with k interpolated), or a file with
//    `tabulated n` alone paired with one holding `tabulated k` (ReadNkPair). Other entry
//    types (`formula N`, `tabulated n2`) are refused with a message naming them.
//  - delimited text (.csv, .txt, .dat, .tsv) as labs and instruments export it:
//    comma, semicolon, tab or whitespace between fields (the delimiter of the first row of
//    numbers; where it is not a comma, "0,5" is read as a decimal comma); a UTF-8 byte
//    order mark; CRLF line ends; trailing delimiters; lines starting
//    with '#' are comments; title lines may precede the header. The header is the line
//    just above the first row of numbers (a '#' comment there counts when it names the
//    columns). Its first named column is the abscissa with its unit, in the usual
//    spellings: wavelength in nm (`lambda_nm`, `Wavelength (nm)`), um (`wl_um`, `µm`,
//    `micron`) or Angstrom (`Å`, `A`, `angstrom`), photon energy in eV (`eV`,
//    `Energy (eV)`), or wavenumber in cm^-1 (`wavenumber (cm-1)`, `1/cm`); rows ascending
//    or descending. The values are n and k (`n`, `k`, `kappa`), or eps1 and eps2 (`e1`,
//    `eps1`, `ε1`, `epsilon_real`, `er`, `Re(eps)` and their imaginary partners), converted
//    with eq. 13, 14: n^2 = (|eps| + eps1)/2, k^2 = (|eps| - eps1)/2. A column may carry a
//    sample tag (`n6`, `k6`, `n_12`); with exactly one n,k (or eps1,eps2) pair the file is
//    read as it is, with several the caller chooses one (NkColumns: a header name or a
//    1-based column number each). A file with no header, an unknown unit or several pairs
//    and no choice is refused with a one-line message saying what was seen and how to say
//    what it is.
// Every reader returns an NkSpectrum on ascending nm. Every error names the file, and the
// line where there is one. n and k must lie in [0, kMaxOpticalConstant], eps2 >= 0; no
// number may be nonzero and below kSmallestMeasuredValue. Wavelengths in a column whose
// header says nm that all lie under 20 (or in um, all over 100) are refused as the other
// unit. A wavelength repeated is averaged with a warning (real files do this).
#ifndef ALLOYCOLOR_CORE_IO_H_
#define ALLOYCOLOR_CORE_IO_H_

#include <string>
#include <string_view>
#include <vector>

#include "alloycolor/core/spectrum.h"

namespace alloycolor {

class OutputGuard;

// The largest n or k a reader accepts. Metals reach k ~ 1e3 in the far infrared; above
// 1e77, |eps|^2 overflows a double and reflectance becomes NaN.
inline constexpr double kMaxOpticalConstant = 1e6;
// The smallest magnitude a number in a data file may have besides 0: no instrument
// measures n, k, eps, R or a wavelength to 1e-30, and a denormal (k = 1e-320) is a value
// of the wrong kind (a damaged export), refused with its file and line.
inline constexpr double kSmallestMeasuredValue = 1e-30;

// The columns of a delimited file that hold the wanted sample: each a header name
// ("n6", matched exactly, else ignoring case) or a 1-based column number ("2"). Both
// empty: found from the header. When the two named columns are eps1 and eps2 by their
// names, they are converted; otherwise they are read as n and k.
struct NkColumns {
  std::string n;
  std::string k;
  bool empty() const { return n.empty() && k.empty(); }
};

// "N,K" as written after --columns; throws Error naming the text when it is not two
// non-empty parts.
NkColumns ParseNkColumns(const std::string& text);

// Chooses the reader from the extension (.yml/.yaml: YAML; .csv, .txt, .dat, .tsv:
// delimited text, unless a line starts with "DATA:", then YAML; another extension is
// read as YAML when a line starts with "DATA:"). columns applies to delimited text only.
// warnings, if given, receive one line per oddity that was repaired, each beginning
// "file:line: " (or "file: ").
NkSpectrum ReadNkFile(const std::string& path, std::vector<std::string>* warnings = nullptr);
NkSpectrum ReadNkFile(const std::string& path, const NkColumns& columns,
                      std::vector<std::string>* warnings = nullptr);
NkSpectrum ReadRefractiveIndexYaml(const std::string& path,
                                   std::vector<std::string>* warnings = nullptr);
NkSpectrum ReadNkDelimited(const std::string& path, const NkColumns& columns = {},
                           std::vector<std::string>* warnings = nullptr);
// The delimited-text reader with columns found from the header (the name it had when it
// read `lambda_nm,n,k` only).
NkSpectrum ReadNkCsv(const std::string& path, std::vector<std::string>* warnings = nullptr);

// A measured reflectance spectrum, ascending in nm, R as a fraction in [0, 1].
struct MeasuredReflectance {
  std::string source;
  std::vector<double> lambda_nm;
  std::vector<double> reflectance;
};

// A reflectance spectrum from delimited text read as flexibly as n,k files (delimiters,
// decimal commas, comments, title lines, the abscissa's units, either order): the value
// column is the one named R, refl, reflectance or reflectivity (or the only other one),
// in percent where its name says so ('R (%)', 'R_percent'). Errors name the file and line.
MeasuredReflectance ReadReflectanceDelimited(const std::string& path,
                                             std::vector<std::string>* warnings = nullptr);

// n from a refractiveindex.info file holding `tabulated n` alone, k from one holding
// `tabulated k` alone, joined on the n grid where both are defined.
NkSpectrum ReadNkPair(const std::string& n_path, const std::string& k_path,
                      std::vector<std::string>* warnings = nullptr);

// Writes lambda_nm,n,k rows with full precision (17 significant digits).
std::string NkCsvText(const std::vector<double>& lambda_nm, const std::vector<double>& n,
                      const std::vector<double>& k);

// The largest input file read (a refractiveindex.info file is under 1 MiB, the largest
// lab export a few MiB).
inline constexpr long long kMaxInputFileBytes = 256LL << 20;

// Whole file as a string; throws Error naming the file when it cannot be read, is not a
// regular file (a FIFO, a device) or is over kMaxInputFileBytes. Reading has no other
// effect: a program that must not overwrite its inputs notes them in its OutputGuard
// (output.h).
// The text is checked with CheckTextEncoding.
std::string ReadFileText(const std::string& path);

// Throws Error naming the file and its encoding when text is UTF-16 or UTF-32 (by its
// byte order mark, or without one by a NUL in every other byte of its start): every
// reader of this library reads UTF-8 (or ASCII) text. (A stray NUL byte elsewhere is left
// to the readers, which name its line.)
void CheckTextEncoding(const std::string& path, std::string_view text);

// Writes through a temporary file in the same folder renamed into place, so that a
// failed or interrupted write never leaves a damaged file nor destroys the old one;
// refuses special files, and with a guard the guard's inputs (output.h,
// WriteFileSetAtomic, which implements it).
void WriteFileAtomic(const std::string& path, const std::string& contents,
                     OutputGuard* guard = nullptr);

// FNV-1a 64-bit checksum of bytes, as 16 hex digits.
std::string Fnv1a64Hex(const std::string& bytes);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_IO_H_
