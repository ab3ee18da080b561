// The real program on the bad-input corpus of tests/bad-inputs/: every file gets a one-line
// error naming the culprit and exit status 2, never a crash or a hang. Which commands run
// depends on the kind of file:
//   *.dataset.json  color --data FILE --x 0.5; sweep --data FILE --steps 3
//   *.model.json    color --model FILE --x 0.5; sweep --model FILE --steps 3;
//                   predict --model FILE --x 0.5 (unless the file is a valid model that
//                   only lacks the visible)
//   anything else   color --nk FILE
// tests/bad-inputs/expectations.txt lists what the error must contain (default: the file's
// name); samples/ holds good files the manifests point at.
//
// Also here: outputs are written atomically, so a run that fails part-way leaves an
// existing file byte-identical and no temporary file behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "test_util.h"

namespace alloycolor::testing {
namespace {

namespace fs = std::filesystem;

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string BadInputs() { return TestsDir() + "/bad-inputs"; }

// expectations.txt: "FILE: NEEDLE | NEEDLE ..." and "FILE [FLAG FLAG]: ...".
struct Expectation {
  std::vector<std::string> needles;
  bool predict = true;
};

std::map<std::string, Expectation> ReadExpectations() {
  std::map<std::string, Expectation> expectations;
  std::istringstream in(ReadBytes(BadInputs() + "/expectations.txt"));
  std::string line;
  const auto trim = [](std::string s) {
    s.erase(0, s.find_first_not_of(' '));
    s.erase(s.find_last_not_of(' ') + 1);
    return s;
  };
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t colon = line.find(": ");
    if (colon == std::string::npos) continue;
    std::string name = trim(line.substr(0, colon));
    Expectation e;
    if (const size_t open = name.find('['); open != std::string::npos) {
      const std::string flags = name.substr(open);
      e.predict = flags.find("no-predict") == std::string::npos;
      name = trim(name.substr(0, open));
    }
    std::istringstream needles(line.substr(colon + 2));
    std::string needle;
    while (std::getline(needles, needle, '|')) {
      needle = trim(needle);
      if (!needle.empty()) e.needles.push_back(needle);
    }
    expectations[name] = e;
  }
  return expectations;
}

std::vector<std::vector<std::string>> CommandsFor(const std::string& path, bool predict) {
  if (EndsWith(path, ".dataset.json")) {
    return {{"color", "--data", path, "--x", "0.5"}, {"sweep", "--data", path, "--steps", "3"}};
  }
  if (EndsWith(path, ".model.json")) {
    std::vector<std::vector<std::string>> commands = {{"color", "--model", path, "--x", "0.5"},
                                                      {"sweep", "--model", path, "--steps", "3"}};
    if (predict) commands.push_back({"predict", "--model", path, "--x", "0.5"});
    return commands;
  }
  return {{"color", "--nk", path}};
}

TEST(BadInputCorpus, EveryFileGetsOneClearErrorAndStatus2) {
  const std::map<std::string, Expectation> expectations = ReadExpectations();
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(BadInputs())) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && name != "expectations.txt") files.push_back(name);
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 60u);
  for (const auto& [name, e] : expectations) {
    EXPECT_TRUE(std::binary_search(files.begin(), files.end(), name))
        << "expectations.txt names " << name << ", which is not in tests/bad-inputs";
  }
  for (const std::string& name : files) {
    const auto it = expectations.find(name);
    const Expectation expectation =
        it != expectations.end() ? it->second : Expectation{{name}, true};
    for (const auto& args : CommandsFor(BadInputs() + "/" + name, expectation.predict)) {
      std::string cmd;
      for (const auto& a : args) cmd += a + " ";
      SCOPED_TRACE(cmd);
      const RunResult r = RunProgram(args);
      EXPECT_EQ(r.status, 2) << r.err;
      EXPECT_EQ(CountLines(r.err), 1) << r.err;
      EXPECT_EQ(r.err.rfind("alloycolor: error: ", 0), 0u) << r.err;
      EXPECT_TRUE(r.out.empty()) << r.out.substr(0, 200);
      for (const std::string& needle : expectation.needles) {
        EXPECT_NE(r.err.find(needle), std::string::npos) << "'" << needle << "' not in " << r.err;
      }
    }
  }
}

// ---- Safe outputs ----

// Files in dir other than the given ones (left-over temporaries).
std::vector<std::string> OtherFiles(const std::string& dir, const std::vector<std::string>& keep) {
  std::vector<std::string> others;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (std::find(keep.begin(), keep.end(), name) == keep.end()) others.push_back(name);
  }
  return others;
}

class SafeOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = MakeTempDir();
    model_ = dir_ + "/model.json";
    const RunResult r =
        RunProgram({"fit", "--data", "Au-Ag", "--method", "paper", "--out", model_, "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
    old_ = ReadBytes(model_);
    ASSERT_FALSE(old_.empty());
  }
  void ExpectUnchanged() {
    EXPECT_EQ(ReadBytes(model_), old_);
    EXPECT_EQ(OtherFiles(dir_, {"model.json"}), std::vector<std::string>{});
  }
  std::string dir_, model_, old_;
};

TEST_F(SafeOutput, AFitThatFailsPartWayLeavesTheOldModel) {
  // The data set loads, then building the model fails (one sample, no common range).
  for (const char* manifest : {"one-sample.dataset.json", "no-common-range.dataset.json"}) {
    for (const char* method : {"paper", "smooth"}) {
      const RunResult r = RunProgram(
          {"fit", "--data", BadInputs() + "/" + manifest, "--method", method, "--out", model_});
      EXPECT_EQ(r.status, 2) << manifest << " " << method << ": " << r.err;
      ExpectUnchanged();
    }
  }
  // A damaged sample part-way through the data set.
  const RunResult r = RunProgram(
      {"fit", "--data", BadInputs() + "/points-at-bad-sample.dataset.json", "--out", model_});
  EXPECT_EQ(r.status, 2) << r.err;
  ExpectUnchanged();
}

TEST_F(SafeOutput, AWriteThatFailsLeavesNothingBehind) {
  // The output is a folder: the rename fails after the temporary file was written.
  fs::create_directory(dir_ + "/folder.json");
  RunResult r = RunProgram(
      {"fit", "--data", "Au-Ag", "--method", "paper", "--out", dir_ + "/folder.json", "--quiet"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("folder.json"), std::string::npos) << r.err;
  EXPECT_EQ(CountLines(r.err), 1) << r.err;
  EXPECT_TRUE(fs::is_directory(dir_ + "/folder.json"));
  fs::remove(dir_ + "/folder.json");
  ExpectUnchanged();
  // A folder that does not exist.
  r = RunProgram({"fit", "--data", "Au-Ag", "--method", "paper", "--out",
                  dir_ + "/no/such/folder/model.json", "--quiet"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("no/such/folder"), std::string::npos) << r.err;
  ExpectUnchanged();
}

TEST_F(SafeOutput, ASuccessfulRunReplacesTheFileWhole) {
  const RunResult r =
      RunProgram({"fit", "--data", "Au-Ag", "--method", "eps-linear", "--out", model_, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string now = ReadBytes(model_);
  EXPECT_NE(now, old_);
  EXPECT_NE(now.find("\"eps-linear\""), std::string::npos);
  EXPECT_EQ(OtherFiles(dir_, {"model.json"}), std::vector<std::string>{});
}

}  // namespace
}  // namespace alloycolor::testing
