// What the libFuzzer targets share: a private folder for the input file (the readers take
// paths), the colour chain run on whatever a reader accepts, and the checks that turn a
// silent fault into a crash the fuzzer reports:
//  - a reader either returns a valid value or throws alloycolor::Error with a one-line
//    message in valid UTF-8 (any other exception escapes and aborts);
//  - a spectrum or model it accepts gives finite n, k and a finite colour.
#ifndef ALLOYCOLOR_FUZZ_FUZZ_UTIL_H_
#define ALLOYCOLOR_FUZZ_FUZZ_UTIL_H_

#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/spectrum.h"
#include "alloycolor/core/text.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::fuzz {

// Stops the fuzzer with a finding.
[[noreturn]] inline void Finding(const std::string& what) {
  std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
  std::abort();
}

inline void Require(bool ok, const std::string& what) {
  if (!ok) Finding(what);
}

// A folder of this process, removed at exit: in /dev/shm where there is one (a file
// written per input costs milliseconds on some disks, microseconds in memory).
inline const std::string& WorkDir() {
  struct Folder {
    std::string path;
    Folder() {
      std::error_code ec;
      const std::filesystem::path base =
          std::filesystem::is_directory("/dev/shm", ec) && access("/dev/shm", W_OK) == 0
              ? std::filesystem::path("/dev/shm")
              : std::filesystem::temp_directory_path();
      path = (base / "alloycolor-fuzz-XXXXXX").string();
      if (mkdtemp(path.data()) == nullptr) Finding("mkdtemp failed");
    }
    ~Folder() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Folder folder;
  return folder.path;
}

// Writes the input to WorkDir()/name and returns that path.
inline std::string WriteInput(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const std::string path = WorkDir() + "/" + name;
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) Finding("cannot write " + path);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t put = write(fd, data + done, size - done);
    if (put <= 0) Finding("cannot write " + path);
    done += static_cast<std::size_t>(put);
  }
  close(fd);
  return path;
}

// An Error's message: one line, not empty, naming `culprit` when given.
inline void CheckMessage(const Error& error, const std::string& culprit) {
  const std::string message = error.what();
  Require(!message.empty(), "empty error message");
  Require(message.find('\n') == std::string::npos, "error message spans lines: " + message);
  // Valid UTF-8 without control characters: a file's bytes never reach a message raw.
  Require(SafeText(message, std::string::npos) == message,
          "error message carries raw bytes: " + SafeText(message, 300));
  if (!culprit.empty()) {
    Require(message.find(culprit) != std::string::npos,
            "error message does not name " + culprit + ": " + message);
  }
}

inline const color::Colorimeter& D65() {
  static const color::Colorimeter colorimeter =
      color::Colorimeter::Load(ALLOYCOLOR_DATA_DIR, "D65", 2);
  return colorimeter;
}

inline void CheckXYZ(const color::XYZ& xyz, const std::string& what) {
  Require(std::isfinite(xyz.X) && std::isfinite(xyz.Y) && std::isfinite(xyz.Z),
          what + ": non-finite colour");
  // Reflectance lies in [0, 1], so XYZ lies between black and the white (with rounding).
  const color::XYZ white = D65().White();
  Require(xyz.X >= -1e-9 && xyz.Y >= -1e-9 && xyz.Z >= -1e-9 && xyz.X <= white.X + 1e-9 &&
              xyz.Y <= white.Y + 1e-9 && xyz.Z <= white.Z + 1e-9,
          what + ": colour outside black..white");
}

inline void CheckIndex(const std::vector<std::complex<double>>& index, const std::string& what) {
  for (const auto& nk : index) {
    Require(std::isfinite(nk.real()) && std::isfinite(nk.imag()), what + ": non-finite n, k");
  }
}

// A spectrum a reader accepted: its invariants, then its colour at 0 and 60 degrees when
// it covers the visible (otherwise EvaluationGrid must refuse it with an Error).
inline void CheckSpectrum(const NkSpectrum& nk) {
  const std::size_t m = nk.lambda_nm.size();
  Require(m >= 2 && nk.n.size() == m && nk.k.size() == m, "spectrum sizes");
  for (std::size_t i = 0; i < m; ++i) {
    Require(std::isfinite(nk.lambda_nm[i]) && nk.lambda_nm[i] > 0, "bad wavelength accepted");
    Require(i == 0 || nk.lambda_nm[i] > nk.lambda_nm[i - 1], "wavelengths not increasing");
    Require(std::isfinite(nk.n[i]) && std::isfinite(nk.k[i]) && nk.n[i] >= 0 && nk.k[i] >= 0,
            "bad n, k accepted");
  }
  std::vector<std::complex<double>> index;
  try {
    index = color::IndexOnGrid(D65(), nk);
  } catch (const Error& e) {
    CheckMessage(e, nk.source);
    return;
  }
  CheckIndex(index, nk.source);
  for (double angle : {0.0, 60.0, 89.9}) {
    CheckXYZ(color::MaterialXYZ(D65(), index, angle), nk.source);
  }
}

// One input to a spectrum reader (`read`: path, warnings -> NkSpectrum), written as
// WorkDir()/name: what it accepts keeps its source and passes CheckSpectrum, its warnings
// and errors are one line each, and an error names the file.
template <typename Reader>
int FuzzSpectrumReader(const std::uint8_t* data, std::size_t size, const std::string& name,
                       Reader read) {
  const std::string path = WriteInput(data, size, name);
  try {
    std::vector<std::string> warnings;
    const NkSpectrum nk = read(path, &warnings);
    Require(nk.source == path, "spectrum source is not the file");
    for (const std::string& w : warnings) {
      Require(w.find('\n') == std::string::npos, "warning spans lines: " + w);
    }
    CheckSpectrum(nk);
  } catch (const Error& e) {
    CheckMessage(e, path);
  }
  return 0;
}

// A model a reader accepted: finite eps over its whole range at its ends and middle, and a
// finite colour when it covers the visible.
inline void CheckModel(const AlloyModel& model, const std::string& what) {
  const double x_lo = model.x_min(), x_hi = model.x_max();
  const double l_lo = model.lambda_min_nm(), l_hi = model.lambda_max_nm();
  Require(std::isfinite(x_lo) && std::isfinite(x_hi) && x_lo <= x_hi, what + ": x range");
  Require(std::isfinite(l_lo) && std::isfinite(l_hi) && l_lo < l_hi, what + ": lambda range");
  const std::vector<double> lambda = {l_lo, 0.5 * (l_lo + l_hi), l_hi};
  for (double x : {x_lo, 0.5 * (x_lo + x_hi), x_hi}) {
    if (!(x >= 0 && x <= 1)) continue;  // the program refuses such compositions
    std::vector<std::complex<double>> index;
    try {
      index = model.Index(x, lambda);
    } catch (const Error& e) {
      CheckMessage(e, "");
      continue;
    }
    CheckIndex(index, what);
    try {
      index = color::IndexOnGrid(D65(), model, x);
    } catch (const Error& e) {
      CheckMessage(e, "");
      return;
    }
    CheckIndex(index, what);
    for (double angle : {0.0, 60.0}) CheckXYZ(color::MaterialXYZ(D65(), index, angle), what);
  }
}

}  // namespace alloycolor::fuzz

#endif  // ALLOYCOLOR_FUZZ_FUZZ_UTIL_H_
