#include "alloycolor/export/spectral_export.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <utility>

#include "alloycolor/core/error.h"
#include "alloycolor/core/markup.h"
#include "text.h"

namespace alloycolor::exports {
namespace {

using text::Number;
using text::OneLine;
using text::ShortNumber;
using text::XmlComment;

constexpr double kToleranceNm = 1e-9;

// One comment line.
std::string Comment(const std::string& text) { return "# " + OneLine(text) + "\n"; }

// The wavelength as the renderers store it: pbrt-v4 parses the text as a 32-bit float,
// Mitsuba 3 as a double and then casts it to float. Both readings of the written text.
std::pair<float, float> AsFloats(double lambda_nm) {
  const std::string text = Number(lambda_nm);
  return {std::strtof(text.c_str(), nullptr),
          static_cast<float>(std::strtod(text.c_str(), nullptr))};
}

// Points whose wavelengths are equal as floats (in either reading) are merged into the
// first of them, with n and k averaged, and a note says how many and where.
ConductorSpectra MergeFloatCollisions(ConductorSpectra spectra) {
  ConductorSpectra out = spectra;
  out.lambda_nm.clear();
  out.n.clear();
  out.k.clear();
  int merged = 0;
  double first_merged = 0.0;
  std::size_t i = 0;
  while (i < spectra.lambda_nm.size()) {
    const auto [f0, d0] = AsFloats(spectra.lambda_nm[i]);
    std::size_t j = i + 1;
    double n_sum = spectra.n[i], k_sum = spectra.k[i];
    while (j < spectra.lambda_nm.size()) {
      const auto [f1, d1] = AsFloats(spectra.lambda_nm[j]);
      if (f1 > f0 && d1 > d0) break;
      n_sum += spectra.n[j];
      k_sum += spectra.k[j];
      ++j;
    }
    if (j - i > 1) {
      if (merged == 0) first_merged = spectra.lambda_nm[i];
      merged += static_cast<int>(j - i - 1);
    }
    out.lambda_nm.push_back(spectra.lambda_nm[i]);
    out.n.push_back(n_sum / static_cast<double>(j - i));
    out.k.push_back(k_sum / static_cast<double>(j - i));
    i = j;
  }
  if (merged > 0) {
    out.notes.push_back(std::to_string(merged) +
                        " point(s) closer than 32-bit floats resolve (the renderers' "
                        "wavelengths) merged into their neighbour, n and k averaged, first at " +
                        ShortNumber(first_merged) + " nm");
  }
  return out;
}

// Adds points at 360 and 830 nm holding the end values where the data stop short, after
// checking that they cover 380-780 nm.
ConductorSpectra HoldEnds(ConductorSpectra spectra, const std::string& what) {
  if (spectra.lambda_nm.empty()) throw Error(what + ": no wavelengths to export");
  for (std::size_t i = 1; i < spectra.lambda_nm.size(); ++i) {
    if (!(spectra.lambda_nm[i] > spectra.lambda_nm[i - 1])) {
      throw Error(what + ": wavelengths are not strictly increasing at " +
                  ShortNumber(spectra.lambda_nm[i]) + " nm");
    }
  }
  for (std::size_t i = 0; i < spectra.n.size(); ++i) {
    const std::string at = " at " + ShortNumber(spectra.lambda_nm[i]) + " nm";
    if (!std::isfinite(spectra.n[i]) || !std::isfinite(spectra.k[i])) {
      throw Error(what + ": n or k is not finite" + at);
    }
    if (!(spectra.n[i] > 0) || spectra.k[i] < 0) {
      throw Error(what + ": n = " + ShortNumber(spectra.n[i]) +
                  ", k = " + ShortNumber(spectra.k[i]) + at +
                  "; renderers need n > 0 and k >= 0 (Mitsuba 3's spectral variants refuse "
                  "negative values)");
    }
  }
  const double lo = spectra.lambda_nm.front();
  const double hi = spectra.lambda_nm.back();
  if (lo > kExportNeedMinNm + kToleranceNm || hi < kExportNeedMaxNm - kToleranceNm) {
    throw Error(what + ": covers " + ShortNumber(lo) + "-" + ShortNumber(hi) +
                " nm; the export needs data over at least " + ShortNumber(kExportNeedMinNm) + "-" +
                ShortNumber(kExportNeedMaxNm) + " nm (it holds the end values out to " +
                ShortNumber(kExportMinNm) + "-" + ShortNumber(kExportMaxNm) + " nm, no further)");
  }
  if (lo > kExportMinNm + kToleranceNm) {
    spectra.notes.push_back("n and k below " + ShortNumber(lo) +
                            " nm (where the data begin) "
                            "are held at their " +
                            ShortNumber(lo) + " nm values; the " + ShortNumber(kExportMinNm) +
                            " nm point is not data");
    spectra.lambda_nm.insert(spectra.lambda_nm.begin(), kExportMinNm);
    spectra.n.insert(spectra.n.begin(), spectra.n.front());
    spectra.k.insert(spectra.k.begin(), spectra.k.front());
  }
  if (hi < kExportMaxNm - kToleranceNm) {
    spectra.notes.push_back("n and k above " + ShortNumber(hi) +
                            " nm (where the data end) "
                            "are held at their " +
                            ShortNumber(hi) + " nm values; the " + ShortNumber(kExportMaxNm) +
                            " nm point is not data");
    spectra.lambda_nm.push_back(kExportMaxNm);
    spectra.n.push_back(spectra.n.back());
    spectra.k.push_back(spectra.k.back());
  }
  return MergeFloatCollisions(std::move(spectra));
}

// Control characters cannot be written in either renderer's strings.
void CheckFileName(const std::string& name) {
  const bool control = std::any_of(name.begin(), name.end(),
                                   [](char c) { return static_cast<unsigned char>(c) < 0x20; });
  if (name.empty() || control) {
    throw Error("file name '" + OneLine(name) + "' cannot be written into a material file");
  }
}

// pbrt-v4's tokenizer reads '\\' in a quoted string as an escape ("\\\\", "\\\"", ...).
std::string PbrtQuoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '\\' || c == '"') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string Range(const ConductorSpectra& s) {
  return ShortNumber(s.lambda_nm.front()) + "-" + ShortNumber(s.lambda_nm.back()) + " nm";
}

}  // namespace

