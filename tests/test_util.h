// Helpers shared by the tests: running the real program, temporary folders.
#ifndef ALLOYCOLOR_TESTS_TEST_UTIL_H_
#define ALLOYCOLOR_TESTS_TEST_UTIL_H_

#include <string>
#include <vector>

namespace alloycolor::testing {

struct RunResult {
  int status;          // exit status, or -1 if killed by a signal
  std::string out;     // stdout
  std::string err;     // stderr
};

// Runs the alloycolor program with the given arguments (no shell), capturing its output.
RunResult RunProgram(const std::vector<std::string>& args);

// A fresh empty folder under the system's temporary folder.
std::string MakeTempDir();

// Writes text to path (overwriting).
void WriteText(const std::string& path, const std::string& text);

// The bundled data folder and the tests folder of the source tree.
std::string DataDir();
std::string TestsDir();

// Counts lines in text.
int CountLines(const std::string& text);

}  // namespace alloycolor::testing

#endif  // ALLOYCOLOR_TESTS_TEST_UTIL_H_
