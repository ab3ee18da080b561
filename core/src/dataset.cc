#include "alloycolor/core/dataset.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/permittivity.h"
#include "alloycolor/core/text.h"

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr const char* kAtomic = "atomic_fraction_a";
constexpr const char* kWeight = "weight_fraction_a";
// Samples closer than this in atomic fraction, but not equal, are a typing slip: a fit
// through both would have to bend by 1/kDistinctComposition. Replicates give one x.
constexpr double kDistinctComposition = 1e-6;

std::string Quote60(const std::string& text) { return Quote(text, 60); }

Json ParseManifest(const std::string& manifest, const std::string& text) {
  try {
    return Json::parse(text, RejectDuplicateKeys(manifest));
  } catch (const Json::parse_error& e) {
    // nlohmann's message reads "[json.exception.parse_error.101] parse error at line 3,
    // column 5: syntax error ..."; keep what follows the position.
    std::string reason = e.what();
    const std::size_t column = reason.find("column ");
    const std::size_t colon = reason.find(": ", column == std::string::npos ? 0 : column);
    if (colon != std::string::npos) reason = reason.substr(colon + 2);
    const std::size_t byte = e.byte > 0 ? e.byte - 1 : 0;
    Fail(manifest + ":" + std::to_string(LineOfByte(text, byte)) + ": invalid JSON: " + reason);
  } catch (const Json::exception& e) {
    Fail(manifest + ": invalid JSON: " + e.what());
  }
}

const Element& ElementField(const std::string& manifest, const Json& system, const char* key) {
  const std::string field = std::string("system.") + key;
  if (!system.contains(key)) Fail(manifest + ": " + field + ": missing");
  const Json& value = system.at(key);
  if (!value.is_string()) Fail(manifest + ": " + field + ": not a string");
  try {
    return FindElement(value.get<std::string>());
  } catch (const Error& e) {
    Fail(manifest + ": " + field + ": " + e.what());
  }
}

void WarnUnknownKeys(const std::string& manifest, const std::string& where, const Json& object,
                     const std::vector<std::string>& known, std::vector<std::string>* warnings) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    if (std::find(known.begin(), known.end(), it.key()) == known.end()) {
      warnings->push_back(manifest + ": " + where + "unknown key " + Quote60(it.key()) +
                          " ignored");
    }
  }
}

// "elements": {"Pd": {"valence": 0.36, "density_g_cm3": 12.0, "atomic_mass": 106.42}}
// replaces the table's values for the system's elements; a valence given here is no
// longer conventional.
void ApplyElementOverrides(const std::string& manifest, const Json& elements, AlloySystem* system) {
  if (!elements.is_object()) {
    Fail(manifest + ": elements: not an object like {\"Pd\": {\"valence\": 0.36}}");
  }
  for (auto it = elements.begin(); it != elements.end(); ++it) {
    const std::string where = "elements." + it.key();
    Element* element = it.key() == system->a.symbol   ? &system->a
                       : it.key() == system->b.symbol ? &system->b
                                                      : nullptr;
    if (element == nullptr) {
      Fail(manifest + ": " + where + ": " + Quote60(it.key()) + " is not an element of " +
           system->Name());
    }
    if (!it.value().is_object()) Fail(manifest + ": " + where + ": not an object");
    for (auto field = it.value().begin(); field != it.value().end(); ++field) {
      const std::string name = where + "." + field.key();
      double* target = field.key() == "valence"         ? &element->valence
                       : field.key() == "density_g_cm3" ? &element->density_g_cm3
                       : field.key() == "atomic_mass"   ? &element->atomic_mass
                                                        : nullptr;
      if (target == nullptr) {
        Fail(manifest + ": " + name +
             ": unknown key (expected valence, density_g_cm3 or atomic_mass)");
      }
      const double value = field.value().is_number() ? field.value().get<double>() : -1;
      if (!field.value().is_number() || !std::isfinite(value) || !(value > 0) || value > 1e4) {
        Fail(manifest + ": " + name + ": " + Quote60(field.value().dump()) +
             " is not a positive number");
      }
      *target = value;
      if (field.key() == "valence") element->valence_conventional = false;
    }
  }
}

