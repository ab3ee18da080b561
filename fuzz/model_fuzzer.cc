// libFuzzer target: the JSON model file (ReadModelFile, every method), then the model's
// eps and colour over its range, and a colour matched over it (bounded work whatever the
// numbers: a crafted model whose colour swings must not hang `match`; -timeout finds it).
// model.dict holds crafted numbers (denormals, near-poles, huge and tiny widths).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "alloycolor/color/match.h"
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
  try {
    color::MatchOptions options;
    options.scan_points = 201;
    options.with_sigma = false;
    const color::ColourMatcher matcher(fuzz::D65(), *model, options);
    for (const color::Match& m : matcher.Find({60.0, 10.0, 20.0})) {
      fuzz::Require(m.x_atomic >= model->x_min() && m.x_atomic <= model->x_max(),
                    path + ": a match outside the model's range");
    }
  } catch (const Error& e) {
    fuzz::CheckMessage(e, "");
  }
  // What the program writes back must read again.
  try {
    ModelFileText(*model);
  } catch (const Error& e) {
    fuzz::CheckMessage(e, "");
  }
  return 0;
}
