// A dense feature grid over an image, L2-normalised per cell, with the exact mapping between
// image pixels and grid cells. For SAM the grid is the image encoder's 256 x 64 x 64
// embedding over the 1024 x 1024 model frame, in which the image was resized (longest side
// to 1024) and zero-padded at the bottom/right; cells beyond the resized image are padding.
//
// Coordinates here are continuous: image pixel (i, j) covers [i, i+1) x [j, j+1), its centre
// is (i + 0.5, j + 0.5); likewise grid cell (gx, gy) spans [gx, gx+1) x [gy, gy+1).
//
// Cells are normalised when read, not when the map is built: an epipolar search reads the
// ~100 cells along one line of 4096, so a map over an embedding costs nothing to build and
// holds no copy of it (a normalised copy is 4 MB per view).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace isegman::models {

class FeatureMap {
 public:
  FeatureMap() = default;
  // `chw` holds channels x grid_h x grid_w values (channel-major, as the encoder writes them).
  // The image (image_w x image_h) was scaled by resized_w / image_w horizontally and
  // resized_h / image_h vertically into a frame of grid_w * cell_px pixels.
  FeatureMap(std::vector<float> chw, int channels, int grid_w, int grid_h, int image_w, int image_h, int resized_w,
             int resized_h, double cell_px);
  // The same over `count` values at `chw` that `owner` keeps alive (an embedding's tensor).
  FeatureMap(std::shared_ptr<const void> owner, const float* chw, size_t count, int channels, int grid_w, int grid_h,
             int image_w, int image_h, int resized_w, int resized_h, double cell_px);

  bool empty() const { return raw_ == nullptr; }
  int channels() const { return channels_; }
  int grid_width() const { return grid_w_; }
  int grid_height() const { return grid_h_; }
  int image_width() const { return image_w_; }
  int image_height() const { return image_h_; }
  // Number of columns / rows of cells that contain any image content (the rest is padding).
  int valid_columns() const { return valid_cols_; }
  int valid_rows() const { return valid_rows_; }

  // Unit-length feature vector of a cell (channels() floats).
  std::vector<float> cell(int gx, int gy) const;

  // Continuous pixel <-> continuous grid coordinates (accounts for resize and padding).
  void pixel_to_grid(double px, double py, double& gx, double& gy) const;
  void grid_to_pixel(double gx, double gy, double& px, double& py) const;
  // The cell containing a pixel position (clamped to the valid cells).
  void pixel_to_cell(double px, double py, int& gx, int& gy) const;
  // Image position of a cell's centre.
  void cell_centre(int gx, int gy, double& px, double& py) const;

  // Bilinearly interpolated feature at a pixel position (cell centres as samples, clamped
  // to the valid cells), re-normalised to unit length.
  std::vector<float> sample(double px, double py) const;
  // Dot product of a unit vector with a cell's feature (cosine affinity).
  float affinity(const std::vector<float>& unit, int gx, int gy) const;

 private:
  float inverse_norm(size_t cell) const;

  std::shared_ptr<const void> owner_;
  const float* raw_ = nullptr;  // channels x grid_h x grid_w, as the encoder wrote them
  int channels_ = 0, grid_w_ = 0, grid_h_ = 0, image_w_ = 0, image_h_ = 0;
  int valid_cols_ = 0, valid_rows_ = 0;
  double sx_ = 1, sy_ = 1;  // grid cells per image pixel
};

}  // namespace isegman::models
