// A data set: an alloy system and its measured samples, described by a JSON manifest
//   {"system": {"a": "Au", "b": "Ag"}, "composition": "atomic_fraction_a",
//    "samples": [{"x": 0.5, "file": "Rioux-Au50Ag50.yml"}, ...]}
// "composition" is "atomic_fraction_a" or "weight_fraction_a"; "file" is relative to the
// manifest's folder or absolute. Optional: "name", "source", "notes".
#ifndef ALLOYCOLOR_CORE_DATASET_H_
#define ALLOYCOLOR_CORE_DATASET_H_

#include <string>
#include <vector>

#include "alloycolor/core/composition.h"
#include "alloycolor/core/spectrum.h"

namespace alloycolor {

struct Sample {
  double x_atomic;      // atomic fraction of element a
  double x_given;       // as written in the manifest
  std::string file;     // as written in the manifest
  std::string path;     // resolved path
  std::string checksum; // Fnv1a64Hex of the file's bytes
  NkSpectrum nk;
};

struct Dataset {
  std::string manifest_path;
  std::string name;
  AlloySystem system;
  std::string composition;       // "atomic_fraction_a" or "weight_fraction_a"
  std::vector<Sample> samples;   // sorted by x_atomic, at most one per composition
  std::vector<std::string> warnings;
};

// Accepts a folder holding dataset.json or the manifest file itself.
Dataset LoadDataset(const std::string& dir_or_manifest);

// The samples whose x_atomic is not within 1e-9 of any of exclude_x (atomic fractions).
Dataset WithoutSamples(const Dataset& dataset, const std::vector<double>& exclude_x);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_DATASET_H_
