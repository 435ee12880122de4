#include "io/colmap.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "core/error.h"
#include "io/atomic_file.h"

namespace isegman {

namespace fs = std::filesystem;

namespace {

// COLMAP's model table (src/colmap/sensor/models.h): id, name, parameter count.
const ColmapCameraModel kModels[] = {
    {0, "SIMPLE_PINHOLE", 3, true, false},
    {1, "PINHOLE", 4, false, false},
    {2, "SIMPLE_RADIAL", 4, true, false},
    {3, "RADIAL", 5, true, false},
    {4, "OPENCV", 8, false, false},
    {5, "OPENCV_FISHEYE", 8, false, true},
    {6, "FULL_OPENCV", 12, false, false},
    {7, "FOV", 5, false, true},
    {8, "SIMPLE_RADIAL_FISHEYE", 4, true, true},
    {9, "RADIAL_FISHEYE", 5, true, true},
    {10, "THIN_PRISM_FISHEYE", 12, false, true},
    {11, "RAD_TAN_THIN_PRISM_FISHEYE", 16, false, true},
};

// Bounds-checked little-endian reader over a byte buffer.
class Reader {
 public:
  Reader(const uint8_t* data, size_t size, const std::string& src) : p_(data), n_(size), src_(src) {}
  size_t left() const { return n_ - pos_; }
  size_t pos() const { return pos_; }
  void need(size_t bytes, const char* what) const {
    if (bytes > left())
      throw Error(src_, std::string("truncated: ") + what + " at byte " + std::to_string(pos_) +
                            " needs " + std::to_string(bytes) + " bytes, " + std::to_string(left()) +
                            " left");
  }
  template <typename T>
  T get(const char* what) {
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, p_ + pos_, sizeof(T));  // the host is little-endian (x86-64, arm64)
    pos_ += sizeof(T);
    return v;
  }
  double get_finite(const char* what, const std::string& whose) {
    double v = get<double>(what);
    if (!std::isfinite(v)) throw Error(src_, whose + " has a non-finite " + what);
    return v;
  }
  std::string get_cstring(const char* what, size_t max_len) {
    const uint8_t* start = p_ + pos_;
    size_t limit = std::min(left(), max_len + 1);
    const void* nul = std::memchr(start, 0, limit);
    if (!nul) {
      if (limit == left()) need(left() + 1, what);  // truncated inside the string
      throw Error(src_, std::string(what) + " at byte " + std::to_string(pos_) + " is longer than " +
                            std::to_string(max_len) + " bytes");
    }
    size_t len = static_cast<const uint8_t*>(nul) - start;
    std::string s(reinterpret_cast<const char*>(start), len);
    pos_ += len + 1;
    return s;
  }
  void skip(size_t bytes, const char* what) {
    need(bytes, what);
    pos_ += bytes;
  }

