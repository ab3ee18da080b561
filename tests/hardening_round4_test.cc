// Issue 49, through the real program (ALLOYCOLOR_BINARY) unless stated, a test per class:
// a report stopped by a signal leaves no folder; every output's folder is checked before
// any work; a target colour that cannot be is blamed on its option, never on the model;
// a file's bytes never reach a message raw (UTF-16, Latin-1); wavelengths in the other
// unit than their header's, and values of the wrong kind (a denormal), are refused at
// read with the file and line; command-line slips (a decimal comma, a longer option
// name) are named. The references are the file system's own state, the exit statuses and
// the one-line error the program documents, and RFC 3629's definition of UTF-8.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "alloycolor/core/dataset.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/text.h"
#include "alloycolor/model/alloy_model.h"
#include "test_util.h"

namespace alloycolor::testing {
namespace {

namespace fs = std::filesystem;

// RFC 3629: every byte belongs to a well-formed sequence (no overlong form, no surrogate,
// nothing past U+10FFFF). Written apart from core's SafeText, from the RFC's table.
bool ValidUtf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const unsigned char c = s[i];
    int n = 0;
    unsigned lo = 0x80, hi = 0xBF;
    if (c < 0x80) {
      ++i;
      continue;
    } else if (c >= 0xC2 && c <= 0xDF) {
      n = 1;
    } else if (c >= 0xE0 && c <= 0xEF) {
      n = 2;
      lo = c == 0xE0 ? 0xA0 : 0x80;
      hi = c == 0xED ? 0x9F : 0xBF;
    } else if (c >= 0xF0 && c <= 0xF4) {
      n = 3;
      lo = c == 0xF0 ? 0x90 : 0x80;
      hi = c == 0xF4 ? 0x8F : 0xBF;
    } else {
      return false;
    }
    if (i + n >= s.size()) return false;
    for (int j = 1; j <= n; ++j) {
      const unsigned char d = s[i + j];
      if (d < (j == 1 ? lo : 0x80) || d > (j == 1 ? hi : 0xBF)) return false;
    }
    i += n + 1;
  }
  return true;
}

// One error line, status 2, valid UTF-8, containing every needle and none of `absent`.
void ExpectOneError(const RunResult& r, const std::vector<std::string>& needles,
                    const std::vector<std::string>& absent = {}) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(CountLines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("alloycolor: error: ", 0), 0u) << r.err;
  EXPECT_TRUE(ValidUtf8(r.err)) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out.substr(0, 200);
  for (const std::string& needle : needles) {
    EXPECT_NE(r.err.find(needle), std::string::npos) << "'" << needle << "' not in " << r.err;
  }
  for (const std::string& word : absent) {
    EXPECT_EQ(r.err.find(word), std::string::npos) << "'" << word << "' in " << r.err;
  }
}

// A model file of the bundled Au-Ag set (eps-linear: quick to fit), made once.
const std::string& ModelFile() {
  static const std::string path = [] {
    const std::string p = MakeTempDir() + "/m.json";
    const RunResult r =
        RunProgram({"fit", "--data", "Au-Ag", "--method", "eps-linear", "--out", p, "--quiet"});
    EXPECT_EQ(r.status, 0) << r.err;
    return p;
  }();
  return path;
}

// A data set of two samples written as CSV with the given header and rows (the same rows
// for both compositions, n and k from Au at three wavelengths).
std::string CsvDataset(const std::string& header, const std::string& rows) {
  const std::string dir = MakeTempDir();
  for (const char* name : {"a", "b"}) WriteText(dir + "/" + name + ".csv", header + "\n" + rows);
  WriteText(dir + "/dataset.json",
            R"({"name": "t", "system": {"a": "Au", "b": "Ag"},
                "composition": "atomic_fraction_a",
                "samples": [{"x": 0.0, "file": "a.csv"}, {"x": 1.0, "file": "b.csv"}]})");
  return dir;
}

constexpr const char* kAuRowsNm =
    "350,1.70,1.90\n400,1.66,1.96\n500,0.97,1.87\n600,0.25,2.98\n700,0.16,3.95\n850,0.19,5.39\n";

// ---- outputs ----------------------------------------------------------------------------

