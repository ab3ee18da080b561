// libFuzzer target: the CSV reader (ReadNkCsv, header lambda_nm,n,k), then the colour
// chain on whatever it accepts.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "alloycolor/core/io.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return alloycolor::fuzz::FuzzSpectrumReader(
      data, size, "input.csv", [](const std::string& path, std::vector<std::string>* warnings) {
        return alloycolor::ReadNkCsv(path, warnings);
      });
}
