#include "models/feature_map.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace isegman::models {

FeatureMap::FeatureMap(std::vector<float> chw, int channels, int grid_w, int grid_h, int image_w, int image_h,
                       int resized_w, int resized_h, double cell_px) {
  auto owned = std::make_shared<const std::vector<float>>(std::move(chw));
  const float* data = owned->data();
  const size_t count = owned->size();
  *this = FeatureMap(std::move(owned), data, count, channels, grid_w, grid_h, image_w, image_h, resized_w, resized_h,
                     cell_px);
}

FeatureMap::FeatureMap(std::shared_ptr<const void> owner, const float* chw, size_t count, int channels, int grid_w,
                       int grid_h, int image_w, int image_h, int resized_w, int resized_h, double cell_px)
    : owner_(std::move(owner)), raw_(chw), channels_(channels), grid_w_(grid_w), grid_h_(grid_h), image_w_(image_w),
      image_h_(image_h) {
  if (size_t(channels) * grid_w * grid_h != count || (count > 0 && !chw))
    throw Error("FeatureMap: data size does not match the grid");
  if (image_w <= 0 || image_h <= 0 || resized_w <= 0 || resized_h <= 0 || cell_px <= 0)
    throw Error("FeatureMap: invalid image geometry");
  sx_ = double(resized_w) / image_w / cell_px;
  sy_ = double(resized_h) / image_h / cell_px;
  valid_cols_ = std::min(grid_w, int(std::ceil(resized_w / cell_px - 1e-9)));
  valid_rows_ = std::min(grid_h, int(std::ceil(resized_h / cell_px - 1e-9)));
}

float FeatureMap::inverse_norm(size_t p) const {
  const size_t plane = size_t(grid_w_) * grid_h_;
  double norm = 0;
  for (int c = 0; c < channels_; ++c) norm += double(raw_[c * plane + p]) * raw_[c * plane + p];
  return norm > 0 ? float(1.0 / std::sqrt(norm)) : 0.f;
}

std::vector<float> FeatureMap::cell(int gx, int gy) const {
  const size_t plane = size_t(grid_w_) * grid_h_, p = size_t(gy) * grid_w_ + gx;
  const float inv = inverse_norm(p);
  std::vector<float> out(static_cast<size_t>(channels_));
  for (int c = 0; c < channels_; ++c) out[size_t(c)] = raw_[c * plane + p] * inv;
  return out;
}

void FeatureMap::pixel_to_grid(double px, double py, double& gx, double& gy) const {
  gx = px * sx_;
  gy = py * sy_;
}

void FeatureMap::grid_to_pixel(double gx, double gy, double& px, double& py) const {
  px = gx / sx_;
  py = gy / sy_;
}

void FeatureMap::pixel_to_cell(double px, double py, int& gx, int& gy) const {
  double fx, fy;
  pixel_to_grid(px, py, fx, fy);
  gx = std::clamp(int(std::floor(fx)), 0, std::max(valid_cols_ - 1, 0));
  gy = std::clamp(int(std::floor(fy)), 0, std::max(valid_rows_ - 1, 0));
}

void FeatureMap::cell_centre(int gx, int gy, double& px, double& py) const { grid_to_pixel(gx + 0.5, gy + 0.5, px, py); }

std::vector<float> FeatureMap::sample(double px, double py) const {
  double fx, fy;
  pixel_to_grid(px, py, fx, fy);
  // Cell centres sit at integer + 0.5 in grid coordinates.
  double ux = std::clamp(fx - 0.5, 0.0, double(valid_cols_ - 1));
  double uy = std::clamp(fy - 0.5, 0.0, double(valid_rows_ - 1));
  int x0 = int(std::floor(ux)), y0 = int(std::floor(uy));
  int x1 = std::min(x0 + 1, valid_cols_ - 1), y1 = std::min(y0 + 1, valid_rows_ - 1);
  float wx = float(ux - x0), wy = float(uy - y0);
  std::vector<float> f(channels_);
  const std::vector<float> a = cell(x0, y0), b = cell(x1, y0), c = cell(x0, y1), d = cell(x1, y1);
  double norm = 0;
  for (int k = 0; k < channels_; ++k) {
    f[k] = (1 - wy) * ((1 - wx) * a[k] + wx * b[k]) + wy * ((1 - wx) * c[k] + wx * d[k]);
    norm += double(f[k]) * f[k];
  }
  if (norm > 0) {
    float inv = float(1.0 / std::sqrt(norm));
    for (float& v : f) v *= inv;
  }
  return f;
}

float FeatureMap::affinity(const std::vector<float>& unit, int gx, int gy) const {
  const size_t plane = size_t(grid_w_) * grid_h_, p = size_t(gy) * grid_w_ + gx;
  const float inv = inverse_norm(p);
  float s = 0;
  for (int k = 0; k < channels_; ++k) s += unit[k] * (raw_[k * plane + p] * inv);
  return s;
}

}  // namespace isegman::models