 private:
  const uint8_t* p_;
  size_t n_;
  size_t pos_ = 0;
  const std::string& src_;
};

template <typename T>
void put(std::vector<uint8_t>& out, T v) {
  uint8_t b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.insert(out.end(), b, b + sizeof(T));
}

std::string fmt(double v) {
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

constexpr uint64_t kMaxImageSide = 1u << 20;  // sanity limit before the int conversion
constexpr size_t kMaxNameLength = 4096;

void check_camera(const ColmapCamera& c, const std::string& src) {
  const std::string who = "camera " + std::to_string(c.camera_id);
  if (c.width == 0 || c.height == 0)
    throw Error(src, who + " has a zero image size " + std::to_string(c.width) + "x" + std::to_string(c.height));
  if (c.width > kMaxImageSide || c.height > kMaxImageSide)
    throw Error(src, who + " has an implausible image size " + std::to_string(c.width) + "x" +
                         std::to_string(c.height));
  for (double p : c.params)
    if (!std::isfinite(p)) throw Error(src, who + " has a non-finite parameter");
}

void check_image(const ColmapImage& im, const std::string& src) {
  const std::string who = "image " + std::to_string(im.image_id) + " ('" + im.name + "')";
  double qn = im.q.norm();
  if (!std::isfinite(qn) || !std::isfinite(im.t.x) || !std::isfinite(im.t.y) || !std::isfinite(im.t.z))
    throw Error(src, who + " has a non-finite pose");
  if (qn < 1e-12) throw Error(src, who + " has a zero rotation quaternion");
  if (im.name.empty()) throw Error(src, who + " has an empty file name");
}

// Splits a line into whitespace-separated tokens.
std::vector<std::string> tokens(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream ss(line);
  std::string tok;
  while (ss >> tok) out.push_back(tok);
  return out;
}

// The characters std::isspace (and so `tokens`) treats as white space in the C locale.
const char kSpace[] = " \t\n\v\f\r";

std::string trim(const std::string& s) {
  size_t b = s.find_first_not_of(kSpace);
  if (b == std::string::npos) return "";
  size_t e = s.find_last_not_of(kSpace);
  return s.substr(b, e - b + 1);
}

double parse_double(const std::string& tok, const std::string& src, size_t line, const char* what) {
  const char* b = tok.c_str();
  char* end = nullptr;
  double v = std::strtod(b, &end);
  if (end == b || *end != '\0')
    throw Error(src, "line " + std::to_string(line) + ": " + what + " '" + tok + "' is not a number");
  if (!std::isfinite(v))
    throw Error(src, "line " + std::to_string(line) + ": " + what + " is not finite");
  return v;
}

uint64_t parse_uint(const std::string& tok, const std::string& src, size_t line, const char* what,
                    uint64_t max_value) {
  if (tok.empty() || tok.size() > 20 || tok.find_first_not_of("0123456789") != std::string::npos)
    throw Error(src, "line " + std::to_string(line) + ": " + what + " '" + tok +
                         "' is not a non-negative integer");
  errno = 0;
  unsigned long long v = std::strtoull(tok.c_str(), nullptr, 10);
  if (errno == ERANGE || v > max_value)
    throw Error(src, "line " + std::to_string(line) + ": " + what + " " + tok + " is out of range");
  return v;
}

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}
bool is_dir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}
bool has_model(const fs::path& d, const char* ext) {
  return is_file(d / (std::string("cameras") + ext)) && is_file(d / (std::string("images") + ext));
}

}  // namespace

const ColmapCameraModel* colmap_model_by_id(int id) {
  for (const ColmapCameraModel& m : kModels)
    if (m.id == id) return &m;
  return nullptr;
}

const ColmapCameraModel* colmap_model_by_name(const std::string& name) {
  for (const ColmapCameraModel& m : kModels)
    if (name == m.name) return &m;
  return nullptr;
}

std::vector<ColmapCamera> parse_colmap_cameras_bin(const uint8_t* data, size_t size, const std::string& src) {
  Reader r(data, size, src);
  uint64_t count = r.get<uint64_t>("camera count");
  // Smallest record: id, model, width, height and 3 parameters.
  constexpr size_t kMinRecord = 4 + 4 + 8 + 8 + 3 * 8;
  if (count > r.left() / kMinRecord)
    throw Error(src, "camera count " + std::to_string(count) + " does not fit in the " +
                         std::to_string(r.left()) + " bytes that follow (truncated or corrupt file)");
  std::vector<ColmapCamera> cams;
  cams.reserve(count);
  std::set<uint32_t> ids;
  for (uint64_t i = 0; i < count; ++i) {
    ColmapCamera c;
    c.camera_id = r.get<uint32_t>("camera id");
    int32_t model = r.get<int32_t>("camera model id");
    const ColmapCameraModel* m = colmap_model_by_id(model);
    if (!m)
      throw Error(src, "camera " + std::to_string(c.camera_id) + " has an unknown camera model id " +
                           std::to_string(model));
    c.model_id = model;
    c.width = r.get<uint64_t>("camera width");
    c.height = r.get<uint64_t>("camera height");
    const std::string who = "camera " + std::to_string(c.camera_id);
    for (int k = 0; k < m->num_params; ++k) c.params.push_back(r.get_finite("camera parameter", who));
    if (!ids.insert(c.camera_id).second)
      throw Error(src, "camera id " + std::to_string(c.camera_id) + " appears twice");
    check_camera(c, src);
    cams.push_back(std::move(c));
  }
  if (r.left() != 0)
    throw Error(src, std::to_string(r.left()) + " unexpected bytes after the last camera (corrupt file?)");
  return cams;
}

