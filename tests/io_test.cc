// Tests of the optical-constant readers and writers (model/io.h) and of spectra
// (model/spectrum.h): the bundled files, hand-checked rows, and every kind of bad input,
// whose error must name the file and line.
#include "alloycolor/core/io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/spectrum.h"
#include "test_util.h"

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
using testing::DataDir;
using testing::ErrorOf;
using ::testing::HasSubstr;
using testing::MakeTempDir;
using ::testing::Not;
using testing::WriteText;

std::vector<std::string> BundledSpectrumFiles() {
  std::vector<std::string> files;
  for (const auto& folder : fs::directory_iterator(DataDir())) {
    if (!folder.is_directory()) continue;
    for (const auto& file : fs::directory_iterator(folder.path())) {
      // about.yml files describe a material; they hold no DATA.
      if (file.path().extension() == ".yml" && file.path().filename() != "about.yml") {
        files.push_back(file.path().string());
      }
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(ReadNkFileTest, AllBundledFilesLoad) {
  const std::vector<std::string> files = BundledSpectrumFiles();
  EXPECT_GE(files.size(), 33u);
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    std::vector<std::string> warnings;
    NkSpectrum nk;
    ASSERT_NO_THROW(nk = ReadNkFile(file, &warnings));
    EXPECT_EQ(nk.source, file);
    ASSERT_GE(nk.lambda_nm.size(), 2u);
    ASSERT_EQ(nk.n.size(), nk.lambda_nm.size());
    ASSERT_EQ(nk.k.size(), nk.lambda_nm.size());
    for (std::size_t i = 1; i < nk.lambda_nm.size(); ++i) {
      ASSERT_LT(nk.lambda_nm[i - 1], nk.lambda_nm[i]);
    }
    for (std::size_t i = 0; i < nk.n.size(); ++i) {
      ASSERT_GE(nk.n[i], 0);
      ASSERT_GE(nk.k[i], 0);
    }
  }
}

TEST(ReadNkFileTest, RiouxRowsByHand) {
  const std::string file = DataDir() + "/Au-Ag/Rioux-Au50Ag50.yml";
  std::vector<std::string> warnings;
  const NkSpectrum nk = ReadNkFile(file, &warnings);
  EXPECT_TRUE(warnings.empty());
  ASSERT_EQ(nk.lambda_nm.size(), 931u);  // 0.270 to 1.200 um in 1 nm steps
  // First row: "0.270 1.34272 1.55989"; last: "1.200 0.73359 8.32187".
  EXPECT_NEAR(nk.lambda_nm.front(), 270.0, 1e-9);
  EXPECT_DOUBLE_EQ(nk.n.front(), 1.34272);
  EXPECT_DOUBLE_EQ(nk.k.front(), 1.55989);
  EXPECT_NEAR(nk.lambda_nm.back(), 1200.0, 1e-9);
  EXPECT_DOUBLE_EQ(nk.n.back(), 0.73359);
  EXPECT_DOUBLE_EQ(nk.k.back(), 8.32187);
  EXPECT_TRUE(nk.Covers(380, 780));
  EXPECT_FALSE(nk.Covers(260, 780));
}

TEST(ReadNkFileTest, QuerryRepeatedWavelengthIsAveragedWithWarning) {
  const std::string file = DataDir() + "/Cu-Zn/Querry-Cu100.yml";
  std::vector<std::string> warnings;
  const NkSpectrum nk = ReadNkFile(file, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  // Lines 444 and 445: "5.1020 2.888 31.137" and "5.1020 2.853 30.846".
  EXPECT_THAT(warnings[0], HasSubstr(file + ":444:"));
  EXPECT_THAT(warnings[0], HasSubstr("5.102"));
  EXPECT_THAT(warnings[0], HasSubstr("mean"));
  const auto it = std::find_if(nk.lambda_nm.begin(), nk.lambda_nm.end(),
                               [](double x) { return std::abs(x - 5102.0) < 1e-6; });
  ASSERT_NE(it, nk.lambda_nm.end());
  EXPECT_EQ(std::count_if(nk.lambda_nm.begin(), nk.lambda_nm.end(),
                          [](double x) { return std::abs(x - 5102.0) < 1e-6; }),
            1);
  const std::size_t i = it - nk.lambda_nm.begin();
  EXPECT_DOUBLE_EQ(nk.n[i], (2.888 + 2.853) / 2);
  EXPECT_DOUBLE_EQ(nk.k[i], (31.137 + 30.846) / 2);
}

class TempDirTest : public ::testing::Test {
 protected:
  std::string Write(const std::string& name, const std::string& text) {
    const std::string path = dir_ + "/" + name;
    WriteText(path, text);
    return path;
  }
  void TearDown() override {
    std::error_code error;
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, error);
    fs::remove_all(dir_, error);
  }
  std::string dir_ = MakeTempDir();
};

using YamlTest = TempDirTest;

constexpr char kYamlHead[] =
    "# line 1\n"
    "REFERENCES: test\n"
    "DATA:\n"
    "  - type: tabulated nk\n"
    "    data: |\n";  // rows start on line 6

TEST_F(YamlTest, MicrometresBecomeNanometres) {
  const std::string path =
      Write("um.yml", std::string(kYamlHead) + "        0.5 1.0 2.0\n        0.6 1.5 2.5\n");
  const NkSpectrum nk = ReadRefractiveIndexYaml(path);
  ASSERT_EQ(nk.lambda_nm.size(), 2u);
  EXPECT_DOUBLE_EQ(nk.lambda_nm[0], 500.0);
  EXPECT_DOUBLE_EQ(nk.lambda_nm[1], 600.0);
  EXPECT_DOUBLE_EQ(nk.n[1], 1.5);
  EXPECT_DOUBLE_EQ(nk.k[1], 2.5);
}

TEST_F(YamlTest, ZeroNIsAllowed) {
  const std::string path =
      Write("n0.yml", std::string(kYamlHead) + "        0.5 0 2.0\n        0.6 0.0 2.5\n");
  EXPECT_NO_THROW(ReadNkFile(path));
}

TEST_F(YamlTest, TabulatedNPlusTabulatedKJoinOnTheNGrid) {
  const std::string path = Write("nk.yml",
                                 "DATA:\n"
                                 "  - type: tabulated n\n"
                                 "    data: |\n"
                                 "        0.4 1.0\n"
                                 "        0.5 1.2\n"
                                 "        0.6 1.4\n"
                                 "  - type: tabulated k\n"
                                 "    data: |\n"
                                 "        0.4 1.0\n"
                                 "        0.6 3.0\n");
  std::vector<std::string> warnings;
  const NkSpectrum nk = ReadNkFile(path, &warnings);
  EXPECT_TRUE(warnings.empty());
  ASSERT_EQ(nk.lambda_nm.size(), 3u);
  EXPECT_DOUBLE_EQ(nk.lambda_nm[1], 500.0);
  EXPECT_DOUBLE_EQ(nk.n[1], 1.2);
  EXPECT_DOUBLE_EQ(nk.k[1], 2.0);  // halfway between 1.0 and 3.0
  EXPECT_DOUBLE_EQ(nk.k[2], 3.0);
}

TEST_F(YamlTest, TabulatedKCoveringPartOfNUsesTheOverlapWithWarning) {
  const std::string path = Write("partial.yml",
                                 "DATA:\n"
                                 "  - type: tabulated k\n"
                                 "    data: |\n"
                                 "        0.45 1.0\n"
                                 "        0.75 4.0\n"
                                 "  - type: tabulated n\n"
                                 "    data: |\n"
                                 "        0.4 1.0\n"
                                 "        0.5 1.2\n"
                                 "        0.6 1.4\n"
                                 "        0.8 1.8\n");
  std::vector<std::string> warnings;
  const NkSpectrum nk = ReadNkFile(path, &warnings);
  ASSERT_EQ(nk.lambda_nm.size(), 2u);
  EXPECT_DOUBLE_EQ(nk.lambda_nm[0], 500.0);
  EXPECT_DOUBLE_EQ(nk.lambda_nm[1], 600.0);
  EXPECT_NEAR(nk.k[0], 1.5, 1e-12);  // 1 + 3 (0.05 / 0.3)
  EXPECT_NEAR(nk.k[1], 2.5, 1e-12);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr(path));
  EXPECT_THAT(warnings[0], HasSubstr("overlap"));
}

TEST_F(YamlTest, LineNumbersCountBlankLinesInTheBlock) {
  const std::string path =
      Write("blank.yml", std::string(kYamlHead) + "\n        0.5 1 2\n\n        0.6 x 2\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(path); }), HasSubstr(path + ":9: cannot parse number 'x'"));
}

TEST_F(YamlTest, RowsOutsideALiteralBlockAreNamedByNumber) {
  const std::string path = Write("quoted.yml",
                                 "DATA:\n"
                                 "  - type: tabulated nk\n"
                                 "    data: \"0.5 1 2\\n0.6 1 abc\"\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(path); }),
              HasSubstr(path + ":3: data row 2: cannot parse number 'abc'"));
}

// A bad YAML file and what its error must say (after the file name).
struct BadYaml {
  const char* name;
  const char* rows;  // appended to kYamlHead, so the first row is line 6
  const char* expected;
};

class BadYamlTest : public TempDirTest, public ::testing::WithParamInterface<BadYaml> {};

TEST_P(BadYamlTest, ErrorNamesFileAndLine) {
  const BadYaml& bad = GetParam();
  const std::string path = Write(std::string(bad.name) + ".yml", std::string(kYamlHead) + bad.rows);
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(path); }), HasSubstr(path + bad.expected));
}

