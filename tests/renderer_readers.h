// The renderers' own reading rules, re-implemented for the export tests from their sources
// (read at pbrt-v4 and Mitsuba 3 master):
//  - pbrt-v4 src/pbrt/util/file.cpp ReadFloatFile: a character loop; a number is a run of
//    digits . e E - + started by a digit . - or +, held in a 32-byte buffer (overflow is
//    fatal), parsed as a 32-bit float and ended by any other character (so a number at the
//    very end of the file without a following character is lost); '#' outside a number
//    skips to the end of the line; any other non-space character is an error.
//    src/pbrt/util/spectrum.cpp PiecewiseLinearSpectrum::Read: no values, or an odd count,
//    fails; wavelengths (as floats) must strictly increase.
//    src/pbrt/util/file.cpp ResolveFilename: a relative name is looked up in the search
//    directory (the folder of the scene file given on the command line) and used from
//    there if it exists, else as given (relative to the working directory).
//    src/pbrt/parser.cpp Tokenizer::Next: quoted strings end at the next unescaped '"',
//    may not hold a newline; '\' escapes b f n r t \ ' " (anything else is an error);
//    '#' starts a comment to the end of the line.
//  - Mitsuba 3 src/core/properties.cpp Properties::Spectrum(const fs::path&) (what a
//    <spectrum filename="..."/> goes through, src/core/parser.cpp): lines read with
//    fgets into 1,024 bytes; a chunk starting with '#', '\n' or '\r' is skipped, any
//    other must start with two numbers (parsed as doubles); at least two entries, strictly
//    increasing wavelengths. src/spectra/irregular.cpp then casts wavelengths and values
//    to float for the single-precision variants and IrregularContinuousDistribution
//    refuses nodes that do not strictly increase and negative entries.
//    src/core/spectrum.cpp spectrum_from_file (the .spd reader of the Python API): '#'
//    starts a comment to '\n'; more than two numbers on a line is an error.
//    FileResolver: load_file prepends the scene file's folder to [working directory]; an
//    <include> prepends the including file's folder while the included file is parsed.
#ifndef ALLOYCOLOR_TESTS_RENDERER_READERS_H_
#define ALLOYCOLOR_TESTS_RENDERER_READERS_H_

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace alloycolor::testing::readers {

struct Spectrum {
  bool ok = false;
  std::string error;
  std::vector<double> lambda_nm;  // as the renderer holds them (float for pbrt)
  std::vector<double> value;
};

inline std::optional<std::string> Slurp(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return std::nullopt;
  std::string text;
  char buf[4096];
  std::size_t got;
  while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, got);
  std::fclose(f);
  return text;
}

// pbrt-v4 ReadFloatFile. Returns nullopt (with the reason) where pbrt errors or aborts.
inline std::optional<std::vector<float>> PbrtReadFloatFile(const std::string& path,
                                                           std::string* error) {
  const std::optional<std::string> text = Slurp(path);
  if (!text) {
    *error = path + ": unable to open file";
    return std::nullopt;
  }
  bool in_number = false;
  char number[32];
  int pos = 0;
  std::vector<float> values;
  for (std::size_t i = 0; i < text->size(); ++i) {
    int c = static_cast<unsigned char>((*text)[i]);
    if (in_number) {
      if (pos >= static_cast<int>(sizeof number)) {
        *error = "overflowed buffer for parsing number";
        return std::nullopt;
      }
      if (std::isdigit(c) || c == '.' || c == 'e' || c == 'E' || c == '-' || c == '+') {
        number[pos++] = static_cast<char>(c);
      } else {
        number[pos++] = '\0';
        char* end = nullptr;
        const float v = std::strtof(number, &end);
        if (end == number || *end != '\0') {
          *error = std::string("unable to parse float value \"") + number + "\"";
          return std::nullopt;
        }
        values.push_back(v);
        in_number = false;
        pos = 0;
      }
    } else {
      if (std::isdigit(c) || c == '.' || c == '-' || c == '+') {
        in_number = true;
        number[pos++] = static_cast<char>(c);
      } else if (c == '#') {
        while (i + 1 < text->size() && (*text)[i + 1] != '\n') ++i;
        ++i;  // the newline
      } else if (!std::isspace(c)) {
        *error = std::string("unexpected character \"") + static_cast<char>(c) + "\"";
        return std::nullopt;
      }
    }
  }
  return values;
}

