#include "alloycolor/export/spectral_export.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "alloycolor/core/error.h"

namespace alloycolor::exports {
namespace {

constexpr double kToleranceNm = 1e-9;

// The shortest of 15-17 significant digits that reads back as the same double.
std::string Number(double value) {
  char buf[40];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, value);
    if (std::strtod(buf, nullptr) == value) break;
  }
  return buf;
}

std::string ShortNumber(double value) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%g", value);
  return buf;
}

// One comment line: no line breaks inside.
std::string Comment(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return "# " + text + "\n";
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
    if (!std::isfinite(spectra.n[i]) || !std::isfinite(spectra.k[i])) {
      throw Error(what + ": n or k is not finite at " + ShortNumber(spectra.lambda_nm[i]) + " nm");
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
  return spectra;
}

void CheckFileName(const std::string& name) {
  if (name.empty() || name.find_first_of("\"\n\r") != std::string::npos) {
    throw Error("file name '" + name + "' cannot be written into a material file");
  }
}

std::string XmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// XML comments may not contain "--".
std::string XmlComment(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  std::string out;
  for (char c : text) {
    if (c == '-' && !out.empty() && out.back() == '-') out += ' ';
    out += c;
  }
  if (!out.empty() && out.back() == '-') out += ' ';
  return "<!-- " + out + " -->\n";
}

std::string Range(const ConductorSpectra& s) {
  return ShortNumber(s.lambda_nm.front()) + "-" + ShortNumber(s.lambda_nm.back()) + " nm";
}

}  // namespace

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
                             const std::string& k_file, const std::vector<std::string>& header) {
  CheckFileName(eta_file);
  CheckFileName(k_file);
  std::string out = Comment("pbrt-v4 smooth conductor: " + spectra.material);
  out += Comment("n and k over " + Range(spectra) +
                 " from the spectrum files (wavelength_nm "
                 "value); relative names resolve against the scene file's folder");
  for (const std::string& note : spectra.notes) out += Comment(note);
  for (const std::string& line : header) out += Comment(line);
  out += "Material \"conductor\" \"spectrum eta\" \"" + eta_file + "\" \"spectrum k\" \"" + k_file +
         "\"\n";
  return out;
}

std::string MitsubaBsdfXml(const ConductorSpectra& spectra, const std::string& id,
                           const std::string& eta_file, const std::string& k_file,
                           const std::vector<std::string>& header) {
  CheckFileName(eta_file);
  CheckFileName(k_file);
  std::string out = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
  out += XmlComment("Mitsuba 3 smooth conductor: " + spectra.material);
  out += XmlComment("n (eta) and k over " + Range(spectra) +
                    " from the .spd files (wavelength_nm value); relative names resolve "
                    "against the scene file's folder");
  for (const std::string& note : spectra.notes) out += XmlComment(note);
  for (const std::string& line : header) out += XmlComment(line);
  out += "<bsdf type=\"conductor\" id=\"" + XmlEscape(id) + "\" version=\"3.0.0\">\n";
  out += "    <spectrum name=\"eta\" filename=\"" + XmlEscape(eta_file) + "\"/>\n";
  out += "    <spectrum name=\"k\" filename=\"" + XmlEscape(k_file) + "\"/>\n";
  out += "</bsdf>\n";
  return out;
}

}  // namespace alloycolor::exports