INSTANTIATE_TEST_SUITE_P(
    Rows, BadYamlTest,
    ::testing::Values(
        BadYaml{"number", "        0.5 1 2\n        0.6 abc 2\n", ":7: cannot parse number 'abc'"},
        BadYaml{"trailing", "        0.5 1 2\n        0.6 1.5x 2\n",
                ":7: cannot parse number '1.5x'"},
        BadYaml{"columns", "        0.5 1 2\n        0.6 1\n", ":7: expected 3 columns"},
        BadYaml{"extra", "        0.5 1 2 4\n        0.6 1 2\n", ":6: expected 3 columns"},
        BadYaml{"nan", "        0.5 1 2\n        0.6 nan 2\n",
                ":7: n is 'nan', not a finite number"},
        BadYaml{"inf", "        0.5 1 inf\n        0.6 1 2\n",
                ":6: k is 'inf', not a finite number"},
        BadYaml{"one_row", "        0.5 1 2\n", ":5: only 1 distinct wavelength"},
        BadYaml{"one_repeated", "        0.5 1 2\n        0.5 1 2\n",
                ":5: only 1 distinct wavelength"},
        BadYaml{"no_rows", "\n", ":5: no data rows"},
        BadYaml{"zero_lambda", "        0 1 2\n        0.6 1 2\n",
                ":6: wavelength_um = 0 is not positive"},
        BadYaml{"negative_lambda", "        0.5 1 2\n        -0.6 1 2\n",
                ":7: wavelength_um = -0.6 is not positive"},
        BadYaml{"decreasing", "        0.5 1 2\n        0.6 1 2\n        0.55 1 2\n",
                ":8: wavelength_um = 0.55 does not increase"},
        BadYaml{"negative_k", "        0.5 1 2\n        0.6 1 -0.1\n", ":7: k = -0.1 is negative"},
        BadYaml{"negative_n", "        0.5 -1 2\n        0.6 1 2\n", ":6: n = -1 is negative"}),
    [](const ::testing::TestParamInfo<BadYaml>& info) { return std::string(info.param.name); });

