// libFuzzer target: the data-set manifest (LoadDataset), in a folder that also holds the
// small sample files of tests/fuzz-regressions/manifest-files/ (a manifest can name them),
// then the paper and eps-linear models built from whatever it accepts.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "alloycolor/core/dataset.h"
#include "alloycolor/model/sample_models.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  namespace fs = std::filesystem;
  const fs::path files = fs::path(ALLOYCOLOR_TESTS_DIR) / "fuzz-regressions" / "manifest-files";
  for (const auto& entry : fs::directory_iterator(files)) {
    fs::copy_file(entry.path(), fs::path(alloycolor::fuzz::WorkDir()) / entry.path().filename(),
                  fs::copy_options::overwrite_existing);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace alloycolor;
  const std::string path = fuzz::WriteInput(data, size, "dataset.json");
  Dataset dataset;
  try {
    dataset = LoadDataset(path);
  } catch (const Error& e) {
    fuzz::CheckMessage(e, "");
    return 0;
  }
  fuzz::Require(!dataset.samples.empty(), "data set without samples accepted");
  for (const Sample& s : dataset.samples) {
    fuzz::Require(s.x_atomic >= 0 && s.x_atomic <= 1, "composition outside [0, 1] accepted");
    fuzz::CheckSpectrum(s.nk);
  }
  for (auto kind : {SampleModel::Kind::kPaper, SampleModel::Kind::kEpsLinear}) {
    try {
      const SampleModel model(kind, dataset);
      fuzz::CheckModel(model, path);
    } catch (const Error& e) {
      fuzz::CheckMessage(e, "");
    }
  }
  return 0;
}
