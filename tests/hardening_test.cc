// Issue 17, through the real program (ALLOYCOLOR_BINARY) unless stated: no command loses
// data (an output that is an input, a device, a FIFO or a symlink is refused; a set of
// files is replaced all or nothing; a signal mid-write leaves no temporary), no size read
// from a file or an option runs away, option values are checked, a closed pipe ends a
// run quietly, and every error is one sanitised line. The references are the inputs' own
// bytes (unchanged), the file system's own state (still a FIFO, still a link) and the
// exit statuses the program documents.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/output.h"
#include "test_util.h"

namespace alloycolor::testing {
namespace {

namespace fs = std::filesystem;

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// One error line, status 2, containing every needle.
void ExpectOneError(const RunResult& r, const std::vector<std::string>& needles) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(CountLines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("alloycolor: error: ", 0), 0u) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out.substr(0, 200);
  for (const std::string& needle : needles) {
    EXPECT_NE(r.err.find(needle), std::string::npos) << "'" << needle << "' not in " << r.err;
  }
}

// A copy of the bundled Au-Ag data set in a temporary folder.
std::string CopyAuAg() {
  const std::string dir = MakeTempDir() + "/ds";
  fs::copy(DataDir() + "/Au-Ag", dir, fs::copy_options::recursive);
  return dir;
}

// Every regular file under dir with its bytes.
std::vector<std::pair<std::string, std::string>> Snapshot(const std::string& dir) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) files.emplace_back(entry.path().string(), ReadBytes(entry.path()));
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(OutputWriter, RefusesEveryInputOfTheCommand) {
  const std::string ds = CopyAuAg();
  const auto before = Snapshot(ds);
  // The manifest, a sample (by a path with "..") and a hard link to a sample.
  ASSERT_EQ(link((ds + "/Rioux-Au50Ag50.yml").c_str(), (ds + "/../linked.yml").c_str()), 0);
  for (const std::string& out :
       {ds + "/dataset.json", ds + "/../ds/Rioux-Au50Ag50.yml", ds + "/../linked.yml"}) {
    SCOPED_TRACE(out);
    ExpectOneError(RunProgram({"fit", "--data", ds, "--method", "paper", "--out", out, "--quiet"}),
                   {"one of this command's inputs"});
  }
  EXPECT_EQ(Snapshot(ds), before);
  // A model file read by render and export (whose --out is a prefix: m + ".gltf").
  const std::string model = ds + "/../m.gltf";
  ASSERT_EQ(
      RunProgram({"fit", "--data", ds, "--method", "paper", "--out", model, "--quiet"}).status, 0);
  const std::string model_bytes = ReadBytes(model);
  ExpectOneError(RunProgram({"render", "--model", model, "--x", "0.5", "--size", "16", "--out",
                             model, "--quiet"}),
                 {"one of this command's inputs"});
  ExpectOneError(RunProgram({"export", "--model", model, "--x", "0.5", "--format", "gltf", "--out",
                             ds + "/../m", "--quiet"}),
                 {"one of this command's inputs"});
  EXPECT_EQ(ReadBytes(model), model_bytes);
  EXPECT_EQ(Snapshot(ds), before);
}

TEST(OutputWriter, RefusesSymlinksFifosAndDevices) {
  const std::string dir = MakeTempDir();
  const std::string target = dir + "/target.json";
  WriteText(target, "keep\n");
  ASSERT_EQ(symlink(target.c_str(), (dir + "/link.json").c_str()), 0);
  ASSERT_EQ(mkfifo((dir + "/fifo.json").c_str(), 0600), 0);
  for (const std::string& out :
       {dir + "/link.json", dir + "/fifo.json", std::string("/dev/null")}) {
    SCOPED_TRACE(out);
    ExpectOneError(
        RunProgram({"fit", "--data", "Au-Ag", "--method", "paper", "--out", out, "--quiet"}),
        {out});
  }
  struct stat info;
  ASSERT_EQ(lstat((dir + "/link.json").c_str(), &info), 0);
  EXPECT_TRUE(S_ISLNK(info.st_mode));
  ASSERT_EQ(lstat((dir + "/fifo.json").c_str(), &info), 0);
  EXPECT_TRUE(S_ISFIFO(info.st_mode));
  ASSERT_EQ(stat("/dev/null", &info), 0);
  EXPECT_TRUE(S_ISCHR(info.st_mode));
  EXPECT_EQ(ReadBytes(target), "keep\n");
}