using YamlStructureTest = TempDirTest;

TEST_F(YamlStructureTest, FormulaIsRefusedByName) {
  const std::string path = Write("formula.yml",
                                 "DATA:\n"
                                 "  - type: formula 2\n"
                                 "    coefficients: 0 1 2\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(path); }),
              HasSubstr(path + ":2: DATA entry 1 is 'formula 2'; only tabulated nk, or "
                               "tabulated n plus tabulated k, are supported"));
}

TEST_F(YamlStructureTest, FormulaNextToTabulatedKIsRefused) {
  const std::string path = Write("formula_k.yml",
                                 "DATA:\n"
                                 "  - type: formula 1\n"
                                 "    coefficients: 0 1 2\n"
                                 "  - type: tabulated k\n"
                                 "    data: |\n"
                                 "        0.5 1\n"
                                 "        0.6 1\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(path); }), HasSubstr("DATA entry 1 is 'formula 1'"));
}

TEST_F(YamlStructureTest, TabulatedN2IsRefusedByName) {
  const std::string path = Write("n2.yml",
                                 "DATA:\n"
                                 "  - type: tabulated nk\n"
                                 "    data: |\n"
                                 "        0.5 1 2\n"
                                 "        0.6 1 2\n"
                                 "  - type: tabulated n2\n"
                                 "    data: |\n"
                                 "        0.5 1\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(path); }),
              HasSubstr(path + ":6: DATA entry 2 is 'tabulated n2'"));
}

TEST_F(YamlStructureTest, TabulatedNAloneIsRefused) {
  const std::string path = Write("n_only.yml",
                                 "DATA:\n"
                                 "  - type: tabulated n\n"
                                 "    data: |\n"
                                 "        0.5 1\n"
                                 "        0.6 1\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(path); }),
              HasSubstr(path + ":2: DATA holds 'tabulated n'; only tabulated nk, or tabulated "
                               "n plus tabulated k, are supported"));
}

TEST_F(YamlStructureTest, BadRowInTabulatedKNamesItsLine) {
  const std::string path = Write("bad_k.yml",
                                 "DATA:\n"
                                 "  - type: tabulated n\n"
                                 "    data: |\n"
                                 "        0.5 1\n"
                                 "        0.6 1\n"
                                 "  - type: tabulated k\n"
                                 "    data: |\n"
                                 "        0.5 1\n"
                                 "        0.6 1 3\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(path); }),
              HasSubstr(path + ":9: expected 2 columns (wavelength_um k), found 3"));
}

TEST_F(YamlStructureTest, DisjointNAndKAreRefused) {
  const std::string path = Write("disjoint.yml",
                                 "DATA:\n"
                                 "  - type: tabulated n\n"
                                 "    data: |\n"
                                 "        0.5 1\n"
                                 "        0.6 1\n"
                                 "  - type: tabulated k\n"
                                 "    data: |\n"
                                 "        0.7 1\n"
                                 "        0.8 1\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(path); }), HasSubstr(path + ": tabulated n covers"));
}

TEST_F(YamlStructureTest, MissingDataIsRefused) {
  const std::string path = Write("no_data.yml", "REFERENCES: nothing\nCOMMENTS: here\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(path); }), HasSubstr(path + ": not a refractiveindex"));
  const std::string empty = Write("empty.yml", "");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(empty); }), HasSubstr(empty + ": "));
  const std::string no_list = Write("no_list.yml", "DATA: 3\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(no_list); }),
              HasSubstr(no_list + ":1: DATA is not a non-empty list"));
  const std::string no_type = Write("no_type.yml", "DATA:\n  - data: |\n      0.5 1 2\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(no_type); }),
              HasSubstr(no_type + ":2: DATA entry 1 has no 'type'"));
  const std::string no_rows = Write("no_rows.yml", "DATA:\n  - type: tabulated nk\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(no_rows); }),
              HasSubstr(no_rows + ":2: DATA entry 1 has no 'data'"));
}

