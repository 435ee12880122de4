#include "io/cameras_json.h"

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/atomic_file.h"

namespace isegman {

using nlohmann::json;

namespace {
double number(const json& j, const char* key, const std::string& src, size_t index) {
  if (!j.contains(key)) throw Error(src, "camera #" + std::to_string(index) + " has no '" + key + "'");
  const json& v = j.at(key);
  if (!v.is_number()) throw Error(src, "camera #" + std::to_string(index) + ": '" + key + "' is not a number");
  return v.get<double>();
}
}  // namespace

std::vector<Camera> parse_cameras_json(const std::string& text, const std::string& src) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(src, std::string("invalid JSON: ") + e.what());
  }
  if (!doc.is_array()) throw Error(src, "expected a JSON list of cameras (INRIA cameras.json)");
  if (doc.empty()) throw Error(src, "contains no cameras");
  std::vector<Camera> cams;
  for (size_t i = 0; i < doc.size(); ++i) {
    const json& j = doc[i];
    if (!j.is_object()) throw Error(src, "camera #" + std::to_string(i) + " is not an object");
    Camera c;
    c.id = j.contains("id") && j["id"].is_number_integer() ? j["id"].get<int>() : int(i);
    c.name = j.contains("img_name") && j["img_name"].is_string() ? j["img_name"].get<std::string>()
                                                                  : std::to_string(c.id);
    double w = number(j, "width", src, i), h = number(j, "height", src, i);
    if (w != double(int(w)) || h != double(int(h))) throw Error(src, "camera '" + c.name + "' has a fractional image size");
    c.width = int(w);
    c.height = int(h);
    c.fx = number(j, "fx", src, i);
    c.fy = number(j, "fy", src, i);
    c.cx = j.contains("cx") ? number(j, "cx", src, i) : 0.5 * c.width;
    c.cy = j.contains("cy") ? number(j, "cy", src, i) : 0.5 * c.height;
    if (!j.contains("position") || !j["position"].is_array() || j["position"].size() != 3)
      throw Error(src, "camera '" + c.name + "' has no 3-element 'position'");
    if (!j.contains("rotation") || !j["rotation"].is_array() || j["rotation"].size() != 3)
      throw Error(src, "camera '" + c.name + "' has no 3x3 'rotation'");
    Vec3 centre;
    Mat3 c2w;
    for (int r = 0; r < 3; ++r) {
      if (!j["position"][r].is_number()) throw Error(src, "camera '" + c.name + "': position is not numeric");
      centre[r] = j["position"][r].get<double>();
      const json& row = j["rotation"][r];
      if (!row.is_array() || row.size() != 3) throw Error(src, "camera '" + c.name + "' has no 3x3 'rotation'");
      for (int k = 0; k < 3; ++k) {
        if (!row[k].is_number()) throw Error(src, "camera '" + c.name + "': rotation is not numeric");
        c2w.m[r][k] = row[k].get<double>();
      }
    }
    Camera pose = Camera::from_center_rotation(centre, c2w);
    c.R = pose.R;
    c.t = pose.t;
    c.validate(src);
    cams.push_back(c);
  }
  return cams;
}

std::vector<Camera> read_cameras_json(const std::string& path) {
  std::vector<uint8_t> bytes = read_file_bytes(path);
  return parse_cameras_json(std::string(bytes.begin(), bytes.end()), path);
}

std::string cameras_to_json(const std::vector<Camera>& cameras) {
  json doc = json::array();
  for (const Camera& c : cameras) {
    Mat3 c2w = c.R.transposed();
    Vec3 centre = c.center();
    json rot = json::array();
    for (int r = 0; r < 3; ++r) rot.push_back({c2w.m[r][0], c2w.m[r][1], c2w.m[r][2]});
    json j = {{"id", c.id}, {"img_name", c.name}, {"width", c.width}, {"height", c.height},
              {"position", {centre.x, centre.y, centre.z}}, {"rotation", rot}, {"fx", c.fx}, {"fy", c.fy}};
    if (std::abs(c.cx - 0.5 * c.width) > 1e-9 || std::abs(c.cy - 0.5 * c.height) > 1e-9) {
      j["cx"] = c.cx;
      j["cy"] = c.cy;
    }
    doc.push_back(j);
  }
  return doc.dump(1) + "\n";
}

void write_cameras_json(const std::string& path, const std::vector<Camera>& cameras) {
  write_file_atomic(path, cameras_to_json(cameras));
}

}  // namespace isegman