TEST(OutputWriter, A250CharacterNameIsWritten) {
  const std::string dir = MakeTempDir();
  const std::string name = std::string(245, 'm') + ".json";
  ASSERT_EQ(name.size(), 250u);
  const RunResult r = RunProgram(
      {"fit", "--data", "Au-Ag", "--method", "paper", "--out", dir + "/" + name, "--quiet"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(dir + "/" + name));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  EXPECT_LE(fs::path(TemporaryPathFor(dir + "/" + name)).filename().string().size(), 255u);
}

TEST(OutputWriter, AReportIsReplacedAsASet) {
  const std::string dir = MakeTempDir();
  const std::string out = dir + "/report";
  const std::vector<std::string> args = {"validate",  "--data", "Au-Ag", "--holdout", "0.5",
                                         "--methods", "paper",  "--out", out,         "--quiet"};
  RunResult r = RunProgram(args);
  ASSERT_EQ(r.status, 0) << r.err;
  WriteText(out + "/report.json", "old json\n");
  fs::remove(out + "/report.html");
  WriteText(dir + "/elsewhere.html", "old html\n");
  ASSERT_EQ(symlink((dir + "/elsewhere.html").c_str(), (out + "/report.html").c_str()), 0);
  // The HTML cannot be written: the JSON must stay the old one, and nothing is left over.
  r = RunProgram(args);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(ReadBytes(out + "/report.json"), "old json\n");
  EXPECT_EQ(ReadBytes(dir + "/elsewhere.html"), "old html\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 2);
}

// In-process: a child writing a large file through an OutputGuard is sent SIGTERM while
// its temporary exists; its handler (the program's, in miniature) removes the guard's
// temporaries: the temporary must be gone and the old file kept. Tried a few times,
// because the child may finish before the parent sees the temporary.
OutputGuard* g_child_guard = nullptr;

extern "C" void ChildRemoveTemporaries(int signal_number) {
  if (g_child_guard) g_child_guard->RemoveTemporaries();
  signal(signal_number, SIG_DFL);
  raise(signal_number);
}

TEST(OutputWriter, SigtermRemovesTheTemporary) {
  const std::string dir = MakeTempDir();
  const std::string out = dir + "/big.bin";
  WriteText(out, "old\n");
  bool caught = false;
  for (int attempt = 0; attempt < 5 && !caught; ++attempt) {
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      OutputGuard guard;
      g_child_guard = &guard;
      signal(SIGTERM, ChildRemoveTemporaries);
      try {
        WriteFileAtomic(out, std::string(256u << 20, 'x'), &guard);
      } catch (...) {
        _exit(3);
      }
      _exit(0);
    }
    // TemporaryPathFor names the caller's own; the child's carries the child's id.
    const std::string temp_for_child = dir + "/big.bin.~" + std::to_string(pid);
    bool seen = false;
    int status = 0;
    while (!seen) {
      if (fs::exists(temp_for_child)) seen = true;
      if (waitpid(pid, &status, WNOHANG) == pid) break;
      if (!seen) usleep(200);
    }
    if (!seen) {
      WriteText(out, "old\n");  // the child finished first: try again
      continue;
    }
    kill(pid, SIGTERM);
    waitpid(pid, &status, 0);
    if (WIFEXITED(status)) {  // the write ended before the signal arrived
      WriteText(out, "old\n");
      continue;
    }
    caught = true;
    EXPECT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(WTERMSIG(status), SIGTERM);
    EXPECT_FALSE(fs::exists(temp_for_child));
    EXPECT_EQ(ReadBytes(out), "old\n");
  }
  if (!caught) GTEST_SKIP() << "the child always finished before the signal";
}

// The same through the real program: a sweep streaming to --out, sent SIGTERM while its
// temporary exists, leaves no temporary and the old file.
TEST(OutputWriter, SigtermRemovesTheProgramsTemporary) {
  const std::string dir = MakeTempDir();
  const std::string out = dir + "/sweep.csv";
  WriteText(out, "old\n");
  bool caught = false;
  for (int attempt = 0; attempt < 3 && !caught; ++attempt) {
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      const char* program = ALLOYCOLOR_BINARY;
      execl(program, program, "sweep", "--data", "Au-Ag", "--method", "eps-linear", "--steps",
            "5000000", "--out", out.c_str(), "--quiet", static_cast<char*>(nullptr));
      _exit(127);
    }
    const std::string temp = out + ".~" + std::to_string(pid);
    bool seen = false;
    int status = 0;
    while (!seen) {
      if (fs::exists(temp) && fs::file_size(temp) > 0) seen = true;
      if (waitpid(pid, &status, WNOHANG) == pid) break;
      if (!seen) usleep(500);
    }
    if (!seen) {
      WriteText(out, "old\n");
      continue;
    }
    kill(pid, SIGTERM);
    waitpid(pid, &status, 0);
    if (WIFEXITED(status)) {
      WriteText(out, "old\n");
      continue;
    }
    caught = true;
    EXPECT_EQ(WTERMSIG(status), SIGTERM);
    EXPECT_FALSE(fs::exists(temp));
    EXPECT_EQ(ReadBytes(out), "old\n");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  }
  if (!caught) GTEST_SKIP() << "the sweep always finished before the signal";
}