bool SameFile(const fs::path& a, const fs::path& b) {
  std::error_code error;
  const bool same = fs::equivalent(a, b, error);
  if (!error) return same;
  return fs::weakly_canonical(a, error) == fs::weakly_canonical(b, error) && !error;
}

// The manifest's "system" (with its element overrides) and the data set's name.
void ReadSystem(const std::string& manifest, const Json& root, Dataset* dataset) {
  if (!root.contains("system") || !root.at("system").is_object()) {
    Fail(manifest + ": system: missing or not an object like {\"a\": \"Au\", \"b\": \"Ag\"}");
  }
  const Json& system = root.at("system");
  dataset->system.a = ElementField(manifest, system, "a");
  dataset->system.b = ElementField(manifest, system, "b");
  if (std::string(dataset->system.a.symbol) == dataset->system.b.symbol) {
    Fail(manifest + ": system: a and b are both '" + dataset->system.a.symbol + "'");
  }
  if (root.contains("elements"))
    ApplyElementOverrides(manifest, root.at("elements"), &dataset->system);

  for (const char* key : {"name", "source", "notes"}) {
    if (root.contains(key) && !root.at(key).is_string()) {
      Fail(manifest + ": " + key + ": not a string");
    }
  }
  dataset->name =
      root.contains("name") ? root.at("name").get<std::string>() : dataset->system.Name();
}

// The manifest's "composition": atomic or weight fraction.
std::string ReadCompositionKind(const std::string& manifest, const Json& root) {
  if (!root.contains("composition")) {
    Fail(manifest + ": composition: missing; write \"" + kAtomic + "\" or \"" + kWeight + "\"");
  }
  const Json& composition = root.at("composition");
  if (!composition.is_string() ||
      (composition.get<std::string>() != kAtomic && composition.get<std::string>() != kWeight)) {
    Fail(manifest + ": composition: " + Quote60(composition.dump()) + " is neither \"" + kAtomic +
         "\" nor \"" + kWeight + "\"");
  }
  return composition.get<std::string>();
}

// A sample's measurement files ("file", or "n_file" and "k_file"), resolved against folder.
void ReadSampleFiles(const std::string& manifest, const std::string& where, const Json& entry,
                     const fs::path& folder, Sample* sample, std::string* file) {
  const auto file_field = [&](const char* key) {
    if (!entry.contains(key)) return std::string();
    if (!entry.at(key).is_string() || entry.at(key).get<std::string>().empty()) {
      Fail(manifest + ": " + where + "." + key + ": not a file name");
    }
    if (entry.at(key).get<std::string>().find('\0') != std::string::npos) {
      Fail(manifest + ": " + where + "." + key + ": the file name holds a NUL byte");
    }
    return entry.at(key).get<std::string>();
  };
  *file = file_field("file");
  const std::string n_file = file_field("n_file");
  const std::string k_file = file_field("k_file");
  if (file->empty() && n_file.empty() && k_file.empty()) {
    Fail(manifest + ": " + where + ".file: missing or not a file name");
  }
  if (!file->empty() == (!n_file.empty() || !k_file.empty()) || n_file.empty() != k_file.empty()) {
    Fail(manifest + ": " + where + ": give either \"file\" or both \"n_file\" and \"k_file\"");
  }
  const auto resolve = [&](const std::string& name) {
    const fs::path given(name);
    std::string path = (given.is_absolute() ? given : folder / given).lexically_normal().string();
    return path.empty() ? name : path;
  };
  if (file->empty()) {
    sample->file = n_file + " + " + k_file;
    sample->path = resolve(n_file);
    sample->k_path = resolve(k_file);
  } else {
    sample->file = *file;
    sample->path = resolve(*file);
  }
}

