#include "io/transforms_json.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/image_size.h"

namespace isegman {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Looks `key` up in the frame first, then at the top level; must be a number if present.
std::optional<double> lookup(const json& frame, const json& top, const char* key, const std::string& src,
                             const std::string& who) {
  for (const json* j : {&frame, &top}) {
    if (!j->is_object() || !j->contains(key)) continue;
    const json& v = j->at(key);
    if (v.is_null()) continue;
    if (!v.is_number()) throw Error(src, who + ": '" + key + "' is not a number");
    double d = v.get<double>();
    if (!std::isfinite(d)) throw Error(src, who + ": '" + key + "' is not finite");
    return d;
  }
  return std::nullopt;
}

int pixels(double v, const std::string& src, const std::string& who, const char* what) {
  if (!(v >= 1 && v <= 65536) || std::fabs(v - std::round(v)) > 1e-6)
    throw Error(src, who + ": '" + what + "' = " + std::to_string(v) + " is not a valid image size");
  return int(std::lround(v));
}

// file_path as written, relative to base_dir; NeRF-synthetic omits the extension.
fs::path resolve_image(const fs::path& base, const std::string& file_path) {
  fs::path p = base / file_path;
  std::error_code ec;
  if (fs::is_regular_file(p, ec) || p.has_extension()) return p.lexically_normal();
  for (const char* ext : {".png", ".jpg", ".jpeg", ".JPG", ".PNG"}) {
    fs::path q = p;
    q += ext;
    if (fs::is_regular_file(q, ec)) return q.lexically_normal();
  }
  return p.lexically_normal();
}

}  // namespace

std::vector<Camera> parse_transforms_json(const std::string& text, const std::string& src,
                                          const std::string& base_dir, std::vector<std::string>* notes) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(src, std::string("invalid JSON: ") + e.what());
  }
  if (!doc.is_object() || !doc.contains("frames"))
    throw Error(src, "expected a JSON object with a 'frames' list (transforms.json)");
  const json& frames = doc["frames"];
  if (!frames.is_array()) throw Error(src, "'frames' is not a list");
  if (frames.empty()) throw Error(src, "'frames' is empty");

  bool noted_distortion = false;
  if (notes && doc.contains("camera_model") && doc["camera_model"].is_string()) {
    std::string model = doc["camera_model"].get<std::string>();
    if (model == "OPENCV_FISHEYE" || model == "EQUIRECTANGULAR")
      notes->push_back("camera_model " + model + " is treated as a pinhole; undistort the images for correct results");
  }
  if (notes && doc.contains("applied_transform"))
    notes->push_back("poses are in the frame of the transforms.json (its applied_transform is kept, not undone)");

  std::vector<Camera> out;
  std::map<std::string, int> stems;
  for (size_t i = 0; i < frames.size(); ++i) {
    const json& f = frames[i];
    std::string who = "frame #" + std::to_string(i);
    if (!f.is_object()) throw Error(src, who + " is not an object");
    if (!f.contains("file_path") || !f["file_path"].is_string()) throw Error(src, who + " has no 'file_path'");
    std::string file_path = f["file_path"].get<std::string>();
    who += " ('" + file_path + "')";
    if (!f.contains("transform_matrix") || !f["transform_matrix"].is_array())
      throw Error(src, who + " has no 'transform_matrix'");
    const json& m = f["transform_matrix"];
    if (m.size() != 4 && m.size() != 3) throw Error(src, who + ": transform_matrix must be 4x4 (or 3x4)");
    double M[4][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 1}};
    for (size_t r = 0; r < m.size(); ++r) {
      if (!m[r].is_array() || m[r].size() != 4) throw Error(src, who + ": transform_matrix must be 4x4 (or 3x4)");
      for (size_t k = 0; k < 4; ++k) {
        if (!m[r][k].is_number()) throw Error(src, who + ": transform_matrix holds a non-number");
        M[r][k] = m[r][k].get<double>();
        if (!std::isfinite(M[r][k])) throw Error(src, who + ": transform_matrix holds a non-finite value");
      }
    }
    if (std::fabs(M[3][0]) > 1e-6 || std::fabs(M[3][1]) > 1e-6 || std::fabs(M[3][2]) > 1e-6 ||
        std::fabs(M[3][3] - 1) > 1e-6)
      throw Error(src, who + ": the last row of transform_matrix is not (0, 0, 0, 1)");

    Camera c;
    c.id = int(i);
    fs::path image = resolve_image(fs::path(base_dir), file_path);
    c.image_path = image.string();
    c.name = fs::path(file_path).stem().string();
    if (c.name.empty() || c.name == ".") c.name = std::to_string(i);

    // OpenGL camera-to-world columns: x right, y up, z back -> OpenCV: y and z flipped.
    Vec3 x{M[0][0], M[1][0], M[2][0]}, y{M[0][1], M[1][1], M[2][1]}, z{M[0][2], M[1][2], M[2][2]};
    Vec3 centre{M[0][3], M[1][3], M[2][3]};
    Camera pose = Camera::from_center_rotation(centre, Mat3::from_cols(x, -y, -z));
    c.R = pose.R;
    c.t = pose.t;

    std::optional<double> w = lookup(f, doc, "w", src, who), h = lookup(f, doc, "h", src, who);
    if (!w || !h) {
      int iw = 0, ih = 0;
      if (!read_image_size(image.string(), iw, ih))
        throw Error(src, who + ": no 'w'/'h' and the image size cannot be read from " + image.string());
      if (!w) w = iw;
      if (!h) h = ih;
    }
    c.width = pixels(*w, src, who, "w");
    c.height = pixels(*h, src, who, "h");
    std::optional<double> fl_x = lookup(f, doc, "fl_x", src, who), fl_y = lookup(f, doc, "fl_y", src, who);
    std::optional<double> ax = lookup(f, doc, "camera_angle_x", src, who);
    std::optional<double> ay = lookup(f, doc, "camera_angle_y", src, who);
    if (!fl_x && ax) fl_x = 0.5 * c.width / std::tan(0.5 * *ax);
    if (!fl_y && ay) fl_y = 0.5 * c.height / std::tan(0.5 * *ay);
    if (!fl_x && fl_y) fl_x = fl_y;
    if (!fl_y && fl_x) fl_y = fl_x;
    if (!fl_x) throw Error(src, who + " has no focal length (fl_x/fl_y or camera_angle_x)");
    c.fx = *fl_x;
    c.fy = *fl_y;
    c.cx = lookup(f, doc, "cx", src, who).value_or(0.5 * c.width);
    c.cy = lookup(f, doc, "cy", src, who).value_or(0.5 * c.height);
    if (notes && !noted_distortion) {
      for (const char* k : {"k1", "k2", "k3", "k4", "p1", "p2"}) {
        std::optional<double> d = lookup(f, doc, k, src, who);
        if (d && *d != 0.0) {
          notes->push_back("distortion (" + std::string(k) + " = " + std::to_string(*d) + ", first seen on " +
                           who + ") is ignored; only fl_x, fl_y, cx, cy are used");
          noted_distortion = true;
          break;
        }
      }
    }
    c.validate(src);
    ++stems[c.name];
    out.push_back(std::move(c));
  }
  // Two frames with the same stem in different folders: name them by their path.
  for (size_t i = 0; i < out.size(); ++i)
    if (stems[out[i].name] > 1) {
      fs::path p(frames[i]["file_path"].get<std::string>());
      out[i].name = (p.parent_path() / p.stem()).lexically_normal().generic_string();
    }
  return out;
}

