// Helpers shared by the tests: running the real program, temporary folders.
#ifndef ALLOYCOLOR_TESTS_TEST_UTIL_H_
#define ALLOYCOLOR_TESTS_TEST_UTIL_H_

#include <gtest/gtest.h>

#include <complex>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/core/error.h"

namespace alloycolor::testing {

struct RunResult {
  int status;       // exit status, or -1 if killed by a signal
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs the alloycolor program with the given arguments (no shell), capturing its output.
RunResult RunProgram(const std::vector<std::string>& args);

// A fresh empty folder under the system's temporary folder, removed with its contents
// when the test program ends.
std::string MakeTempDir();

// Writes text to path (overwriting).
void WriteText(const std::string& path, const std::string& text);

// The whole file at path, as bytes ("" when it cannot be read).
std::string ReadText(const std::string& path);

// The message of the Error thrown by f, which must be one line, or "" and
// a test failure when none is thrown.
template <typename F>
std::string ErrorOf(F f) {
  try {
    f();
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "message spans lines: " << message;
    return message;
  }
  ADD_FAILURE() << "no Error thrown";
  return "";
}

// The bundled data folder and the tests folder of the source tree.
std::string DataDir();
std::string TestsDir();

// The rows of a CSV table in tests/reference/ as numbers: lines that start with '#' and
// the header line are skipped.
std::vector<std::vector<double>> ReadReferenceTable(const std::string& name);

// Counts lines in text.
int CountLines(const std::string& text);

// A data set (a folder with dataset.json, system Au-Ag, atomic fractions) of the given
// compositions whose eps at (x, lambda) is truth(x, lambda), as n, k CSV files every 5 nm
// from first_nm to last_nm.
std::string WriteSyntheticDataset(const std::vector<double>& xs,
                                  const std::function<std::complex<double>(double, double)>& truth,
                                  double first_nm = 380, double last_nm = 800);

// A dielectric (x = 0) and a metal (x = 1) with ln eps linear in composition between them:
// eps the geometric interpolation, arg eps running from near 0 to near pi.
std::complex<double> Geometric(double x, double lambda_nm);

// Two metals with eps linear in composition between them.
std::complex<double> LinearEps(double x, double lambda_nm);

// Reading `doc` as a model file named "m.json" fails with one message naming the file and
// containing `needle` (a GoogleTest failure otherwise).
void ExpectModelFileError(const nlohmann::json& doc, const std::string& needle);

}  // namespace alloycolor::testing

#endif  // ALLOYCOLOR_TESTS_TEST_UTIL_H_
