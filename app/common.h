// What the subcommands share: finding the bundled data, reading compositions, building
// or loading a model, writing outputs safely, printing warnings and progress.
#ifndef ALLOYCOLOR_APP_COMMON_H_
#define ALLOYCOLOR_APP_COMMON_H_

#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/output.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/core/setting.h"
#include "alloycolor/core/spectrum.h"
#include "alloycolor/model/alloy_model.h"
#include "output_guard.h"

namespace alloycolor::app {

// The bundled data folder: $ALLOYCOLOR_DATA_DIR, else the installed share/alloycolor/data
// next to the program, else the source tree's data/.
std::string DataRoot();

// The bundled data sets' names ("Au-Ag", ...): DataRoot()'s folders holding dataset.json.
std::vector<std::string> BundledDatasets();

// A data set given on the command line: a path, or the name of a bundled set ("Au-Ag");
// its files are noted as inputs (output_guard.h). An unknown name lists the bundled sets
// and the nearest; a model file or an n,k file is named as such (`takes_nk`: the command
// also takes --nk, which the message then offers).
Dataset LoadDatasetArg(const std::string& arg, bool takes_nk = false);

// A model file given on the command line, noted as an input; a data set or an n,k file
// given instead is named as such (and --nk offered where the command takes it).
// `option`: the option that named the file, in the messages ("--model", "--refit").
std::unique_ptr<AlloyModel> LoadModelArg(const std::string& path, bool takes_nk = false,
                                         const std::string& option = "--model");

// Colorimeter for --illuminant and --observer; the colour tables are noted as inputs.
color::Colorimeter LoadColorimeter(const std::string& illuminant, int observer_deg);

// Comma-separated compositions ("0.5,75wt%,18k") as atomic fractions of element a; errors
// name `option`.
std::vector<double> ParseCompositions(const std::string& text, const AlloySystem& system,
                                      const std::string& option);
// One composition, naming the option on error.
double ParseCompositionArg(const std::string& text, const AlloySystem& system,
                           const std::string& option);
// The samples of `dataset` at the comma-separated compositions of `text`, each once, in
// the order given: a plain number matches a sample's atomic fraction or, failing that, the
// number the manifest gives it (a weight fraction in a weight-fraction manifest); 75at%,
// 75wt% and 18k as in ParseCompositions. Throws Error naming `option` and listing the
// samples when a composition matches none.
std::vector<const Sample*> SamplesAt(const std::string& text, const Dataset& dataset,
                                     const std::string& option);
// Comma-separated numbers, naming the option on error.
std::vector<double> ParseNumberList(const std::string& text, const std::string& option);

// Progress lines on stderr ("alloycolor: ..."), or none when quiet.
ProgressCallback ProgressPrinter(bool quiet);

// Every method with its summary, a line each, for --help.
std::string MethodsHelp();

// Writes a file atomically (output.h, with the program's guard: never over an input or a
// special file, its temporary removed on a signal) and says so
// on stderr unless quiet. WriteOutputs writes several as a set: all or none replaced.
void WriteOutput(const std::string& path, const std::string& contents, bool quiet);
void WriteOutputs(const std::vector<OutputFile>& files, bool quiet);

// Queues a warning ("alloycolor: warning: ..."); FlushWarnings prints them once the
// command has succeeded, so a failed run prints its one error line only.
void Warn(const std::string& message);
void FlushWarnings();

// Options common to commands that take a composition source: --model, --data + --method.
struct ModelSource {
  std::string model_path;
  std::string data_dir;
  std::string method = "auto";
  bool extrapolate = false;
  bool takes_nk = false;  // the command takes --nk too (MaterialSource), for messages
  // with_extrapolate: offer --extrapolate (not for commands that keep to the model's range).
  void AddOptions(CLI::App* cmd, bool with_data, bool with_extrapolate = true);
  // Loads or builds the model; throws Error when neither or both are given.
  std::unique_ptr<AlloyModel> Load(bool quiet) const;
};

// Where the material comes from, for commands that take a measured metal or an alloy:
// --nk FILE alone (with --columns N,K for a file holding several samples), or --model FILE
// / --data DIR (+ --method) with --x compositions.
struct MaterialSource {
  std::string nk_file;
  std::string columns;  // --columns N,K: which columns of a multi-sample text file
  ModelSource source;
  std::string x_text;
  void AddOptions(CLI::App* cmd, const std::string& x_help, const std::string& x_names = "--x");
  bool measured() const { return !nk_file.empty(); }
  // The --nk spectrum (its repairs queued as warnings unless quiet); throws Error when
  // --model, --data or --x are given too.
  NkSpectrum LoadMeasured(bool quiet) const;
  // The model of --model or --data; throws Error naming what is missing.
  // needs_x false: --x may be absent (a command over the model's whole range).
  std::unique_ptr<AlloyModel> LoadModel(bool quiet, bool needs_x = true) const;
  // The --x compositions, each checked against the model's range; `single`: exactly one.
  std::vector<double> Compositions(const AlloyModel& model, bool single) const;
  // The --x compositions as the user wrote them ("18k"), trimmed, in the same order.
  std::vector<std::string> CompositionTexts() const;
};

// --illuminant and --observer, the same on every command that computes colour.
void AddColorimetryOptions(CLI::App* cmd, std::string* illuminant, int* observer);

// An option check: the value must be a finite number in [lo, hi] ("nan", "-1" refused
// with a message naming the range). For integer options too: "2.5" and 2^40 are refused.
CLI::Validator NumberIn(double lo, double hi, bool whole = false);
// The same for a library's named range (core/setting.h), with its words.
CLI::Validator NumberIn(const NumberRange& range);

// The methods' options as the program's options, generated from their declarations in
// the registry (model/registry.h DeclaredOptions): one per option, spelt by its flag, its
// help line naming the methods that take it, its values and default; a value the
// declaration refuses is refused while the command line is read. The values given go into
// `values` (kept by the caller) by the options' names.
void AddMethodOptions(CLI::App* cmd, OptionValues* values);

// Refuses an output path whose folder does not exist, before any work is done.
void CheckOutputFolder(const std::string& path, const std::string& option);
// Why an output cannot go to `path`'s folder ("folder 'x' does not exist"), or "": what
// main checks of every command's --out while it reads the command line.
std::string OutputFolderProblem(const std::string& path);

// Checks x against the model's range unless extrapolation is allowed.
void CheckComposition(const AlloyModel& model, double x_atomic, bool extrapolate);
// --from and --to as atomic fractions (the model's range where empty), each checked
// against the model's range unless extrapolation is allowed.
std::pair<double, double> CompositionRange(const AlloyModel& model, const std::string& from_text,
                                           const std::string& to_text, bool extrapolate);

// A composition as the program prints it: "0.7512 (75.12 at% Au, 84.6 wt% Au, 20.3 k)"
// (karat for gold alloys only), and the same as JSON fields x_atomic, at_percent,
// wt_percent and, for gold alloys, karat.
std::string DescribeComposition(double x_atomic, const AlloySystem& system);
nlohmann::json CompositionJson(double x_atomic, const AlloySystem& system);

// Subcommand registration (one file each).
void RegisterColor(CLI::App& app);
void RegisterFit(CLI::App& app);
void RegisterPredict(CLI::App& app);
void RegisterRender(CLI::App& app);
void RegisterExport(CLI::App& app);
void RegisterValidate(CLI::App& app);
void RegisterChart(CLI::App& app);
void RegisterParams(CLI::App& app);
void RegisterSweep(CLI::App& app);
void RegisterExplore(CLI::App& app);
void RegisterMatch(CLI::App& app);
void RegisterTolerance(CLI::App& app);
void RegisterSuggest(CLI::App& app);

}  // namespace alloycolor::app

#endif  // ALLOYCOLOR_APP_COMMON_H_