// One document per file: a second is refused at its line, an empty one after it is
// nothing. A line starting with a comma made yaml-cpp 0.7's LoadAll read empty documents
// without end (found by the YAML fuzzer; the reader asks for the second document once).
TEST_F(YamlStructureTest, OneDocumentAndNoEndlessEmptyOnes) {
  const std::string body =
      "DATA:\n  - type: tabulated nk\n    data: |\n        0.5 1 2\n"
      "        0.6 1 2\n";
  const std::string two = Write("two.yml", body + "---\nDATA: []\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(two); }),
              HasSubstr(two + ":6: a second YAML document ('---')"));
  EXPECT_EQ(ReadNkFile(Write("empty_second.yml", body + "---\n")).lambda_nm.size(), 2u);
  for (const std::string text : {",\n", "# a comment\n ,\n0.5 1 2\n"}) {
    const std::string path = Write("comma.yml", text);
    EXPECT_THAT(ErrorOf([&] { ReadNkFile(path); }),
                HasSubstr(path + ": not a refractiveindex.info file"));
  }
}

TEST_F(YamlStructureTest, InvalidYamlNamesFileAndLine) {
  const std::string path = Write("syntax.yml", "DATA:\n  - type: tabulated nk\n    data: [1, 2\n");
  const std::string message = ErrorOf([&] { ReadNkFile(path); });
  EXPECT_THAT(message, HasSubstr(path + ":"));
  EXPECT_THAT(message, HasSubstr("invalid YAML"));
}

using CsvTest = TempDirTest;

