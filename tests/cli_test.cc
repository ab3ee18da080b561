// The real program end to end: the published brass figure, JSON keys, and every kind of
// bad input giving one line naming the culprit and exit status 2.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "test_util.h"

namespace alloycolor::testing {
namespace {

// A bad input: one line on stderr containing every needle, nothing on stdout, status 2.
void ExpectCleanError(const std::vector<std::string>& args,
                      const std::vector<std::string>& needles) {
  const RunResult r = RunProgram(args);
  std::string cmd;
  for (const auto& a : args) cmd += a + " ";
  EXPECT_EQ(r.status, 2) << cmd << "\n" << r.err;
  EXPECT_EQ(CountLines(r.err), 1) << cmd << "\n" << r.err;
  EXPECT_TRUE(r.out.empty()) << cmd << "\n" << r.out;
  for (const auto& needle : needles) {
    EXPECT_NE(r.err.find(needle), std::string::npos)
        << cmd << ": '" << needle << "' not in " << r.err;
  }
}

nlohmann::json ColorJson(const std::vector<std::string>& args) {
  std::vector<std::string> full = {"color", "--json", "--quiet"};
  full.insert(full.end(), args.begin(), args.end());
  const RunResult r = RunProgram(full);
  EXPECT_EQ(r.status, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

TEST(Cli, QuerryBrassMatchesThePublishedFigure) {
  // Linear sRGB of Querry's Cu70Zn30 at normal incidence under D65, 2 degrees: (0.910,
  // 0.778, 0.423), a published figure computed the same way.
  const nlohmann::json c = ColorJson({"--nk", DataDir() + "/Cu-Zn/Querry-Cu70Zn30.yml"});
  EXPECT_NEAR(c["linear_srgb"][0].get<double>(), 0.910, 0.005);
  EXPECT_NEAR(c["linear_srgb"][1].get<double>(), 0.778, 0.005);
  EXPECT_NEAR(c["linear_srgb"][2].get<double>(), 0.423, 0.005);
  for (const char* key : {"XYZ", "Lab", "linear_srgb", "srgb8", "paper_rgb"}) {
    EXPECT_TRUE(c.contains(key)) << key;
  }
}

TEST(Cli, PerfectReflectorIsTheIlluminantsWhite) {
  // n = 0 reflects everything at every angle (R = 1 in eq. 2-4): XYZ is the white point.
  const std::string dir = MakeTempDir();
  WriteText(dir + "/mirror.csv", "lambda_nm,n,k\n300,0,4\n900,0,4\n");
  nlohmann::json c = ColorJson({"--nk", dir + "/mirror.csv"});
  EXPECT_NEAR(c["XYZ"][0].get<double>(), 0.95047, 1e-3);  // ASTM E308 D65, 2 degrees
  EXPECT_NEAR(c["XYZ"][1].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(c["XYZ"][2].get<double>(), 1.08883, 1e-3);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(c["linear_srgb"][i].get<double>(), 1.0, 2e-3);
  EXPECT_NEAR(c["Lab"][0].get<double>(), 100.0, 1e-9);
  c = ColorJson(
      {"--nk", dir + "/mirror.csv", "--illuminant", "A", "--observer", "10", "--angle", "60"});
  EXPECT_NEAR(c["XYZ"][0].get<double>(), 1.11144, 1e-3);  // ASTM E308 A, 10 degrees
  EXPECT_NEAR(c["XYZ"][2].get<double>(), 0.35200, 1e-3);
}

TEST(Cli, GrazingIncidenceGoesWhite) {
  const nlohmann::json c =
      ColorJson({"--nk", DataDir() + "/Au-Ag/Rioux-Au100Ag0.yml", "--angle", "89.9"});
  EXPECT_GT(c["XYZ"][1].get<double>(), 0.99);
}

TEST(Cli, PaperBaselineAtAKnownSampleIsThatSample) {
  const nlohmann::json direct = ColorJson({"--nk", DataDir() + "/Au-Ag/Rioux-Au50Ag50.yml"});
  const nlohmann::json paper =
      ColorJson({"--data", DataDir() + "/Au-Ag", "--method", "paper", "--x", "0.5"});
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(paper["XYZ"][i].get<double>(), direct["XYZ"][i].get<double>(), 1e-9);
  }
  // Karats and weight percent go through the atomic masses: 18k Au-Ag is 62.2 at% Au.
  const nlohmann::json karat = ColorJson({"--data", "Au-Ag", "--x", "18k"});
  EXPECT_NEAR(karat["x"].get<double>(), 0.6216, 1e-3);
}

// The top level lists each command on one short line; a command's help has its options
// and its details, and the method list there is a line, not the fit's paragraph.
TEST(Cli, HelpExplainsEveryCommand) {
  const RunResult r = RunProgram({"--help"});
  EXPECT_EQ(r.status, 0);
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) {
    EXPECT_LE(line.size(), 120u) << line;
  }
  for (const char* cmd : {"color", "fit", "predict", "render", "export", "validate", "chart",
                          "params", "sweep", "explore", "match", "tolerance"}) {
    EXPECT_NE(r.out.find("\n  " + std::string(cmd) + " "), std::string::npos) << cmd;
    const RunResult sub = RunProgram({cmd, "--help"});
    EXPECT_EQ(sub.status, 0) << cmd;
    EXPECT_NE(sub.out.find("--"), std::string::npos) << cmd;
    if (std::string(cmd) != "fit") {
      const std::size_t method = sub.out.find("--method");
      if (method == std::string::npos) continue;
      const std::size_t end = sub.out.find("\n", method);
      EXPECT_LT(end - method, 300u) << cmd << ": " << sub.out.substr(method, end - method);
    }
  }
}

// stderr is quiet by default: a smooth fit's cross-validation table comes with --verbose
// only; the fit's summary line and the model against its own samples come either way.
TEST(Cli, CrossValidationTablesComeWithVerbose) {
  const std::string out = MakeTempDir() + "/m.json";
  for (const bool verbose : {false, true}) {
    std::vector<std::string> args = {"fit", "--data", "Cu-Zn", "--method", "smooth", "--out", out};
    if (verbose) args.push_back("--verbose");
    const RunResult r = RunProgram(args);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("smooth fit: "), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("cross-validation (eps): smoothing 0.001") != std::string::npos, verbose)
        << r.err;
    EXPECT_NE(r.err.find("smooth against its own samples"), std::string::npos) << r.err;
  }
  ExpectCleanError({"fit", "--data", "Cu-Zn", "--out", out, "--verbose", "--quiet"},
                   {"--verbose", "--quiet"});
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = MakeTempDir(); }
  std::string File(const std::string& name, const std::string& text) {
    WriteText(dir_ + "/" + name, text);
    return dir_ + "/" + name;
  }
  std::string Manifest(const std::string& body) { return File("dataset.json", body); }
  std::string dir_;
};

TEST_F(BadInput, OpticalConstantFiles) {
  ExpectCleanError({"color", "--nk", dir_ + "/missing.yml"}, {"missing.yml"});
  ExpectCleanError({"color", "--nk", dir_}, {dir_});
  ExpectCleanError({"color", "--nk", File("word.csv", "lambda_nm,n,k\n400,1,2\n500,abc,2\n")},
                   {"word.csv", ":3", "abc"});
  ExpectCleanError({"color", "--nk", File("one.csv", "lambda_nm,n,k\n400,1,2\n")}, {"one.csv"});
  ExpectCleanError(
      {"color", "--nk", File("order.csv", "lambda_nm,n,k\n500,1,2\n400,1,2\n450,1,2\n")},
      {"order.csv", ":4"});
  ExpectCleanError({"color", "--nk", File("negk.csv", "lambda_nm,n,k\n400,1,2\n500,1,-2\n")},
                   {"negk.csv", ":3"});
  ExpectCleanError({"color", "--nk", File("nan.csv", "lambda_nm,n,k\n400,1,2\n500,nan,2\n")},
                   {"nan.csv", ":3"});
  ExpectCleanError({"color", "--nk", File("header.csv", "wavelength,n\n400,1\n500,1\n")},
                   {"header.csv"});
  ExpectCleanError({"color", "--nk",
                    File("bad.yml",
                         "DATA:\n  - type: tabulated nk\n    data: |\n"
                         "        0.4 1.0 2.0\n        0.5 x 2.0\n")},
                   {"bad.yml", ":5"});
  ExpectCleanError({"color", "--nk",
                    File("formula.yml",
                         "DATA:\n  - type: formula 2\n"
                         "    coefficients: 0 1 2\n")},
                   {"formula.yml", "formula"});
  ExpectCleanError({"color", "--nk", File("binary.yml", std::string("\x00\x01\xff\xfe", 4))},
                   {"binary.yml"});
  // Infrared data do not cover the visible: no colour, said clearly.
  ExpectCleanError({"color", "--nk", DataDir() + "/Nb-Sn/Golovashkin-22.yml"},
                   {"Golovashkin-22.yml", "380"});
}

TEST_F(BadInput, Manifests) {
  const std::string au = DataDir() + "/Au-Ag/Rioux-Au100Ag0.yml";
  const std::string ag = DataDir() + "/Au-Ag/Rioux-Au0Ag100.yml";
  auto manifest = [&](const std::string& a, const std::string& samples) {
    return Manifest(R"({"system": {"a": ")" + a +
                    R"(", "b": "Ag"}, "composition": "atomic_fraction_a", "samples": [)" + samples +
                    "]}");
  };
  ExpectCleanError(
      {"color", "--data", manifest("Xx", R"({"x": 0, "file": ")" + ag + R"("})"), "--x", "0.5"},
      {"dataset.json", "Xx"});
  ExpectCleanError(
      {"color", "--data",
       manifest("Au", R"({"x": 1.5, "file": ")" + au + R"("}, {"x": 0, "file": ")" + ag + R"("})"),
       "--x", "0.5"},
      {"dataset.json", "1.5"});
  ExpectCleanError({"color", "--data",
                    manifest("Au", R"({"x": 0.5, "file": ")" + au + R"("}, {"x": 0.5, "file": ")" +
                                       ag + R"("})"),
                    "--x", "0.5"},
                   {"dataset.json", "Rioux-Au100Ag0.yml", "Rioux-Au0Ag100.yml"});
  ExpectCleanError(
      {"color", "--data",
       manifest("Au", R"({"x": 1, "file": "nowhere.yml"}, {"x": 0, "file": ")" + ag + R"("})"),
       "--x", "0.5"},
      {"nowhere.yml"});
  ExpectCleanError({"color", "--data", File("broken.json", "{\"system\": "), "--x", "0.5"},
                   {"broken.json"});
  ExpectCleanError({"color", "--data", dir_ + "/none", "--x", "0.5"}, {"none"});
}