std::vector<ColmapImage> parse_colmap_images_bin(const uint8_t* data, size_t size, const std::string& src) {
  Reader r(data, size, src);
  uint64_t count = r.get<uint64_t>("image count");
  // Smallest record: id, 7 doubles, camera id, a 1-character name + NUL, point count.
  constexpr size_t kMinRecord = 4 + 7 * 8 + 4 + 2 + 8;
  if (count > r.left() / kMinRecord)
    throw Error(src, "image count " + std::to_string(count) + " does not fit in the " +
                         std::to_string(r.left()) + " bytes that follow (truncated or corrupt file)");
  std::vector<ColmapImage> images;
  images.reserve(count);
  std::set<uint32_t> ids;
  for (uint64_t i = 0; i < count; ++i) {
    ColmapImage im;
    im.image_id = r.get<uint32_t>("image id");
    const std::string who = "image " + std::to_string(im.image_id);
    im.q.w = r.get_finite("rotation", who);
    im.q.x = r.get_finite("rotation", who);
    im.q.y = r.get_finite("rotation", who);
    im.q.z = r.get_finite("rotation", who);
    im.t.x = r.get_finite("translation", who);
    im.t.y = r.get_finite("translation", who);
    im.t.z = r.get_finite("translation", who);
    im.camera_id = r.get<uint32_t>("image camera id");
    im.name = r.get_cstring("image name", kMaxNameLength);
    uint64_t points = r.get<uint64_t>("2D point count");
    constexpr size_t kPointRecord = 8 + 8 + 8;  // x, y, point3D id
    if (points > r.left() / kPointRecord)
      throw Error(src, "image '" + im.name + "' claims " + std::to_string(points) +
                           " 2D points, more than the bytes left (truncated or corrupt file)");
    r.skip(points * kPointRecord, "2D points");
    if (!ids.insert(im.image_id).second)
      throw Error(src, "image id " + std::to_string(im.image_id) + " appears twice");
    check_image(im, src);
    images.push_back(std::move(im));
  }
  if (r.left() != 0)
    throw Error(src, std::to_string(r.left()) + " unexpected bytes after the last image (corrupt file?)");
  return images;
}

std::vector<ColmapCamera> parse_colmap_cameras_txt(const std::string& text, const std::string& src) {
  std::vector<ColmapCamera> cams;
  std::set<uint32_t> ids;
  std::istringstream in(text);
  std::string raw;
  size_t line_no = 0;
  while (std::getline(in, raw)) {
    ++line_no;
    std::string line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> tok = tokens(line);
    if (tok.size() < 4)
      throw Error(src, "line " + std::to_string(line_no) + ": expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS[]");
    ColmapCamera c;
    c.camera_id = uint32_t(parse_uint(tok[0], src, line_no, "camera id", UINT32_MAX));
    const ColmapCameraModel* m = colmap_model_by_name(tok[1]);
    if (!m)
      throw Error(src, "line " + std::to_string(line_no) + ": unknown camera model '" + tok[1] + "'");
    c.model_id = m->id;
    c.width = parse_uint(tok[2], src, line_no, "width", UINT64_MAX);
    c.height = parse_uint(tok[3], src, line_no, "height", UINT64_MAX);
    if (tok.size() != size_t(4 + m->num_params))
      throw Error(src, "line " + std::to_string(line_no) + ": camera model " + m->name + " takes " +
                           std::to_string(m->num_params) + " parameters, found " +
                           std::to_string(tok.size() - 4));
    for (size_t k = 4; k < tok.size(); ++k) c.params.push_back(parse_double(tok[k], src, line_no, "parameter"));
    if (!ids.insert(c.camera_id).second)
      throw Error(src, "line " + std::to_string(line_no) + ": camera id " + std::to_string(c.camera_id) +
                           " appears twice");
    check_camera(c, src);
    cams.push_back(std::move(c));
  }
  return cams;
}