TEST_F(CsvTest, ReadsCommentsBlankLinesAndLooseHeader) {
  const std::string path = Write("good.csv",
                                 "# source: a test\n"
                                 "\n"
                                 " Lambda_NM , n , K \r\n"
                                 "500, 1.5, 2\n"
                                 "# a comment between rows\n"
                                 "600,1.25,3e0\n");
  const NkSpectrum nk = ReadNkFile(path);
  ASSERT_EQ(nk.lambda_nm.size(), 2u);
  EXPECT_DOUBLE_EQ(nk.lambda_nm[0], 500.0);
  EXPECT_DOUBLE_EQ(nk.n[1], 1.25);
  EXPECT_DOUBLE_EQ(nk.k[1], 3.0);
}

TEST_F(CsvTest, RepeatedWavelengthIsAveragedWithWarning) {
  const std::string path = Write("repeat.csv", "lambda_nm,n,k\n500,1,2\n500,2,4\n600,1,2\n");
  std::vector<std::string> warnings;
  const NkSpectrum nk = ReadNkCsv(path, &warnings);
  ASSERT_EQ(nk.lambda_nm.size(), 2u);
  EXPECT_DOUBLE_EQ(nk.n[0], 1.5);
  EXPECT_DOUBLE_EQ(nk.k[0], 3.0);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr(path + ":2:"));
}

TEST_F(CsvTest, BadInputNamesFileAndLine) {
  struct Case {
    const char* text;
    const char* expected;
  };
  const Case cases[] = {
      {"", ": no data"},
      {"# only a comment\n\n", ": no data"},
      {"lambda_nm,n,k\n", ":1: no data rows"},
      {"# c\nwavelength,n,k\n500,1,2\n", ":2: header column 'wavelength' gives no unit"},
      {"lambda_nm,n,k\n500,1,2\n600,one,2\n", ":3: cannot parse number 'one'"},
      {"lambda_nm,n,k\n500,1,2\n600,1\n", ":3: expected 3 columns (lambda_nm,n,k), found 2"},
      {"lambda_nm,n,k\n500,1,2\n600,1,2,3\n", ":3: expected 3 columns"},
      {"lambda_nm,n,k\n500,1,2\n600,,2\n", ":3: cannot parse number ''"},
      {"lambda_nm,n,k\n500,1,2\n600,1,NaN\n", ":3: k is 'NaN', not a finite number"},
      {"lambda_nm,n,k\n500,1,2\n", ":1: only 1 distinct wavelength"},
      {"lambda_nm,n,k\n-500,1,2\n600,1,2\n", ":2: lambda_nm = -500 is not positive"},
      {"lambda_nm,n,k\n400,1,2\n500,1,2\n450,1,2\n", ":4: lambda_nm = 450 does not increase"},
      {"lambda_nm,n,k\n500,1,2\n400,1,2\n450,1,2\n", ":4: lambda_nm = 450 does not decrease"},
      {"lambda_nm,n,k\n500,-1,2\n600,1,2\n", ":2: n = -1 is negative"},
      {"lambda_nm,n,k\n500,1,2\n600,1,-2\n", ":3: k = -2 is negative"},
  };
  int i = 0;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    const std::string path = Write("bad" + std::to_string(i++) + ".csv", c.text);
    EXPECT_THAT(ErrorOf([&] { ReadNkFile(path); }), HasSubstr(path + c.expected));
  }
}

using ReadNkFileTest2 = TempDirTest;

TEST_F(ReadNkFileTest2, ExtensionChoosesTheReader) {
  const std::string yaml_text = std::string(kYamlHead) + "        0.5 1 2\n        0.6 1 2\n";
  EXPECT_NO_THROW(ReadNkFile(Write("upper.YAML", yaml_text)));
  EXPECT_NO_THROW(ReadNkFile(Write("looks_like_yaml.txt", yaml_text)));
  EXPECT_NO_THROW(ReadNkFile(Write("table.txt", "lambda_nm,n,k\n500,1,2\n600,1,2\n")));
  const std::string other = Write("table.xyz", "lambda_nm,n,k\n500,1,2\n600,1,2\n");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(other); }), HasSubstr(other + ": cannot tell the format"));
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(other); }), HasSubstr("'.xyz'"));
}

