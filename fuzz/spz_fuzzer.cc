// libFuzzer harness: the .spz reader (gzip v1-3, zstd v4) on arbitrary bytes. Every input
// must either decode into a consistent scene or throw isegman::Error.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "io/spz.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    std::vector<std::string> notes;
    isegman::GaussianScene scene = isegman::parse_spz(data, size, "fuzz.spz", &notes);
    scene.validate("fuzz.spz");
  } catch (const isegman::Error&) {
  }
  return 0;
}