std::vector<ColmapImage> parse_colmap_images_txt(const std::string& text, const std::string& src) {
  std::vector<ColmapImage> images;
  std::set<uint32_t> ids;
  std::istringstream in(text);
  std::string raw;
  size_t line_no = 0;
  while (std::getline(in, raw)) {
    ++line_no;
    std::string line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    // IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME; the next line holds the 2D points
    // (possibly empty) and is skipped.
    std::vector<std::string> tok = tokens(line);
    if (tok.size() < 10)
      throw Error(src, "line " + std::to_string(line_no) +
                           ": expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME");
    ColmapImage im;
    im.image_id = uint32_t(parse_uint(tok[0], src, line_no, "image id", UINT32_MAX));
    im.q.w = parse_double(tok[1], src, line_no, "QW");
    im.q.x = parse_double(tok[2], src, line_no, "QX");
    im.q.y = parse_double(tok[3], src, line_no, "QY");
    im.q.z = parse_double(tok[4], src, line_no, "QZ");
    im.t.x = parse_double(tok[5], src, line_no, "TX");
    im.t.y = parse_double(tok[6], src, line_no, "TY");
    im.t.z = parse_double(tok[7], src, line_no, "TZ");
    im.camera_id = uint32_t(parse_uint(tok[8], src, line_no, "camera id", UINT32_MAX));
    // The name is the rest of the line after nine tokens (split on the same whitespace
    // as `tokens`), so names with spaces survive.
    size_t pos = 0;
    for (int k = 0; k < 9; ++k) {
      pos = line.find_first_not_of(kSpace, pos);
      pos = line.find_first_of(kSpace, pos);
    }
    im.name = pos == std::string::npos ? std::string() : trim(line.substr(pos));
    if (!ids.insert(im.image_id).second)
      throw Error(src, "line " + std::to_string(line_no) + ": image id " + std::to_string(im.image_id) +
                           " appears twice");
    check_image(im, src);
    images.push_back(std::move(im));
    if (std::getline(in, raw)) ++line_no;  // POINTS2D[] as (X, Y, POINT3D_ID)
  }
  return images;
}

std::vector<Camera> colmap_to_cameras(const std::vector<ColmapCamera>& cameras,
                                      const std::vector<ColmapImage>& images,
                                      const std::string& cameras_src, const std::string& images_src,
                                      const std::string& images_dir, std::vector<std::string>* notes) {
  if (images.empty()) throw Error(images_src, "contains no images");
  std::map<uint32_t, const ColmapCamera*> by_id;
  for (const ColmapCamera& c : cameras) by_id[c.camera_id] = &c;

  std::vector<const ColmapImage*> order;
  for (const ColmapImage& im : images) order.push_back(&im);
  std::sort(order.begin(), order.end(),
            [](const ColmapImage* a, const ColmapImage* b) { return a->name < b->name; });

  // Names: the file stem, or the whole relative path without extension when two
  // images in different folders share a stem.
  std::map<std::string, int> stem_count;
  for (const ColmapImage* im : order) ++stem_count[fs::path(im->name).stem().string()];

  std::set<uint32_t> noted;
  std::vector<Camera> out;
  for (const ColmapImage* im : order) {
    auto it = by_id.find(im->camera_id);
    if (it == by_id.end())
      throw Error(images_src, "image '" + im->name + "' refers to camera " + std::to_string(im->camera_id) +
                                  ", which " + cameras_src + " does not define");
    const ColmapCamera& cc = *it->second;
    const ColmapCameraModel* m = colmap_model_by_id(cc.model_id);
    if (!m || cc.params.size() != size_t(m->num_params))
      throw Error(cameras_src, "camera " + std::to_string(cc.camera_id) + " has an invalid model");
    check_camera(cc, cameras_src);  // also for cameras built in memory, before the int casts
    if (im->image_id > uint32_t(INT_MAX))
      throw Error(images_src, "image id " + std::to_string(im->image_id) + " is too large");
    Camera c;
    c.id = int(im->image_id);
    fs::path name_path(im->name);
    c.name = name_path.stem().string();
    if (stem_count[c.name] > 1) c.name = (name_path.parent_path() / name_path.stem()).generic_string();
    if (!images_dir.empty()) c.image_path = (fs::path(images_dir) / name_path).string();
    c.width = int(cc.width);  // check_camera bounded the size
    c.height = int(cc.height);
    if (m->single_focal) {
      c.fx = c.fy = cc.params[0];
      c.cx = cc.params[1];
      c.cy = cc.params[2];
    } else {
      c.fx = cc.params[0];
      c.fy = cc.params[1];
      c.cx = cc.params[2];
      c.cy = cc.params[3];
    }
    c.R = im->q.to_matrix();
    c.t = im->t;
    if (notes && noted.insert(cc.camera_id).second) {
      bool distorted = false;
      for (int k = m->single_focal ? 3 : 4; k < m->num_params; ++k) distorted |= cc.params[k] != 0.0;
      if (m->fisheye)
        notes->push_back("camera " + std::to_string(cc.camera_id) + " (" + m->name + ", first used by '" +
                         c.name + "') is a fisheye model: it is treated as a pinhole with the same focal "
                         "length and principal point; undistort the images for correct results");
      else if (distorted)
        notes->push_back("distortion of camera " + std::to_string(cc.camera_id) + " (" + m->name +
                         ", first used by '" + c.name + "') is ignored; only fx, fy, cx, cy are used");
    }
    c.validate(images_src);
    out.push_back(std::move(c));
  }
  return out;
}

