#include "test_util.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/optics.h"

namespace alloycolor::testing {
namespace {

// The folders MakeTempDir made, removed with their contents when the test program ends.
class TempDirs {
 public:
  ~TempDirs() {
    for (const std::string& path : paths_) {
      std::error_code ignored;  // a test may have left a folder unreadable: nothing to do
      std::filesystem::remove_all(path, ignored);
    }
  }
  void Add(std::string path) { paths_.push_back(std::move(path)); }

 private:
  std::vector<std::string> paths_;
};

TempDirs& Made() {
  static TempDirs dirs;
  return dirs;
}

}  // namespace

std::string MakeTempDir() {
  std::string templ = (std::filesystem::temp_directory_path() / "alloycolor-test-XXXXXX").string();
  if (mkdtemp(templ.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  Made().Add(templ);
  return templ;
}

RunResult RunProgram(const std::vector<std::string>& args) {
  const std::string dir = MakeTempDir();
  const std::string out_path = dir + "/stdout";
  const std::string err_path = dir + "/stderr";
  pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    int out = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    int err = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    int in = open("/dev/null", O_RDONLY);
    dup2(in, 0);
    dup2(out, 1);
    dup2(err, 2);
    std::vector<char*> argv;
    std::string binary = ALLOYCOLOR_BINARY;
    argv.push_back(binary.data());
    std::vector<std::string> copy = args;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(binary.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  RunResult result;
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = ReadText(out_path);
  result.err = ReadText(err_path);
  std::filesystem::remove_all(dir);
  return result;
}

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string DataDir() { return ALLOYCOLOR_DATA_DIR; }
std::string TestsDir() { return ALLOYCOLOR_TESTS_DIR; }

std::vector<std::vector<double>> ReadReferenceTable(const std::string& name) {
  std::ifstream in(TestsDir() + "/reference/" + name);
  EXPECT_TRUE(in) << "cannot read tests/reference/" << name;
  std::vector<std::vector<double>> rows;
  bool header = true;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    std::vector<double> row;
    std::stringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

int CountLines(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  if (!text.empty() && text.back() != '\n') ++lines;
  return lines;
}

std::string WriteSyntheticDataset(const std::vector<double>& xs,
                                  const std::function<std::complex<double>(double, double)>& truth,
                                  double first_nm, double last_nm) {
  const std::string dir = MakeTempDir();
  std::string samples;
  for (size_t i = 0; i < xs.size(); ++i) {
    std::vector<double> l, n, k;
    for (double lambda = first_nm; lambda <= last_nm + 1e-9; lambda += 5) {
      const std::complex<double> e = truth(xs[i], lambda);
      const Complex<double> nk = IndexFromPermittivity(Complex<double>{e.real(), e.imag()});
      l.push_back(lambda);
      n.push_back(nk.re);
      k.push_back(nk.im);
    }
    const std::string file = "s" + std::to_string(i) + ".csv";
    WriteText(dir + "/" + file, NkCsvText(l, n, k));
    samples += (i ? "," : "") + std::string("{\"x\": ") + std::to_string(xs[i]) + ", \"file\": \"" +
               file + "\"}";
  }
  WriteText(dir + "/dataset.json",
            "{\"system\": {\"a\": \"Au\", \"b\": \"Ag\"}, \"composition\": \"atomic_fraction_a\", "
            "\"samples\": [" +
                samples + "]}");
  return dir;
}

std::complex<double> Geometric(double x, double lambda_nm) {
  const std::complex<double> metal(-20.0 - 0.02 * (lambda_nm - 500), 1.5 + 0.002 * lambda_nm);
  const std::complex<double> dielectric(4.0 + 0.001 * lambda_nm, 0.3);
  return std::exp((1 - x) * std::log(dielectric) + x * std::log(metal));
}

std::complex<double> LinearEps(double x, double lambda_nm) {
  return (1 - x) * std::complex<double>(-20.0 - 0.02 * (lambda_nm - 500), 1.5) +
         x * std::complex<double>(-5.0, 5.0 + 0.001 * lambda_nm);
}

void ExpectModelFileError(const nlohmann::json& doc, const std::string& needle) {
  try {
    ModelFromJson(doc, "m.json");
    ADD_FAILURE() << "no error for " << needle;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("m.json"), std::string::npos) << e.what();
  }
}

}  // namespace alloycolor::testing