// A sample's "columns": the n and k columns of its one delimited file.
void ReadSampleColumns(const std::string& manifest, const std::string& where, const Json& columns,
                       const std::string& file, Sample* sample) {
  const auto column = [&](const Json& value) {
    if (value.is_string() && !value.get<std::string>().empty()) return value.get<std::string>();
    if (value.is_number_unsigned() && value.get<unsigned long long>() >= 1 &&
        value.get<unsigned long long>() < 1000000) {
      return std::to_string(value.get<unsigned long long>());
    }
    Fail(manifest + ": " + where + ".columns: " + Quote60(value.dump()) +
         " is neither a header name nor a 1-based column number");
  };
  if (!columns.is_array() || columns.size() != 2) {
    Fail(manifest + ": " + where +
         ".columns: not a list of two columns like [\"n6\", \"k6\"] or [2, 3]");
  }
  if (file.empty()) {
    Fail(manifest + ": " + where + ".columns: applies to \"file\", not to n_file/k_file");
  }
  sample->columns.n = column(columns.at(0));
  sample->columns.k = column(columns.at(1));
  sample->file = file + " (columns " + sample->columns.n + "," + sample->columns.k + ")";
}

// The manifest's "precision" (optional): {"n": sd, "k": sd}, each a number from 0 to 10.
void ReadPrecision(const std::string& manifest, const Json& root, Dataset* dataset) {
  if (!root.contains("precision")) return;
  const Json& precision = root.at("precision");
  if (!precision.is_object()) {
    Fail(manifest + ": precision: " + Quote60(precision.dump()) +
         " is not an object such as {\"n\": 0.002, \"k\": 0.002}");
  }
  WarnUnknownKeys(manifest, "precision: ", precision, {"n", "k"}, &dataset->warnings);
  dataset->precision_stated = true;
  for (const auto& [key, target] :
       {std::pair{"n", &dataset->precision_n}, std::pair{"k", &dataset->precision_k}}) {
    if (!precision.contains(key)) continue;
    const Json& value = precision.at(key);
    const double v = value.is_number() ? value.get<double>() : -1;
    if (!value.is_number() || !std::isfinite(v) || v < 0 || v > 10) {
      Fail(manifest + ": precision: " + key + ": " + Quote60(value.dump()) +
           " is not a standard deviation from 0 to 10");
    }
    *target = v;
  }
}

// Entry i of the manifest's "samples": its files, columns and composition (not yet its data).
Sample ReadSampleEntry(const std::string& manifest, const fs::path& manifest_path, std::size_t i,
                       const Json& entry, const Dataset& dataset,
                       std::vector<std::string>* warnings) {
  const std::string where = "samples[" + std::to_string(i) + "]";
  if (!entry.is_object()) Fail(manifest + ": " + where + ": not an object");
  WarnUnknownKeys(manifest, where + ": ", entry,
                  {"x", "file", "n_file", "k_file", "columns", "exclude"}, warnings);
  Sample sample;
  std::string file;
  ReadSampleFiles(manifest, where, entry, manifest_path.parent_path(), &sample, &file);
  if (entry.contains("columns")) {
    ReadSampleColumns(manifest, where, entry.at("columns"), file, &sample);
  }
  const std::string named = manifest + ": " + where + " (" + Quote60(sample.file) + ")";
  if (!entry.contains("x") || !entry.at("x").is_number()) {
    Fail(named + ": x: missing or not a number");
  }
  sample.x_given = entry.at("x").get<double>();
  if (!(sample.x_given >= 0 && sample.x_given <= 1)) {
    Fail(named + ": x = " + FormatNumber(sample.x_given) + " lies outside [0, 1]");
  }
  if (entry.contains("exclude")) {
    const Json& reason = entry.at("exclude");
    const std::string text = reason.is_string() ? reason.get<std::string>() : std::string();
    if (Trim(text).empty()) {
      Fail(named + ": exclude: " + Quote60(reason.dump()) +
           " is not a reason; write why the sample is set aside, as text "
           "(\"exclude\": \"oxidised film\")");
    }
    sample.excluded = std::string(Trim(text));
  }
  sample.x_atomic = dataset.composition == kWeight
                        ? AtomicFromWeightFraction(sample.x_given, dataset.system)
                        : sample.x_given;
  for (const std::string* path : {&sample.path, &sample.k_path}) {
    if (!path->empty() && SameFile(*path, manifest_path)) {
      Fail(named + ": the sample file is the manifest itself");
    }
  }
  return sample;
}