std::string find_colmap_model_dir(const std::string& path) {
  fs::path p(path);
  for (const fs::path& d : {p, p / "sparse" / "0", p / "sparse"})
    if (has_model(d, ".bin") || has_model(d, ".txt")) return d.string();
  return "";
}

std::vector<Camera> read_colmap_model(const std::string& path, std::vector<std::string>* notes,
                                      std::string* format) {
  std::string dir = find_colmap_model_dir(path);
  if (dir.empty())
    throw Error(path, "no COLMAP model here: expected cameras.bin+images.bin or cameras.txt+images.txt "
                      "in this folder, in sparse/0 or in sparse/");
  fs::path d(dir);
  const bool binary = has_model(d, ".bin");
  std::vector<ColmapCamera> cams;
  std::vector<ColmapImage> images;
  std::string cam_src, img_src;
  if (binary) {
    cam_src = (d / "cameras.bin").string();
    img_src = (d / "images.bin").string();
    std::vector<uint8_t> cb = read_file_bytes(cam_src);
    cams = parse_colmap_cameras_bin(cb.data(), cb.size(), cam_src);
    std::vector<uint8_t> ib = read_file_bytes(img_src);
    images = parse_colmap_images_bin(ib.data(), ib.size(), img_src);
    if (notes && has_model(d, ".txt"))
      notes->push_back(dir + " holds both a binary and a text model; the binary one was read");
  } else {
    cam_src = (d / "cameras.txt").string();
    img_src = (d / "images.txt").string();
    std::vector<uint8_t> cb = read_file_bytes(cam_src);
    cams = parse_colmap_cameras_txt(std::string(cb.begin(), cb.end()), cam_src);
    std::vector<uint8_t> ib = read_file_bytes(img_src);
    images = parse_colmap_images_txt(std::string(ib.begin(), ib.end()), img_src);
  }
  if (format) *format = binary ? "COLMAP binary" : "COLMAP text";

  // The photos: images/ in the scene folder (the parent of sparse/ or sparse/0), or
  // beside the model.
  std::string images_dir;
  fs::path model = fs::absolute(d).lexically_normal();
  if (model.filename().empty()) model = model.parent_path();
  std::vector<fs::path> candidates = {model / "images", model.parent_path() / "images"};
  if (model.parent_path().filename() == "sparse") candidates.push_back(model.parent_path().parent_path() / "images");
  for (const fs::path& c : candidates)
    if (is_dir(c)) {
      images_dir = c.string();
      break;
    }
  return colmap_to_cameras(cams, images, cam_src, img_src, images_dir, notes);
}

std::vector<uint8_t> serialize_colmap_cameras_bin(const std::vector<ColmapCamera>& cameras) {
  std::vector<uint8_t> out;
  put<uint64_t>(out, cameras.size());
  for (const ColmapCamera& c : cameras) {
    put<uint32_t>(out, c.camera_id);
    put<int32_t>(out, c.model_id);
    put<uint64_t>(out, c.width);
    put<uint64_t>(out, c.height);
    for (double p : c.params) put<double>(out, p);
  }
  return out;
}