// pbrt-v4 PiecewiseLinearSpectrum::Read.
inline Spectrum PbrtReadSpectrumFile(const std::string& path) {
  Spectrum s;
  const std::optional<std::vector<float>> values = PbrtReadFloatFile(path, &s.error);
  if (!values) return s;
  if (values->empty()) {
    s.error = path + ": unable to read spectrum file";
    return s;
  }
  if (values->size() % 2 != 0) {
    s.error = path + ": extra value found in spectrum file";
    return s;
  }
  for (std::size_t i = 0; i < values->size() / 2; ++i) {
    const float l = (*values)[2 * i];
    if (i > 0 && !(l > static_cast<float>(s.lambda_nm.back()))) {
      s.error = path + ": wavelengths aren't increasing at entry " + std::to_string(i);
      return s;
    }
    s.lambda_nm.push_back(l);
    s.value.push_back((*values)[2 * i + 1]);
  }
  s.ok = true;
  return s;
}

// pbrt-v4 ResolveFilename, with the working directory explicit.
inline std::string PbrtResolveFilename(const std::string& search_dir, const std::string& name,
                                       const std::string& cwd) {
  namespace fs = std::filesystem;
  if (!search_dir.empty() && !name.empty() && !fs::path(name).is_absolute()) {
    const fs::path candidate = fs::path(search_dir) / name;
    if (fs::exists(candidate)) return fs::absolute(candidate).string();
  }
  if (fs::path(name).is_absolute()) return name;
  return (fs::path(cwd) / name).string();
}

// pbrt-v4 Tokenizer::Next over a whole file: quoted strings are returned dequoted with a
// leading '"' to mark them; comments are dropped. nullopt on a tokenizer error.
inline std::optional<std::vector<std::string>> PbrtTokens(const std::string& text,
                                                          std::string* error) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == ' ' || c == '\n' || c == '\t' || c == '\r') {
      ++i;
    } else if (c == '"') {
      std::string value = "\"";
      ++i;
      while (true) {
        if (i >= text.size()) {
          *error = "premature EOF";
          return std::nullopt;
        }
        char ch = text[i++];
        if (ch == '"') break;
        if (ch == '\n') {
          *error = "unterminated string";
          return std::nullopt;
        }
        if (ch == '\\') {
          if (i >= text.size()) {
            *error = "premature EOF";
            return std::nullopt;
          }
          ch = text[i++];
          switch (ch) {
            case 'b':
              ch = '\b';
              break;
            case 'f':
              ch = '\f';
              break;
            case 'n':
              ch = '\n';
              break;
            case 'r':
              ch = '\r';
              break;
            case 't':
              ch = '\t';
              break;
            case '\\':
            case '\'':
            case '"':
              break;
            default:
              *error = std::string("unexpected escaped character \"") + ch + "\"";
              return std::nullopt;
          }
        }
        value += ch;
      }
      tokens.push_back(value);
    } else if (c == '[' || c == ']') {
      tokens.emplace_back(1, c);
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n' && text[i] != '\r') ++i;
    } else {
      const std::size_t start = i;
      while (i < text.size() && std::strchr(" \n\t\r\"[]", text[i]) == nullptr) ++i;
      tokens.push_back(text.substr(start, i - start));
    }
  }
  return tokens;
}