TEST_F(BadInput, CompositionsAndOptions) {
  ExpectCleanError({"color", "--data", "Au-Ag", "--x", "1.5"}, {"1.5"});
  ExpectCleanError({"color", "--data", "Au-Ag", "--x", "banana"}, {"banana"});
  ExpectCleanError({"color", "--data", "Cu-Zn", "--x", "18k"}, {"18k"});
  ExpectCleanError({"color", "--data", "Au-Ag", "--x", "0.5", "--illuminant", "D99"}, {"D99"});
  ExpectCleanError({"color", "--data", "Au-Ag", "--x", "0.5", "--observer", "5"}, {"5"});
  ExpectCleanError({"color", "--data", "Au-Ag", "--x", "0.5", "--angle", "120"}, {"120"});
  ExpectCleanError({"color", "--data", "Au-Ag", "--x", "0.5", "--method", "magic"}, {"magic"});
  ExpectCleanError({"color", "--bogus"}, {"--bogus"});
  ExpectCleanError({"color"}, {"--model"});
  ExpectCleanError({"fit", "--data", "Au-Ag", "--method", "smooth", "--space", "magic", "--out",
                    dir_ + "/m.json"},
                   {"--space", "magic"});
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/m.json"));
}

// --space fixes the space of the smooth model's curves, and the file says which.
TEST(Cli, FitSmoothInTheSpaceGiven) {
  const std::string dir = MakeTempDir();
  for (const char* space : {"eps", "log_eps"}) {
    const std::string out = dir + "/" + space + ".json";
    const RunResult r = RunProgram({"fit", "--data", "Au-Ag", "--method", "smooth", "--space",
                                    space, "--quiet", "--out", out});
    ASSERT_EQ(r.status, 0) << r.err;
    std::ifstream in(out);
    const nlohmann::json model = nlohmann::json::parse(in);
    EXPECT_EQ(model["parameters"]["space"], space);
    EXPECT_EQ(model["fit"]["space_chosen_by"], "given");
  }
}

