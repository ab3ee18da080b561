// Tests of what `alloycolor export` writes for renderers.
//  - Spectral files: every export is loaded the way pbrt-v4 and Mitsuba 3 load it, through
//    their reading rules re-implemented from their sources (renderer_readers.h): scenes in
//    the material's folder and in another folder, run from elsewhere; a wavelength grid
//    tighter than floats resolve; fitted models at the ends of their range; names with
//    backslashes and quotes; long comments; negative k.
//  - RGB reductions, against independent computations written here: F0 and F82 from
//    eq. 2-4 with std::complex and the IEC 61966-2-1 matrix; Gulbrandsen's formulas as
//    MaterialX's mx_artistic_ior writes them; the RGB conductor's angular CIEDE2000 on a
//    finer angle grid than the fit's; the gamut limit for golds whose red lies above 1.
//  - MaterialX documents checked with a real XML parser (xmllint) against the node
//    definitions of MaterialX's pbrlib_defs.mtlx and stdlib_defs.mtlx; glTF against the
//    rules of the glTF 2.0 JSON schema (glTF, asset, material,
//    material.pbrMetallicRoughness).
//  - BuildExport: the files of each format, and the F82 and Gulbrandsen documents carrying
//    the fitted numbers into the settings they name.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/export/export_files.h"
#include "alloycolor/export/renderer_materials.h"
#include "alloycolor/export/spectral_export.h"
#include "renderer_readers.h"
#include "test_util.h"

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
namespace rd = testing::readers;
using testing::CountLines;
using testing::DataDir;
using testing::MakeTempDir;
using testing::RunProgram;
using testing::WriteText;

constexpr double kPiTest = 3.14159265358979323846;

// --- helpers -----------------------------------------------------------------------------

// xmllint's answer to an XPath query (a real XML parser); status 0 when well-formed.
struct XmlAnswer {
  int status;
  std::string out;
};
XmlAnswer Xml(const std::string& path, const std::string& xpath) {
  const std::string command = xpath.empty()
                                  ? "xmllint --noout '" + path + "' 2>&1"
                                  : "xmllint --xpath \"" + xpath + "\" '" + path + "' 2>/dev/null";
  XmlAnswer answer{-1, ""};
  std::FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return answer;
  char buf[4096];
  std::size_t got;
  while ((got = std::fread(buf, 1, sizeof buf, pipe)) > 0) answer.out.append(buf, got);
  answer.status = pclose(pipe);
  while (!answer.out.empty() && answer.out.back() == '\n') answer.out.pop_back();
  return answer;
}

// pbrt-v4 loading `scene` (given on its command line) from working directory `cwd`: the
// Material statement's spectra, following Include statements.
struct PbrtLoad {
  std::string error;
  rd::Spectrum eta, k;
};
PbrtLoad LoadPbrtScene(const std::string& scene, const std::string& cwd) {
  PbrtLoad load;
  const std::string search_dir = fs::path(scene).parent_path().string();
  std::vector<std::string> files = {scene};
  while (!files.empty()) {
    const std::string file = files.back();
    files.pop_back();
    const auto text = rd::Slurp(file);
    if (!text) {
      load.error = "cannot open " + file;
      return load;
    }
    std::string error;
    const auto tokens = rd::PbrtTokens(*text, &error);
    if (!tokens) {
      load.error = file + ": " + error;
      return load;
    }
    for (std::size_t i = 0; i < tokens->size(); ++i) {
      const std::string& t = (*tokens)[i];
      if (t == "Include" && i + 1 < tokens->size()) {
        files.push_back(rd::PbrtResolveFilename(search_dir, (*tokens)[i + 1].substr(1), cwd));
      }
      if (t == "Material") {
        if (i + 5 >= tokens->size() || (*tokens)[i + 1] != "\"conductor" ||
            (*tokens)[i + 2] != "\"spectrum eta" || (*tokens)[i + 4] != "\"spectrum k") {
          load.error = "unexpected Material statement";
          return load;
        }
        load.eta = rd::PbrtReadSpectrumFile(
            rd::PbrtResolveFilename(search_dir, (*tokens)[i + 3].substr(1), cwd));
        load.k = rd::PbrtReadSpectrumFile(
            rd::PbrtResolveFilename(search_dir, (*tokens)[i + 5].substr(1), cwd));
        if (!load.eta.ok || !load.k.ok) load.error = load.eta.error + load.k.error;
        return load;
      }
    }
  }
  load.error = "no Material statement";
  return load;
}

