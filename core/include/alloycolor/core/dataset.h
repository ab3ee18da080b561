// A data set: an alloy system and its measured samples, described by a JSON manifest
//   {"system": {"a": "Au", "b": "Ag"}, "composition": "atomic_fraction_a",
//    "samples": [{"x": 0.5, "file": "Rioux-Au50Ag50.yml"}, ...]}
// "composition" is "atomic_fraction_a" or "weight_fraction_a"; "file" is relative to the
// manifest's folder or absolute. Optional: "name", "source", "notes", and
//  - "elements": {"Pd": {"valence": 0.36, "density_g_cm3": 12.0, "atomic_mass": 106.42}}
//    overrides the element table (composition.h) for the system's elements, any subset of
//    the three keys, each a positive number;
//  - per sample, "columns": ["n6", "k6"] (header names or 1-based column numbers) chooses
//    the sample's columns in a delimited file holding several (io.h);
//  - per sample, "n_file" and "k_file" instead of "file": refractiveindex.info files
//    holding `tabulated n` and `tabulated k` alone, paired (ReadNkPair);
//  - per sample, "exclude": "reason" keeps a file listed but set aside: it is read and
//    checked like the others, kept in Dataset::excluded with its reason, and no model is
//    fitted to it (a validation report scores it as a held-out sample).
// Unknown keys at the top level and in samples are warnings; in "elements", errors.
// Replicates, distinct files at the same x (two films of one alloy), are welcome: each stays
// a sample of its own. The same file (or the same n, k under two names) twice is refused,
// as are two x closer than 1e-6 but not equal.
#ifndef ALLOYCOLOR_CORE_DATASET_H_
#define ALLOYCOLOR_CORE_DATASET_H_

#include <functional>
#include <string>
#include <vector>

#include "alloycolor/core/composition.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/spectrum.h"

namespace alloycolor {

struct Sample {
  double x_atomic;       // atomic fraction of element a
  double x_given;        // as written in the manifest
  std::string file;      // as written in the manifest ("a.csv (columns n6,k6)",
                         // "n.yml + k.yml" for a pair)
  std::string path;      // resolved path (of the n file for a pair)
  std::string k_path;    // resolved path of the k file of a pair; empty otherwise
  NkColumns columns;     // the manifest's "columns"; empty when not given
  std::string checksum;  // Fnv1a64Hex of the file's bytes
  NkSpectrum nk;
  std::string excluded;  // the manifest's "exclude": why it is set aside; empty when used
};

struct Dataset {
  std::string manifest_path;
  std::string name;
  AlloySystem system;
  std::string composition;  // "atomic_fraction_a" or "weight_fraction_a"
  // Sorted by x_atomic (stable: the replicates of a composition adjacent, in the
  // manifest's order).
  std::vector<Sample> samples;
  // The samples the manifest sets aside ("exclude": "reason"), sorted the same way; never
  // fitted, but scored as held out by a validation report.
  std::vector<Sample> excluded;
  std::vector<std::string> warnings;
  // The manifest's "precision": one standard deviation of a measured n and of a measured k
  // as the user's instrument states it (absolute; a value not given is 0). Where the
  // manifest states none, the error bars' floor takes kTypicalPrecisionNk instead; either
  // way, the printed digits' resolution where it is larger.
  double precision_n = 0, precision_k = 0;
  bool precision_stated = false;
};

// Compositions (atomic fractions) this close are one: a sample's replicates.
inline constexpr double kSameComposition = 1e-9;

// Whether x is one of xs (within kSameComposition).
bool AmongCompositions(double x, const std::vector<double>& xs);

// One standard deviation of a measured n and k where the manifest states no precision:
// what spectroscopic ellipsometry of metal films typically reproduces in the visible
// (about 0.01 in n and in k between repeated measurements and careful fits), so that no
// error bar claims more than a measurement can tell (docs/data.md).
inline constexpr double kTypicalPrecisionNk = 0.01;

// Accepts a folder holding dataset.json or the manifest file itself.
Dataset LoadDataset(const std::string& dir_or_manifest);

// What a path given as a data set or a model holds, told from its name and contents (for
// a message that says what was given instead): a data set (a folder holding dataset.json,
// or a JSON object with "samples" and no "format"), a model file (a JSON object with
// "format"), one sample's optical constants (a .yml, .yaml, .csv, .txt, .dat or .tsv
// file), or none of these. Never throws.
enum class InputKind { kUnknown, kDataset, kModelFile, kNkFile };
InputKind GuessInputKind(const std::string& path);

// The sample at composition x: the one whose atomic fraction is x (within 1e-9) or,
// failing that, whose number in the manifest is (a weight fraction in a weight-fraction
// manifest); the first of its replicates; null when there is none.
const Sample* FindSample(const Dataset& dataset, double x);

// The sample whose file is `file`: as written in the manifest (Sample::file, or its "file"
// alone when columns were chosen), its resolved path, or its file name when that names
// one sample only; null when none (or several) match.
const Sample* FindSampleByFile(const Dataset& dataset, const std::string& file);

// The data set with the samples `keep` accepts alone, in their order (all else as it is).
Dataset KeepSamples(const Dataset& dataset, const std::function<bool(const Sample&)>& keep);

// The samples whose x_atomic is not within 1e-9 of any of exclude_x (atomic fractions).
Dataset WithoutSamples(const Dataset& dataset, const std::vector<double>& exclude_x);

// The samples' compositions (atomic fraction), each once, increasing: one per group of
// replicates.
std::vector<double> DistinctCompositions(const Dataset& dataset);

// The samples at composition x_atomic (within 1e-9): its replicates, in the data set's
// order; empty when there is none.
std::vector<const Sample*> SamplesAtComposition(const Dataset& dataset, double x_atomic);

// The replicates' mean: eps = N^2 (eq. 9, 10) of each, interpolated linearly in n, k onto
// the union of their wavelengths inside the range all of them cover, averaged, and turned
// back into n, k >= 0 (eq. 13, 14). One spectrum is returned unchanged. The source names
// every replicate ("mean of a.csv, b.csv"). Throws Error when there is none or they
// share no wavelength range.
NkSpectrum MeanSpectrum(const std::vector<const Sample*>& replicates);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_DATASET_H_
