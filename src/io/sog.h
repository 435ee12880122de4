// PlayCanvas SOG ("spatially ordered Gaussians", version 2): meta.json plus lossless WebP
// images, either zipped into one .sog file or as a folder holding meta.json.
//   means:  means_l.webp / means_u.webp, low and high bytes of 16-bit fractions of
//           [mins, maxs] of sign(x) ln(|x| + 1) per axis
//   quats:  RGB = the three smaller components of the unit quaternion (w x y z) mapped
//           from [-1/sqrt2, 1/sqrt2] to 0..255, A = 252 + index of the largest
//   scales: RGB = indices into a 256-entry codebook of log-scales
//   sh0:    RGB = indices into a codebook of f_dc values, A = sigmoid(opacity) x 255
//   shN:    labels (16-bit palette index in RG) -> centroids image (64 palette entries
//           per row, one pixel per coefficient, RGB = codebook indices)
// Pixel i is row-major in every image. Coordinates are those of the INRIA PLY.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.h"

namespace isegman {

// True when `path` is a folder with SOG's meta.json (not a trained scene's folder with notes
// of its own), or the bytes are a zip archive.
bool is_sog_dir(const std::string& path);
bool looks_like_zip(const uint8_t* data, size_t size);

// A zipped .sog in memory; `source` names it in errors.
GaussianScene parse_sog_zip(const uint8_t* data, size_t size, const std::string& source);
// A folder holding meta.json and its images.
GaussianScene read_sog_dir(const std::string& dir);

// Encodes as a zipped .sog (version 2): 256-entry codebooks by 1-D k-means, WebP lossless
// images (exact RGB under transparent pixels). SH bands: one palette entry per Gaussian
// up to 65536 Gaussians (only the codebook quantises them); beyond, a 65536-entry k-means
// palette whose nearest-centroid search is limited to centroids adjacent along the SH
// vectors' principal direction. `notes` says which.
std::vector<uint8_t> serialize_sog(const GaussianScene& scene, std::vector<std::string>* notes = nullptr);

}  // namespace isegman
