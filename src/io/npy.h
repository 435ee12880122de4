// NumPy .npy arrays (format versions 1.0, 2.0 and 3.0) of little-endian float64 or
// float32 in C order — what LLFF's poses_bounds.npy and similar files hold. Anything else
// (other dtypes, big-endian, Fortran order, object arrays) is refused with a clear error.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace isegman {

struct NpyArray {
  std::vector<size_t> shape;
  std::vector<double> data;  // row-major (C order), converted to double
  std::string dtype;         // as stored: "<f8" or "<f4"
  size_t rows() const { return shape.empty() ? 1 : shape[0]; }
};

// True when the bytes start with the .npy magic string.
bool is_npy(const uint8_t* data, size_t size);
NpyArray parse_npy(const uint8_t* data, size_t size, const std::string& source);
NpyArray read_npy(const std::string& path);
// Writes a float64 array ("<f8", version 1.0 header padded to 64 bytes).
std::vector<uint8_t> serialize_npy(const std::vector<size_t>& shape, const std::vector<double>& data);
void write_npy(const std::string& path, const std::vector<size_t>& shape, const std::vector<double>& data);

}  // namespace isegman