std::string SpectrumFileReference(const std::string& spd_path, const std::string& scene_dir) {
  namespace fs = std::filesystem;
  if (scene_dir.empty()) return fs::path(spd_path).filename().generic_string();
  const fs::path target = fs::absolute(spd_path).lexically_normal();
  const fs::path base = fs::absolute(scene_dir).lexically_normal();
  const fs::path relative = target.lexically_relative(base);
  return (relative.empty() ? target : relative).generic_string();
}

std::vector<double> ModelExportGrid(const AlloyModel& model) {
  if (const std::vector<double> native = model.native_grid_nm(); !native.empty()) {
    std::vector<double> grid;
    for (double l : native) {
      if (l >= model.lambda_min_nm() - kToleranceNm && l <= model.lambda_max_nm() + kToleranceNm) {
        grid.push_back(std::clamp(l, model.lambda_min_nm(), model.lambda_max_nm()));
      }
    }
    if (!grid.empty()) return grid;
  }
  const double lo = model.lambda_min_nm();
  const double hi = model.lambda_max_nm();
  std::vector<double> grid{lo};
  for (double l = std::ceil(lo / kExportStepNm) * kExportStepNm; l < hi; l += kExportStepNm) {
    if (l > grid.back() + kToleranceNm) grid.push_back(l);
  }
  if (hi > grid.back() + kToleranceNm) grid.push_back(hi);
  return grid;
}

ConductorSpectra ModelSpectra(const AlloyModel& model, double x_atomic,
                              const std::string& material) {
  ConductorSpectra spectra;
  spectra.material = material;
  spectra.lambda_nm = ModelExportGrid(model);
  const std::vector<std::complex<double>> index = model.Index(x_atomic, spectra.lambda_nm);
  for (const auto& nk : index) {
    spectra.n.push_back(nk.real());
    spectra.k.push_back(nk.imag());
  }
  return HoldEnds(std::move(spectra), "the " + model.method() + " model");
}

ConductorSpectra MeasuredSpectra(const NkSpectrum& nk, const std::string& material) {
  ConductorSpectra spectra;
  spectra.material = material;
  spectra.lambda_nm = nk.lambda_nm;
  spectra.n = nk.n;
  spectra.k = nk.k;
  return HoldEnds(std::move(spectra), nk.source);
}

std::string SpdText(const ConductorSpectra& spectra, bool eta,
                    const std::vector<std::string>& header) {
  std::string out =
      Comment(spectra.material + (eta ? ": n (\"eta\"), real part of the refractive index "
                                        "N = n + ik"
                                      : ": k, imaginary part of the refractive index N = n + ik"));
  out += Comment(std::string("columns: wavelength_nm ") + (eta ? "n" : "k") + "; " +
                 std::to_string(spectra.lambda_nm.size()) + " points over " + Range(spectra));
  for (const std::string& note : spectra.notes) out += Comment(note);
  for (const std::string& line : header) out += Comment(line);
  const std::vector<double>& values = eta ? spectra.n : spectra.k;
  for (std::size_t i = 0; i < spectra.lambda_nm.size(); ++i) {
    out += Number(spectra.lambda_nm[i]) + " " + Number(values[i]) + "\n";
  }
  return out;
}

std::string PbrtMaterialText(const ConductorSpectra& spectra, const std::string& eta_file,
                             const std::string& k_file, const std::string& names_note,
                             const std::vector<std::string>& header) {
  CheckFileName(eta_file);
  CheckFileName(k_file);
  std::string out = Comment("pbrt-v4 smooth conductor: " + spectra.material);
  out +=
      Comment("n and k over " + Range(spectra) + " from the spectrum files (wavelength_nm value)");
  out += Comment(names_note);
  for (const std::string& note : spectra.notes) out += Comment(note);
  for (const std::string& line : header) out += Comment(line);
  out += "Material \"conductor\" \"spectrum eta\" " + PbrtQuoted(eta_file) + " \"spectrum k\" " +
         PbrtQuoted(k_file) + "\n";
  return out;
}

std::string MitsubaBsdfXml(const ConductorSpectra& spectra, const std::string& id,
                           const std::string& eta_file, const std::string& k_file,
                           const std::string& names_note, const std::vector<std::string>& header) {
  CheckFileName(eta_file);
  CheckFileName(k_file);
  std::string out = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
  out += XmlComment("Mitsuba 3 smooth conductor: " + spectra.material);
  out += XmlComment("n (eta) and k over " + Range(spectra) +
                    " from the .spd files (wavelength_nm value)");
  out += XmlComment(names_note);
  for (const std::string& note : spectra.notes) out += XmlComment(note);
  for (const std::string& line : header) out += XmlComment(line);
  out += "<bsdf type=\"conductor\" id=\"" + EscapeXml(id) + "\" version=\"3.0.0\">\n";
  out += "    <spectrum name=\"eta\" filename=\"" + EscapeXml(eta_file) + "\"/>\n";
  out += "    <spectrum name=\"k\" filename=\"" + EscapeXml(k_file) + "\"/>\n";
  out += "</bsdf>\n";
  return out;
}

}  // namespace alloycolor::exports
