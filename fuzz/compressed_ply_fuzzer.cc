// libFuzzer harness: SuperSplat's compressed PLY reader on arbitrary bytes. Every input
// must either decode into a consistent scene or throw isegman::Error.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "io/compressed_ply.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    isegman::GaussianScene scene = isegman::parse_compressed_ply(data, size, "fuzz.compressed.ply");
    scene.validate("fuzz.compressed.ply");
  } catch (const isegman::Error&) {
  }
  return 0;
}
