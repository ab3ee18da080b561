#include "common.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/output.h"
#include "alloycolor/core/setting.h"
#include "alloycolor/core/text.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/registry.h"

namespace alloycolor::app {

namespace fs = std::filesystem;

// The most values a comma-separated option takes (--x, --angles, ...).
constexpr std::size_t kMaxListValues = 1000;

std::string DataRoot() {
  if (const char* env = std::getenv("ALLOYCOLOR_DATA_DIR"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path() / ALLOYCOLOR_INSTALL_DATA_RELPATH;
    if (fs::is_directory(installed / "cie", ec)) return fs::weakly_canonical(installed).string();
  }
  return ALLOYCOLOR_SOURCE_DATA_DIR;
}

std::vector<std::string> BundledDatasets() {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(DataRoot(), ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code file_ec;
    if (fs::is_regular_file(it->path() / "dataset.json", file_ec)) {
      names.push_back(it->path().filename().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

namespace {

std::string Joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// Why `arg`, which exists, is not a data set, when the file is something else the program
// reads ("" when it is not).
std::string NotADataset(const std::string& arg, bool takes_nk) {
  switch (GuessInputKind(arg)) {
    case InputKind::kModelFile:
      return arg + ": this is a model file: use --model";
    case InputKind::kNkFile:
      return arg + ": this is one sample's n,k, not a data set (a folder or a dataset.json " +
             "manifest listing n,k files at several compositions; see docs/data.md)" +
             (takes_nk ? "; for this sample alone use --nk" : "");
    default:
      return "";
  }
}

Dataset LoadDatasetFrom(const std::string& arg, bool takes_nk) {
  std::error_code ec;
  if (!fs::exists(arg, ec)) {
    const fs::path bundled = fs::path(DataRoot()) / arg;
    if (!arg.empty() && fs::path(arg).is_relative() && fs::exists(bundled, ec)) {
      return LoadDataset(bundled.string());
    }
    const std::vector<std::string> names = BundledDatasets();
    const std::string nearest = NearestName(arg, names);
    throw Error("no data set " + Quote(arg, 100) + ": not a folder, a manifest or a bundled set (" +
                Joined(names) + ")" + (nearest.empty() ? "" : "; did you mean " + nearest + "?"));
  }
  try {
    return LoadDataset(arg);
  } catch (const Error&) {
    const std::string why = NotADataset(arg, takes_nk);
    if (why.empty()) throw;
    throw Error(why);
  }
}

}  // namespace

Dataset LoadDatasetArg(const std::string& arg, bool takes_nk) {
  Dataset dataset = LoadDatasetFrom(arg, takes_nk);
  NoteInputs(dataset);
  return dataset;
}

std::unique_ptr<AlloyModel> LoadModelArg(const std::string& path, bool takes_nk,
                                         const std::string& option) {
  try {
    auto model = ReadModelFile(path);
    NoteInput(path);
    return model;
  } catch (const Error&) {
    std::error_code ec;
    std::string kind;
    switch (GuessInputKind(path)) {
      case InputKind::kDataset:
        kind = std::string("a data set") + (fs::is_directory(path, ec) ? "" : " manifest");
        if (option == "--model") throw Error(path + ": this is " + kind + ": use --data");
        break;
      case InputKind::kNkFile:
        kind = "one sample's n,k";
        if (option == "--model") {
          throw Error(path + ": this is " + kind + ", not a model file (which 'alloycolor " +
                      "fit --out' writes)" + (takes_nk ? ": use --nk" : ""));
        }
        break;
      default:
        throw;
    }
    throw Error(path + ": this is " + kind + ", not a model file: " + option +
                " takes the model an earlier 'alloycolor fit --out' wrote");
  }
}

color::Colorimeter LoadColorimeter(const std::string& illuminant, int observer_deg) {
  const std::string root = DataRoot();
  color::Colorimeter colorimeter = color::Colorimeter::Load(root, illuminant, observer_deg);
  // The colour tables read are inputs too: note the folder's files.
  ProgramGuard().NoteFolder((fs::path(root) / "cie").string());
  return colorimeter;
}

namespace {

std::vector<std::string> SplitComma(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) parts.push_back(part);
  if (!text.empty() && text.back() == ',') parts.push_back("");
  return parts;
}

}  // namespace

namespace {

// A composition list past kMaxListValues is refused by its length alone, so the check can
// come before the model is loaded or fitted.
void CheckCompositionCount(std::size_t count, const std::string& option) {
  if (count > kMaxListValues) {
    throw Error(option + ": " + std::to_string(count) + " compositions given, at most " +
                std::to_string(kMaxListValues) + " (use 'alloycolor sweep' for more)");
  }
}

}  // namespace

std::vector<double> ParseCompositions(const std::string& text, const AlloySystem& system,
                                      const std::string& option) {
  std::vector<double> xs;
  const std::vector<std::string> parts = SplitComma(text);
  CheckCompositionCount(parts.size(), option);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (parts[i].find('\0') != std::string::npos) throw Error(option + ": a NUL byte in the list");
    try {
      xs.push_back(ParseComposition(parts[i], system));
    } catch (const Error& e) {
      if (const std::string meant = DecimalCommaReading(parts, i, system); !meant.empty()) {
        throw Error(option + ": " + Quote(text) + " has a decimal comma: write " + meant +
                    " (a comma separates compositions; the decimal mark is a point)");
      }
      throw Error(option + ": " + e.what());
    }
  }
  if (xs.empty()) throw Error(option + ": no composition given");
  return xs;
}

double ParseCompositionArg(const std::string& text, const AlloySystem& system,
                           const std::string& option) {
  try {
    return ParseComposition(text, system);
  } catch (const Error& e) {
    if (const std::string meant = DecimalCommaReading(SplitComma(text), 0, system);
        !meant.empty() && SplitComma(text).size() == 2) {
      throw Error(option + ": " + Quote(text) + " has a decimal comma: write " + meant +
                  " (the decimal mark is a point)");
    }
    throw Error(option + ": " + e.what());
  }
}

std::vector<const Sample*> SamplesAt(const std::string& text, const Dataset& dataset,
                                     const std::string& option) {
  const auto list = [&dataset] {
    std::string s;
    for (const Sample& sample : dataset.samples) {
      char x[32];
      std::snprintf(x, sizeof x, "%g", sample.x_given);
      s += (s.empty() ? "" : ", ") + std::string(x);
    }
    return s;
  };
  std::vector<const Sample*> found;
  for (std::string part : SplitComma(text)) {
    const size_t b = part.find_first_not_of(" \t"), e = part.find_last_not_of(" \t");
    part = b == std::string::npos ? "" : part.substr(b, e - b + 1);
    if (part.empty()) throw Error(option + ": empty composition in '" + text + "'");
    const Sample* match = FindSample(dataset, ParseComposition(part, dataset.system));
    if (!match) {
      throw Error(option + ": no sample at " + part + " in " + dataset.manifest_path +
                  " (samples at " + list() + ")");
    }
    if (std::find(found.begin(), found.end(), match) == found.end()) found.push_back(match);
  }
  if (found.empty()) throw Error(option + ": no composition given");
  return found;
}

std::vector<double> ParseNumberList(const std::string& text, const std::string& option) {
  std::vector<double> values;
  const std::vector<std::string> parts = SplitComma(text);
  if (parts.size() > kMaxListValues) {
    throw Error(option + ": " + std::to_string(parts.size()) + " values given, at most " +
                std::to_string(kMaxListValues));
  }
  for (const std::string& part : parts) {
    if (part.find('\0') != std::string::npos) throw Error(option + ": a NUL byte in a number");
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (part.empty() || end == part.c_str() || *end != '\0' || !std::isfinite(v)) {
      throw Error(option + ": cannot read " + Quote(MessageLine(part, 40)) + " as a number");
    }
    values.push_back(v);
  }
  if (values.empty()) throw Error(option + ": no value given");
  return values;
}

ProgressCallback ProgressPrinter(bool quiet) {
  if (quiet) return {};
  return [](const std::string& m) { std::cerr << "alloycolor: " << MessageLine(m) << "\n"; };
}

void WriteOutput(const std::string& path, const std::string& contents, bool quiet) {
  WriteOutputs({{path, contents}}, quiet);
}

void WriteOutputs(const std::vector<OutputFile>& files, bool quiet) {
  WriteFileSetAtomic(files, &ProgramGuard());
  if (quiet) return;
  for (const OutputFile& file : files) {
    std::cerr << "alloycolor: wrote " << MessageLine(file.path) << "\n";
  }
}

namespace {
std::vector<std::string>& PendingWarnings() {
  static std::vector<std::string> pending;
  return pending;
}
}  // namespace

void Warn(const std::string& message) { PendingWarnings().push_back(message); }

void FlushWarnings() {
  for (const std::string& w : PendingWarnings()) {
    std::cerr << "alloycolor: warning: " << MessageLine(w) << "\n";
  }
  PendingWarnings().clear();
}

std::string MethodsHelp() {
  std::string text;
  for (const MethodInfo& m : Methods()) text += "  " + m.name + ": " + m.summary + "\n";
  return text;
}

void ModelSource::AddOptions(CLI::App* cmd, bool with_data, bool with_extrapolate) {
  cmd->add_option("--model", model_path, "Fitted model file (JSON, from 'alloycolor fit')");
  if (with_data) {
    cmd->add_option("--data", data_dir,
                    "Data set: folder with dataset.json, a manifest, or a bundled set's name "
                    "(Au-Ag, Cu-Zn, Nb-Sn)");
    cmd->add_option("--method", method,
                    "Model built from --data: auto (chosen by leave-one-out), or one of " +
                        MethodNamesText() + " ('alloycolor fit --help', docs/methods.md)")
        ->capture_default_str();
  }
  if (with_extrapolate) {
    cmd->add_flag("--extrapolate", extrapolate,
                  "Allow compositions outside the training samples' range");
  }
}

std::unique_ptr<AlloyModel> ModelSource::Load(bool quiet) const {
  if (!model_path.empty() && !data_dir.empty()) {
    throw Error("give either --model or --data, not both");
  }
  if (!model_path.empty()) return LoadModelArg(model_path, takes_nk);
  if (!data_dir.empty()) {
    const Dataset dataset = LoadDatasetArg(data_dir, takes_nk);
    if (!quiet) {
      for (const std::string& w : dataset.warnings) Warn(w);
    }
    // No progress lines: a command that then fails on another option prints its one error
    // line only (fit, whose work this is, reports its progress itself).
    fit::FitSettings settings;
    ThreadBudget threads;  // every core
    settings.threads = &threads;
    const color::Colorimeter colorimeter = LoadColorimeter("D65", 2);
    settings.colorimeter = &colorimeter;
    auto model = fit::BuildModel(method, dataset, settings);
    if (!quiet) {
      for (const std::string& w : model->warnings()) Warn(w);
    }
    return model;
  }
  throw Error("give --model FILE or --data DIR");
}

void MaterialSource::AddOptions(CLI::App* cmd, const std::string& x_help,
                                const std::string& x_names) {
  cmd->add_option("--nk", nk_file,
                  "Measured optical constants: refractiveindex.info YAML, or delimited text "
                  "(.csv, .txt, .dat, .tsv; comma, semicolon, tab or whitespace) with a header "
                  "naming the abscissa and its unit (wavelength in nm, um or A, energy in eV, "
                  "wavenumber in cm-1) and n,k or eps1,eps2 columns");
  cmd->add_option("--columns", columns,
                  "For a --nk text file holding several samples: the n and k (or eps1 and eps2) "
                  "columns to read, as N,K by header name or 1-based column number, e.g. "
                  "n6,k6 or 2,3");
  source.AddOptions(cmd, true);
  source.takes_nk = true;
  cmd->add_option(x_names, x_text, x_help);
}

NkSpectrum MaterialSource::LoadMeasured(bool quiet) const {
  if (!source.model_path.empty() || !source.data_dir.empty() || !x_text.empty()) {
    throw Error("--nk takes no --model, --data or --x");
  }
  std::vector<std::string> warnings;
  NkSpectrum nk =
      ReadNkFile(nk_file, columns.empty() ? NkColumns{} : ParseNkColumns(columns), &warnings);
  NoteInput(nk_file);
  if (!quiet) {
    for (const auto& w : warnings) Warn(w);
  }
  return nk;
}

std::unique_ptr<AlloyModel> MaterialSource::LoadModel(bool quiet, bool needs_x) const {
  if (!columns.empty()) throw Error("--columns applies to --nk FILE only");
  if (source.model_path.empty() && source.data_dir.empty()) {
    throw Error("give --nk FILE, or --model FILE (or --data DIR) with --x");
  }
  if (needs_x && x_text.empty()) {
    throw Error("--x: give the composition(s), e.g. --x 0.75 or 18k");
  }
  if (!x_text.empty()) CheckCompositionCount(SplitComma(x_text).size(), "--x");
  return source.Load(quiet);
}

std::vector<double> MaterialSource::Compositions(const AlloyModel& model, bool single) const {
  const std::vector<double> xs = ParseCompositions(x_text, model.system(), "--x");
  if (single && xs.size() != 1) throw Error("--x: give one composition, not " + x_text);
  for (double x : xs) CheckComposition(model, x, source.extrapolate);
  return xs;
}

std::vector<std::string> MaterialSource::CompositionTexts() const {
  std::vector<std::string> texts;
  for (const std::string& part : SplitComma(x_text)) texts.emplace_back(Trim(part));
  return texts;
}

void AddColorimetryOptions(CLI::App* cmd, std::string* illuminant, int* observer) {
  cmd->add_option("--illuminant", *illuminant, "CIE illuminant: A, C, D50, D65, E, F2, F11")
      ->capture_default_str();
  cmd->add_option("--observer", *observer, "CIE observer: 2 (1931) or 10 (1964)")
      ->capture_default_str();
}

CLI::Validator NumberIn(double lo, double hi, bool whole) {
  return NumberIn(NumberRange{lo, hi, whole});
}

CLI::Validator NumberIn(const NumberRange& range) {
  return CLI::Validator(
      [range](std::string& text) -> std::string { return NumberProblem(text, range); },
      (range.whole ? "INT in [" : "NUMBER in [") + FormatNumber(range.lo) + ", " +
          FormatNumber(range.hi) + "]");
}

void AddMethodOptions(CLI::App* cmd, OptionValues* values) {
  for (const DeclaredOption& declared : DeclaredOptions()) {
    const OptionSpec& spec = declared.spec;
    std::string methods;
    for (const std::string& m : declared.methods) methods += (methods.empty() ? "" : ", ") + m;
    std::string help = methods + ": " + spec.help;
    if (spec.kind == OptionKind::kFlag) {
      // The flag sets the value other than the default (--no-covariance: false).
      const bool set_to = !(spec.default_value && spec.default_value->flag);
      cmd->add_flag_callback(
          spec.flag, [values, name = spec.name, set_to] { values->Set(name, set_to); }, help);
      continue;
    }
    if (spec.default_value) help += " (default: " + OptionValueText(*spec.default_value) + ")";
    const bool number = spec.kind == OptionKind::kWhole || spec.kind == OptionKind::kNumber;
    std::string type = spec.kind == OptionKind::kWhole ? "INT" : number ? "NUMBER" : "TEXT";
    if (spec.kind == OptionKind::kChoice) {
      type.clear();
      for (const std::string& c : spec.choices) type += (type.empty() ? "{" : ",") + c;
      type += "}";
    }
    cmd->add_option_function<std::string>(
           spec.flag,
           [values, spec](const std::string& text) {
             values->Set(spec.name, OptionFromText(spec, text, OptionSpelling::kFlag));
           },
           help)
        ->type_name(number ? type + " in [" + FormatNumber(spec.range.lo) + ", " +
                                 FormatNumber(spec.range.hi) + "]"
                           : type)
        ->check(CLI::Validator(
            [spec](std::string& text) -> std::string { return OptionTextProblem(spec, text); },
            ""));
  }
}

void CheckOutputFolder(const std::string& path, const std::string& option) {
  if (const std::string problem = OutputFolderProblem(path); !problem.empty()) {
    throw Error(option + ": " + problem);
  }
}

std::string OutputFolderProblem(const std::string& path) {
  std::string file = path;  // "dir/new/" names the folder new in dir: dir must exist
  while (file.size() > 1 && file.back() == '/') file.pop_back();
  const fs::path folder = fs::path(file).parent_path();
  std::error_code ec;
  if (folder.empty() || fs::is_directory(folder, ec)) return "";
  return "folder " + Quote(folder.string(), 200) +
         (fs::exists(folder, ec) ? " is not a folder" : " does not exist") +
         " (outputs go into an existing folder)";
}

void CheckComposition(const AlloyModel& model, double x_atomic, bool extrapolate) {
  if (!(x_atomic >= 0.0 && x_atomic <= 1.0)) {
    throw Error("composition " + std::to_string(x_atomic) + " lies outside [0, 1]");
  }
  if (!extrapolate) model.CheckInRange(x_atomic);
}

std::pair<double, double> CompositionRange(const AlloyModel& model, const std::string& from_text,
                                           const std::string& to_text, bool extrapolate) {
  const double from =
      from_text.empty() ? model.x_min() : ParseCompositionArg(from_text, model.system(), "--from");
  const double to =
      to_text.empty() ? model.x_max() : ParseCompositionArg(to_text, model.system(), "--to");
  CheckComposition(model, from, extrapolate);
  CheckComposition(model, to, extrapolate);
  return {from, to};
}

std::string DescribeComposition(double x_atomic, const AlloySystem& system) {
  char text[160];
  const std::string a = system.a.symbol;
  const double w = WeightFromAtomicFraction(x_atomic, system);
  std::snprintf(text, sizeof text, "%.4f (%.2f at%% %s, %.2f wt%% %s", x_atomic, 100 * x_atomic,
                a.c_str(), 100 * w, a.c_str());
  std::string out = text;
  if (IsGoldAlloy(system)) {
    std::snprintf(text, sizeof text, ", %.2f k", KaratFromAtomicFraction(x_atomic, system));
    out += text;
  }
  return out + ")";
}

nlohmann::json CompositionJson(double x_atomic, const AlloySystem& system) {
  nlohmann::json out = {{"x_atomic", x_atomic},
                        {"at_percent", 100 * x_atomic},
                        {"wt_percent", 100 * WeightFromAtomicFraction(x_atomic, system)}};
  if (IsGoldAlloy(system)) out["karat"] = KaratFromAtomicFraction(x_atomic, system);
  return out;
}

}  // namespace alloycolor::app