// The guard is an object: reading a file notes nothing; a guard refuses the inputs noted
// in it, and only those; without a guard, only special files are refused.
TEST(OutputGuard, OnlyNotedInputsAreRefused) {
  const std::string dir = MakeTempDir();
  const std::string input = dir + "/in.csv";
  WriteText(input, "lambda_nm,n,k\n500,1,2\n600,1,2\n");
  EXPECT_FALSE(ReadFileText(input).empty());
  WriteFileAtomic(input, ReadFileText(input));  // read, then written back: allowed
  OutputGuard guard;
  WriteFileAtomic(input, ReadFileText(input), &guard);  // read but not noted: allowed
  guard.NoteInput(input);
  EXPECT_THAT(ErrorOf([&] { WriteFileAtomic(input, "new\n", &guard); }),
              ::testing::HasSubstr("one of this command's inputs"));
  EXPECT_THAT(ErrorOf([&] {
                StreamOutput stream(dir + "/../" + fs::path(dir).filename().string() + "/in.csv",
                                    &guard);
              }),
              ::testing::HasSubstr("one of this command's inputs"));
  OutputGuard other;
  WriteFileAtomic(input, "other\n", &other);
  EXPECT_EQ(ReadBytes(input), "other\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

// The program run under `ulimit -f KB` through bash, its outputs captured in files
// outside the limit's reach (the shell opens them before the limit applies to writes).
RunResult RunWithFileLimit(int kilobytes, const std::vector<std::string>& args,
                           const std::string& stdout_path = "") {
  const std::string files = MakeTempDir();
  std::string command =
      "ulimit -f " + std::to_string(kilobytes) + "; exec '" + std::string(ALLOYCOLOR_BINARY) + "'";
  for (const std::string& a : args) command += " '" + a + "'";
  const std::string out = stdout_path.empty() ? files + "/out" : stdout_path;
  command += " >'" + out + "' 2>'" + files + "/err'";
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/bash", "bash", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  RunResult r;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = ReadBytes(out);
  r.err = ReadBytes(files + "/err");
  fs::remove_all(files);
  return r;
}

// No file in dir whose name holds ".~" (a temporary left behind).
void ExpectNoTemporary(const std::string& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".~"), std::string::npos) << entry.path();
  }
}