// A report stopped by SIGTERM while its work is under way leaves no folder it made, not
// even empty ones (--out a/b/c made three).
TEST(OutputFolders, ASignalDuringAReportLeavesNoFolderItMade) {
  const std::string dir = MakeTempDir();
  const std::string out = dir + "/new/report/here";
  bool caught = false;
  for (int attempt = 0; attempt < 3 && !caught; ++attempt) {
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      const int null = open("/dev/null", O_WRONLY);
      dup2(null, 2);
      const char* program = ALLOYCOLOR_BINARY;
      execl(program, program, "validate", "--data", "Au-Ag", "--methods", "all", "--out",
            out.c_str(), "--quiet", static_cast<char*>(nullptr));
      _exit(127);
    }
    int status = 0;
    bool seen = false;
    while (!seen) {
      seen = fs::exists(out);
      if (waitpid(pid, &status, WNOHANG) == pid) break;
      if (!seen) usleep(500);
    }
    if (!seen) continue;
    usleep(100000);  // into the work
    kill(pid, SIGTERM);
    waitpid(pid, &status, 0);
    if (WIFEXITED(status)) {  // finished first
      fs::remove_all(dir + "/new");
      continue;
    }
    caught = true;
    EXPECT_EQ(WTERMSIG(status), SIGTERM);
    EXPECT_FALSE(fs::exists(dir + "/new")) << "a folder the report made is left";
  }
  if (!caught) GTEST_SKIP() << "the report always finished before the signal";
  // A run refused before its work makes no folder; a folder that was there stays.
  const std::string kept = dir + "/kept";
  fs::create_directory(kept);
  ExpectOneError(
      RunProgram({"validate", "--data", "/nonexistent", "--out", kept + "/r", "--quiet"}),
      {"/nonexistent"});
  EXPECT_TRUE(fs::is_directory(kept));
  EXPECT_FALSE(fs::exists(kept + "/r"));
}

// Every command's output folder is checked before any work: the data set named is never
// read (it does not exist), so the one line is about the folder.
TEST(OutputFolders, EveryCommandChecksItsFolderFirst) {
  const std::string missing = MakeTempDir() + "/missing-folder";
  const std::vector<std::vector<std::string>> commands = {
      {"fit", "--data", "/nonexistent/ds", "--out", missing + "/m.json"},
      {"render", "--data", "/nonexistent/ds", "--x", "0.5", "--out", missing + "/i.png"},
      {"export", "--data", "/nonexistent/ds", "--x", "0.5", "--out", missing + "/e"},
      {"chart", "--data", "/nonexistent/ds", "--out", missing + "/c.svg"},
      {"sweep", "--data", "/nonexistent/ds", "--out", missing + "/s.csv"},
      {"explore", "--data", "/nonexistent/ds", "--out", missing + "/p.html"},
  };
  for (const auto& args : commands) {
    SCOPED_TRACE(args.front());
    ExpectOneError(RunProgram(args), {"--out", "missing-folder", "does not exist"},
                   {"/nonexistent"});
  }
  EXPECT_FALSE(fs::exists(missing));
  // A file where the folder should be is named as such.
  const std::string file = MakeTempDir() + "/file";
  WriteText(file, "x");
  ExpectOneError(RunProgram({"fit", "--data", "Au-Ag", "--out", file + "/m.json"}),
                 {"--out", "is not a folder"});
}

// ---- command-line slips -----------------------------------------------------------------

TEST(CommandLine, ADecimalCommaIsNamed) {
  ExpectOneError(RunProgram({"color", "--model", ModelFile(), "--x", "0,75"}),
                 {"--x", "'0,75'", "decimal comma", "0.75"});
  ExpectOneError(RunProgram({"color", "--model", ModelFile(), "--x", "0.2,0,75"}),
                 {"--x", "decimal comma", "0.75"});
  ExpectOneError(RunProgram({"tolerance", "--model", ModelFile(), "--x", "0,6"}),
                 {"--x", "decimal comma", "0.6"});
  ExpectOneError(RunProgram({"predict", "--model", ModelFile(), "--x", "0,5at%,1"}), {"--x"});
  // Two compositions that read as such stay two.
  EXPECT_EQ(RunProgram({"color", "--model", ModelFile(), "--x", "0.2,0.6"}).status, 0);
}

TEST(CommandLine, AnUnknownOptionSuggestsTheNearest) {
  ExpectOneError(RunProgram({"fit", "--data", "Au-Ag", "--output", "m.json"}),
                 {"'--output'", "did you mean --out?"});
  ExpectOneError(RunProgram({"render", "--model", ModelFile(), "--x", "0.5", "--sizes", "8"}),
                 {"'--sizes'", "did you mean --size?"});
  ExpectOneError(RunProgram({"color", "--model", ModelFile(), "--x", "0.5", "--illum", "D65"}),
                 {"'--illum'", "did you mean --illuminant?"});
}

// ---- targets ----------------------------------------------------------------------------

