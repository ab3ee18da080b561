#include "alloycolor/core/dataset.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr const char* kAtomic = "atomic_fraction_a";
constexpr const char* kWeight = "weight_fraction_a";
constexpr double kSameComposition = 1e-9;

[[noreturn]] void Fail(std::string message) {
  for (char& c : message) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  throw Error(message);
}

std::string Number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.10g", value);
  return buffer;
}

std::string Quote(const std::string& text) {
  constexpr std::size_t kMax = 60;
  if (text.size() <= kMax) return "'" + text + "'";
  return "'" + text.substr(0, kMax) + "...'";
}

// 1-based line of a byte offset of text.
int LineOfByte(const std::string& text, std::size_t byte) {
  byte = std::min(byte, text.size());
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + byte, '\n'));
}

Json ParseManifest(const std::string& manifest, const std::string& text) {
  try {
    return Json::parse(text);
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
      warnings->push_back(manifest + ": " + where + "unknown key " + Quote(it.key()) + " ignored");
    }
  }
}

bool SameFile(const fs::path& a, const fs::path& b) {
  std::error_code error;
  const bool same = fs::equivalent(a, b, error);
  if (!error) return same;
  return fs::weakly_canonical(a, error) == fs::weakly_canonical(b, error) && !error;
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
  WarnUnknownKeys(manifest, "", root,
                  {"name", "system", "composition", "samples", "source", "notes"},
                  &dataset.warnings);

  if (!root.contains("system") || !root.at("system").is_object()) {
    Fail(manifest + ": system: missing or not an object like {\"a\": \"Au\", \"b\": \"Ag\"}");
  }
  const Json& system = root.at("system");
  dataset.system.a = ElementField(manifest, system, "a");
  dataset.system.b = ElementField(manifest, system, "b");
  if (std::string(dataset.system.a.symbol) == dataset.system.b.symbol) {
    Fail(manifest + ": system: a and b are both '" + dataset.system.a.symbol + "'");
  }

  for (const char* key : {"name", "source", "notes"}) {
    if (root.contains(key) && !root.at(key).is_string()) {
      Fail(manifest + ": " + key + ": not a string");
    }
  }
  dataset.name = root.contains("name") ? root.at("name").get<std::string>() : dataset.system.Name();

  if (!root.contains("composition")) {
    Fail(manifest + ": composition: missing; write \"" + kAtomic + "\" or \"" + kWeight + "\"");
  }
  const Json& composition = root.at("composition");
  if (!composition.is_string() ||
      (composition.get<std::string>() != kAtomic && composition.get<std::string>() != kWeight)) {
    Fail(manifest + ": composition: " + Quote(composition.dump()) + " is neither \"" + kAtomic +
         "\" nor \"" + kWeight + "\"");
  }
  dataset.composition = composition.get<std::string>();
  const bool by_weight = dataset.composition == kWeight;

  if (!root.contains("samples") || !root.at("samples").is_array() || root.at("samples").empty()) {
    Fail(manifest + ": samples: missing or not a non-empty list");
  }
  const fs::path folder = manifest_path.parent_path();
  const Json& samples = root.at("samples");
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const std::string where = "samples[" + std::to_string(i) + "]";
    const Json& entry = samples.at(i);
    if (!entry.is_object()) Fail(manifest + ": " + where + ": not an object");
    WarnUnknownKeys(manifest, where + ": ", entry, {"x", "file"}, &dataset.warnings);
    if (!entry.contains("file") || !entry.at("file").is_string() ||
        entry.at("file").get<std::string>().empty()) {
      Fail(manifest + ": " + where + ".file: missing or not a file name");
    }
    Sample sample;
    sample.file = entry.at("file").get<std::string>();
    const std::string named = manifest + ": " + where + " (" + Quote(sample.file) + ")";
    if (!entry.contains("x") || !entry.at("x").is_number()) {
      Fail(named + ": x: missing or not a number");
    }
    sample.x_given = entry.at("x").get<double>();
    if (!(sample.x_given >= 0 && sample.x_given <= 1)) {
      Fail(named + ": x = " + Number(sample.x_given) + " lies outside [0, 1]");
    }
    sample.x_atomic =
        by_weight ? AtomicFromWeightFraction(sample.x_given, dataset.system) : sample.x_given;
    const fs::path file(sample.file);
    sample.path = (file.is_absolute() ? file : folder / file).lexically_normal().string();
    if (sample.path.empty()) sample.path = sample.file;
    if (SameFile(sample.path, manifest_path)) {
      Fail(named + ": the sample file is the manifest itself");
    }
    dataset.samples.push_back(std::move(sample));
  }

  std::stable_sort(dataset.samples.begin(), dataset.samples.end(),
                   [](const Sample& s, const Sample& t) { return s.x_atomic < t.x_atomic; });
  for (std::size_t i = 1; i < dataset.samples.size(); ++i) {
    const Sample& s = dataset.samples[i - 1];
    const Sample& t = dataset.samples[i];
    if (t.x_atomic - s.x_atomic <= kSameComposition) {
      Fail(manifest + ": samples " + Quote(s.file) + " and " + Quote(t.file) +
           " have the same composition, x = " + Number(s.x_given));
    }
  }

  for (Sample& sample : dataset.samples) {
    std::vector<std::string> warnings;
    sample.nk = ReadNkFile(sample.path, &warnings);
    sample.checksum = Fnv1a64Hex(ReadFileText(sample.path));
    // The readers' warnings already begin with the file (and line).
    for (std::string& warning : warnings) dataset.warnings.push_back(std::move(warning));
  }
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

Dataset WithoutSamples(const Dataset& dataset, const std::vector<double>& exclude_x) {
  Dataset result = dataset;
  result.samples.clear();
  for (const Sample& sample : dataset.samples) {
    const bool excluded = std::any_of(exclude_x.begin(), exclude_x.end(), [&sample](double x) {
      return std::abs(sample.x_atomic - x) <= kSameComposition;
    });
    if (!excluded) result.samples.push_back(sample);
  }
  return result;
}

}  // namespace alloycolor