TEST_F(ReadNkFileTest2, MissingFileOrFolderIsRefused) {
  const std::string missing = dir_ + "/missing.yml";
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(missing); }),
              HasSubstr("cannot read '" + missing + "': No such file or directory"));
  fs::create_directory(dir_ + "/folder.csv");
  EXPECT_THAT(ErrorOf([&] { ReadNkFile(dir_ + "/folder.csv"); }),
              HasSubstr("cannot read '" + dir_ + "/folder.csv': Is a directory"));
  EXPECT_THAT(ErrorOf([&] { ReadFileText(dir_); }), HasSubstr("Is a directory"));
}

TEST(SpectrumTest, NkAtInterpolatesLinearly) {
  NkSpectrum nk;
  nk.source = "hand.csv";
  nk.lambda_nm = {500, 600, 700};
  nk.n = {1, 2, 4};
  nk.k = {3, 5, 5};
  // At 525 nm, a quarter of the way from 500 to 600: n = 1 + 0.25 (2 - 1), k = 3 + 0.25 (5 - 3).
  const std::complex<double> at_525 = NkAt(nk, 525);
  EXPECT_DOUBLE_EQ(at_525.real(), 1.25);
  EXPECT_DOUBLE_EQ(at_525.imag(), 3.5);
  // At 650 nm: n = 2 + 0.5 (4 - 2).
  EXPECT_DOUBLE_EQ(NkAt(nk, 650).real(), 3.0);
  EXPECT_DOUBLE_EQ(NkAt(nk, 500).real(), 1.0);
  EXPECT_DOUBLE_EQ(NkAt(nk, 600).real(), 2.0);
  EXPECT_DOUBLE_EQ(NkAt(nk, 700).real(), 4.0);
  EXPECT_THAT(ErrorOf([&] { NkAt(nk, 499.9); }), HasSubstr("hand.csv: wavelength 499.9 nm"));
  EXPECT_THAT(ErrorOf([&] { NkAt(nk, 700.1); }), HasSubstr("hand.csv"));
  EXPECT_THAT(ErrorOf([&] { NkAt(nk, std::nan("")); }), HasSubstr("hand.csv"));
  EXPECT_THAT(ErrorOf([&] { NkAt(NkSpectrum{"empty", {}, {}, {}}, 500); }), HasSubstr("empty"));
}

TEST(SpectrumTest, NkOnIsTheHandInterpolationInAnyOrder) {
  NkSpectrum nk;
  nk.source = "hand.csv";
  nk.lambda_nm = {500, 600, 700};
  nk.n = {1, 2, 4};
  nk.k = {3, 5, 5};
  // By hand as above: 500 -> 1+3i, 525 -> 1.25+3.5i, 600 -> 2+5i, 650 -> 3+5i, 700 -> 4+5i;
  // increasing, repeated and falling wavelengths alike.
  const std::vector<double> at = {500, 525, 525, 600, 650, 700, 525, 500};
  const std::vector<std::complex<double>> want = {{1, 3}, {1.25, 3.5}, {1.25, 3.5}, {2, 5},
                                                  {3, 5}, {4, 5},      {1.25, 3.5}, {1, 3}};
  const std::vector<std::complex<double>> got = NkOn(nk, at);
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_DOUBLE_EQ(got[i].real(), want[i].real()) << at[i];
    EXPECT_DOUBLE_EQ(got[i].imag(), want[i].imag()) << at[i];
  }
  EXPECT_TRUE(NkOn(nk, {}).empty());
  EXPECT_THAT(ErrorOf([&] { NkOn(nk, {550, 700.1}); }), HasSubstr("hand.csv: wavelength 700.1"));
}

TEST(SpectrumTest, ResampleAndUniformGrid) {
  const std::vector<double> grid = UniformGrid(380, 780, 5);
  ASSERT_EQ(grid.size(), 81u);
  EXPECT_EQ(grid.front(), 380);
  EXPECT_EQ(grid.back(), 780);
  const std::vector<double> fine = UniformGrid(380, 780, 0.1);
  ASSERT_EQ(fine.size(), 4001u);
  EXPECT_LE(fine.back(), 780);
  EXPECT_EQ(UniformGrid(500, 500, 10).size(), 1u);
  EXPECT_THAT(ErrorOf([] { UniformGrid(780, 380, 5); }), HasSubstr("wavelength grid"));
  EXPECT_THAT(ErrorOf([] { UniformGrid(380, 780, 0); }), HasSubstr("positive step"));
  EXPECT_THAT(ErrorOf([] { UniformGrid(1, 1e9, 1e-9); }), HasSubstr("too many points"));

  NkSpectrum nk{"hand", {500, 600}, {1, 2}, {3, 5}};
  const NkSpectrum resampled = Resample(nk, {500, 550, 600});
  EXPECT_EQ(resampled.source, "hand");
  EXPECT_EQ(resampled.lambda_nm, (std::vector<double>{500, 550, 600}));
  EXPECT_DOUBLE_EQ(resampled.n[1], 1.5);
  EXPECT_DOUBLE_EQ(resampled.k[1], 4.0);
  EXPECT_THROW(Resample(nk, {450}), Error);
}