// What SameFile compares of a path, found once for every pair it is in: its device and
// inode where the file exists (as fs::equivalent compares them), else its weakly canonical
// form (SameFile's fallback when neither exists).
struct FileIdentity {
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  std::string canonical;  // where it does not exist; empty when that failed too
};

FileIdentity IdentityOf(const std::string& path) {
  FileIdentity id;
  struct stat st;
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.device = st.st_dev;
    id.inode = st.st_ino;
    return id;
  }
  std::error_code error;
  const fs::path canonical = fs::weakly_canonical(path, error);
  if (!error) id.canonical = canonical.string();
  return id;
}

bool SameIdentity(const FileIdentity& a, const FileIdentity& b) {
  if (a.exists || b.exists)
    return a.exists && b.exists && a.device == b.device && a.inode == b.inode;
  return !a.canonical.empty() && a.canonical == b.canonical;
}

// Refuses two samples that read the same file and columns, by any path (each path's
// identity found once: with a thousand samples, a million comparisons and no million stats).
void CheckDistinctFiles(const std::string& manifest, const std::vector<Sample>& samples) {
  std::vector<FileIdentity> files, k_files;
  for (const Sample& s : samples) {
    files.push_back(IdentityOf(s.path));
    k_files.push_back(s.k_path.empty() ? FileIdentity{} : IdentityOf(s.k_path));
  }
  for (std::size_t i = 0; i < samples.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const Sample& s = samples[j];
      const Sample& t = samples[i];
      if (s.columns.n == t.columns.n && s.columns.k == t.columns.k &&
          SameIdentity(files[j], files[i]) &&
          (s.k_path.empty() ? t.k_path.empty()
                            : !t.k_path.empty() && SameIdentity(k_files[j], k_files[i]))) {
        Fail(manifest + ": samples[" + std::to_string(j) + "] and samples[" + std::to_string(i) +
             "] both use " + Quote60(t.file) + " (at x = " + FormatNumber(s.x_given) + " and " +
             FormatNumber(t.x_given) + "); one file is one composition");
      }
    }
  }
}

// Sorts the samples by composition and refuses compositions almost but not exactly equal.
void SortByComposition(const std::string& manifest, std::vector<Sample>* samples) {
  // Replicates (distinct files at one composition) stay in the manifest's order, adjacent.
  std::stable_sort(samples->begin(), samples->end(),
                   [](const Sample& s, const Sample& t) { return s.x_atomic < t.x_atomic; });
  for (std::size_t i = 1; i < samples->size(); ++i) {
    const Sample& s = (*samples)[i - 1];
    const Sample& t = (*samples)[i];
    if (t.x_atomic != s.x_atomic && t.x_atomic - s.x_atomic <= kDistinctComposition) {
      Fail(manifest + ": samples " + Quote60(s.file) + " and " + Quote60(t.file) +
           " have almost the same composition, x = " + FormatNumber(s.x_given) + " and " +
           FormatNumber(t.x_given) +
           " (closer than 1e-6); replicates of one composition give the same x");
    }
  }
}

// Reads every sample's n, k and checksum, gathering the readers' warnings.
void ReadSampleData(std::vector<Sample>* samples, std::vector<std::string>* dataset_warnings) {
  for (Sample& sample : *samples) {
    std::vector<std::string> warnings;
    if (sample.k_path.empty()) {
      sample.nk = ReadNkFile(sample.path, sample.columns, &warnings);
      sample.checksum = Fnv1a64Hex(ReadFileText(sample.path));
    } else {
      sample.nk = ReadNkPair(sample.path, sample.k_path, &warnings);
      sample.checksum = Fnv1a64Hex(ReadFileText(sample.path) + ReadFileText(sample.k_path));
    }
    // The readers' warnings already begin with the file (and line).
    for (std::string& warning : warnings) dataset_warnings->push_back(std::move(warning));
  }
}

