// Tests of the readers for files as labs and instruments export them (core/io.h): one
// spectrum (the bundled Rioux Au50Ag50, read by the YAML reader) written in every layout
// the delimited-text reader detects must give back the same n, k and the same colour;
// every ambiguous file must be refused with one line saying how to state what it is.
// The layouts are generated here from the reference rows; the unit conversions the files
// carry are the definitions (1 um = 1000 nm, 1 A = 0.1 nm, lambda = hc/E with
// hc = 1239.84198 eV nm, lambda_nm = 1e7 / wavenumber_cm-1, eps = (n + ik)^2).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/spectrum.h"
#include "test_util.h"

namespace alloycolor {
namespace {

using color::Colorimeter;
using testing::DataDir;
using testing::ErrorOf;
using ::testing::HasSubstr;
using testing::MakeTempDir;
using testing::RunProgram;
using testing::WriteText;

constexpr double kHcEvNm = 1239.8419843320026;  // CODATA 2018, exact from h, c, e

std::string Reference() { return DataDir() + "/Au-Ag/Rioux-Au50Ag50.yml"; }

// One row of a generated file: the abscissa in the file's unit, then two values.
using RowText = std::function<std::string(double lambda_nm, double n, double k)>;

// 9 significant digits, as instruments write.
std::string G(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", value);
  return buffer;
}

struct Layout {
  const char* name;
  const char* file;    // file name (its extension chooses the reader)
  std::string head;    // everything before the first row
  RowText row;         // one row, with its line end
  bool descending_nm;  // rows in decreasing order of wavelength
  NkColumns columns;   // the columns to choose, if any
};

double Eps1(double n, double k) { return n * n - k * k; }
double Eps2(double n, double k) { return 2 * n * k; }

std::vector<Layout> Layouts() {
  const auto nm = [](const char* sep, const char* end) {
    return [=](double l, double n, double k) { return G(l) + sep + G(n) + sep + G(k) + end; };
  };
  std::vector<Layout> layouts = {
      {"today's csv", "a.csv", "lambda_nm,n,k\n", nm(",", "\n"), false, {}},
      {"semicolon, descending", "b.csv", "Wavelength (nm);n;k\n", nm(";", "\n"), true, {}},
      {"tab, um",
       "c.tsv",
       "wl_um\tn\tk\n",
       [](double l, double n, double k) { return G(l / 1000) + "\t" + G(n) + "\t" + G(k) + "\n"; },
       false,
       {}},
      {"whitespace, um with micro sign",
       "d.dat",
       "Wavelength (\xC2\xB5m)   n   k\n",
       [](double l, double n, double k) {
         return "  " + G(l / 1000) + "   " + G(n) + "  " + G(k) + "\n";
       },
       true,
       {}},
      {"angstrom",
       "e.csv",
       "lambda (\xC3\x85),n,k\n",
       [](double l, double n, double k) { return G(l * 10) + "," + G(n) + "," + G(k) + "\n"; },
       false,
       {}},
      {"eV, e1 e2, ascending energy",
       "f.txt",
       "Energy (eV),e1,e2\n",
       [](double l, double n, double k) {
         return G(kHcEvNm / l) + "," + G(Eps1(n, k)) + "," + G(Eps2(n, k)) + "\n";
       },
       true,
       {}},
      {"eV, epsilon_real/imag, descending energy",
       "g.dat",
       "eV epsilon_real epsilon_imag\n",
       [](double l, double n, double k) {
         return G(kHcEvNm / l) + " " + G(Eps1(n, k)) + " " + G(Eps2(n, k)) + "\n";
       },
       false,
       {}},
      {"wavenumber, eps1 eps2, tab",
       "h.txt",
       "wavenumber (cm-1)\teps1\teps2\n",
       [](double l, double n, double k) {
         return G(1e7 / l) + "\t" + G(Eps1(n, k)) + "\t" + G(Eps2(n, k)) + "\n";
       },
       true,
       {}},
      {"photon energy [eV], er ei, semicolon",
       "i.csv",
       "Photon energy [eV];er;ei\n",
       [](double l, double n, double k) {
         return G(kHcEvNm / l) + ";" + G(Eps1(n, k)) + ";" + G(Eps2(n, k)) + "\n";
       },
       false,
       {}},
      {"BOM, CRLF, comments, title lines",
       "j.csv",
       "\xEF\xBB\xBF# exported by a spectrometer\r\nAu50Ag50 film, sample 3\r\n"
       "Measured 2024-05-01\r\nInfo,2024\r\n# header follows\r\nWavelength (nm),n,k\r\n",
       nm(",", "\r\n"),
       false,
       {}},
      {"trailing delimiters", "k.csv", "lambda_nm,n,k,\n", nm(",", ",\n"), false, {}},
      {"header in a comment",
       "l.dat",
       "# wl_um n k\n",
       [](double l, double n, double k) { return G(l / 1000) + " " + G(n) + " " + G(k) + "\n"; },
       false,
       {}},
      {"Re/Im eps with the Greek letter",
       "m.tsv",
       "E (eV)\tRe(\xCE\xB5)\tIm(\xCE\xB5)\n",
       [](double l, double n, double k) {
         return G(kHcEvNm / l) + "\t" + G(Eps1(n, k)) + "\t" + G(Eps2(n, k)) + "\n";
       },
       false,
       {}},
  };
  // A European spreadsheet: semicolons and decimal commas, a German header.
  layouts.push_back({"decimal comma",
                     "p.csv",
                     "Wellenl\xC3\xA4nge (nm);n;k\n",
                     [](double l, double n, double k) {
                       std::string row = G(l) + ";" + G(n) + ";" + G(k) + "\n";
                       for (char& c : row) c = c == '.' ? ',' : c;
                       return row;
                     },
                     false,
                     {}});
  // The ellipsometer export: two title lines, several samples' n,k pairs, CRLF, a
  // trailing comma on every line; the reference is sample 12, chosen by name or number.
  const RowText multi = [](double l, double n, double k) {
    return G(l) + "," + G(1.5 * n) + "," + G(0.5 * k) + "," + G(n) + "," + G(k) + ",\r\n";
  };
  const std::string multi_head =
      "Ellipsometry export,\r\nProject AuAg 2024,\r\nWavelength(nm),n6,k6,n12,k12,\r\n";
  layouts.push_back({"multi-sample by name", "n.csv", multi_head, multi, true, {"n12", "k12"}});
  layouts.push_back({"multi-sample by number", "o.csv", multi_head, multi, true, {"4", "5"}});
  return layouts;
}

class LabFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = MakeTempDir();
    reference_ = ReadNkFile(Reference());
  }
  // The reference rows in the layout's text.
  std::string Write(const Layout& layout) const {
    std::string text = layout.head;
    const std::size_t count = reference_.lambda_nm.size();
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t j = layout.descending_nm ? count - 1 - i : i;
      text += layout.row(reference_.lambda_nm[j], reference_.n[j], reference_.k[j]);
    }
    const std::string path = dir_ + "/" + layout.file;
    WriteText(path, text);
    return path;
  }
  std::string dir_;
  NkSpectrum reference_;
};

