// libFuzzer harness: format detection plus the chosen reader (PLY, compressed PLY, .splat,
// .spz, .sog), as load_gaussians runs them. Must decode or throw isegman::Error.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "io/gaussian_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const isegman::SplatFormat f = isegman::detect_splat_format(data, size, "fuzz");
    std::vector<std::string> notes;
    isegman::GaussianScene scene = isegman::parse_gaussians(data, size, f, "fuzz", &notes);
    scene.validate("fuzz");
  } catch (const isegman::Error&) {
  }
  return 0;
}