std::vector<uint8_t> serialize_colmap_images_bin(const std::vector<ColmapImage>& images) {
  std::vector<uint8_t> out;
  put<uint64_t>(out, images.size());
  for (const ColmapImage& im : images) {
    put<uint32_t>(out, im.image_id);
    for (double v : {im.q.w, im.q.x, im.q.y, im.q.z, im.t.x, im.t.y, im.t.z}) put<double>(out, v);
    put<uint32_t>(out, im.camera_id);
    out.insert(out.end(), im.name.begin(), im.name.end());
    out.push_back(0);
    put<uint64_t>(out, 0);  // no 2D points
  }
  return out;
}

void cameras_to_colmap(const std::vector<Camera>& cameras, std::vector<ColmapCamera>& out_cameras,
                       std::vector<ColmapImage>& out_images) {
  out_cameras.clear();
  out_images.clear();
  for (size_t i = 0; i < cameras.size(); ++i) {
    const Camera& c = cameras[i];
    ColmapCamera cc;
    cc.model_id = 1;  // PINHOLE
    cc.width = uint64_t(std::max(c.width, 0));
    cc.height = uint64_t(std::max(c.height, 0));
    cc.params = {c.fx, c.fy, c.cx, c.cy};
    uint32_t camera_id = 0;
    for (const ColmapCamera& o : out_cameras)
      if (o.width == cc.width && o.height == cc.height && o.params == cc.params) camera_id = o.camera_id;
    if (camera_id == 0) {
      cc.camera_id = camera_id = uint32_t(out_cameras.size() + 1);
      out_cameras.push_back(cc);
    }
    ColmapImage im;
    im.image_id = uint32_t(i + 1);
    im.q = Quat::from_matrix(c.R);
    im.t = c.t;
    im.camera_id = camera_id;
    std::string ext = fs::path(c.image_path).extension().string();
    im.name = (c.name.empty() ? std::to_string(c.id) : c.name) + (ext.empty() ? ".png" : ext);
    out_images.push_back(std::move(im));
  }
}

void write_colmap_text(const std::string& dir, const std::vector<Camera>& cameras) {
  std::vector<ColmapCamera> cams;
  std::vector<ColmapImage> images;
  cameras_to_colmap(cameras, cams, images);
  std::string ct = "# Camera list with one line of data per camera:\n"
                   "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
                   "# Number of cameras: " + std::to_string(cams.size()) + "\n";
  for (const ColmapCamera& c : cams) {
    ct += std::to_string(c.camera_id) + " " + colmap_model_by_id(c.model_id)->name + " " +
          std::to_string(c.width) + " " + std::to_string(c.height);
    for (double p : c.params) ct += " " + fmt(p);
    ct += "\n";
  }
  std::string it = "# Image list with two lines of data per image:\n"
                   "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
                   "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
                   "# Number of images: " + std::to_string(images.size()) + "\n";
  for (const ColmapImage& im : images) {
    it += std::to_string(im.image_id);
    for (double v : {im.q.w, im.q.x, im.q.y, im.q.z, im.t.x, im.t.y, im.t.z}) it += " " + fmt(v);
    it += " " + std::to_string(im.camera_id) + " " + im.name + "\n\n";
  }
  fs::path d(dir);
  write_file_atomic((d / "cameras.txt").string(), ct);
  write_file_atomic((d / "images.txt").string(), it);
  write_file_atomic((d / "points3D.txt").string(),
                    std::string("# 3D point list with one line of data per point:\n"
                                "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
                                "# Number of points: 0\n"));
}

void write_colmap_binary(const std::string& dir, const std::vector<Camera>& cameras) {
  std::vector<ColmapCamera> cams;
  std::vector<ColmapImage> images;
  cameras_to_colmap(cameras, cams, images);
  fs::path d(dir);
  write_file_atomic((d / "cameras.bin").string(), serialize_colmap_cameras_bin(cams));
  write_file_atomic((d / "images.bin").string(), serialize_colmap_images_bin(images));
  std::vector<uint8_t> points;
  put<uint64_t>(points, 0);
  write_file_atomic((d / "points3D.bin").string(), points);
}

}  // namespace isegman