TEST_F(LabFilesTest, EveryLayoutGivesTheSameNkAndColour) {
  const Colorimeter colorimeter = Colorimeter::Load(DataDir(), "D65", 2);
  const color::XYZ white = colorimeter.White();
  const color::Lab reference_lab = color::LabFromXYZ(
      color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, reference_), 0), white);
  for (const Layout& layout : Layouts()) {
    SCOPED_TRACE(layout.name);
    const std::string path = Write(layout);
    std::vector<std::string> warnings;
    NkSpectrum nk;
    ASSERT_NO_THROW(nk = ReadNkFile(path, layout.columns, &warnings));
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    ASSERT_EQ(nk.lambda_nm.size(), reference_.lambda_nm.size());
    // The files carry 9 significant digits: wavelengths agree to 1e-8 relative, n and k
    // to 1e-6 (the eps files lose a little more where n << k: n = eps2 / 2k).
    for (std::size_t i = 0; i < nk.lambda_nm.size(); ++i) {
      EXPECT_NEAR(nk.lambda_nm[i], reference_.lambda_nm[i], 1e-8 * reference_.lambda_nm[i]);
      EXPECT_NEAR(nk.n[i], reference_.n[i], 1e-6) << nk.lambda_nm[i];
      EXPECT_NEAR(nk.k[i], reference_.k[i], 1e-6) << nk.lambda_nm[i];
    }
    const color::Lab lab = color::LabFromXYZ(
        color::MaterialXYZ(colorimeter, color::IndexOnGrid(colorimeter, nk), 0), white);
    EXPECT_LT(color::DeltaE00(lab, reference_lab), 0.02);
  }
}

TEST_F(LabFilesTest, RepeatedWavelengthInATextFileIsAveragedWithWarning) {
  const std::string path = dir_ + "/repeat.dat";
  WriteText(path, "Energy (eV) n k\n3.0 1 2\n2.5 1 2\n2.5 3 4\n2.0 1 2\n");
  std::vector<std::string> warnings;
  const NkSpectrum nk = ReadNkFile(path, &warnings);
  ASSERT_EQ(nk.lambda_nm.size(), 3u);
  EXPECT_NEAR(nk.lambda_nm[1], kHcEvNm / 2.5, 1e-9);
  EXPECT_DOUBLE_EQ(nk.n[1], 2);
  EXPECT_DOUBLE_EQ(nk.k[1], 3);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr(path + ":3: Energy (eV) = 2.5 is given 2 times"));
}