// Mitsuba 3 Properties::Spectrum(file) followed by the irregular spectrum's float checks.
inline Spectrum MitsubaPropertiesSpectrum(const std::string& path) {
  Spectrum s;
  std::FILE* file = std::fopen(path.c_str(), "r");
  if (!file) {
    s.error = "could not open " + path;
    return s;
  }
  char line[1024];
  std::vector<double> wavelengths, values;
  std::size_t line_num = 0;
  while (std::fgets(line, sizeof line, file)) {
    ++line_num;
    if (line[0] == '#' || line[0] == '\n' || line[0] == '\r') continue;
    char* p = line;
    char* tmp = nullptr;
    const double wl = std::strtod(p, &tmp);
    if (tmp == p) {
      s.error = "could not extract wavelength in line " + std::to_string(line_num);
      std::fclose(file);
      return s;
    }
    p = tmp;
    const double val = std::strtod(p, &tmp);
    if (tmp == p) {
      s.error = "could not extract value in line " + std::to_string(line_num);
      std::fclose(file);
      return s;
    }
    wavelengths.push_back(wl);
    values.push_back(val);
  }
  std::fclose(file);
  if (wavelengths.size() < 2) {
    s.error = "spectrum must have at least two entries";
    return s;
  }
  for (std::size_t i = 1; i < wavelengths.size(); ++i) {
    if (wavelengths[i] <= wavelengths[i - 1]) {
      s.error = "wavelengths must be specified in increasing order";
      return s;
    }
  }
  bool mass = false;
  for (std::size_t i = 0; i < wavelengths.size(); ++i) {
    const float l = static_cast<float>(wavelengths[i]);
    const float v = static_cast<float>(values[i]);
    if (i > 0 && !(l > static_cast<float>(s.lambda_nm.back()))) {
      s.error = "IrregularContinuousDistribution: node positions must be strictly increasing!";
      return s;
    }
    if (v < 0) {
      s.error = "IrregularContinuousDistribution: entries must be non-negative!";
      return s;
    }
    mass = mass || v > 0;
    s.lambda_nm.push_back(l);
    s.value.push_back(v);
  }
  if (!mass) {
    s.error = "IrregularContinuousDistribution: no probability mass found!";
    return s;
  }
  s.ok = true;
  return s;
}

// Mitsuba 3 spectrum_from_file (.spd).
inline Spectrum MitsubaSpectrumFromFile(const std::string& path) {
  Spectrum s;
  const std::optional<std::string> text = Slurp(path);
  if (!text) {
    s.error = "file does not exist";
    return s;
  }
  if (std::filesystem::path(path).extension() != ".spd") {
    s.error = "needs the .spd extension";
    return s;
  }
  const char* current = text->c_str();
  const char* end = current + text->size();
  bool comment = false;
  std::size_t counter = 0;
  while (current != end) {
    const char c = *current;
    if (c == '#') {
      comment = true;
      ++current;
    } else if (c == '\n') {
      comment = false;
      counter = 0;
      ++current;
    } else if (!comment && c != ' ' && c != '\r') {
      char* tmp = nullptr;
      const float val = std::strtof(current, &tmp);
      if (tmp == current) {
        s.error = "could not parse a number";
        return s;
      }
      current = tmp;
      if (counter == 0) {
        s.lambda_nm.push_back(val);
      } else if (counter == 1) {
        s.value.push_back(val);
      } else {
        s.error = "more than two elements were defined in a line";
        return s;
      }
      ++counter;
    } else {
      ++current;
    }
  }
  s.ok = s.lambda_nm.size() == s.value.size() && !s.lambda_nm.empty();
  if (!s.ok) s.error = "wavelengths and values differ in number";
  return s;
}

// Mitsuba 3 FileResolver::resolve over the given search paths.
inline std::string MitsubaResolve(const std::vector<std::string>& paths, const std::string& name) {
  namespace fs = std::filesystem;
  if (!fs::path(name).is_absolute()) {
    for (const std::string& base : paths) {
      const fs::path combined = fs::path(base) / name;
      if (fs::exists(combined)) return combined.string();
    }
  }
  return name;
}

}  // namespace alloycolor::testing::readers

#endif  // ALLOYCOLOR_TESTS_RENDERER_READERS_H_
