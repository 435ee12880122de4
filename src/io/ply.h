// INRIA-layout Gaussian PLY files: read binary (little/big endian) and ASCII, write
// binary little-endian. SH degree comes from the number of f_rest_* properties.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/scene.h"

namespace isegman {

struct PlyReadReport {
  std::vector<std::string> notes;  // what was tolerated or dropped, for the user
};

// Parses a PLY from memory; `source` names the file in error messages. Binary Gaussian
// records are parsed in parallel; `parsed` (optional) hears of each byte range that will
// not be read again (read_ply drops those pages from memory).
GaussianScene parse_ply(const uint8_t* data, size_t size, const std::string& source,
                        PlyReadReport* report = nullptr,
                        const std::function<void(size_t offset, size_t length)>& parsed = {});
GaussianScene read_ply(const std::string& path, PlyReadReport* report = nullptr);

// Serialises in the INRIA order (x y z nx ny nz f_dc_* f_rest_* opacity scale_* rot_*,
// then extra properties). Normals are always written (zeros when the scene has none)
// because some viewers read a fixed record layout.
std::vector<uint8_t> serialize_ply(const GaussianScene& scene);
// Validates (refuses empty or non-finite scenes) and writes atomically.
void write_ply(const std::string& path, const GaussianScene& scene);

}  // namespace isegman