// Mitsuba 3 load_file(scene) with `<include filename="material"/>` from `cwd`: both
// Properties::Spectrum and spectrum_from_file on each spectrum file.
struct MitsubaLoad {
  std::string error;
  rd::Spectrum eta, k, eta_spd, k_spd;
};
MitsubaLoad LoadMitsubaScene(const std::string& scene, const std::string& cwd) {
  MitsubaLoad load;
  const std::string scene_dir = fs::path(scene).parent_path().string();
  if (Xml(scene, "").status != 0) {
    load.error = "scene is not well-formed XML";
    return load;
  }
  const XmlAnswer include = Xml(scene, "string(/scene/include/@filename)");
  // load_file prepends the scene's folder; <include> the including file's folder.
  const std::string material = rd::MitsubaResolve({scene_dir, cwd}, include.out);
  const std::string copy = scene_dir + "/.material-for-xmllint.xml";  // a plain path
  fs::copy_file(material, copy, fs::copy_options::overwrite_existing);
  if (Xml(copy, "").status != 0) {
    load.error = "material is not well-formed XML";
    return load;
  }
  const std::vector<std::string> paths = {scene_dir, scene_dir, cwd};
  const std::string eta = Xml(copy, "string(/bsdf/spectrum[@name='eta']/@filename)").out;
  const std::string k = Xml(copy, "string(/bsdf/spectrum[@name='k']/@filename)").out;
  fs::remove(copy);
  load.eta = rd::MitsubaPropertiesSpectrum(rd::MitsubaResolve(paths, eta));
  load.k = rd::MitsubaPropertiesSpectrum(rd::MitsubaResolve(paths, k));
  load.eta_spd = rd::MitsubaSpectrumFromFile(rd::MitsubaResolve(paths, eta));
  load.k_spd = rd::MitsubaSpectrumFromFile(rd::MitsubaResolve(paths, k));
  for (const rd::Spectrum* s : {&load.eta, &load.k, &load.eta_spd, &load.k_spd}) {
    if (!s->ok) load.error += s->error + "; ";
  }
  return load;
}

void WriteScenes(const std::string& dir, const std::string& pbrt_include,
                 const std::string& xml_include) {
  WriteText(dir + "/scene.pbrt", "# test scene\nInclude \"" + pbrt_include + "\"\n");
  WriteText(dir + "/scene.xml",
            "<scene version=\"3.0.0\">\n  <include filename=\"" + xml_include + "\"/>\n</scene>\n");
}

// Both renderers load the export; the values they see equal the source's n, k (float).
void ExpectLoads(const std::string& dir, const std::string& cwd, const NkSpectrum* source,
                 const std::string& what) {
  const PbrtLoad pbrt = LoadPbrtScene(dir + "/scene.pbrt", cwd);
  EXPECT_EQ(pbrt.error, "") << what;
  const MitsubaLoad mitsuba = LoadMitsubaScene(dir + "/scene.xml", cwd);
  EXPECT_EQ(mitsuba.error, "") << what;
  if (!pbrt.error.empty() || !mitsuba.error.empty()) return;
  EXPECT_LE(pbrt.eta.lambda_nm.front(), 360.0) << what;
  EXPECT_GE(pbrt.eta.lambda_nm.back(), 830.0) << what;
  EXPECT_EQ(pbrt.eta.lambda_nm, mitsuba.eta.lambda_nm) << what;
  EXPECT_EQ(mitsuba.eta.lambda_nm, mitsuba.eta_spd.lambda_nm) << what;
  if (source == nullptr) return;
  for (std::size_t i = 0; i < pbrt.eta.lambda_nm.size(); ++i) {
    const double l = pbrt.eta.lambda_nm[i];
    if (l < source->lambda_nm.front() || l > source->lambda_nm.back()) continue;
    const std::complex<double> nk = NkAt(*source, l);
    EXPECT_NEAR(pbrt.eta.value[i], nk.real(), 1e-5 * (1 + nk.real())) << what << " " << l;
    EXPECT_NEAR(pbrt.k.value[i], nk.imag(), 1e-5 * (1 + nk.imag())) << what << " " << l;
  }
}

// --- spectral files through the renderers' readers -------------------------------------

TEST(RendererExportTest, EveryMeasuredMetalLoadsFromItsFolderRunFromElsewhere) {
  const std::string dir = MakeTempDir();
  for (const auto& entry : fs::directory_iterator(DataDir() + "/pure")) {
    const std::string file = entry.path().string();
    const std::string scene_dir = dir + "/" + entry.path().stem().string();
    fs::create_directories(scene_dir);
    const auto run = RunProgram({"export", "--nk", file, "--out", scene_dir + "/metal", "--quiet"});
    ASSERT_EQ(run.status, 0) << run.err;
    WriteScenes(scene_dir, "metal.pbrt", "metal.xml");
    const NkSpectrum nk = ReadNkFile(file);
    ExpectLoads(scene_dir, "/", &nk, file);
  }
  fs::remove_all(dir);
}

TEST(RendererExportTest, SceneInAnotherFolderNeedsSceneDir) {
  const std::string dir = MakeTempDir();
  fs::create_directories(dir + "/materials");
  fs::create_directories(dir + "/scenes");
  const std::string gold = DataDir() + "/pure/Au-Johnson.yml";
  // Without --scene-dir the names are relative to the material's folder, which neither
  // renderer searches when the scene sits elsewhere: the load fails, as it would there.
  ASSERT_EQ(RunProgram({"export", "--nk", gold, "--out", dir + "/materials/au", "--quiet"}).status,
            0);
  WriteScenes(dir + "/scenes", "../materials/au.pbrt", "../materials/au.xml");
  EXPECT_NE(LoadPbrtScene(dir + "/scenes/scene.pbrt", "/").error, "");
  EXPECT_NE(LoadMitsubaScene(dir + "/scenes/scene.xml", "/").error, "");
  // With --scene-dir they are relative to the scene's folder and load from anywhere.
  const auto run = RunProgram({"export", "--nk", gold, "--out", dir + "/materials/au",
                               "--scene-dir", dir + "/scenes", "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(ReadFileText(dir + "/materials/au.pbrt").find("\"../materials/au.eta.spd\""),
            std::string::npos);
  const NkSpectrum nk = ReadNkFile(gold);
  ExpectLoads(dir + "/scenes", "/", &nk, "scene-dir");
  fs::remove_all(dir);
}

