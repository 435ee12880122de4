#include "io/llff.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "io/image_size.h"

namespace isegman {

namespace fs = std::filesystem;

namespace {

bool is_image_file(const fs::path& p) {
  std::string ext = p.extension().string();
  for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

std::vector<std::string> list_images(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec) && is_image_file(it->path())) out.push_back(it->path().string());
  std::sort(out.begin(), out.end());
  return out;
}

// images/ beside the file, else images_N with the smallest N.
fs::path find_images_dir(const fs::path& base) {
  std::error_code ec;
  if (fs::is_directory(base / "images", ec)) return base / "images";
  fs::path best;
  long best_n = std::numeric_limits<long>::max();
  for (fs::directory_iterator it(base, ec), end; !ec && it != end; it.increment(ec)) {
    std::string n = it->path().filename().string();
    if (n.rfind("images_", 0) != 0 || !it->is_directory(ec)) continue;
    std::string digits = n.substr(7);
    if (digits.empty() || digits.size() > 6 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    long f = std::stol(digits);
    if (f < best_n) {
      best_n = f;
      best = it->path();
    }
  }
  return best;
}

int integral(double v, const std::string& src, size_t row, const char* what) {
  if (!std::isfinite(v) || v < 1 || v > 65536 || std::fabs(v - std::round(v)) > 1e-6)
    throw Error(src, "row " + std::to_string(row) + ": " + what + " " + std::to_string(v) +
                         " is not a positive whole number of pixels");
  return int(std::lround(v));
}

}  // namespace

std::vector<Camera> llff_to_cameras(const NpyArray& a, const std::string& src,
                                    const std::vector<std::string>& image_paths,
                                    std::vector<std::pair<double, double>>* bounds) {
  if (a.dtype != "<f8" && a.dtype != "<f4") throw Error(src, "LLFF poses must be float32 or float64");
  if (a.shape.size() != 2 || a.shape[1] != 17) {
    std::string s = "(";
    for (size_t i = 0; i < a.shape.size(); ++i) s += (i ? ", " : "") + std::to_string(a.shape[i]);
    throw Error(src, "expected an N x 17 array (LLFF poses_bounds), found shape " + s + ")");
  }
  const size_t n = a.shape[0];
  if (n == 0) throw Error(src, "contains no cameras");
  const bool named = image_paths.size() == n;
  std::vector<Camera> out;
  if (bounds) bounds->clear();
  for (size_t i = 0; i < n; ++i) {
    const double* row = a.data.data() + 17 * i;
    for (int k = 0; k < 17; ++k)
      if (!std::isfinite(row[k])) throw Error(src, "row " + std::to_string(i) + " holds a non-finite value");
    auto at = [&](int r, int c) { return row[5 * r + c]; };
    Vec3 down{at(0, 0), at(1, 0), at(2, 0)};
    Vec3 right{at(0, 1), at(1, 1), at(2, 1)};
    Vec3 back{at(0, 2), at(1, 2), at(2, 2)};
    Vec3 centre{at(0, 3), at(1, 3), at(2, 3)};
    Camera c = Camera::from_center_rotation(centre, Mat3::from_cols(right, down, -back));
    c.id = int(i);
    char num[32];
    std::snprintf(num, sizeof(num), "%03zu", i);
    c.name = named ? fs::path(image_paths[i]).stem().string() : std::string(num);
    if (named) c.image_path = image_paths[i];
    c.height = integral(at(0, 4), src, i, "image height");
    c.width = integral(at(1, 4), src, i, "image width");
    c.fx = c.fy = at(2, 4);
    c.cx = 0.5 * c.width;
    c.cy = 0.5 * c.height;
    double near_b = row[15], far_b = row[16];
    if (near_b < 0 || far_b < near_b)
      throw Error(src, "row " + std::to_string(i) + " has invalid depth bounds near " + std::to_string(near_b) +
                           ", far " + std::to_string(far_b));
    c.validate(src + " row " + std::to_string(i));
    if (bounds) bounds->emplace_back(near_b, far_b);
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<Camera> read_llff(const std::string& path, const LlffOptions& opt, std::vector<std::string>* notes,
                              std::vector<std::pair<double, double>>* bounds) {
  NpyArray a = read_npy(path);
  fs::path images_dir = opt.images_dir.empty() ? find_images_dir(fs::path(path).parent_path()) : fs::path(opt.images_dir);
  std::vector<std::string> images;
  if (!images_dir.empty()) {
    images = list_images(images_dir);
    if (!opt.images_dir.empty() && images.empty())
      throw Error(opt.images_dir, "holds no PNG or JPEG images");
  }
  const size_t n = a.shape.size() == 2 ? a.shape[0] : 0;
  if (!images.empty() && images.size() != n && notes)
    notes->push_back(images_dir.string() + " holds " + std::to_string(images.size()) + " images for " +
                     std::to_string(n) + " poses: cameras are named 000, 001, ...");
  std::vector<Camera> cams = llff_to_cameras(a, path, images.size() == n ? images : std::vector<std::string>{}, bounds);

  if (opt.target_width > 0) {
    for (Camera& c : cams) {
      int h = int(std::lround(double(c.height) * opt.target_width / c.width));
      c = c.resized(opt.target_width, std::max(h, 1));
    }
  } else if (opt.size_from_images && images.size() == n) {
    int w = 0, h = 0;
    const Camera& c0 = cams.front();
    if (read_image_size(images.front(), w, h) && (w != c0.width || h != c0.height)) {
      double sx = double(w) / c0.width, sy = double(h) / c0.height;
      if (std::fabs(sx - sy) <= 0.01 * std::max(sx, sy)) {
        for (Camera& c : cams) c = c.resized(int(std::lround(c.width * sx)), int(std::lround(c.height * sy)));
        if (notes)
          notes->push_back("poses are for " + std::to_string(c0.width) + "x" + std::to_string(c0.height) +
                           " photos; cameras scaled to the " + std::to_string(w) + "x" + std::to_string(h) +
                           " images in " + images_dir.string());
      } else if (notes) {
        notes->push_back(images.front() + " is " + std::to_string(w) + "x" + std::to_string(h) +
                         ", not the " + std::to_string(c0.width) + "x" + std::to_string(c0.height) +
                         " of the poses, and has another aspect ratio: sizes kept from the poses");
      }
    }
  }
  if (notes && bounds && !bounds->empty()) {
    double lo = bounds->front().first, hi = bounds->front().second;
    for (auto& b : *bounds) {
      lo = std::min(lo, b.first);
      hi = std::max(hi, b.second);
    }
    notes->push_back("scene depth bounds " + std::to_string(lo) + " to " + std::to_string(hi));
  }
  return cams;
}

std::vector<double> cameras_to_llff(const std::vector<Camera>& cameras, double near_bound, double far_bound) {
  std::vector<double> rows;
  for (const Camera& c : cameras) {
    const std::string who = "camera '" + c.name + "'";
    if (std::fabs(c.fx - c.fy) > 1e-9 * c.fx)
      throw Error("LLFF poses_bounds", who + " has fx != fy, which LLFF cannot store");
    if (std::fabs(c.cx - 0.5 * c.width) > 1e-9 || std::fabs(c.cy - 0.5 * c.height) > 1e-9)
      throw Error("LLFF poses_bounds", who + " has an off-centre principal point, which LLFF cannot store");
    Mat3 c2w = c.R.transposed();
    Vec3 right = c2w.col(0), down = c2w.col(1), back = -c2w.col(2), centre = c.center();
    Vec3 cols[5] = {down, right, back, centre, Vec3(c.height, c.width, c.fx)};
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 5; ++k) rows.push_back(cols[k][r]);
    rows.push_back(near_bound);
    rows.push_back(far_bound);
  }
  return rows;
}

void write_llff(const std::string& path, const std::vector<Camera>& cameras, double near_bound, double far_bound) {
  write_npy(path, {cameras.size(), 17}, cameras_to_llff(cameras, near_bound, far_bound));
}

}  // namespace isegman