// SIGXFSZ is ignored, so a file past `ulimit -f` is an error the writer sees (EFBIG): one
// line naming the output and the limit, status 2, no temporary, no partial output, the
// old file kept.
TEST(Resources, AFileSizeLimitIsOneErrorAndNoPartialOutput) {
  const std::string dir = MakeTempDir();
  const std::string model = dir + "/m.json";
  ASSERT_EQ(
      RunProgram({"fit", "--data", "Au-Ag", "--method", "paper", "--out", model, "--quiet"}).status,
      0);
  const std::string old = dir + "/old.out";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"fit", "--data", "Au-Ag", "--method", "paper", "--out", old,
                                 "--quiet"},
        {"sweep", "--model", model, "--steps", "100000", "--out", old, "--quiet"},
        {"sweep", "--model", model, "--steps", "100000", "--format", "json", "--out", old},
        {"explore", "--model", model, "--size", "64", "--out", old, "--quiet"}}) {
    SCOPED_TRACE(args[0] + " " + args.back());
    WriteText(old, "old\n");
    const RunResult r = RunWithFileLimit(10, args);
    EXPECT_NE(r.status, 0);
    ExpectOneError(r, {old, "ulimit -f"});
    EXPECT_EQ(ReadBytes(old), "old\n");
    ExpectNoTemporary(dir);
  }
  // Standard output redirected to a file: refused before a byte is written.
  const std::string stdout_file = dir + "/stdout.csv";
  const RunResult r =
      RunWithFileLimit(10, {"sweep", "--model", model, "--steps", "100000"}, stdout_file);
  ExpectOneError(r, {"standard output", "ulimit -f"});
  EXPECT_EQ(ReadBytes(stdout_file), "");
  ExpectNoTemporary(dir);
  // Under the limit, the same commands work.
  const RunResult small = RunWithFileLimit(100000, {"sweep", "--model", model, "--steps", "5"});
  EXPECT_EQ(small.status, 0) << small.err;
  EXPECT_EQ(CountLines(small.out), 6);
}