// fit --exclude takes compositions as validate --holdout does: Cu-Zn's manifest gives weight
// fractions, so a plain 0.85 is the sample its manifest calls 0.85 (85wt% Cu, 85.4 at%), the
// same as 85wt%; a composition of no sample is refused naming the samples there are.
TEST_F(BadInput, FitExcludesBySampleAsTheManifestNamesIt) {
  std::vector<nlohmann::json> models;
  for (const char* exclude : {"0.85", "85wt%"}) {
    const std::string out = dir_ + "/ex" + std::to_string(models.size()) + ".json";
    const RunResult r = RunProgram({"fit", "--data", "Cu-Zn", "--method", "eps-linear", "--exclude",
                                    exclude, "--out", out, "--quiet"});
    ASSERT_EQ(r.status, 0) << exclude << ": " << r.err;
    std::ifstream in(out);
    models.push_back(nlohmann::json::parse(in));
  }
  ASSERT_EQ(models[0]["training_samples"].size(), 4u) << models[0].dump();
  EXPECT_EQ(models[0]["training_samples"], models[1]["training_samples"]);
  for (const auto& sample : models[0]["training_samples"]) {
    EXPECT_EQ(sample["file"].get<std::string>().find("Cu85"), std::string::npos) << sample.dump();
  }
  ExpectCleanError({"fit", "--data", "Cu-Zn", "--exclude", "0.5", "--out", dir_ + "/no.json"},
                   {"--exclude", "no sample at 0.5", "0, 0.7, 0.85, 0.9, 1"});
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/no.json"));
}