using WriteTest = TempDirTest;

TEST_F(WriteTest, NkCsvTextRoundTripsExactly) {
  const std::vector<double> lambda = {400.1, 1300.0 / 3, 1e3};
  const std::vector<double> n = {0.1, 1.0 / 7, 2.0 / 3};
  const std::vector<double> k = {3.0, 1e-17, 0};
  const std::string text = NkCsvText(lambda, n, k);
  EXPECT_EQ(text.substr(0, 14), "lambda_nm,n,k\n");
  EXPECT_THAT(text, HasSubstr("400.10000000000002,0.10000000000000001,3\n"));
  const std::string path = dir_ + "/out.csv";
  WriteFileAtomic(path, text);
  const NkSpectrum nk = ReadNkFile(path);
  EXPECT_EQ(nk.lambda_nm, lambda);
  EXPECT_EQ(nk.n, n);
  EXPECT_EQ(nk.k, k);
  EXPECT_THROW(NkCsvText({1, 2}, {1}, {1, 2}), Error);
}

TEST_F(WriteTest, ReplacesAnOldFileAndLeavesNoTemporary) {
  const std::string path = Write("file.txt", "old");
  WriteFileAtomic(path, "new contents");
  EXPECT_EQ(ReadFileText(path), "new contents");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(WriteTest, OldFileIsKeptWhenTheFolderIsUnwritable) {
  const std::string folder = dir_ + "/locked";
  fs::create_directory(folder);
  const std::string path = folder + "/file.txt";
  WriteText(path, "old");
  fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec);
  // Root ignores permissions; then the folder cannot be made unwritable this way.
  const std::string probe = folder + "/probe";
  WriteText(probe, "x");
  if (fs::exists(probe)) {
    fs::permissions(folder, fs::perms::owner_all);
    GTEST_SKIP() << "running with privileges that ignore folder permissions";
  }
  EXPECT_THAT(ErrorOf([&] { WriteFileAtomic(path, "new"); }),
              HasSubstr("cannot write '" + path + "': Permission denied"));
  EXPECT_EQ(ReadFileText(path), "old");
  fs::permissions(folder, fs::perms::owner_all);
}

TEST_F(WriteTest, OldFileIsKeptWhenTheTargetIsAFolder) {
  const std::string target = dir_ + "/target";
  fs::create_directory(target);
  Write("target/inside.txt", "old");
  EXPECT_THAT(ErrorOf([&] { WriteFileAtomic(target, "new"); }),
              HasSubstr("cannot write '" + target + "'"));
  EXPECT_TRUE(fs::is_directory(target));
  EXPECT_EQ(ReadFileText(target + "/inside.txt"), "old");
  // Only the folder remains: the temporary file was removed.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(WriteTest, MissingFolderIsRefused) {
  const std::string path = dir_ + "/no/such/folder/file.txt";
  EXPECT_THAT(ErrorOf([&] { WriteFileAtomic(path, "x"); }),
              HasSubstr("cannot write '" + path + "': No such file or directory"));
}

TEST(Fnv1a64HexTest, StandardVectors) {
  // Reference values of FNV-1a 64 (Fowler, Noll, Vo; draft-eastlake-fnv).
  EXPECT_EQ(Fnv1a64Hex(""), "cbf29ce484222325");
  EXPECT_EQ(Fnv1a64Hex("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(Fnv1a64Hex("foobar"), "85944171f73967e8");
  EXPECT_EQ(Fnv1a64Hex(std::string("\0", 1)), "af63bd4c8601b7df");
}

}  // namespace
}  // namespace alloycolor
