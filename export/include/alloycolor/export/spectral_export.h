// Optical constants for physically based renderers: a conductor's n (pbrt's and Mitsuba's
// "eta") and k as a pair of spectrum files, with the material definitions that read them.
//
//  - PREFIX.eta.spd, PREFIX.k.spd: comment lines starting with '#' (the first names the
//    material and composition), then one `wavelength_nm value` pair per line, separated by
//    one space, wavelengths strictly increasing, with enough digits (15-17) to read back as
//    the same doubles.
//    This is the format of pbrt-v4's ReadFloatFile (numbers separated by white space, '#'
//    to the end of the line a comment) and of Mitsuba 3's spectrum_from_file (".spd"
//    extension, '#' comment lines, two numbers per line). Both renderers interpolate
//    linearly between the points and see nothing outside them, so the files always reach
//    360 and 830 nm (pbrt-v4's visible range, CIE 1931 tables).
//  - PREFIX.pbrt: a pbrt-v4 `Material "conductor" "spectrum eta" "PREFIX.eta.spd"
//    "spectrum k" "PREFIX.k.spd"` line (a smooth conductor; pbrt's "roughness" defaults
//    to 0).
//  - PREFIX.xml: a Mitsuba 3 `<bsdf type="conductor" version="3.0.0">` with
//    `<spectrum name="eta" filename="PREFIX.eta.spd"/>` and `k`, loadable by itself
//    (mitsuba.load_file) or through `<include>`.
// The spectrum files are named in the material files as given (PREFIX as written on the
// command line); pbrt-v4 and Mitsuba 3 resolve a relative name against the folder of the
// scene file they load.
//
// Wavelengths: those of the data (a model's own grid where it has one, else every 5 nm of
// its range plus the range's ends; a measured file's own wavelengths). Where the data stop
// short of 360 or 830 nm but cover 380-780 nm, a point at 360 or 830 nm holds n and k at
// their values at the end of the data, and a comment line says so, as the colour
// computations do (material_color.h); data not covering 380-780 nm are refused.
#ifndef ALLOYCOLOR_EXPORT_SPECTRAL_EXPORT_H_
#define ALLOYCOLOR_EXPORT_SPECTRAL_EXPORT_H_

#include <string>
#include <vector>

#include "alloycolor/model/alloy_model.h"
#include "alloycolor/core/spectrum.h"

namespace alloycolor::exports {

inline constexpr double kExportMinNm = 360.0;
inline constexpr double kExportMaxNm = 830.0;
// The range the data themselves must cover.
inline constexpr double kExportNeedMinNm = 380.0;
inline constexpr double kExportNeedMaxNm = 780.0;
inline constexpr double kExportStepNm = 5.0;

struct ConductorSpectra {
  std::string material;           // "Au-Ag at x = 0.75 (...)": the first comment line
  std::vector<double> lambda_nm;  // strictly increasing, reaching 360 and 830 nm
  std::vector<double> n;
  std::vector<double> k;
  std::vector<std::string> notes;  // further comment lines (held ends, source)
};

// The wavelengths at which a model is exported: SmoothModel's grid, or every
// kExportStepNm nm in [lambda_min_nm, lambda_max_nm] plus both ends.
std::vector<double> ModelExportGrid(const AlloyModel& model);

// n and k of the model at x_atomic on ModelExportGrid, held out to 360 and 830 nm.
// Throws Error when the model does not cover 380-780 nm.
ConductorSpectra ModelSpectra(const AlloyModel& model, double x_atomic,
                              const std::string& material);
// The measured spectrum at its own wavelengths, held out to 360 and 830 nm.
ConductorSpectra MeasuredSpectra(const NkSpectrum& nk, const std::string& material);

// File contents. `eta` chooses n (true) or k (false); header lines are written as
// comments before the material and notes (each line without its '#').
std::string SpdText(const ConductorSpectra& spectra, bool eta,
                    const std::vector<std::string>& header = {});
std::string PbrtMaterialText(const ConductorSpectra& spectra, const std::string& eta_file,
                             const std::string& k_file,
                             const std::vector<std::string>& header = {});
std::string MitsubaBsdfXml(const ConductorSpectra& spectra, const std::string& id,
                           const std::string& eta_file, const std::string& k_file,
                           const std::vector<std::string>& header = {});

}  // namespace alloycolor::exports

#endif  // ALLOYCOLOR_EXPORT_SPECTRAL_EXPORT_H_