TEST(Bounds, OptionValuesAreChecked) {
  const std::string out = MakeTempDir() + "/m.json";
  for (const std::vector<std::string>& extra : {std::vector<std::string>{"--smoothing", "nan"},
                                                {"--smoothing", "-1"},
                                                {"--smoothing", "inf"},
                                                {"--degree", "2.5"},
                                                {"--degree", "1099511627776"},
                                                {"--lambda-step", "1e-6"},
                                                {"--lambda-step", "0.02"}}) {
    std::vector<std::string> args = {"fit",    "--data", "Au-Ag", "--method",
                                     "smooth", "--out",  out,     "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    SCOPED_TRACE(extra[0] + " " + extra[1]);
    ExpectOneError(RunProgram(args), {extra[0]});
  }
  EXPECT_FALSE(fs::exists(out));
  // 20,000 compositions: refused at once rather than computed for a minute.
  std::string xs = "0.5";
  for (int i = 1; i < 20000; ++i) xs += ",0.5";
  ExpectOneError(RunProgram({"color", "--data", "Au-Ag", "--x", xs}), {"at most 1000"});
}

TEST(Bounds, ColourTablesMustBeSmallRegularFiles) {
  const std::string data = MakeTempDir() + "/data";
  fs::create_directories(data + "/cie");
  fs::copy(DataDir() + "/cie", data + "/cie", fs::copy_options::recursive);
  const std::string table = data + "/cie/illuminant-D65.csv";
  fs::remove(table);
  ASSERT_EQ(mkfifo(table.c_str(), 0600), 0);
  const std::string nk = DataDir() + "/pure/Au-Johnson.yml";
  ASSERT_TRUE(fs::exists(nk)) << nk;
  setenv("ALLOYCOLOR_DATA_DIR", data.c_str(), 1);
  ExpectOneError(RunProgram({"color", "--nk", nk}), {"illuminant-D65.csv", "not a regular file"});
  fs::remove(table);
  ASSERT_EQ(symlink("/dev/zero", table.c_str()), 0);
  ExpectOneError(RunProgram({"color", "--nk", nk}), {"illuminant-D65.csv", "not a regular file"});
  unsetenv("ALLOYCOLOR_DATA_DIR");
}

TEST(Bounds, AnOversizedYamlFileIsRefused) {
  const std::string path = MakeTempDir() + "/big.yml";
  std::string text = "IGNORED: [";
  while (text.size() < (9u << 20)) text += "1,2,3,4,5,6,7,8,9,";
  text +=
      "0]\nDATA:\n  - type: tabulated nk\n    data: |\n        0.4 0.2 2.0\n        0.8 0.2 5.0\n";
  WriteText(path, text);
  ExpectOneError(RunProgram({"color", "--nk", path}), {"big.yml", "too large"});
}

TEST(Streams, AClosedPipeEndsTheRunQuietly) {
  const std::string dir = MakeTempDir();
  const std::string err = dir + "/err";
  for (const std::string& command :
       {std::string("sweep --data Au-Ag --method eps-linear --steps 300000"),
        std::string("sweep --data Au-Ag --method eps-linear --steps 300000 --format json")}) {
    SCOPED_TRACE(command);
    const std::string shell = "set -o pipefail; '" + std::string(ALLOYCOLOR_BINARY) + "' " +
                              command + " 2>'" + err + "' | head -c 100 >/dev/null";
    const int status = std::system(("bash -c \"" + shell + "\"").c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
    EXPECT_EQ(ReadBytes(err), "");
  }
}

TEST(Messages, OptionValuesAreShownOnOneSafeLine) {
  const RunResult r =
      RunProgram({"color", "--data", "Au-Ag", "--x", "0.5\n\x1b[31mred" + std::string(600, 'z')});
  ExpectOneError(r, {});
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos);
  EXPECT_LE(r.err.size(), 330u);
}

TEST(Messages, AModelWithAStringFinalCostNamesTheField) {
  const std::string dir = MakeTempDir();
  const std::string model = dir + "/m.json";
  ASSERT_EQ(RunProgram({"fit", "--data", "Au-Ag", "--method", "smooth", "--out", model, "--quiet"})
                .status,
            0);
  std::string text = ReadBytes(model);
  const std::size_t at = text.find("\"final_cost\":");
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = text.find_first_of(",\n}", at + 13);
  text = text.substr(0, at) + "\"final_cost\": \"cheap\"" + text.substr(end);
  WriteText(model, text);
  ExpectOneError(RunProgram({"color", "--model", model, "--x", "0.5"}), {"m.json", "final_cost"});
  ExpectOneError(RunProgram({"fit", "--data", "Au-Ag", "--method", "smooth", "--refit", model,
                             "--out", dir + "/new.json", "--quiet"}),
                 {"m.json", "final_cost"});
}

// A full device (ENOSPC) on standard output: one line naming standard output and the
// cause, status 2, for a command that prints a table and for a sweep.
TEST(Resources, AFullDiskIsOneErrorNamingTheOutput) {
  const std::string dir = MakeTempDir();
  for (const std::string& args : {std::string("color --data Au-Ag --method paper --x 0.5,0.6"),
                                  std::string("sweep --data Au-Ag --method paper --steps 10"),
                                  std::string("predict --data Au-Ag --method paper --x 0.5")}) {
    SCOPED_TRACE(args);
    const std::string command =
        "exec '" + std::string(ALLOYCOLOR_BINARY) + "' " + args + " >/dev/full 2>'" + dir + "/err'";
    const int status = std::system(("bash -c \"" + command + "\"").c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2);
    const std::string err = ReadBytes(dir + "/err");
    EXPECT_EQ(CountLines(err), 1) << err;
    EXPECT_NE(err.find("cannot write standard output: no space left"), std::string::npos) << err;
  }
}

// A file name that is not UTF-8 (byte 0xff, from a Latin-1 folder) reaches JSON output
// with U+FFFD in its place, instead of nlohmann's "invalid UTF-8 byte" naming nothing.
TEST(Messages, AFileNameThatIsNotUtf8IsReplacedInJson) {
  const std::string dir = MakeTempDir();
  const std::string nk = dir + "/Au\xff.yml";
  fs::copy_file(DataDir() + "/pure/Au-Johnson.yml", nk);
  const RunResult color = RunProgram({"color", "--nk", nk, "--json"});
  ASSERT_EQ(color.status, 0) << color.err;
  const nlohmann::json out = nlohmann::json::parse(color.out);
  EXPECT_EQ(out.at("source").get<std::string>(), dir + "/Au\xef\xbf\xbd.yml");
  const RunResult exported = RunProgram(
      {"export", "--nk", nk, "--format", "f82", "--out", dir + "/e\xff", "--json", "--quiet"});
  ASSERT_EQ(exported.status, 0) << exported.err;
  const nlohmann::json files = nlohmann::json::parse(exported.out).at("files");
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].get<std::string>(), dir + "/e\xef\xbf\xbd.f82.json");
  EXPECT_TRUE(fs::exists(dir + "/e\xff.f82.json"));
}

