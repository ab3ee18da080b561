#include "alloycolor/core/spectrum.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include "alloycolor/core/error.h"

namespace alloycolor {
namespace {

// A grid longer than this is certainly a mistake in its arguments (1 nm to 1 m at 1 pm).
constexpr double kMaxGridPoints = 1e8;

std::string FormatNm(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.10g", value);
  return buffer;
}

// n + i k between grid[hi - 1] and grid[hi], the first grid point above lambda_nm (past
// the last: the last point's).
std::complex<double> NkBelow(const NkSpectrum& spectrum, std::size_t hi, double lambda_nm) {
  const std::vector<double>& grid = spectrum.lambda_nm;
  if (hi == grid.size()) return {spectrum.n.back(), spectrum.k.back()};
  const std::size_t lo = hi - 1;
  const double t = (lambda_nm - grid[lo]) / (grid[hi] - grid[lo]);
  return {spectrum.n[lo] + t * (spectrum.n[hi] - spectrum.n[lo]),
          spectrum.k[lo] + t * (spectrum.k[hi] - spectrum.k[lo])};
}

void CheckCovers(const NkSpectrum& spectrum, double lambda_nm) {
  const std::vector<double>& grid = spectrum.lambda_nm;
  if (grid.empty() || spectrum.n.size() != grid.size() || spectrum.k.size() != grid.size()) {
    throw Error(spectrum.source + ": spectrum is empty or its columns differ in length");
  }
  if (!(grid.front() <= lambda_nm && lambda_nm <= grid.back())) {
    throw Error(spectrum.source + ": wavelength " + FormatNm(lambda_nm) +
                " nm lies outside the data, " + FormatNm(grid.front()) + " to " +
                FormatNm(grid.back()) + " nm");
  }
}

}  // namespace

bool NkSpectrum::Covers(double lambda_nm_lo, double lambda_nm_hi) const {
  if (lambda_nm.empty()) return false;
  return lambda_nm.front() <= lambda_nm_lo && lambda_nm_hi <= lambda_nm.back();
}

std::complex<double> NkAt(const NkSpectrum& spectrum, double lambda_nm) {
  CheckCovers(spectrum, lambda_nm);
  const std::vector<double>& grid = spectrum.lambda_nm;
  return NkBelow(spectrum, std::upper_bound(grid.begin(), grid.end(), lambda_nm) - grid.begin(),
                 lambda_nm);
}

std::vector<std::complex<double>> NkOn(const NkSpectrum& spectrum,
                                       const std::vector<double>& lambda_nm) {
  const std::vector<double>& grid = spectrum.lambda_nm;
  std::vector<std::complex<double>> nk(lambda_nm.size());
  std::size_t hi = 0;
  for (std::size_t i = 0; i < lambda_nm.size(); ++i) {
    const double l = lambda_nm[i];
    CheckCovers(spectrum, l);
    if (i > 0 && l < lambda_nm[i - 1]) hi = 0;  // not increasing: search from the start
    while (hi < grid.size() && grid[hi] <= l) ++hi;
    nk[i] = NkBelow(spectrum, hi, l);
  }
  return nk;
}

NkSpectrum Resample(const NkSpectrum& spectrum, const std::vector<double>& grid_nm) {
  NkSpectrum result;
  result.source = spectrum.source;
  result.lambda_nm = grid_nm;
  result.n.reserve(grid_nm.size());
  result.k.reserve(grid_nm.size());
  for (const std::complex<double>& nk : NkOn(spectrum, grid_nm)) {
    result.n.push_back(nk.real());
    result.k.push_back(nk.imag());
  }
  return result;
}

std::vector<double> UniformGrid(double first_nm, double last_nm, double step_nm) {
  if (!std::isfinite(first_nm) || !std::isfinite(last_nm) || !std::isfinite(step_nm) ||
      !(step_nm > 0) || last_nm < first_nm) {
    throw Error("wavelength grid " + FormatNm(first_nm) + " to " + FormatNm(last_nm) +
                " nm in steps of " + FormatNm(step_nm) +
                " nm: need first <= last and a positive step");
  }
  const double intervals = std::floor((last_nm - first_nm) / step_nm + 1e-9);
  if (intervals + 1 > kMaxGridPoints) {
    throw Error("wavelength grid " + FormatNm(first_nm) + " to " + FormatNm(last_nm) +
                " nm in steps of " + FormatNm(step_nm) + " nm has too many points");
  }
  const std::size_t count = static_cast<std::size_t>(intervals) + 1;
  std::vector<double> grid(count);
  for (std::size_t i = 0; i < count; ++i) {
    // Clamped so that rounding never puts the last point past last_nm.
    grid[i] = std::min(first_nm + static_cast<double>(i) * step_nm, last_nm);
  }
  return grid;
}

}  // namespace alloycolor
