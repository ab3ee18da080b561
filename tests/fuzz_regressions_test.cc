// Replays the inputs the fuzzers (fuzz/) once crashed on, kept in tests/fuzz-regressions/
// TARGET/, through the real program: each must now succeed (status 0) or give one clean
// error line (status 2), never a crash, an internal error or a hang. The manifest cases run
// in a folder holding the sample files of manifest-files/, as the manifest fuzzer does.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "test_util.h"

namespace alloycolor::testing {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> Cases(const std::string& target) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(TestsDir()) / "fuzz-regressions" / target;
  if (!fs::is_directory(dir)) return files;  // git keeps no empty folder
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

void ExpectCleanRun(const std::vector<std::string>& args) {
  std::string cmd;
  for (const auto& a : args) cmd += a + " ";
  const RunResult r = RunProgram(args);
  EXPECT_TRUE(r.status == 0 || r.status == 2) << cmd << "\nstatus " << r.status << "\n" << r.err;
  if (r.status == 2) {
    EXPECT_EQ(CountLines(r.err), 1) << cmd << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("alloycolor: error: ", 0), 0u) << cmd << "\n" << r.err;
  }
}

// A copy of the case with the extension its reader is chosen by.
std::string CopyAs(const fs::path& file, const std::string& dir, const std::string& name) {
  const fs::path to = fs::path(dir) / name;
  fs::copy_file(file, to, fs::copy_options::overwrite_existing);
  return to.string();
}

TEST(FuzzRegressions, OpticalConstantFiles) {
  const std::string dir = MakeTempDir();
  int count = 0;
  for (const auto& [target, extension] :
       std::vector<std::pair<std::string, std::string>>{{"yaml", ".yml"}, {"csv", ".csv"}}) {
    for (const fs::path& file : Cases(target)) {
      SCOPED_TRACE(file.string());
      ExpectCleanRun({"color", "--quiet", "--nk", CopyAs(file, dir, "input" + extension)});
      ++count;
    }
  }
  EXPECT_GE(count, 1);
}

TEST(FuzzRegressions, Manifests) {
  for (const fs::path& file : Cases("manifest")) {
    SCOPED_TRACE(file.string());
    const std::string dir = MakeTempDir();
    for (const auto& sample :
         fs::directory_iterator(fs::path(TestsDir()) / "fuzz-regressions" / "manifest-files")) {
      fs::copy_file(sample.path(), fs::path(dir) / sample.path().filename());
    }
    const std::string manifest = CopyAs(file, dir, "dataset.json");
    ExpectCleanRun({"color", "--quiet", "--data", manifest, "--x", "0.5"});
    ExpectCleanRun({"sweep", "--quiet", "--data", manifest, "--steps", "3"});
  }
}

TEST(FuzzRegressions, ModelFiles) {
  const std::string dir = MakeTempDir();
  int count = 0;
  for (const fs::path& file : Cases("model")) {
    SCOPED_TRACE(file.string());
    const std::string model = CopyAs(file, dir, "model.json");
    ExpectCleanRun({"color", "--quiet", "--model", model, "--x", "0.5"});
    ExpectCleanRun({"sweep", "--quiet", "--model", model, "--steps", "3"});
    ExpectCleanRun({"predict", "--quiet", "--model", model, "--x", "0.5"});
    ++count;
  }
  EXPECT_GE(count, 1);
}

}  // namespace
}  // namespace alloycolor::testing