// ---- Round two: the classes still open after the first pass.

std::string BadInput(const std::string& name) { return TestsDir() + "/bad-inputs/" + name; }

// A sweep past 1 GB is refused before the work, naming its size and --force; forced, it
// must still fit the size limit for files and the free space of its file system. "Before
// the work": before the model is built, so a data set that cannot be fitted is not reached.
TEST(Resources, AHugeSweepIsRefusedUnlessForced) {
  const std::string dir = MakeTempDir();
  const std::string out = dir + "/huge.csv";
  const std::string one_sample = BadInput("one-sample.dataset.json");
  const RunResult r =
      RunProgram({"sweep", "--data", one_sample, "--steps", "1000000000", "--out", out});
  ExpectOneError(r, {"--steps 1000000000", "1000000000 rows", "78 GB", "1 GB", "--force"});
  ExpectOneError(
      RunProgram({"sweep", "--data", one_sample, "--steps", "20000000", "--format", "json"}),
      {"2.2 GB", "--force"});
  // Forced past `ulimit -f`: refused before the work, naming the limit.
  const RunResult forced = RunWithFileLimit(
      1000, {"sweep", "--data", one_sample, "--steps", "20000000", "--force", "--out", out});
  ExpectOneError(forced, {out, "1.6 GB", "ulimit -f"});
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 0);
  // Forced past the free space: only tried where the file system has less than the
  // sweep's 111 GB of JSON (otherwise the sweep would start writing them).
  struct statvfs fs_info;
  ASSERT_EQ(statvfs(dir.c_str(), &fs_info), 0);
  const double free_bytes = static_cast<double>(fs_info.f_bavail) * fs_info.f_frsize;
  if (free_bytes > 100e9) GTEST_SKIP() << "over 100 GB free: the free-space check is not tried";
  ExpectOneError(RunProgram({"sweep", "--data", one_sample, "--steps", "1000000000", "--format",
                             "json", "--force", "--out", out, "--quiet"}),
                 {out, "111 GB to write", "free on its file system"});
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 0);
}

// Every command that reads a model refuses one that cannot be used over its stated range,
// at once, naming the file and what is wrong: a grid past the range, a sample short of it,
// eps the physical model cannot compute (it returns 0 there: never a white colour with
// sigma 0), covariance draws that overflow.
TEST(ModelFiles, AnUnusableModelIsRefusedByEveryCommand) {
  const std::string dir = MakeTempDir();
  const std::vector<std::pair<std::string, std::string>> models = {
      {"smooth-grid-short-of-range.model.json", "parameters.lambda_nm"},
      {"paper-sample-short.model.json", "parameters.samples[1].lambda_nm"},
      {"lambda-range-1e17.model.json", "lambda_range_nm"},
      {"physical-eps-zero.model.json", "no usable permittivity"},
      {"physical-covariance-overflow.model.json", "parameters.covariance"}};
  for (const auto& [name, field] : models) {
    const std::string model = BadInput(name);
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"color", "--model", model, "--x", "0.5", "--json"},
          {"sweep", "--model", model, "--steps", "1000"},
          {"sweep", "--model", model, "--steps", "5", "--exact"},
          {"predict", "--model", model, "--x", "0.5", "--format", "json"},
          {"params", "--model", model},
          {"render", "--model", model, "--x", "0.5", "--size", "8", "--out", dir + "/r.png"},
          {"export", "--model", model, "--x", "0.5", "--out", dir + "/e"},
          {"chart", "--model", model, "--steps", "3", "--out", dir + "/c.svg"}}) {
      SCOPED_TRACE(args[0] + " " + name);
      ExpectOneError(RunProgram(args), {name, field});
    }
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 0);
}

