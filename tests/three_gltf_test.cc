// The glTF export in three.js: tests/three/gltf_check.html (three.js pinned in
// tests/three/package-lock.json, installed by scripts/setup.sh with `npm ci`), served from
// a loopback HTTP server and opened in headless Chromium (WebGL on SwiftShader), loads each
// exported PREFIX.gltf with GLTFLoader and renders a sphere with its material under a
// uniform white environment of radiance 1, no tone mapping, sRGB output. At the sphere's
// centre the view is normal to the surface, where three.js's image-based specular is
// F0 * A + B with A = 1, B = 0 at mu = 1: the centre pixel must be the 8-bit sRGB colour
// `alloycolor color --angle 0` gives (within 3), and the page must report no console warning
// or error and no loader error. The colour 10 at% away must differ from the centre by more
// than 3, so a drifted colour would fail. Skipped without Chromium, python3 (the server) or
// tests/three/node_modules.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "test_util.h"

extern char** environ;

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
using testing::MakeTempDir;
using testing::ReadText;
using testing::RunProgram;
using testing::RunResult;
using testing::TestsDir;

constexpr const char* kChromium = "/usr/bin/chromium";
constexpr const char* kPython = "/usr/bin/python3";
constexpr int kTolerance8Bit = 3;

std::string ThreeDir() { return TestsDir() + "/three"; }

// `python3 -m http.server` on 127.0.0.1 at a free port, serving dir; stopped on
// destruction. port() is 0 when it did not start.
class LoopbackServer {
 public:
  explicit LoopbackServer(const std::string& dir) {
    const std::string log = dir + "/server.log";
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<std::string> args = {kPython,     "-u",          "-m", "http.server", "0", "--bind",
                                     "127.0.0.1", "--directory", dir};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, kPython, &actions, nullptr, argv.data(), environ) != 0) pid_ = 0;
    posix_spawn_file_actions_destroy(&actions);
    // It prints "Serving HTTP on 127.0.0.1 port N ..." once it listens.
    const std::regex re("port ([0-9]+)");
    for (int i = 0; pid_ != 0 && i < 200 && port_ == 0; ++i) {
      std::smatch m;
      const std::string text = ReadText(log);
      if (std::regex_search(text, m, re)) {
        port_ = std::stoi(m[1]);
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    }
  }
  ~LoopbackServer() {
    if (pid_ == 0) return;
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
  }
  LoopbackServer(const LoopbackServer&) = delete;
  LoopbackServer& operator=(const LoopbackServer&) = delete;
  int port() const { return port_; }

 private:
  pid_t pid_ = 0;
  int port_ = 0;
};

// The JSON the page writes into #result once it is done ("" when it is absent).
std::string PageResult(const std::string& dom) {
  const std::regex re("<pre id=\"result\" data-done=\"true\">([^<]*)</pre>");
  std::smatch m;
  if (!std::regex_search(dom, m, re)) return "";
  std::string text = m[1];
  for (const auto& [entity, c] : std::vector<std::pair<std::string, std::string>>{
           {"&lt;", "<"}, {"&gt;", ">"}, {"&nbsp;", " "}, {"&amp;", "&"}}) {
    for (std::size_t at = text.find(entity); at != std::string::npos;
         at = text.find(entity, at + c.size())) {
      text.replace(at, entity.size(), c);
    }
  }
  return text;
}

// The page at url after its script has run, with SwiftShader's WebGL.
std::string DumpDom(const std::string& dir, const std::string& url) {
  const std::string command =
      std::string("timeout 120 ") + kChromium +
      " --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader "
      "--no-first-run --disable-background-networking --disable-component-update "
      "--disable-sync --user-data-dir=" +
      dir + "/chromium-profile --virtual-time-budget=30000 --dump-dom '" + url + "' >" + dir +
      "/dom.html 2>" + dir + "/chromium.log";
  if (std::system(command.c_str()) != 0) return "";
  return ReadText(dir + "/dom.html");
}

nlohmann::json ColorAt(const std::string& model, const std::string& x) {
  const RunResult r = RunProgram({"color", "--model", model, "--x", x, "--angle", "0", "--json"});
  EXPECT_EQ(r.status, 0) << r.err;
  return r.status == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
}

// The largest channel difference between two 8-bit colours.
int MaxDifference(const nlohmann::json& a, const nlohmann::json& b) {
  int largest = 0;
  for (int c = 0; c < 3; ++c)
    largest = std::max(largest, std::abs(a[c].get<int>() - b[c].get<int>()));
  return largest;
}

struct Alloy {
  std::string name;     // also the glTF file's prefix
  std::string dataset;  // bundled data set, fitted with eps-linear
  std::string x;        // composition as --x takes it
};