// Every malformed or impossible target names its option and blames the target: never the
// model file, never "not finite anywhere".
TEST(Targets, ABadTargetNamesItsOptionNotTheModel) {
  const struct {
    std::string option, value, needle;
  } cases[] = {
      {"--hex", "#ggg", "'g' is not a hexadecimal digit"},
      {"--hex", "#12345", "5 hexadecimal digits"},
      {"--hex", "#1234567", "7 hexadecimal digits"},
      {"--hex", "#123456 ", "space"},
      {"--hex", "##", "'#' comes once"},
      {"--hex", "#123456,#654321", "give one colour"},
      {"--xyz", "-1,0.5,0.5", "negative"},
      {"--xyz", "1e308,1,1", "lies above 2"},
      {"--xyz", "41,42,20", "divide values on the 0-100 scale by 100"},
      {"--lab", "1e308,0,0", "L* = 1e+308"},
      {"--lab", "-5,0,0", "L* = -5"},
      {"--lab", "50,1e200,0", "a* = 1e+200"},
      {"--lab", "50,0,-1e300", "b* = -1e+300"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.option + " " + c.value);
    ExpectOneError(RunProgram({"match", "--model", ModelFile(), c.option, c.value}),
                   {c.option + ":", c.needle}, {"m.json", "not finite anywhere", "model"});
  }
  // A target at the edge of what is allowed is answered.
  for (const auto& [option, value] : std::vector<std::pair<std::string, std::string>>{
           {"--lab", "150,600,-600"}, {"--xyz", "2,2,2"}, {"--hex", "ABCDEF"}}) {
    const RunResult r = RunProgram({"match", "--model", ModelFile(), option, value});
    EXPECT_EQ(r.status, 0) << option << " " << value << ": " << r.err;
    EXPECT_NE(r.out.find("not reachable"), std::string::npos) << r.out;
  }
}

// ---- files' bytes -----------------------------------------------------------------------

std::string Utf16(const std::string& ascii, bool little, bool bom) {
  std::string out = bom ? (little ? std::string("\xFF\xFE") : std::string("\xFE\xFF")) : "";
  for (const char c : ascii) {
    out += little ? std::string{c, '\0'} : std::string{'\0', c};
  }
  return out;
}

// A file in UTF-16 (either byte order, with or without a byte order mark) is named with its
// encoding, whichever reader meets it; no message carries a byte that is not UTF-8.
TEST(FileBytes, AFileInUtf16IsNamedWithItsEncoding) {
  const std::string model_text = ReadText(ModelFile());
  const std::string dir = MakeTempDir();
  for (const bool little : {true, false}) {
    for (const bool bom : {true, false}) {
      SCOPED_TRACE(std::string(little ? "LE" : "BE") + (bom ? " with BOM" : ""));
      const std::string model = dir + "/m16.json";
      WriteText(model, Utf16(model_text, little, bom));
      ExpectOneError(RunProgram({"color", "--model", model, "--x", "0.5"}),
                     {model, "UTF-16", little ? "little-endian" : "big-endian", "UTF-8"});
      const std::string csv = dir + "/nk16.csv";
      WriteText(csv, Utf16(std::string("lambda_nm,n,k\n") + kAuRowsNm, little, bom));
      ExpectOneError(RunProgram({"color", "--nk", csv}), {csv, "UTF-16"});
      const std::string ds = CsvDataset("lambda_nm,n,k", kAuRowsNm);
      WriteText(ds + "/dataset.json", Utf16(ReadText(ds + "/dataset.json"), little, bom));
      ExpectOneError(RunProgram({"fit", "--data", ds, "--out", dir + "/o.json"}),
                     {"dataset.json", "UTF-16"});
    }
  }
  // Latin-1 bytes (0xB5 for µ, 0xFF) quoted from a file reach the line as '?'.
  const std::string latin = dir + "/latin.json";
  WriteText(latin, "{\"format\": \xB5\xFF}");
  ExpectOneError(RunProgram({"color", "--model", latin, "--x", "0.5"}), {latin});
  const std::string csv = dir + "/latin.csv";
  WriteText(csv, "lambda_nm,n,k\n400,1.6\xFF,1.9\n500,1,2\n");
  ExpectOneError(RunProgram({"color", "--nk", csv}), {csv + ":2"});
}