TEST(RendererExportTest, WavelengthsTighterThanFloatsAreMerged) {
  const std::string dir = MakeTempDir();
  std::string csv = "lambda_nm,n,k\n";
  for (int l = 360; l <= 830; l += 10) {
    char row[120];
    std::snprintf(row, sizeof row, "%d,%.6f,%.6f\n", l, 0.3 + l / 2000.0, l / 150.0);
    csv += row;
    if (l == 500) {
      for (int i = 1; i <= 4; ++i) {  // 1e-5 nm apart: floats near 500 are 3.05e-5 apart
        std::snprintf(row, sizeof row, "%.5f,%.6f,3.4\n", 500 + i * 1e-5, 0.55 + i * 0.001);
        csv += row;
      }
    }
  }
  WriteText(dir + "/tight.csv", csv);
  const auto run = RunProgram({"export", "--nk", dir + "/tight.csv", "--out", dir + "/tight"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.err.find("merged"), std::string::npos) << run.err;
  EXPECT_NE(ReadFileText(dir + "/tight.eta.spd").find("merged"), std::string::npos);
  WriteScenes(dir, "tight.pbrt", "tight.xml");
  ExpectLoads(dir, "/", nullptr, "tight grid");
  const rd::Spectrum eta = rd::PbrtReadSpectrumFile(dir + "/tight.eta.spd");
  EXPECT_LT(eta.lambda_nm.size(), 48u + 4u);
  fs::remove_all(dir);
}

TEST(RendererExportTest, FittedModelsAtTheEndsOfTheirRangeLoad) {
  const std::string dir = MakeTempDir();
  const std::string model = dir + "/auag.json";
  ASSERT_EQ(RunProgram({"fit", "--data", "Au-Ag", "--out", model, "--quiet"}).status, 0);
  const std::vector<std::vector<std::string>> sources = {
      {"--model", model, "--x", "0"},
      {"--model", model, "--x", "1"},
      {"--data", "Au-Ag", "--method", "paper", "--x", "0"},
      {"--data", "Cu-Zn/dataset-werner-zn.json", "--method", "eps-linear", "--x", "0.7"},
  };
  int i = 0;
  for (const auto& source : sources) {
    const std::string scene_dir = dir + "/s" + std::to_string(i++);
    fs::create_directories(scene_dir);
    std::vector<std::string> args = {"export"};
    args.insert(args.end(), source.begin(), source.end());
    args.insert(args.end(), {"--out", scene_dir + "/m", "--quiet"});
    const auto run = RunProgram(args);
    ASSERT_EQ(run.status, 0) << run.err;
    WriteScenes(scene_dir, "m.pbrt", "m.xml");
    ExpectLoads(scene_dir, "/", nullptr, source[1] + " " + source.back());
  }
  fs::remove_all(dir);
}

TEST(RendererExportTest, NonPositiveNOrNegativeKIsRefusedWithOneLine) {
  const std::string dir = MakeTempDir();
  for (const std::string bad : {"600,0,3", "600,0.5,-0.01", "600,-0.2,3"}) {
    std::string csv = "lambda_nm,n,k\n";
    for (int l = 360; l <= 830; l += 10) {
      csv += l == 600 ? bad + "\n" : std::to_string(l) + ",0.5,3\n";
    }
    WriteText(dir + "/bad.csv", csv);
    const auto run = RunProgram({"export", "--nk", dir + "/bad.csv", "--out", dir + "/bad"});
    EXPECT_EQ(run.status, 2) << bad;
    EXPECT_EQ(CountLines(run.err), 1) << run.err;
    if (bad == "600,0,3") {
      // The reader takes n = 0; the export refuses it, naming the wavelength.
      EXPECT_NE(run.err.find("at 600 nm"), std::string::npos) << run.err;
      EXPECT_NE(run.err.find("n > 0 and k >= 0"), std::string::npos) << run.err;
    } else {
      // The reader refuses negative values itself, naming the line.
      EXPECT_NE(run.err.find("bad.csv:26:"), std::string::npos) << run.err;
    }
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(RendererExportTest, NamesWithBackslashesAndQuotesReadBackExactly) {
  const std::string dir = MakeTempDir();
  const std::string base = "we\"ird\\name";
  const auto run = RunProgram(
      {"export", "--nk", DataDir() + "/pure/Ag-Johnson.yml", "--out", dir + "/" + base, "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  std::string error;
  const auto tokens = rd::PbrtTokens(ReadFileText(dir + "/" + base + ".pbrt"), &error);
  ASSERT_TRUE(tokens.has_value()) << error;
  ASSERT_EQ(tokens->size(), 6u);
  EXPECT_EQ((*tokens)[3], "\"" + base + ".eta.spd");
  EXPECT_EQ((*tokens)[5], "\"" + base + ".k.spd");
  EXPECT_TRUE(rd::PbrtReadSpectrumFile(dir + "/" + base + ".eta.spd").ok);
  fs::copy_file(dir + "/" + base + ".xml", dir + "/plain.xml");
  EXPECT_EQ(Xml(dir + "/plain.xml", "string(/bsdf/spectrum[@name='eta']/@filename)").out,
            base + ".eta.spd");
  fs::remove_all(dir);
}

TEST(RendererExportTest, LongMaterialNamesKeepCommentLinesShort) {
  const std::string dir = MakeTempDir();
  exports::ConductorSpectra spectra;
  spectra.material = std::string(3000, 'x') + " \xc3\xa9" + std::string(3000, 'y');
  spectra.lambda_nm = {360, 600, 830};
  spectra.n = {0.5, 0.4, 0.3};
  spectra.k = {2, 3, 4};
  spectra.notes = {std::string(2000, 'z')};
  WriteText(dir + "/long.spd", exports::SpdText(spectra, true, {std::string(5000, 'h')}));
  std::istringstream lines(ReadFileText(dir + "/long.spd"));
  std::string line;
  while (std::getline(lines, line)) EXPECT_LT(line.size() + 1, 1024u);
  const rd::Spectrum s = rd::MitsubaPropertiesSpectrum(dir + "/long.spd");
  EXPECT_TRUE(s.ok) << s.error;
  EXPECT_EQ(s.lambda_nm.size(), 3u);
  EXPECT_TRUE(rd::PbrtReadSpectrumFile(dir + "/long.spd").ok);
  fs::remove_all(dir);
}

TEST(RendererExportTest, LibraryRefusesNegativeValues) {
  NkSpectrum nk;
  nk.source = "lab.csv";
  nk.lambda_nm = {360, 500, 650, 830};
  nk.n = {0.5, 0.5, 0.5, 0.5};
  nk.k = {3, 3, -1e-3, 3};
  try {
    exports::MeasuredSpectra(nk, "m");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lab.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("650 nm"), std::string::npos) << e.what();
  }
}

// --- RGB reductions against independent computations ----------------------------------

// eq. 2-4 with std::complex: unpolarised reflectance at angle theta.
double Fresnel(std::complex<double> n, double theta_deg) {
  const double c = std::cos(theta_deg * kPiTest / 180.0);
  const double s2 = 1 - c * c;
  const std::complex<double> root = std::sqrt(n * n - s2);
  const double rs = std::norm((c - root) / (c + root));
  const double rp = std::norm((n * n * c - root) / (n * n * c + root));
  return 0.5 * (rs + rp);
}

// IEC 61966-2-1 XYZ -> linear sRGB.
color::RGB SrgbOf(double x, double y, double z) {
  return {3.2406 * x - 1.5372 * y - 0.4986 * z, -0.9689 * x + 1.8758 * y + 0.0415 * z,
          0.0557 * x - 0.2040 * y + 1.0570 * z};
}

// The spectral colour at theta from the colorimeter's weights, reflectance from `Fresnel`.
color::RGB SpectralRgb(const color::Colorimeter& d65,
                       const std::vector<std::complex<double>>& index, double theta_deg) {
  double x = 0, y = 0, z = 0;
  for (std::size_t i = 0; i < index.size(); ++i) {
    const double r = Fresnel(index[i], theta_deg);
    x += d65.wx()[i] * r;
    y += d65.wy()[i] * r;
    z += d65.wz()[i] * r;
  }
  return SrgbOf(x, y, z);
}

double Ch(const color::RGB& c, int i) { return i == 0 ? c.r : (i == 1 ? c.g : c.b); }

struct Material {
  std::string name;
  std::vector<std::complex<double>> index;
};

std::vector<Material> BundledMaterials(const color::Colorimeter& d65) {
  std::vector<Material> out;
  for (const std::string dir : {"pure", "Au-Ag", "Cu-Zn"}) {
    for (const auto& entry : fs::directory_iterator(DataDir() + "/" + dir)) {
      const std::string name = entry.path().filename().string();
      if (entry.path().extension() != ".yml" || name == "about.yml") continue;
      if (name.find("Zn100") != std::string::npos) continue;  // zinc: not a coloured metal
      out.push_back({dir + "/" + name, color::IndexOnGrid(d65, ReadNkFile(entry.path()))});
    }
  }
  return out;
}

struct Fitted {
  Material m;
  exports::RendererMaterials fit;
};

class RendererMaterialsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    d65_ = new color::Colorimeter(color::Colorimeter::Load(DataDir(), "D65", 2));
    fitted_ = new std::vector<Fitted>;
    for (const Material& m : BundledMaterials(*d65_)) {
      fitted_->push_back({m, exports::FitRendererMaterials(*d65_, m.index, m.name)});
    }
  }
  static void TearDownTestSuite() {
    delete d65_;
    delete fitted_;
  }
  static color::Colorimeter* d65_;
  static std::vector<Fitted>* fitted_;
};
color::Colorimeter* RendererMaterialsTest::d65_ = nullptr;
std::vector<Fitted>* RendererMaterialsTest::fitted_ = nullptr;

TEST_F(RendererMaterialsTest, F0AndF82AreTheSpectralColourAt0And82Degrees) {
  for (const auto& [m, fit] : *fitted_) {
    const color::RGB f0 = SpectralRgb(*d65_, m.index, 0.0);
    const color::RGB f82 = SpectralRgb(*d65_, m.index, 82.0);
    // The test's sRGB matrix is rounded to 4 decimals: tolerance 1e-4 relative.
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(Ch(fit.f82.f0, c), Ch(f0, c), 1e-4) << m.name << " channel " << c;
      EXPECT_NEAR(Ch(fit.f82.f82, c), Ch(f82, c), 1e-4) << m.name << " channel " << c;
      // tint = F82 / Schlick(F0, cos 82), and OpenPBR's curve passes through
      // tint * Schlick at mu_bar = 1/7.
      const double mu82 = std::cos(82.0 * kPiTest / 180.0);
      const double schlick82 = Ch(fit.f82.f0, c) + (1 - Ch(fit.f82.f0, c)) * std::pow(1 - mu82, 5);
      EXPECT_NEAR(Ch(fit.f82.tint, c) * schlick82, Ch(fit.f82.f82, c), 1e-12);
      const double mb = 1.0 / 7.0;
      const double schlick_mb = Ch(fit.f82.f0, c) + (1 - Ch(fit.f82.f0, c)) * std::pow(1 - mb, 5);
      EXPECT_NEAR(exports::F82TintFresnel(Ch(fit.f82.f0, c), Ch(fit.f82.tint, c), mb),
                  Ch(fit.f82.tint, c) * schlick_mb, 1e-12);
      EXPECT_NEAR(exports::F82TintFresnel(Ch(fit.f82.f0, c), Ch(fit.f82.tint, c), 1.0),
                  Ch(fit.f82.f0, c), 1e-12);
    }
  }
}

TEST_F(RendererMaterialsTest, GulbrandsenRAndGGiveBackF0AndTheEdgeColour) {
  for (const auto& [m, fit] : *fitted_) {
    for (int c = 0; c < 3; ++c) {
      // mx_artistic_ior (MaterialX pbrlib), written out here.
      const double r = Ch(fit.gulbrandsen.r, c), g = Ch(fit.gulbrandsen.g, c);
      const double n_min = (1 - r) / (1 + r);
      const double n_max = (1 + std::sqrt(r)) / (1 - std::sqrt(r));
      const double n = n_max * (1 - g) + n_min * g;
      const double k =
          std::sqrt(std::max(0.0, ((n + 1) * (n + 1) * r - (n - 1) * (n - 1)) / (1 - r)));
      EXPECT_NEAR(Fresnel({n, k}, 0.0), r, 1e-9) << m.name;
      if (!fit.gulbrandsen.r_clamped[c]) {
        EXPECT_NEAR(r, Ch(fit.f82.f0, c), 1e-12) << m.name;
      } else {
        EXPECT_GT(Ch(fit.f82.f0, c), 0.99) << m.name;
      }
      if (!fit.gulbrandsen.g_clamped[c]) {
        EXPECT_NEAR(Fresnel({n, k}, 82.0), Ch(fit.f82.f82, c), 1e-6) << m.name << " " << c;
      }
    }
  }
}

double MaxDeltaE(const color::Colorimeter& d65, const std::vector<std::complex<double>>& index,
                 const std::array<std::complex<double>, 3>& rgb_index, double step_deg,
                 double* at_deg = nullptr) {
  double worst = 0;
  for (double theta = 0; theta <= 85.0 + 1e-9; theta += step_deg) {
    const color::RGB truth = SpectralRgb(d65, index, theta);
    const color::RGB approx{Fresnel(rgb_index[0], theta), Fresnel(rgb_index[1], theta),
                            Fresnel(rgb_index[2], theta)};
    const double de =
        color::DeltaE00(color::LabFromXYZ(color::XYZFromLinearSRGB(truth), d65.White()),
                        color::LabFromXYZ(color::XYZFromLinearSRGB(approx), d65.White()));
    if (de > worst) {
      worst = de;
      if (at_deg) *at_deg = theta;
    }
  }
  return worst;
}

// The smallest CIEDE2000 any colour with every channel <= 1 has from the spectral colour
// at normal incidence (a grid search): no conductor, whose R <= 1, can do better.
double GamutLimitAtNormal(const color::Colorimeter& d65,
                          const std::vector<std::complex<double>>& index) {
  const color::RGB f0 = SpectralRgb(d65, index, 0.0);
  const color::Lab lab = color::LabFromXYZ(color::XYZFromLinearSRGB(f0), d65.White());
  double best = 1e9;
  for (double g = std::min(f0.g, 1.0) - 0.08; g <= std::min(f0.g, 1.0) + 1e-9; g += 0.0005) {
    for (double b = f0.b - 0.08; b <= f0.b + 0.02; b += 0.0005) {
      const color::RGB c{std::min(f0.r, 1.0), g, b};
      best = std::min(
          best, color::DeltaE00(lab, color::LabFromXYZ(color::XYZFromLinearSRGB(c), d65.White())));
    }
  }
  return best;
}

TEST_F(RendererMaterialsTest, RgbConductorIsWithinItsReportedErrorAndBelowOne) {
  for (const auto& [m, fit] : *fitted_) {
    const auto& c = fit.rgb_conductor;
    const std::array<std::complex<double>, 3> rgb_index = {std::complex<double>(c.eta.r, c.k.r),
                                                           std::complex<double>(c.eta.g, c.k.g),
                                                           std::complex<double>(c.eta.b, c.k.b)};
    // On the fit's grid the figure is reproduced; on a grid four times finer it holds to
    // within 0.02 (the curves are smooth).
    EXPECT_NEAR(MaxDeltaE(*d65_, m.index, rgb_index, 0.5), c.error.max_delta_e00, 2e-3) << m.name;
    EXPECT_LE(MaxDeltaE(*d65_, m.index, rgb_index, 0.125), c.error.max_delta_e00 + 0.02) << m.name;
    const double limit = GamutLimitAtNormal(*d65_, m.index);
    if (SpectralRgb(*d65_, m.index, 0.0).r <= 1.0) {
      EXPECT_LT(c.error.max_delta_e00, 1.0) << m.name;
    } else {
      // Gold's red lies above 1 in linear sRGB: the fit reaches the gamut limit.
      EXPECT_LT(c.error.max_delta_e00, std::max(1.0, limit + 0.02)) << m.name << " limit " << limit;
    }
    // Not a naive average: n, k taken at one wavelength per channel do worse.
    const auto at = [&](double l) {
      const std::vector<double>& grid = d65_->lambda_nm();
      std::size_t i = 0;
      while (i + 1 < grid.size() && grid[i] < l) ++i;
      return m.index[i];
    };
    const double naive = MaxDeltaE(*d65_, m.index, {at(610), at(550), at(465)}, 0.5);
    EXPECT_LT(c.error.max_delta_e00, naive) << m.name;
  }
}

// --- files for RGB renderers --------------------------------------------------------------

std::vector<double> Numbers(const std::string& text) {
  std::vector<double> out;
  std::string t = text;
  for (char& ch : t) {
    if (ch == ',') ch = ' ';
  }
  std::istringstream in(t);
  double v;
  while (in >> v) out.push_back(v);
  return out;
}

TEST(RendererFilesTest, EveryFormatWritesLoadableFilesThatStateTheirColourSpace) {
  const std::string dir = MakeTempDir();
  const std::vector<std::vector<std::string>> sources = {
      {"--nk", DataDir() + "/pure/Cu-Johnson.yml"},
      {"--data", "Au-Ag", "--method", "paper", "--x", "0.5"},
  };
  int i = 0;
  for (const auto& source : sources) {
    const std::string prefix = dir + "/m" + std::to_string(i++);
    std::vector<std::string> args = {"export"};
    args.insert(args.end(), source.begin(), source.end());
    args.insert(args.end(), {"--format", "all", "--out", prefix, "--json", "--roughness", "0.25"});
    const auto run = RunProgram(args);
    ASSERT_EQ(run.status, 0) << run.err;
    // stderr: what each approximation loses.
    for (const std::string what : {"rgb-conductor", "f82", "gulbrandsen", "gltf"}) {
      EXPECT_NE(run.err.find("alloycolor: " + what), std::string::npos) << run.err;
    }
    EXPECT_NE(run.err.find("largest CIEDE2000"), std::string::npos);
    const nlohmann::json j = nlohmann::json::parse(run.out);
    EXPECT_EQ(j["files"].size(), 10u);
    for (const std::string key : {"rgb_conductor", "f82_tint", "gulbrandsen", "schlick_f0"}) {
      ASSERT_TRUE(j.contains(key)) << key;
      const double de = j[key]["error"]["max_delta_e00"];
      EXPECT_TRUE(std::isfinite(de) && de >= 0) << key;
    }
    EXPECT_LT(j["rgb_conductor"]["error"]["max_delta_e00"].get<double>(), 1.0);
    const std::vector<double> eta = j["rgb_conductor"]["eta"];
    const std::vector<double> k = j["rgb_conductor"]["k"];

    // Mitsuba 3 RGB conductor.
    const std::string rgb_xml = prefix + ".rgb.xml";
    EXPECT_EQ(Xml(rgb_xml, "").status, 0);
    EXPECT_EQ(Xml(rgb_xml, "string(/bsdf/@type)").out, "conductor");
    const std::vector<double> x_eta =
        Numbers(Xml(rgb_xml, "string(/bsdf/rgb[@name='eta']/@value)").out);
    const std::vector<double> x_k =
        Numbers(Xml(rgb_xml, "string(/bsdf/rgb[@name='k']/@value)").out);
    ASSERT_EQ(x_eta.size(), 3u);
    ASSERT_EQ(x_k.size(), 3u);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(x_eta[c], eta[c], 1e-5 * eta[c]);
      EXPECT_NEAR(x_k[c], k[c], 1e-5 * k[c]);
    }
    EXPECT_NE(ReadFileText(rgb_xml).find("Rec. 709"), std::string::npos);
    EXPECT_NE(ReadFileText(prefix + ".blender.py").find("PHYSICAL_CONDUCTOR"), std::string::npos);

    // MaterialX: well-formed, every element and input as the node definitions say
    // (pbrlib_defs.mtlx ND_conductor_bsdf, ND_surface; stdlib_defs.mtlx ND_surfacematerial).
    const std::string mtlx = prefix + ".mtlx";
    EXPECT_EQ(Xml(mtlx, "").status, 0);
    EXPECT_EQ(Xml(mtlx, "string(/materialx/@colorspace)").out, "lin_rec709");
    EXPECT_TRUE(
        std::regex_match(Xml(mtlx, "string(/materialx/@version)").out, std::regex("1\\.3[89]")));
    const std::map<std::string, std::map<std::string, std::string>> nodedefs = {
        {"conductor_bsdf",
         {{"weight", "float"},
          {"ior", "color3"},
          {"extinction", "color3"},
          {"roughness", "vector2"},
          {"retroreflective", "boolean"},
          {"thinfilm_thickness", "float"},
          {"thinfilm_ior", "float"},
          {"normal", "vector3"},
          {"tangent", "vector3"},
          {"distribution", "string"}}},
        {"surface",
         {{"bsdf", "BSDF"}, {"edf", "EDF"}, {"opacity", "float"}, {"thin_walled", "boolean"}}},
        {"surfacematerial",
         {{"surfaceshader", "surfaceshader"},
          {"backsurfaceshader", "surfaceshader"},
          {"displacementshader", "displacementshader"}}}};
    const std::map<std::string, std::string> output_type = {
        {"conductor_bsdf", "BSDF"}, {"surface", "surfaceshader"}, {"surfacematerial", "material"}};
    EXPECT_EQ(Xml(mtlx, "count(/materialx/*)").out, "3");
    std::map<std::string, std::string> names;
    for (const auto& [node, inputs] : nodedefs) {
      EXPECT_EQ(Xml(mtlx, "count(/materialx/" + node + ")").out, "1") << node;
      EXPECT_EQ(Xml(mtlx, "string(/materialx/" + node + "/@type)").out, output_type.at(node));
      const std::string name = Xml(mtlx, "string(/materialx/" + node + "/@name)").out;
      EXPECT_TRUE(std::regex_match(name, std::regex("[A-Za-z_][A-Za-z0-9_]*"))) << name;
      names[node] = name;
      const int count = std::stoi(Xml(mtlx, "count(/materialx/" + node + "/input)").out);
      for (int n = 1; n <= count; ++n) {
        const std::string base = "/materialx/" + node + "/input[" + std::to_string(n) + "]";
        const std::string input = Xml(mtlx, "string(" + base + "/@name)").out;
        ASSERT_TRUE(inputs.count(input)) << node << " has no input " << input;
        EXPECT_EQ(Xml(mtlx, "string(" + base + "/@type)").out, inputs.at(input)) << input;
      }
    }
    EXPECT_EQ(Xml(mtlx, "string(/materialx/surface/input[@name='bsdf']/@nodename)").out,
              names["conductor_bsdf"]);
    EXPECT_EQ(
        Xml(mtlx, "string(/materialx/surfacematerial/input[@name='surfaceshader']/@nodename)").out,
        names["surface"]);
    const std::vector<double> m_ior =
        Numbers(Xml(mtlx, "string(/materialx/conductor_bsdf/input[@name='ior']/@value)").out);
    const std::vector<double> m_rough =
        Numbers(Xml(mtlx, "string(/materialx/conductor_bsdf/input[@name='roughness']/@value)").out);
    ASSERT_EQ(m_ior.size(), 3u);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m_ior[c], eta[c], 1e-5 * eta[c]);
    EXPECT_EQ(m_rough, (std::vector<double>{0.25, 0.25}));

    // glTF 2.0: the schema's rules for glTF, asset, material, pbrMetallicRoughness.
    const nlohmann::json g = nlohmann::json::parse(ReadFileText(prefix + ".gltf"));
    ASSERT_TRUE(g.is_object());
    ASSERT_TRUE(g.contains("asset"));
    EXPECT_TRUE(std::regex_match(g["asset"]["version"].get<std::string>(),
                                 std::regex("^(0|[1-9][0-9]{0,8})\\.(0|[1-9][0-9]{0,8})$")));
    EXPECT_EQ(g["asset"]["version"], "2.0");
    ASSERT_TRUE(g["materials"].is_array());
    ASSERT_GE(g["materials"].size(), 1u);
    for (const auto& [key, value] : g.items()) {
      EXPECT_TRUE(key == "asset" || key == "materials" || key == "extras") << key;
      (void)value;
    }
    const auto& mat = g["materials"][0];
    EXPECT_TRUE(mat["name"].is_string());
    const auto& pbr = mat["pbrMetallicRoughness"];
    ASSERT_TRUE(pbr["baseColorFactor"].is_array());
    ASSERT_EQ(pbr["baseColorFactor"].size(), 4u);
    for (const auto& v : pbr["baseColorFactor"]) {
      EXPECT_TRUE(v.is_number());
      EXPECT_GE(v.get<double>(), 0.0);
      EXPECT_LE(v.get<double>(), 1.0);
    }
    EXPECT_EQ(pbr["metallicFactor"].get<double>(), 1.0);
    EXPECT_EQ(pbr["roughnessFactor"].get<double>(), 0.25);
    const std::vector<double> f0 = j["f82_tint"]["f0"];
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(pbr["baseColorFactor"][c].get<double>(), std::clamp(f0[c], 0.0, 1.0), 1e-12);
    }
    EXPECT_NE(mat["extras"]["colour_space"].get<std::string>().find("Rec. 709"), std::string::npos);

    // f82 and gulbrandsen files.
    const nlohmann::json f82 = nlohmann::json::parse(ReadFileText(prefix + ".f82.json"));
    EXPECT_EQ(f82["openpbr"]["base_color"], j["f82_tint"]["f0"]);
    EXPECT_EQ(f82["openpbr"]["specular_color"], j["f82_tint"]["tint"]);
    const nlohmann::json gb = nlohmann::json::parse(ReadFileText(prefix + ".gulbrandsen.json"));
    EXPECT_EQ(gb["standard_surface"]["base_color"], j["gulbrandsen"]["r"]);
    EXPECT_EQ(gb["materialx_artistic_ior"]["edge_color"], j["gulbrandsen"]["g"]);
  }
  fs::remove_all(dir);
}