TEST_F(LabFilesTest, EpsilonConvertsWithEquations13And14) {
  // eps = -16 + 0.8i (n = 0.1, k = 4 by hand: n^2 - k^2 = -15.99, 2nk = 0.8 gives
  // n = sqrt((|eps| + eps1)/2) with |eps| = sqrt(256.64) = 16.0199875...).
  const std::string path = dir_ + "/eps.csv";
  WriteText(path, "lambda_nm,e1,e2\n500,-15.99,0.8\n600,3,0\n");
  const NkSpectrum nk = ReadNkFile(path);
  EXPECT_NEAR(nk.n[0], 0.1, 1e-12);
  EXPECT_NEAR(nk.k[0], 4.0, 1e-12);
  EXPECT_NEAR(nk.n[1], std::sqrt(3.0), 1e-12);  // a dielectric: k = 0
  EXPECT_NEAR(nk.k[1], 0.0, 1e-12);
}

TEST_F(LabFilesTest, AmbiguousOrBadFilesAreRefusedWithAdvice) {
  struct Case {
    const char* name;
    const char* text;
    NkColumns columns;
    std::vector<const char*> expected;
  };
  const Case cases[] = {
      {"headerless.csv", "400,0.1,2\n500,0.2,3\n", {}, {":1: no header line", "wavelength_nm,n,k"}},
      {"headerless.dat", "# measured\n400 0.1 2\n500 0.2 3\n", {}, {":2: no header line"}},
      {"no_unit.csv", "Wavelength,n,k\n400,1,2\n500,1,2\n", {}, {":1:", "gives no unit"}},
      {"mm.csv", "wavelength (mm),n,k\n400,1,2\n500,1,2\n", {}, {"the unit 'mm', not one known"}},
      {"energy_nm.csv", "energy (nm),n,k\n400,1,2\n500,1,2\n", {}, {"do not match"}},
      {"no_abscissa.csv", "x,n,k\n400,1,2\n500,1,2\n", {}, {"names no wavelength, energy"}},
      {"two_pairs.csv",
       "Wavelength(nm),n6,k6,n12,k12\n400,1,2,1,2\n500,1,2,1,2\n",
       {},
       {":1: the header holds 2 column pairs (n6/k6, n12/k12)", "--columns N,K", "\"columns\""}},
      {"no_pair.csv",
       "lambda_nm,a,b\n400,1,2\n500,1,2\n",
       {},
       {"no n,k (or eps1,eps2) column pair"}},
      {"k_alone.csv", "lambda_nm,k\n400,1\n500,1\n", {}, {"no n,k (or eps1,eps2) column pair"}},
      {"no_such_column.csv",
       "lambda_nm,n,k\n400,1,2\n500,1,2\n",
       {"n6", "k6"},
       {"no column named 'n6'"}},
      {"column_zero.csv", "lambda_nm,n,k\n400,1,2\n500,1,2\n", {"0", "3"}, {"does not exist"}},
      {"column_four.csv", "lambda_nm,n,k\n400,1,2\n500,1,2\n", {"2", "4"}, {"does not exist"}},
      {"column_abscissa.csv", "lambda_nm,n,k\n400,1,2\n500,1,2\n", {"1", "3"}, {"the abscissa"}},
      {"mixed.csv",
       "lambda_nm,e1,e2,n,k\n400,1,2,1,2\n500,1,2,1,2\n",
       {"e1", "k"},
       {"neither n and k nor eps1 and eps2"}},
      {"negative_eps2.csv",
       "lambda_nm,e1,e2\n400,-10,1\n500,-10,-1\n",
       {},
       {":3: e2 = -1 is negative"}},
      {"width.csv", "lambda_nm,n,k\n400,1,2,5\n500,1,2,5\n", {}, {":2: expected 3 columns"}},
      {"order.csv", "Energy (eV),n,k\n2,1,2\n3,1,2\n2.5,1,2\n", {}, {":4:", "does not increase"}},
      {"utf16.csv", "\xFF\xFEl\0a\0", {}, {":1: the file is UTF-16"}},
      {"words.csv", "Title\nlambda_nm,n,k\n", {}, {":1: no data rows"}},
      {"gap.csv", "lambda_nm,n,k\n400,1,2\n500,,2\n", {}, {":3: cannot parse number ''"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = dir_ + "/" + c.name;
    WriteText(path,
              std::string(c.text, std::string(c.name) == "utf16.csv" ? 6 : std::strlen(c.text)));
    const std::string message = ErrorOf([&] { ReadNkFile(path, c.columns); });
    EXPECT_THAT(message, HasSubstr(path));
    for (const char* expected : c.expected) EXPECT_THAT(message, HasSubstr(expected));
  }
  const std::string yaml = Reference();
  EXPECT_THAT(ErrorOf([&] {
                ReadNkFile(yaml, NkColumns{"n", "k"});
              }),
              HasSubstr("applies to delimited text files"));
  EXPECT_THAT(ErrorOf([] { ParseNkColumns("n6"); }), HasSubstr("expected N,K"));
  EXPECT_THAT(ErrorOf([] { ParseNkColumns("n6,k6,x"); }), HasSubstr("expected N,K"));
  EXPECT_THAT(ErrorOf([] { ParseNkColumns(",k6"); }), HasSubstr("expected N,K"));
  EXPECT_EQ(ParseNkColumns(" n6 , k6 ").n, "n6");
  EXPECT_EQ(ParseNkColumns(" n6 , k6 ").k, "k6");
}

TEST_F(LabFilesTest, NAndKFromTwoYamlFiles) {
  std::string n_text = "DATA:\n  - type: tabulated n\n    data: |\n";
  std::string k_text = "DATA:\n  - type: tabulated k\n    data: |\n";
  for (std::size_t i = 0; i < reference_.lambda_nm.size(); ++i) {
    n_text += "        " + G(reference_.lambda_nm[i] / 1000) + " " + G(reference_.n[i]) + "\n";
    k_text += "        " + G(reference_.lambda_nm[i] / 1000) + " " + G(reference_.k[i]) + "\n";
  }
  const std::string n_path = dir_ + "/n.yml";
  const std::string k_path = dir_ + "/k.yml";
  WriteText(n_path, n_text);
  WriteText(k_path, k_text);
  const NkSpectrum nk = ReadNkPair(n_path, k_path);
  ASSERT_EQ(nk.lambda_nm.size(), reference_.lambda_nm.size());
  for (std::size_t i = 0; i < nk.lambda_nm.size(); ++i) {
    EXPECT_NEAR(nk.n[i], reference_.n[i], 1e-6);
    EXPECT_NEAR(nk.k[i], reference_.k[i], 1e-6);
  }
  EXPECT_EQ(nk.source, n_path);
  // Each file alone says how to pair it; swapped files are refused.
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(n_path); }), HasSubstr("\"n_file\" and \"k_file\""));
  EXPECT_THAT(ErrorOf([&] { ReadNkPair(k_path, n_path); }),
              HasSubstr(k_path + ":2: DATA holds 'tabulated k'; expected 'tabulated n' alone"));
  EXPECT_THAT(ErrorOf([&] { ReadNkPair(n_path, Reference()); }),
              HasSubstr("expected 'tabulated k' alone"));
}

