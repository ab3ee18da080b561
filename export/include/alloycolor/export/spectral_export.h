// Optical constants for physically based renderers: a conductor's n (pbrt's and Mitsuba's
// "eta") and k as a pair of spectrum files, with the material definitions that read them.
//
//  - PREFIX.eta.spd, PREFIX.k.spd: comment lines starting with '#' (the first names the
//    material and composition; every comment line under 240 bytes, as Mitsuba 3 reads
//    lines into 1,024), then one `wavelength_nm value` pair per line, separated by one
//    space, with enough digits (15-17) to read back as the same doubles.
//    This is the format of pbrt-v4's ReadFloatFile (numbers separated by white space, '#'
//    to the end of the line a comment) read by PiecewiseLinearSpectrum::Read (an even
//    count, wavelengths strictly increasing as 32-bit floats), and of Mitsuba 3's
//    Properties::Spectrum(file) (lines of two numbers, '#' lines skipped, at least two
//    points, increasing wavelengths; the spectral variants store them as floats and refuse
//    negative values). Hence: wavelengths that collapse as floats are merged (n and k
//    averaged, with a note), n <= 0 or k < 0 is refused naming the wavelength. Both
//    renderers interpolate linearly between the points and see nothing outside them, so
//    the files always reach 360 and 830 nm (pbrt-v4's visible range, CIE 1931 tables).
//  - PREFIX.pbrt: a pbrt-v4 `Material "conductor" "spectrum eta" "NAME.eta.spd"
//    "spectrum k" "NAME.k.spd"` line (a smooth conductor; pbrt's "roughness" defaults
//    to 0), names quoted with pbrt's escapes (backslash and quote).
//  - PREFIX.xml: a Mitsuba 3 `<bsdf type="conductor" version="3.0.0">` with
//    `<spectrum name="eta" filename="NAME.eta.spd"/>` and `k`, loadable by itself
//    (mitsuba.load_file) or through `<include>`.
// Both renderers resolve a relative spectrum file name against the folder of the scene
// file they were given (pbrt-v4: SetSearchDirectory on each file of its command line;
// Mitsuba 3: load_file prepends the file's folder, then the working directory; neither
// looks in the folder of an included file). The names are therefore written relative to
// the material files' own folder (the files sit side by side), which is right when the
// material file is the scene or sits in the scene's folder; SpectrumFileReference writes
// them relative to another scene folder instead.
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

#include "alloycolor/core/grid.h"
#include "alloycolor/core/spectrum.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::exports {

// The colour tables' grid (core/grid.h): 360-830 nm every 5 nm.
inline constexpr double kExportMinNm = kColourTableMinNm;
inline constexpr double kExportMaxNm = kColourTableMaxNm;
// The range the data themselves must cover.
inline constexpr double kExportNeedMinNm = 380.0;
inline constexpr double kExportNeedMaxNm = 780.0;
inline constexpr double kExportStepNm = kGridStepNm;

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
// Throws Error when the model does not cover 380-780 nm, or gives n <= 0 or k < 0.
ConductorSpectra ModelSpectra(const AlloyModel& model, double x_atomic,
                              const std::string& material);
// The measured spectrum at its own wavelengths, held out to 360 and 830 nm.
ConductorSpectra MeasuredSpectra(const NkSpectrum& nk, const std::string& material);

// How a material file names a spectrum file: its path relative to scene_dir, with '/'
// separators; the file name alone when scene_dir is empty (the files side by side).
std::string SpectrumFileReference(const std::string& spd_path, const std::string& scene_dir);

// File contents. `names_note` is a comment line saying what the names are relative to. `eta`
// chooses n (true) or k (false); header lines are written as comments before the material and notes
// (each line without its '#').
std::string SpdText(const ConductorSpectra& spectra, bool eta,
                    const std::vector<std::string>& header = {});
std::string PbrtMaterialText(const ConductorSpectra& spectra, const std::string& eta_file,
                             const std::string& k_file, const std::string& names_note,
                             const std::vector<std::string>& header = {});
std::string MitsubaBsdfXml(const ConductorSpectra& spectra, const std::string& id,
                           const std::string& eta_file, const std::string& k_file,
                           const std::string& names_note,
                           const std::vector<std::string>& header = {});

}  // namespace alloycolor::exports

#endif  // ALLOYCOLOR_EXPORT_SPECTRAL_EXPORT_H_