TEST(ThreeGltfTest, CentrePixelIsF0AndTheLoaderWarnsOfNothing) {
  if (!fs::exists(kChromium)) GTEST_SKIP() << kChromium << " is absent (Debian package chromium)";
  if (!fs::exists(kPython)) GTEST_SKIP() << kPython << " is absent (Debian package python3)";
  if (!fs::exists(ThreeDir() + "/node_modules/three/package.json")) {
    GTEST_SKIP() << ThreeDir() << "/node_modules is absent (scripts/setup.sh runs npm ci there)";
  }
  const std::vector<Alloy> alloys = {
      {"au18k", "Au-Ag", "18k"}, {"au24k", "Au-Ag", "24k"}, {"brass70", "Cu-Zn", "70wt%"}};
  const std::string dir = MakeTempDir();
  for (const char* name : {"gltf_check.html", "gltf_check.js", "node_modules"}) {
    fs::create_symlink(ThreeDir() + "/" + name, dir + "/" + name);
  }
  std::vector<nlohmann::json> colors, shifted;
  std::string files;
  for (const Alloy& alloy : alloys) {
    const std::string model = dir + "/" + alloy.dataset + ".json";
    if (!fs::exists(model)) {
      const RunResult fit = RunProgram(
          {"fit", "--data", alloy.dataset, "--method", "eps-linear", "--out", model, "--quiet"});
      ASSERT_EQ(fit.status, 0) << fit.err;
    }
    const RunResult r = RunProgram({"export", "--model", model, "--x", alloy.x, "--format", "gltf",
                                    "--out", dir + "/" + alloy.name});
    ASSERT_EQ(r.status, 0) << r.err;
    colors.push_back(ColorAt(model, alloy.x));
    // 10 at% more of the first element (less where that passes 100 %).
    const double x = colors.back()["x"].get<double>();
    shifted.push_back(
        ColorAt(model, std::to_string(100 * (x + 0.1 <= 1 ? x + 0.1 : x - 0.1)) + "at%"));
    files += (files.empty() ? "" : ",") + alloy.name + ".gltf";
  }

  const LoopbackServer server(dir);
  ASSERT_NE(server.port(), 0) << ReadText(dir + "/server.log");
  const std::string dom = DumpDom(
      dir, "http://127.0.0.1:" + std::to_string(server.port()) + "/gltf_check.html?files=" + files);
  const std::string text = PageResult(dom);
  ASSERT_FALSE(text.empty()) << "no result in the page:\n"
                             << dom << ReadText(dir + "/chromium.log");
  const nlohmann::json page = nlohmann::json::parse(text);

  EXPECT_TRUE(page["warnings"].empty()) << page["warnings"].dump(1);
  const nlohmann::json pinned =
      nlohmann::json::parse(ReadText(ThreeDir() + "/package.json"))["dependencies"]["three"];
  EXPECT_EQ("0." + page["three"].get<std::string>() + ".0", pinned.get<std::string>());
  ASSERT_EQ(page["files"].size(), alloys.size()) << text;
  for (std::size_t i = 0; i < alloys.size(); ++i) {
    SCOPED_TRACE(alloys[i].name);
    const nlohmann::json& rendered = page["files"][i];
    const nlohmann::json& color = colors[i];
    EXPECT_EQ(rendered["file"], alloys[i].name + ".gltf");
    EXPECT_TRUE(rendered["extensions"].empty()) << rendered["extensions"];
    EXPECT_EQ(rendered["material"]["type"], "MeshStandardMaterial");
    EXPECT_EQ(rendered["material"]["metalness"], 1.0);
    EXPECT_EQ(rendered["material"]["roughness"], 0.0);
    for (int c = 0; c < 3; ++c) {
      // What three.js read: F0 clamped to [0, 1].
      const double f0 = std::clamp(color["linear_srgb"][c].get<double>(), 0.0, 1.0);
      EXPECT_NEAR(rendered["baseColorFactor"][c].get<double>(), f0, 1e-12);
    }
    // three.js's own reflectance at the centre, before 8-bit rounding: F0 * A + B.
    double residual = 0;
    for (int c = 0; c < 3; ++c) {
      const double f0 = std::clamp(color["linear_srgb"][c].get<double>(), 0.0, 1.0);
      residual = std::max(residual, std::abs(rendered["centre_linear"][c].get<double>() - f0));
    }
    EXPECT_LT(residual, 0.005) << rendered["centre_linear"];
    const int difference = MaxDifference(rendered["centre"], color["srgb8"]);
    const int drift = MaxDifference(shifted[i]["srgb8"], rendered["centre"]);
    RecordProperty(alloys[i].name + "_centre_minus_srgb8", difference);
    RecordProperty(alloys[i].name + "_shifted_10at_minus_centre", drift);
    std::printf(
        "%s: centre %s, srgb8 %s (largest difference %d); linear centre - F0 %.2g; 10 at%% "
        "away %s (%d)\n",
        alloys[i].name.c_str(), rendered["centre"].dump().c_str(), color["srgb8"].dump().c_str(),
        difference, residual, shifted[i]["srgb8"].dump().c_str(), drift);
    EXPECT_LE(difference, kTolerance8Bit);
    EXPECT_GT(drift, kTolerance8Bit) << "10 at% away is not told apart; the check could not fail";
  }
}

}  // namespace
}  // namespace alloycolor