TEST(BuildExportTest, EachFormatBuildsItsFiles) {
  const color::Colorimeter d65 = color::Colorimeter::Load(DataDir(), "D65", 2);
  const exports::ExportMaterial gold =
      exports::MeasuredExportMaterial(d65, ReadNkFile(DataDir() + "/pure/Au-Johnson.yml"));
  EXPECT_EQ(gold.id, "alloycolor_Au-Johnson");
  const std::map<std::string, std::vector<std::string>> suffixes = {
      {"spd", {".eta.spd", ".k.spd", ".pbrt", ".xml"}},
      {"rgb-conductor", {".rgb.xml", ".blender.py"}},
      {"f82", {".f82.json"}},
      {"gulbrandsen", {".gulbrandsen.json"}},
      {"materialx", {".mtlx"}},
      {"gltf", {".gltf"}}};
  std::vector<std::string> all;
  for (const std::string& format : exports::ExportFormats()) {
    if (format == "all" || exports::ExportFormatCoversRange(format)) continue;
    for (const std::string& suffix : suffixes.at(format)) all.push_back("p" + suffix);
  }
  for (const std::string& format : exports::ExportFormats()) {
    // A table over an alloy's range (blender_table_test.cc) is refused for measured n, k.
    if (exports::ExportFormatCoversRange(format)) continue;
    const exports::ExportFiles e = exports::BuildExport(d65, gold, "p", {format, "", 0.0});
    std::vector<std::string> paths;
    for (const OutputFile& f : e.files) paths.push_back(f.path);
    std::vector<std::string> expected = all;
    if (format != "all") {
      expected.clear();
      for (const std::string& suffix : suffixes.at(format)) expected.push_back("p" + suffix);
    }
    EXPECT_EQ(paths, expected) << format;
    EXPECT_EQ(e.summary["files"], nlohmann::json(paths)) << format;
    EXPECT_EQ(e.summary["format"], format);
    if (format != "all") continue;
    const auto document = [&e](const std::string& path) {
      for (const OutputFile& f : e.files) {
        if (f.path == path) return nlohmann::json::parse(f.contents);
      }
      return nlohmann::json();
    };
    const nlohmann::json f82 = document("p.f82.json");
    EXPECT_EQ(f82["openpbr"]["base_color"], e.summary["f82_tint"]["f0"]);
    EXPECT_EQ(f82["openpbr"]["specular_color"], e.summary["f82_tint"]["tint"]);
    EXPECT_EQ(f82["blender_metallic_f82"]["Edge Tint"], e.summary["f82_tint"]["tint"]);
    const nlohmann::json g = document("p.gulbrandsen.json");
    EXPECT_EQ(g["standard_surface"]["base_color"], e.summary["gulbrandsen"]["r"]);
    EXPECT_EQ(g["materialx_artistic_ior"]["edge_color"], e.summary["gulbrandsen"]["g"]);
    EXPECT_EQ(g["material"], gold.spectra.material);
  }
}

