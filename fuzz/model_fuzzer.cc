// libFuzzer target: the JSON model file (ReadModelFile, every method), then the model's
// eps and colour over its range.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "alloycolor/model/alloy_model.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace alloycolor;
  const std::string path = fuzz::WriteInput(data, size, "model.json");
  std::unique_ptr<AlloyModel> model;
  try {
    model = ReadModelFile(path);
  } catch (const Error& e) {
    fuzz::CheckMessage(e, path);
    return 0;
  }
  fuzz::CheckModel(*model, path);
  // What the program writes back must read again.
  try {
    ModelFileText(*model);
  } catch (const Error& e) {
    fuzz::CheckMessage(e, "");
  }
  return 0;
}