std::vector<Camera> read_transforms_json(const std::string& path, std::vector<std::string>* notes) {
  std::vector<uint8_t> bytes = read_file_bytes(path);
  return parse_transforms_json(std::string(bytes.begin(), bytes.end()), path,
                               fs::path(path).parent_path().string(), notes);
}

std::string cameras_to_transforms_json(const std::vector<Camera>& cameras) {
  json doc = json::object();
  bool shared = !cameras.empty();
  for (const Camera& c : cameras) {
    const Camera& a = cameras.front();
    shared &= c.width == a.width && c.height == a.height && c.fx == a.fx && c.fy == a.fy && c.cx == a.cx &&
              c.cy == a.cy;
  }
  auto intrinsics = [](json& j, const Camera& c) {
    j["w"] = c.width;
    j["h"] = c.height;
    j["fl_x"] = c.fx;
    j["fl_y"] = c.fy;
    j["cx"] = c.cx;
    j["cy"] = c.cy;
  };
  if (shared) {
    doc["camera_model"] = "OPENCV";
    intrinsics(doc, cameras.front());
  }
  json frames = json::array();
  for (const Camera& c : cameras) {
    json f = json::object();
    std::string ext = fs::path(c.image_path).extension().string();
    f["file_path"] = "images/" + (c.name.empty() ? std::to_string(c.id) : c.name) + (ext.empty() ? ".png" : ext);
    Mat3 c2w = c.R.transposed();
    Vec3 x = c2w.col(0), y = -c2w.col(1), z = -c2w.col(2), p = c.center();
    f["transform_matrix"] = {{x.x, y.x, z.x, p.x}, {x.y, y.y, z.y, p.y}, {x.z, y.z, z.z, p.z}, {0, 0, 0, 1}};
    if (!shared) intrinsics(f, c);
    frames.push_back(f);
  }
  doc["frames"] = frames;
  return doc.dump(2) + "\n";
}

void write_transforms_json(const std::string& path, const std::vector<Camera>& cameras) {
  write_file_atomic(path, cameras_to_transforms_json(cameras));
}

}  // namespace isegman