TEST_F(BadInput, ModelFilesAndRefit) {
  const std::string model = dir_ + "/model.json";
  RunResult r = RunProgram({"fit", "--data", "Au-Ag", "--method", "smooth", "--exclude", "0.3,0.7",
                            "--out", model, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(model);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ExpectCleanError(
      {"predict", "--model", File("cut.json", text.substr(0, text.size() / 2)), "--x", "0.5"},
      {"cut.json"});
  nlohmann::json doc = nlohmann::json::parse(text);
  doc["version"] = 7;
  ExpectCleanError({"predict", "--model", File("v7.json", doc.dump()), "--x", "0.5"},
                   {"v7.json", "version"});
  doc = nlohmann::json::parse(text);
  doc.erase("parameters");
  ExpectCleanError({"predict", "--model", File("noparams.json", doc.dump()), "--x", "0.5"},
                   {"noparams.json", "parameters"});
  doc = nlohmann::json::parse(text);
  doc["x_range"] = "two";
  ExpectCleanError({"predict", "--model", File("type.json", doc.dump()), "--x", "0.5"},
                   {"type.json", "x_range"});
  doc = nlohmann::json::parse(text);
  doc["uncertainty"]["calibration"] = -1;
  ExpectCleanError({"predict", "--model", File("calibration.json", doc.dump()), "--x", "0.5"},
                   {"calibration.json", "uncertainty.calibration"});
  doc = nlohmann::json::parse(text);
  doc["uncertainty"]["end_factor"] = 0.5;
  ExpectCleanError({"predict", "--model", File("end.json", doc.dump()), "--x", "0.5"},
                   {"end.json", "uncertainty.end_factor"});
  doc = nlohmann::json::parse(text);
  doc["uncertainty"]["gap_exponent"] = 5;
  ExpectCleanError({"predict", "--model", File("gap.json", doc.dump()), "--x", "0.5"},
                   {"gap.json", "uncertainty.gap_exponent"});
  // Refit: reports the added samples, keeps the old model; the report is what --refit asks
  // for, so --quiet keeps it. The old name --from still works, with a note.
  r = RunProgram(
      {"fit", "--data", "Au-Ag", "--refit", model, "--out", dir_ + "/new.json", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("refit: added Rioux-Au30Ag70.yml (x = 0.3): the old"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("refit: final cost"), std::string::npos) << r.err;
  r = RunProgram({"fit", "--data", "Au-Ag", "--from", model, "--out", dir_ + "/new2.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("--from is now --refit"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("refit: added Rioux-Au30Ag70.yml (x = 0.3): the old"), std::string::npos)
      << r.err;
  std::ifstream again(model);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>()),
            text);
  ExpectCleanError({"fit", "--data", "Au-Ag", "--refit", model, "--out", model}, {"--refit"});
  // A failing fit leaves the old file byte-identical.
  ExpectCleanError({"fit", "--data", dir_ + "/none", "--out", model}, {"none"});
  std::ifstream kept(model);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(kept)), std::istreambuf_iterator<char>()),
            text);
  // Compositions outside the training range need --extrapolate.
  r = RunProgram({"fit", "--data", "Au-Ag", "--exclude", "0,1", "--degree", "2", "--out",
                  dir_ + "/inner.json", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  ExpectCleanError({"predict", "--model", dir_ + "/inner.json", "--x", "0.95"},
                   {"0.95", "--extrapolate"});
  r = RunProgram({"predict", "--model", dir_ + "/inner.json", "--x", "0.95", "--extrapolate"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, 14), "lambda_nm,n,k\n");
}

// A program that guides: what was wrong and what would be right, on one line, status 2.
std::vector<std::string> Args(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

TEST_F(BadInput, AnUnknownDataSetNameListsTheBundledOnes) {
  ExpectCleanError({"color", "--data", "AuAg", "--x", "0.5"},
                   {"no data set 'AuAg': not a folder, a manifest or a bundled set (Au-Ag, Cu-Zn, "
                    "Nb-Sn); did you mean Au-Ag?"});
  ExpectCleanError({"fit", "--data", "nb-sn", "--out", dir_ + "/m.json"},
                   {"'nb-sn'", "did you mean Nb-Sn?"});
  // Far from every name: the list without a guess.
  ExpectCleanError({"color", "--data", "Pt-Ir", "--x", "0.5"}, {"(Au-Ag, Cu-Zn, Nb-Sn)"});
  EXPECT_EQ(RunProgram({"color", "--data", "Pt-Ir", "--x", "0.5"}).err.find("did you mean"),
            std::string::npos);
}

TEST_F(BadInput, AMalformedCompositionSaysWhatIsAccepted) {
  const std::vector<std::string> color = {"color", "--data", "Au-Ag", "--method", "paper"};
  ExpectCleanError(Args(color, {"--x", "75wt"}),
                   {"--x: composition '75wt': did you mean 75wt%?", "0.75, 75at%, 75wt%", "18k"});
  ExpectCleanError(Args(color, {"--x", "0.5,75%wt"}), {"'75%wt'", "did you mean 75wt%?"});
  ExpectCleanError(Args(color, {"--x", "18ct"}), {"did you mean 18k?"});
  ExpectCleanError(Args(color, {"--x", "75"}), {"'75'", "did you mean 75at% or 75wt%?"});
  ExpectCleanError(Args(color, {"--x", "abc"}), {"--x: composition 'abc'", "accepted: "});
  EXPECT_EQ(RunProgram(Args(color, {"--x", "abc"})).err.find("did you mean"), std::string::npos);
  ExpectCleanError({"predict", "--data", "Au-Ag", "--method", "paper", "--x", "50at"},
                   {"--x: composition '50at': did you mean 50at%?"});
  ExpectCleanError({"sweep", "--data", "Au-Ag", "--method", "paper", "--from", "75wt"},
                   {"--from: composition '75wt': did you mean 75wt%?"});
}

TEST_F(BadInput, ADataSetGivenAsAModelAndTheReverseAreNamed) {
  const std::string model = dir_ + "/model.json";
  ASSERT_EQ(
      RunProgram({"fit", "--data", "Au-Ag", "--method", "paper", "--out", model, "--quiet"}).status,
      0);
  const std::string manifest = DataDir() + "/Au-Ag/dataset.json";
  const std::string yml = DataDir() + "/Au-Ag/Rioux-Au50Ag50.yml";
  ExpectCleanError({"color", "--model", manifest, "--x", "0.5"},
                   {manifest + ": this is a data set manifest: use --data"});
  ExpectCleanError({"predict", "--model", DataDir() + "/Au-Ag", "--x", "0.5"},
                   {"this is a data set: use --data"});
  ExpectCleanError({"color", "--data", model, "--x", "0.5"},
                   {model + ": this is a model file: use --model"});
  ExpectCleanError({"sweep", "--data", model}, {"this is a model file: use --model"});
  // One sample's n, k: what a data set is, and --nk where the command takes it.
  ExpectCleanError(
      {"fit", "--data", yml, "--out", dir_ + "/m.json"},
      {yml + ": this is one sample's n,k, not a data set", "dataset.json", "several compositions"});
  EXPECT_EQ(RunProgram({"fit", "--data", yml, "--out", dir_ + "/m.json"}).err.find("--nk"),
            std::string::npos);
  ExpectCleanError(
      {"color", "--data", File("gold.csv", "lambda_nm,n,k\n400,1,2\n500,1,2\n"), "--x", "0.5"},
      {"gold.csv: this is one sample's n,k", "use --nk"});
  ExpectCleanError({"render", "--model", yml, "--x", "0.5", "--out", dir_ + "/r.png"},
                   {"one sample's n,k, not a model file", "use --nk"});
  // fit --refit takes a model: a data set or a sample there is named, with what is taken.
  ExpectCleanError({"fit", "--data", "Au-Ag", "--refit", manifest, "--out", dir_ + "/m.json"},
                   {manifest + ": this is a data set manifest, not a model file",
                    "--refit takes the model an earlier 'alloycolor fit --out' wrote"});
  ExpectCleanError({"fit", "--data", "Au-Ag", "--refit", yml, "--out", dir_ + "/m.json"},
                   {"one sample's n,k, not a model file: --refit takes"});
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/m.json"));
}

TEST_F(BadInput, AnUnknownOptionOrCommandSuggestsTheNearest) {
  const std::vector<std::string> color = {"color", "--data", "Au-Ag", "--method",
                                          "paper", "--x",    "0.5"};
  ExpectCleanError(Args(color, {"--angel", "45"}),
                   {"color: unknown option '--angel'; did you mean --angle?"});
  ExpectCleanError(Args(color, {"--illuminnt=D50"}), {"'--illuminnt'; did you mean --illuminant?"});
  // Named before the required option it hides.
  ExpectCleanError(
      {"render", "--nk", DataDir() + "/pure/Au-Johnson.yml", "--outt", dir_ + "/r.png"},
      {"render: unknown option '--outt'; did you mean --out?"});
  ExpectCleanError({"colour", "--data", "Au-Ag"},
                   {"unknown command 'colour'; did you mean color?", "fit, predict"});
  ExpectCleanError(Args(color, {"--zzzzzz"}), {"unknown option '--zzzzzz'"});
  EXPECT_EQ(RunProgram(Args(color, {"--zzzzzz"})).err.find("did you mean"), std::string::npos);
}

TEST(Cli, CompositionsAreEchoedAsWritten) {
  const RunResult r = RunProgram(
      {"color", "--data", "Au-Ag", "--method", "paper", "--x", "18k, 0.5,75at%", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\n18k (x = 0.6216) "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n0.5 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n75at% (x = 0.75) "), std::string::npos) << r.out;
  const nlohmann::json one = ColorJson({"--data", "Au-Ag", "--method", "paper", "--x", "18k"});
  EXPECT_EQ(one["x_given"], "18k");
  EXPECT_NEAR(one["x"].get<double>(), 0.6216, 1e-4);
  const nlohmann::json two =
      ColorJson({"--data", "Au-Ag", "--method", "paper", "--x", "75wt%,0.25"});
  EXPECT_EQ(two["results"][0]["x_given"], "75wt%");
  EXPECT_EQ(two["results"][1]["x_given"], "0.25");
  EXPECT_EQ(two["results"][1]["x"].get<double>(), 0.25);
}

TEST_F(BadInput, OutputNamesTheCommandDoesNotWriteAreRefused) {
  const std::string gold = DataDir() + "/pure/Au-Johnson.yml";
  ExpectCleanError({"render", "--nk", gold, "--size", "8", "--out", dir_ + "/x.jpg"},
                   {"x.jpg", "render writes PNG only"});
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/x.jpg"));
  ASSERT_EQ(RunProgram({"render", "--nk", gold, "--size", "8", "--out", dir_ + "/x.PNG", "--quiet"})
                .status,
            0);
  std::filesystem::remove(dir_ + "/x.PNG");
  // export's --out is a prefix: a folder would get hidden files (.eta.spd, .pbrt) inside.
  ExpectCleanError({"export", "--nk", gold, "--out", dir_ + "/"},
                   {"--out is a file name prefix, e.g. " + dir_ + "/au18k"});
  ExpectCleanError({"export", "--nk", gold, "--out", dir_}, {"names a folder"});
  ExpectCleanError({"export", "--nk", gold, "--out", dir_ + "/new/"}, {"names a folder"});
  EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

TEST(Cli, PredictWritesTheModelsIndex) {
  const std::string dir = MakeTempDir();
  ASSERT_EQ(RunProgram({"fit", "--data", "Au-Ag", "--method", "paper", "--out", dir + "/paper.json",
                        "--quiet"})
                .status,
            0);
  const RunResult r =
      RunProgram({"predict", "--model", dir + "/paper.json", "--x", "0.5", "--lambda-from", "400",
                  "--lambda-to", "410", "--lambda-step", "10"});
  ASSERT_EQ(r.status, 0) << r.err;
  // The old names (until 0.3): the same rows, and a note naming the new ones; not both.
  const RunResult old = RunProgram({"predict", "--model", dir + "/paper.json", "--x", "0.5",
                                    "--from", "400", "--to", "410", "--step", "10"});
  ASSERT_EQ(old.status, 0) << old.err;
  EXPECT_EQ(old.out, r.out);
  EXPECT_NE(old.err.find("--from is now --lambda-from"), std::string::npos) << old.err;
  EXPECT_NE(old.err.find("--step is now --lambda-step"), std::string::npos) << old.err;
  ExpectCleanError({"predict", "--model", dir + "/paper.json", "--x", "0.5", "--from", "400",
                    "--lambda-from", "400"},
                   {"--from is --lambda-from's old name"});
  // The paper model at a known sample is the sample: Rioux-Au50Ag50.yml rows 0.400, 0.410.
  ASSERT_EQ(CountLines(r.out), 3);
  double lambda = 0, n = 0, k = 0;
  ASSERT_EQ(std::sscanf(r.out.c_str() + r.out.find('\n') + 1, "%lf,%lf,%lf", &lambda, &n, &k), 3);
  EXPECT_EQ(lambda, 400.0);
  EXPECT_NEAR(n, 1.07148, 1e-9);
  EXPECT_NEAR(k, 1.60428, 1e-9);
}

}  // namespace
}  // namespace alloycolor::testing