// A sweep is all or nothing. A model that cannot be evaluated part-way (the physical
// model, its x range narrowed by hand to [0, 0.3] and an E0 given a P6 term, extrapolated:
// E0 reaches 0 near x = 0.77) prints no row, on standard output or in --out.
TEST(Streams, ASweepThatFailsPartWayShowsNoRow) {
  const std::string model = TestsDir() + "/hardening/physical-narrow-x-range.model.json";
  const std::vector<std::string> sweep = {"sweep",   "--model", model,   "--extrapolate",
                                          "--exact", "--steps", "20000", "--from",
                                          "0",       "--to",    "1",     "--quiet"};
  ExpectOneError(RunProgram(sweep), {model, "no usable permittivity"});
  const std::string dir = MakeTempDir();
  const std::string out = dir + "/sweep.csv";
  WriteText(out, "old\n");
  std::vector<std::string> args = sweep;
  args.insert(args.end(), {"--out", out});
  ExpectOneError(RunProgram(args), {model, "no usable permittivity"});
  EXPECT_EQ(ReadBytes(out), "old\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  // In range it works.
  const RunResult r = RunProgram({"sweep", "--model", model, "--steps", "5", "--exact"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(CountLines(r.out), 6);
}

// The program run with $TMPDIR set (RunProgram itself needs the caller's): through the
// shell, arguments without quotes or spaces.
RunResult RunWithTmpdir(const std::string& tmpdir, const std::vector<std::string>& args) {
  const std::string files = MakeTempDir();
  std::string command = "TMPDIR='" + tmpdir + "' '" + std::string(ALLOYCOLOR_BINARY) + "'";
  for (const std::string& a : args) command += " '" + a + "'";
  command += " >'" + files + "/out' 2>'" + files + "/err'";
  const int status = std::system(command.c_str());
  RunResult r;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = ReadBytes(files + "/out");
  r.err = ReadBytes(files + "/err");
  fs::remove_all(files);
  return r;
}

// Past 64 MiB standard output is held in an unlinked file in $TMPDIR until the sweep is
// complete: a sweep that cannot hold it (no such folder) prints nothing; one that can
// prints every row, complete JSON, the same bytes as --out.
TEST(Streams, ASweepPast64MiBIsHeldUntilComplete) {
  const std::vector<std::string> sweep = {"sweep",      "--data",  "Au-Ag",    "--method",
                                          "eps-linear", "--exact", "--format", "json",
                                          "--steps",    "700000",  "--quiet"};
  const std::string dir = MakeTempDir();
  ExpectOneError(RunWithTmpdir(dir + "/no-such-folder", sweep),
                 {"standard output", "64 MiB", "no-such-folder"});
  const RunResult r = RunWithTmpdir(dir, sweep);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_GT(r.out.size(), std::size_t{64} << 20);
  EXPECT_EQ(r.out.substr(r.out.size() - 4), "\n]}\n");
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 700000 + 2);  // head, rows, end
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 0);
  const std::string out = dir + "/sweep.json";
  std::vector<std::string> args = sweep;
  args.insert(args.end(), {"--out", out});
  ASSERT_EQ(RunProgram(args).status, 0);
  EXPECT_TRUE(ReadBytes(out) == r.out);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

// The colour table of `color` is all or nothing too: a list whose last composition cannot
// be coloured prints no row.
TEST(Streams, AColourListThatFailsPrintsNothing) {
  const std::string model = TestsDir() + "/hardening/physical-narrow-x-range.model.json";
  for (const char* format : {"--quiet", "--json"}) {
    ExpectOneError(
        RunProgram({"color", "--model", model, "--extrapolate", "--x", "0,0.2,0.95", format}),
        {model, "x = 0.95"});
  }
}

// Two validate runs into one folder, at the same time: the folder ends up holding one
// run's report.json and report.html, never one of each, and no temporary.
TEST(OutputWriter, TwoValidateRunsIntoOneFolderDoNotMix) {
  const std::string out = MakeTempDir() + "/report";
  const std::string program = ALLOYCOLOR_BINARY;
  auto run = [&](const std::string& method) {
    return "'" + program + "' validate --data Au-Ag --holdout 0.5 --methods " + method +
           " --out '" + out + "' --quiet >/dev/null 2>&1";
  };
  for (int round = 0; round < 4; ++round) {
    const std::string both = run("paper") + " & " + run("eps-linear") + " & wait";
    ASSERT_EQ(std::system(("bash -c \"" + both + "\"").c_str()), 0);
    const nlohmann::json report = nlohmann::json::parse(ReadBytes(out + "/report.json"));
    const std::string method = report.at("methods").at(0).get<std::string>();
    const std::string html = ReadBytes(out + "/report.html");
    SCOPED_TRACE("round " + std::to_string(round) + ": report.json is " + method + "'s");
    EXPECT_EQ(html.find("eps-linear") != std::string::npos, method == "eps-linear");
    EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 2);
  }
}

// Option lists are bounded and checked at once: before the model is built, so a data set
// that cannot be fitted (one sample) is never reached. NUL bytes, fractional degrees, a
// system of one element and one spectrum at two compositions are refused.
TEST(Bounds, ManyValuesAndOddInputsAreRefusedAtOnce) {
  std::string xs = "0.5";
  for (int i = 1; i < 20000; ++i) xs += ",0.5";
  const std::string one_sample = BadInput("one-sample.dataset.json");
  ExpectOneError(RunProgram({"color", "--data", one_sample, "--x", "0.5"}), {"one-sample"});
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"color", "--data", one_sample, "--x", xs},
        {"render", "--data", one_sample, "--x", xs, "--out", MakeTempDir() + "/r.png"},
        {"validate", "--data", one_sample, "--angles", xs, "--out", MakeTempDir() + "/v"}}) {
    SCOPED_TRACE(args[0]);
    ExpectOneError(RunProgram(args), {"at most 1000"});
  }
  ExpectOneError(RunProgram({"color", "--nk", BadInput("nul-in-number.yml")}),
                 {"nul-in-number.yml:5", "NUL"});
  ExpectOneError(RunProgram({"color", "--nk", BadInput("nul-in-number.csv")}),
                 {"nul-in-number.csv:3"});
  ExpectOneError(
      RunProgram({"color", "--data", BadInput("nul-in-file-name.dataset.json"), "--x", "0.5"}),
      {"NUL"});
  ExpectOneError(RunProgram({"fit", "--data", "Au-Ag", "--method", "smooth", "--degree", "1.5",
                             "--out", MakeTempDir() + "/m.json"}),
                 {"--degree"});
  ExpectOneError(
      RunProgram({"color", "--model", BadInput("system-au-au.model.json"), "--x", "0.5"}),
      {"system-au-au.model.json", "both 'Au'"});
  for (const char* manifest :
       {"same-file-twice.dataset.json", "same-spectrum-twice.dataset.json"}) {
    ExpectOneError(RunProgram({"fit", "--data", BadInput(manifest), "--method", "paper", "--out",
                               MakeTempDir() + "/m.json"}),
                   {manifest, "one"});
  }
}

// An output that is an input or a device is refused before the work, so the one error
// line is all a command prints (render and explore used to print their progress first).
TEST(OutputWriter, ABadOutputIsRefusedBeforeTheWork) {
  const std::string dir = MakeTempDir();
  const std::string model = dir + "/m.png";
  ASSERT_EQ(
      RunProgram({"fit", "--data", "Au-Ag", "--method", "paper", "--out", model, "--quiet"}).status,
      0);
  const std::string bytes = ReadBytes(model);
  ExpectOneError(
      RunProgram({"render", "--model", model, "--x", "0.5", "--size", "8", "--out", model}),
      {"one of this command's inputs"});
  ExpectOneError(
      RunProgram({"render", "--model", model, "--x", "0.5", "--size", "8", "--out", "/dev/null"}),
      {"/dev/null"});
  ExpectOneError(RunProgram({"explore", "--model", model, "--out", "/dev/null"}), {"/dev/null"});
  EXPECT_EQ(ReadBytes(model), bytes);
}

}  // namespace
}  // namespace alloycolor::testing
