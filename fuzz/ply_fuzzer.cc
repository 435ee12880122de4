// libFuzzer harness: the INRIA Gaussian PLY parser on arbitrary bytes. Every input must
// either parse into a consistent scene or throw isegman::Error.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "io/ply.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    isegman::PlyReadReport report;
    isegman::GaussianScene scene = isegman::parse_ply(data, size, "fuzz.ply", &report);
    scene.validate("fuzz.ply");
  } catch (const isegman::Error&) {
  }
  return 0;
}
