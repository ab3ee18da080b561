// One list of typed compositions (tests/reference/composition_inputs.json: forms, spacing,
// case, signs, exponents, out-of-range values, slips, hostile text, 30,000-digit runs) read
// by the library's parser (ParseComposition, the reference), by the explorer page's
// (export/explore/input.js, under Node) and by the Blender add-on's conversions
// (blender/alloycolor_material/compositions.py, under Python): every input the library
// reads, the others read to the same atomic fraction; every input it refuses, they refuse.
// Skipped without Node (Debian package nodejs) or Python 3.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"
#include "test_util.h"

namespace alloycolor::testing {
namespace {

namespace fs = std::filesystem;

// The first of `names` on PATH, or "".
std::string OnPath(const std::vector<std::string>& names) {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path ? path : "/usr/bin");
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    for (const std::string& name : names) {
      const fs::path candidate = fs::path(folder) / name;
      std::error_code ec;
      if (fs::is_regular_file(candidate, ec)) return candidate.string();
    }
  }
  return "";
}

// Standard output of a command line (arguments quoted by the caller).
std::string Capture(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  char buffer[4096];
  std::size_t got;
  while ((got = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, got);
  pclose(pipe);
  return out;
}

std::vector<std::string> Inputs() {
  return nlohmann::json::parse(ReadText(TestsDir() + "/reference/composition_inputs.json"))
      .get<std::vector<std::string>>();
}

// Gold as a, gold as b, no gold; masses from the library's element table.
std::vector<AlloySystem> Systems() {
  return {{FindElement("Au"), FindElement("Ag")},
          {FindElement("Ag"), FindElement("Au")},
          {FindElement("Cu"), FindElement("Zn")}};
}

// The library's reading, NaN where it refuses.
double Library(const std::string& text, const AlloySystem& system) {
  try {
    return ParseComposition(text, system);
  } catch (const Error&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

void ExpectSame(double reference, const nlohmann::json& other, const std::string& what) {
  if (std::isnan(reference)) {
    EXPECT_TRUE(other.is_null()) << what << ": the library refuses it, read as " << other;
  } else {
    ASSERT_TRUE(other.is_number()) << what << ": the library reads " << reference;
    EXPECT_NEAR(other.get<double>(), reference, 1e-14) << what;
  }
}

TEST(CompositionParsers, ThePageReadsWhatTheLibraryReads) {
  const std::string node = OnPath({"node", "nodejs"});
  if (node.empty()) GTEST_SKIP() << "no Node (Debian package nodejs)";
  const std::string dir = MakeTempDir();
  nlohmann::json systems = nlohmann::json::array();
  for (const AlloySystem& s : Systems()) {
    systems.push_back({{"a", s.a.symbol},
                       {"b", s.b.symbol},
                       {"mass_a", s.a.atomic_mass},
                       {"mass_b", s.b.atomic_mass}});
  }
  WriteText(dir + "/systems.json", systems.dump());
  WriteText(dir + "/page.js",
            "const I = require(process.argv[2]);\n"
            "const inputs = JSON.parse(require('fs').readFileSync(process.argv[3], 'utf8'));\n"
            "const systems = JSON.parse(require('fs').readFileSync(process.argv[4], 'utf8'));\n"
            "const out = systems.map(s => inputs.map(t => {\n"
            "  const x = I.parseComposition(t, s); return Number.isNaN(x) ? null : x; }));\n"
            "process.stdout.write(JSON.stringify(out));\n");
  const std::string output = Capture(
      "'" + node + "' '" + dir + "/page.js' '" + TestsDir() + "/../export/explore/input.js' '" +
      TestsDir() + "/reference/composition_inputs.json' '" + dir + "/systems.json'");
  const nlohmann::json page = nlohmann::json::parse(output, nullptr, false);
  ASSERT_TRUE(page.is_array()) << output.substr(0, 300);
  const std::vector<std::string> inputs = Inputs();
  const std::vector<AlloySystem> all = Systems();
  ASSERT_EQ(page.size(), all.size());
  int read = 0;
  for (std::size_t s = 0; s < all.size(); ++s) {
    ASSERT_EQ(page[s].size(), inputs.size());
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      const double reference = Library(inputs[i], all[s]);
      read += !std::isnan(reference);
      ExpectSame(reference, page[s][i], all[s].Name() + " " + Quote(inputs[i]));
    }
  }
  EXPECT_GT(read, 40);  // the list holds both kinds
}

// The add-on sets x from a property (at%, wt% or karat) and a number: on every input of the
// list that is a number and one of those units, the add-on's x is the library's, and the
// add-on's ranges refuse what the library refuses.
TEST(CompositionParsers, TheBlenderAddOnReadsWhatTheLibraryReads) {
  const std::string python = OnPath({"python3"});
  if (python.empty()) GTEST_SKIP() << "no Python 3";
  struct Case {
    std::string text, unit;
    double value;
    std::size_t system;
  };
  std::vector<Case> cases;
  const std::vector<AlloySystem> all = Systems();
  for (const std::string& text : Inputs()) {
    // A property holds a number, not text: the bound on typed text is not the add-on's.
    if (Trim(text).size() > kMaxCompositionChars) continue;
    const std::string lower = Lower(Trim(text));
    for (const auto& [suffix, unit] : std::vector<std::pair<std::string, std::string>>{
             {"at%", "AT"}, {"wt%", "WT"}, {"kt", "KARAT"}, {"k", "KARAT"}}) {
      if (!EndsWith(lower, suffix)) continue;
      double value = 0;
      if (ParseFiniteDouble(Trim(lower.substr(0, lower.size() - suffix.size())), &value)) {
        for (std::size_t s = 0; s < all.size(); ++s) cases.push_back({text, unit, value, s});
      }
      break;
    }
  }
  ASSERT_GT(cases.size(), 30u);
  nlohmann::json calls = nlohmann::json::array();
  for (const Case& c : cases) {
    const AlloySystem& s = all[c.system];
    const int gold = std::string(s.a.symbol) == "Au" ? 0 : std::string(s.b.symbol) == "Au" ? 1 : -1;
    calls.push_back({c.unit, c.value, {s.a.atomic_mass, s.b.atomic_mass}, gold});
  }
  const std::string dir = MakeTempDir();
  WriteText(dir + "/calls.json", calls.dump());
  WriteText(dir + "/addon.py",
            "import importlib.util, json, sys\n"
            "spec = importlib.util.spec_from_file_location('compositions', sys.argv[1])\n"
            "c = importlib.util.module_from_spec(spec); spec.loader.exec_module(c)\n"
            "calls = json.load(open(sys.argv[2]))\n"
            "print(json.dumps([c.x_from_property(u, v, m, g) for u, v, m, g in calls]))\n");
  const std::string output =
      Capture("'" + python + "' '" + dir + "/addon.py' '" + TestsDir() +
              "/../blender/alloycolor_material/compositions.py' '" + dir + "/calls.json'");
  const nlohmann::json addon = nlohmann::json::parse(output, nullptr, false);
  ASSERT_TRUE(addon.is_array()) << output.substr(0, 300);
  ASSERT_EQ(addon.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    ExpectSame(Library(c.text, all[c.system]), addon[i],
               all[c.system].Name() + " " + Quote(c.text));
  }
}

}  // namespace
}  // namespace alloycolor::testing