// Refuses one measurement copied under two names (or columns) as two compositions.
void CheckDistinctMeasurements(const std::string& manifest, const std::vector<Sample>& samples) {
  for (std::size_t i = 0; i < samples.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const Sample& s = samples[j];
      const Sample& t = samples[i];
      if (s.nk.lambda_nm == t.nk.lambda_nm && s.nk.n == t.nk.n && s.nk.k == t.nk.k) {
        Fail(manifest + ": samples " + Quote60(s.file) + " and " + Quote60(t.file) +
             " hold the same n, k at every wavelength (at x = " + FormatNumber(s.x_given) +
             " and " + FormatNumber(t.x_given) +
             "); one measurement is one composition, and one sample");
      }
    }
  }
}

Dataset Load(const std::string& dir_or_manifest) {
  std::error_code error;
  const bool is_folder = fs::is_directory(dir_or_manifest, error);
  const fs::path manifest_path =
      is_folder ? fs::path(dir_or_manifest) / "dataset.json" : fs::path(dir_or_manifest);
  const std::string manifest = manifest_path.string();
  const Json root = ParseManifest(manifest, ReadFileText(manifest));

  Dataset dataset;
  dataset.manifest_path = manifest;
  if (!root.is_object()) Fail(manifest + ": the manifest is not a JSON object");
  WarnUnknownKeys(
      manifest, "", root,
      {"name", "system", "composition", "samples", "source", "notes", "elements", "precision"},
      &dataset.warnings);
  ReadSystem(manifest, root, &dataset);
  ReadPrecision(manifest, root, &dataset);
  dataset.composition = ReadCompositionKind(manifest, root);

  if (!root.contains("samples") || !root.at("samples").is_array() || root.at("samples").empty()) {
    Fail(manifest + ": samples: missing or not a non-empty list");
  }
  const Json& samples = root.at("samples");
  for (std::size_t i = 0; i < samples.size(); ++i) {
    dataset.samples.push_back(
        ReadSampleEntry(manifest, manifest_path, i, samples.at(i), dataset, &dataset.warnings));
  }
  // One measurement cannot be two compositions (the same file and columns, by any path).
  CheckDistinctFiles(manifest, dataset.samples);
  SortByComposition(manifest, &dataset.samples);
  ReadSampleData(&dataset.samples, &dataset.warnings);
  // Nor can one measurement copied under two names (or columns) be two compositions.
  CheckDistinctMeasurements(manifest, dataset.samples);
  // The samples set aside leave the fit but stay known, in the same order.
  const auto set_aside = std::stable_partition(dataset.samples.begin(), dataset.samples.end(),
                                               [](const Sample& s) { return s.excluded.empty(); });
  dataset.excluded.assign(std::make_move_iterator(set_aside),
                          std::make_move_iterator(dataset.samples.end()));
  dataset.samples.erase(set_aside, dataset.samples.end());
  return dataset;
}

}  // namespace

Dataset LoadDataset(const std::string& dir_or_manifest) {
  try {
    return Load(dir_or_manifest);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    Fail(dir_or_manifest + ": cannot load the data set: " + e.what());
  }
}

InputKind GuessInputKind(const std::string& path) {
  try {
    std::error_code error;
    if (fs::is_directory(path, error)) {
      return fs::is_regular_file(fs::path(path) / "dataset.json", error) ? InputKind::kDataset
                                                                         : InputKind::kUnknown;
    }
    const std::string extension = Lower(fs::path(path).extension().string());
    for (const char* nk : {".yml", ".yaml", ".csv", ".txt", ".dat", ".tsv"}) {
      if (extension == nk) return InputKind::kNkFile;
    }
    const Json root = Json::parse(ReadFileText(path), nullptr, /*allow_exceptions=*/false);
    if (!root.is_object()) return InputKind::kUnknown;
    if (root.contains("format")) return InputKind::kModelFile;
    if (root.contains("samples")) return InputKind::kDataset;
  } catch (const std::exception&) {
    // Unreadable: nothing to tell.
  }
  return InputKind::kUnknown;
}

