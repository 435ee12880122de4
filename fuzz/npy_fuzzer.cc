// libFuzzer harness: the .npy parser and the LLFF conversion of what it returns.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "io/llff.h"
#include "io/npy.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    isegman::NpyArray a = isegman::parse_npy(data, size, "fuzz.npy");
    std::vector<std::pair<double, double>> bounds;
    isegman::llff_to_cameras(a, "fuzz.npy", {}, &bounds);
  } catch (const isegman::Error&) {
  }
  return 0;
}
