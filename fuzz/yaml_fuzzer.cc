// libFuzzer target: the refractiveindex.info YAML reader (ReadRefractiveIndexYaml), then
// the colour chain on whatever it accepts.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "alloycolor/core/io.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace alloycolor;
  const std::string path = fuzz::WriteInput(data, size, "input.yml");
  try {
    std::vector<std::string> warnings;
    const NkSpectrum nk = ReadRefractiveIndexYaml(path, &warnings);
    fuzz::Require(nk.source == path, "spectrum source is not the file");
    for (const std::string& w : warnings) {
      fuzz::Require(w.find('\n') == std::string::npos, "warning spans lines: " + w);
    }
    fuzz::CheckSpectrum(nk);
  } catch (const Error& e) {
    fuzz::CheckMessage(e, path);
  }
  return 0;
}