TEST(BuildExportTest, BadSettingsAreNamed) {
  const color::Colorimeter d65 = color::Colorimeter::Load(DataDir(), "D65", 2);
  const exports::ExportMaterial gold =
      exports::MeasuredExportMaterial(d65, ReadNkFile(DataDir() + "/pure/Au-Johnson.yml"));
  const std::vector<std::pair<exports::ExportSettings, std::string>> cases = {
      {{"obj", "", 0.0}, "format: "},
      {{"gltf", "", 1.5}, "roughness: "},
      {{"gltf", "", std::nan("")}, "roughness: "},
      {{"spd", DataDir() + "/no-such-folder", 0.0}, "scene_dir: "}};
  for (const auto& [settings, start] : cases) {
    try {
      exports::BuildExport(d65, gold, "p", settings);
      ADD_FAILURE() << start;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(start, 0), 0u) << e.what();
    }
  }
}

TEST(RendererFilesTest, BadOptionsAreRefusedWithOneLine) {
  const std::string dir = MakeTempDir();
  const std::string gold = DataDir() + "/pure/Au-Johnson.yml";
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"export", "--nk", gold, "--format", "obj", "--out", dir + "/a"},
           {"export", "--nk", gold, "--format", "gltf", "--roughness", "1.5", "--out", dir + "/a"},
           {"export", "--nk", gold, "--scene-dir", dir + "/none", "--out", dir + "/a"}}) {
    const auto run = RunProgram(args);
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(CountLines(run.err), 1) << run.err;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace alloycolor