TEST_F(LabFilesTest, ProgramReadsTheInstrumentExportWithColumns) {
  const Layout multi = Layouts().back();
  const std::string path = Write(multi);
  const auto color_json = [](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"color", "--json", "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto run = RunProgram(args);
    EXPECT_EQ(run.status, 0) << run.err;
    return run.status == 0 ? nlohmann::json::parse(run.out) : nlohmann::json();
  };
  const nlohmann::json reference = color_json({"--nk", Reference()});
  for (const char* columns : {"n12,k12", "4,5"}) {
    SCOPED_TRACE(columns);
    const nlohmann::json got = color_json({"--nk", path, "--columns", columns});
    ASSERT_FALSE(got.is_null());
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(got["Lab"][i].get<double>(), reference["Lab"][i].get<double>(), 1e-3);
    }
  }
  // Without --columns: one line, status 2, saying how to choose.
  const auto ambiguous = RunProgram({"color", "--nk", path});
  EXPECT_EQ(ambiguous.status, 2);
  EXPECT_EQ(testing::CountLines(ambiguous.err), 1) << ambiguous.err;
  EXPECT_THAT(ambiguous.err, HasSubstr("--columns N,K"));
  EXPECT_TRUE(ambiguous.out.empty());
  const auto stray = RunProgram({"color", "--columns", "2,3", "--data", "Au-Ag", "--x", "0.5"});
  EXPECT_EQ(stray.status, 2);
  EXPECT_THAT(stray.err, HasSubstr("--columns applies to --nk"));
  // render and export read the same option.
  const auto exported =
      RunProgram({"export", "--nk", path, "--columns", "n12,k12", "--out", dir_ + "/multi"});
  EXPECT_EQ(exported.status, 0) << exported.err;
}

}  // namespace
}  // namespace alloycolor
