// libFuzzer harness: the zipped .sog reader (zip, meta.json, WebP images) on arbitrary
// bytes. Every input must either decode into a consistent scene or throw isegman::Error.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "io/sog.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    isegman::GaussianScene scene = isegman::parse_sog_zip(data, size, "fuzz.sog");
    scene.validate("fuzz.sog");
  } catch (const isegman::Error&) {
  }
  return 0;
}
