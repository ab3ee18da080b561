// Optical constants n(lambda), k(lambda) on an explicit wavelength grid (nm). Resampling
// is explicit (NkAt, Resample), linear in n and k, and refuses to extrapolate.
#ifndef ALLOYCOLOR_CORE_SPECTRUM_H_
#define ALLOYCOLOR_CORE_SPECTRUM_H_

#include <complex>
#include <string>
#include <vector>

namespace alloycolor {

struct NkSpectrum {
  std::string source;             // file or description, named in error messages
  std::vector<double> lambda_nm;  // strictly increasing
  std::vector<double> n;
  std::vector<double> k;

  double lambda_min_nm() const { return lambda_nm.front(); }
  double lambda_max_nm() const { return lambda_nm.back(); }
  bool Covers(double lambda_nm_lo, double lambda_nm_hi) const;
};

// n + i k at lambda_nm by linear interpolation; throws Error naming the source when
// lambda_nm lies outside the spectrum's range.
std::complex<double> NkAt(const NkSpectrum& spectrum, double lambda_nm);

// n + i k at each of lambda_nm, as NkAt gives it, found in one pass where lambda_nm
// increases (a search per point where it does not).
std::vector<std::complex<double>> NkOn(const NkSpectrum& spectrum,
                                       const std::vector<double>& lambda_nm);

// The spectrum on another grid (each point as NkAt).
NkSpectrum Resample(const NkSpectrum& spectrum, const std::vector<double>& grid_nm);

// first, first + step, ..., up to last (inclusive within step * 1e-9).
std::vector<double> UniformGrid(double first_nm, double last_nm, double step_nm);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_SPECTRUM_H_