const Sample* FindSample(const Dataset& dataset, double x) {
  for (const auto given : {false, true}) {
    for (const Sample& s : dataset.samples) {
      if (std::abs((given ? s.x_given : s.x_atomic) - x) <= kSameComposition) return &s;
    }
  }
  return nullptr;
}

const Sample* FindSampleByFile(const Dataset& dataset, const std::string& file) {
  if (file.empty()) return nullptr;
  for (const Sample& s : dataset.samples) {
    if (s.file == file || s.path == file) return &s;
  }
  const Sample* found = nullptr;
  for (const Sample& s : dataset.samples) {
    const std::string written = s.columns.n.empty() ? s.file : s.file.substr(0, s.file.rfind(" ("));
    const bool match = written == file || fs::path(s.path).filename().string() == file ||
                       (!s.k_path.empty() && fs::path(s.k_path).filename().string() == file);
    if (!match) continue;
    if (found != nullptr) return nullptr;  // ambiguous
    found = &s;
  }
  return found;
}

std::vector<const Sample*> SamplesAtComposition(const Dataset& dataset, double x_atomic) {
  std::vector<const Sample*> found;
  for (const Sample& s : dataset.samples) {
    if (std::abs(s.x_atomic - x_atomic) <= kSameComposition) found.push_back(&s);
  }
  return found;
}

NkSpectrum MeanSpectrum(const std::vector<const Sample*>& replicates) {
  if (replicates.empty()) Fail("the mean of no spectrum");
  if (replicates.size() == 1) return replicates.front()->nk;
  double lo = -HUGE_VAL, hi = HUGE_VAL;
  std::string names;
  for (const Sample* s : replicates) {
    lo = std::max(lo, s->nk.lambda_min_nm());
    hi = std::min(hi, s->nk.lambda_max_nm());
    names += (names.empty() ? "" : ", ") + s->file;
  }
  if (!(lo < hi)) Fail("replicates " + names + " share no wavelength range");
  std::vector<double> grid;
  for (const Sample* s : replicates) {
    for (double l : s->nk.lambda_nm) {
      if (l >= lo && l <= hi) grid.push_back(l);
    }
  }
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
  NkSpectrum mean;
  mean.source = "mean of " + names;
  mean.lambda_nm = grid;
  for (double l : grid) {
    Complex<double> eps{0, 0};
    for (const Sample* s : replicates) {
      const std::complex<double> nk = NkAt(s->nk, l);
      const Complex<double> e = PermittivityFromIndex(Complex<double>{nk.real(), nk.imag()});
      eps.re += e.re / replicates.size();
      eps.im += e.im / replicates.size();
    }
    const Complex<double> nk = IndexFromPermittivity(eps);
    mean.n.push_back(nk.re);
    mean.k.push_back(nk.im);
  }
  return mean;
}

std::vector<double> DistinctCompositions(const Dataset& dataset) {
  std::vector<double> xs;
  for (const Sample& s : dataset.samples) xs.push_back(s.x_atomic);
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  return xs;
}

Dataset KeepSamples(const Dataset& dataset, const std::function<bool(const Sample&)>& keep) {
  // Everything but the samples copied, then the samples kept (not all copied, then cut).
  Dataset result{dataset.manifest_path,
                 dataset.name,
                 dataset.system,
                 dataset.composition,
                 {},
                 dataset.excluded,
                 dataset.warnings,
                 dataset.precision_n,
                 dataset.precision_k,
                 dataset.precision_stated};
  for (const Sample& sample : dataset.samples) {
    if (keep(sample)) result.samples.push_back(sample);
  }
  return result;
}

bool AmongCompositions(double x, const std::vector<double>& xs) {
  return std::any_of(xs.begin(), xs.end(),
                     [x](double y) { return std::abs(x - y) <= kSameComposition; });
}

Dataset WithoutSamples(const Dataset& dataset, const std::vector<double>& exclude_x) {
  return KeepSamples(dataset, [&exclude_x](const Sample& sample) {
    return !AmongCompositions(sample.x_atomic, exclude_x);
  });
}

}  // namespace alloycolor
