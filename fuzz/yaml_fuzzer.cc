// libFuzzer target: the refractiveindex.info YAML reader (ReadRefractiveIndexYaml), then
// the colour chain on whatever it accepts.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "alloycolor/core/io.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return alloycolor::fuzz::FuzzSpectrumReader(
      data, size, "input.yml", [](const std::string& path, std::vector<std::string>* warnings) {
        return alloycolor::ReadRefractiveIndexYaml(path, warnings);
      });
}