// The library's messages are valid UTF-8 whatever bytes they quote (what Python receives
// too: the program's own line is made safe again by main), and keep what is valid: µ (C2
// B5) stays, a lone B5 or an overlong C0 AF becomes '?'.
TEST(FileBytes, MessagesAreValidUtf8) {
  const std::string dir = MakeTempDir();
  const std::string bytes = "\xB5\xFF\xFE\xC0\xAF";
  WriteText(dir + "/m.json", "{\"format\": " + bytes + "}");
  WriteText(dir + "/nk.csv", "lambda_nm,n,k\n400," + bytes + ",1\n500,1,2\n");
  WriteText(dir + "/nk.yml", "DATA:\n  - type: tabulated nk\n    data: " + bytes + "\n");
  WriteText(dir + "/dataset.json", "{\"name\": " + bytes + "}");
  for (const std::string& message :
       {ErrorOf([&] { ReadModelFile(dir + "/m.json"); }),
        ErrorOf([&] { ReadNkFile(dir + "/nk.csv"); }),
        ErrorOf([&] { ReadNkFile(dir + "/nk.yml"); }), ErrorOf([&] { LoadDataset(dir); })}) {
    EXPECT_TRUE(ValidUtf8(message)) << message;
    EXPECT_NE(message.find(dir), std::string::npos) << message;
  }
  EXPECT_EQ(Quote("\xC2\xB5m"), "'\xC2\xB5m'");
  EXPECT_EQ(Quote("\xB5m"), "'?m'");
  EXPECT_EQ(Quote("a\xC0\xAF"), "'a?\?'");
  EXPECT_EQ(Quote("\xED\xA0\x80"), "'?\?\?'");        // a UTF-16 surrogate written as UTF-8
  EXPECT_EQ(Quote("\xF4\x90\x80\x80"), "'?\?\?\?'");  // past U+10FFFF
  EXPECT_EQ(Quote("\xE2\x82"), "'?\?'");              // cut short
  EXPECT_EQ(MessageLine("a\nb\x1B[31m"), "a?b?[31m");
  const std::string message = ErrorOf([] { Fail(std::string("x \xFF\xFE y")); });
  EXPECT_EQ(message, "x ?? y");
  EXPECT_EQ(SafeText("\xC3\xA9\xC3\xA9\xC3\xA9", 2), "\xC3\xA9\xC3\xA9...");  // by character
}

// ---- values of the wrong kind -----------------------------------------------------------

// Wavelengths in um under a header that says nm (and nm under um) are refused at read,
// naming the file, the header line and the likely mistake, by fit and by color --nk.
TEST(FileValues, WavelengthsInTheOtherUnitAreNamed) {
  const std::string um_rows =
      "0.35,1.70,1.90\n0.4,1.66,1.96\n0.5,0.97,1.87\n0.6,0.25,2.98\n0.7,0.16,3.95\n0.85,0.19,5."
      "39\n";
  const std::string ds = CsvDataset("lambda_nm,n,k", um_rows);
  ExpectOneError(RunProgram({"fit", "--data", ds, "--out", MakeTempDir() + "/m.json"}),
                 {"a.csv:1", "micrometres", "wavelength_um"}, {"no method could be scored"});
  ExpectOneError(RunProgram({"color", "--nk", ds + "/a.csv"}),
                 {"a.csv:1", "0.35-0.85", "micrometres"});
  const std::string nm_as_um = CsvDataset("Wavelength (um),n,k", kAuRowsNm);
  ExpectOneError(RunProgram({"color", "--nk", nm_as_um + "/a.csv"}),
                 {"a.csv:1", "nanometres", "wavelength_nm"});
  const std::string r = MakeTempDir() + "/r.csv";
  WriteText(r, "wavelength_nm,R\n0.4,0.5\n0.5,0.6\n0.6,0.7\n");
  ExpectOneError(RunProgram({"match", "--model", ModelFile(), "--reflectance", r}),
                 {"r.csv:1", "micrometres"});
  // The right unit reads.
  EXPECT_EQ(RunProgram({"color", "--nk", CsvDataset("lambda_um,n,k", um_rows) + "/a.csv"}).status,
            0);
}

// A number nonzero but below 1e-30 (a denormal among them) is a value of the wrong kind:
// refused at read with its file and line, in every numeric column, CSV and YAML alike.
TEST(FileValues, ADenormalIsRefusedWithItsFileAndLine) {
  const std::string ds =
      CsvDataset("lambda_nm,n,k", "400,1.66,1.96\n500,0.2,1e-320\n600,0.25,2.98\n700,0.16,3.95\n");
  ExpectOneError(RunProgram({"fit", "--data", ds, "--out", MakeTempDir() + "/m.json"}),
                 {"a.csv:3", "k", "1e-320", "denormal"});
  ExpectOneError(RunProgram({"color", "--nk", ds + "/a.csv"}), {"a.csv:3", "1e-320"});
  const std::string dir = MakeTempDir();
  WriteText(dir + "/n.csv", "lambda_nm,n,k\n400,1e-35,1.96\n500,0.97,1.87\n");
  ExpectOneError(RunProgram({"color", "--nk", dir + "/n.csv"}), {"n.csv:2", "below 1e-30"});
  WriteText(dir + "/y.yml",
            "DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1.66 1.96\n"
            "        0.5 4.9e-324 1.87\n");
  ExpectOneError(RunProgram({"color", "--nk", dir + "/y.yml"}), {"y.yml:5", "denormal"});
  // Zero itself is a measured value.
  WriteText(dir + "/z.csv", std::string("lambda_nm,n,k\n") + kAuRowsNm + "900,1.66,0\n");
  EXPECT_EQ(RunProgram({"color", "--nk", dir + "/z.csv"}).status, 0);
}

}  // namespace
}  // namespace alloycolor::testing
