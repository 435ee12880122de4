#include "io/splat.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/sh.h"
#include "io/atomic_file.h"

namespace isegman {
namespace {

uint8_t to_byte(double v) { return uint8_t(std::clamp(std::lround(v), 0L, 255L)); }

void put_f32(uint8_t* p, float v) {
  uint32_t u;
  std::memcpy(&u, &v, 4);
  for (int i = 0; i < 4; ++i) p[i] = uint8_t(u >> (8 * i));
}

}  // namespace

std::vector<uint8_t> serialize_splat(const GaussianScene& scene, std::vector<std::string>* notes) {
  scene.validate("splat output");
  if (scene.size() == 0) throw Error("splat output", "the scene has no Gaussians");
  const size_t n = scene.size();
  std::vector<uint8_t> out(n * kSplatRecordBytes);
  size_t clamped_colour = 0;
  for (size_t i = 0; i < n; ++i) {
    uint8_t* r = out.data() + i * kSplatRecordBytes;
    for (int a = 0; a < 3; ++a) put_f32(r + 4 * a, scene.positions[3 * i + a]);
    for (int a = 0; a < 3; ++a) {
      const float s = std::exp(scene.scales[3 * i + a]);
      if (!std::isfinite(s)) throw Error("splat output", "Gaussian " + std::to_string(i) + " has an infinite scale");
      put_f32(r + 12 + 4 * a, s);
    }
    const float* c = scene.sh_of(i);
    for (int ch = 0; ch < 3; ++ch) {
      const double v = 0.5 + double(kShC0) * double(c[ch]);
      if (v < 0 || v > 1) ++clamped_colour;
      r[24 + ch] = to_byte(v * 255.0);
    }
    r[27] = to_byte(255.0 * sigmoid(double(scene.opacity[i])));
    const Quat q = scene.rotation(i).normalized();
    const double qv[4] = {q.w, q.x, q.y, q.z};
    for (int a = 0; a < 4; ++a) r[28 + a] = to_byte(qv[a] * 128.0 + 128.0);
  }
  if (notes) {
    if (scene.sh_degree > 0)
      notes->push_back(".splat stores base colours only: SH bands 1-" + std::to_string(scene.sh_degree) +
                       " (view-dependent colour) were dropped");
    if (clamped_colour)
      notes->push_back(".splat stores colours in [0, 1]: " + std::to_string(clamped_colour) +
                       " colour values outside were clamped");
    if (!scene.extras.empty()) notes->push_back(".splat has no room for extra properties: they were dropped");
  }
  return out;
}

GaussianScene parse_splat(const uint8_t* data, size_t size, const std::string& source) {
  if (size == 0) throw Error(source, "empty .splat file");
  if (size % kSplatRecordBytes != 0)
    throw Error(source, "not a .splat file: " + std::to_string(size) + " bytes is not a multiple of the 32-byte record");
  const size_t n = size / kSplatRecordBytes;
  GaussianScene s;
  s.resize(n, 0);
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* r = data + i * kSplatRecordBytes;
    for (int a = 0; a < 3; ++a) {
      const float p = splat_f32(r + 4 * a);
      if (!std::isfinite(p)) throw Error(source, "Gaussian " + std::to_string(i) + " has a non-finite position");
      s.positions[3 * i + a] = p;
    }
    for (int a = 0; a < 3; ++a) {
      const float v = splat_f32(r + 12 + 4 * a);
      if (!std::isfinite(v) || !(v > 0))
        throw Error(source, "Gaussian " + std::to_string(i) + " has a scale that is not a positive finite number");
      s.scales[3 * i + a] = std::log(v);
    }
    for (int ch = 0; ch < 3; ++ch) s.sh[3 * i + ch] = rgb_to_sh_dc(float(r[24 + ch]) / 255.0f);
    // Alpha bytes 0 and 255 would be infinite logits: read them half a step inside.
    const double a = std::clamp(double(r[27]), 0.5, 254.5) / 255.0;
    s.opacity[i] = float(std::log(a / (1.0 - a)));
    double q[4];
    for (int k = 0; k < 4; ++k) q[k] = (double(r[28 + k]) - 128.0) / 128.0;
    const double qn = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (qn == 0) throw Error(source, "Gaussian " + std::to_string(i) + " has a zero rotation");
    for (int k = 0; k < 4; ++k) s.rotations[4 * i + k] = float(q[k] / qn);
  }
  return s;
}

GaussianScene read_splat(const std::string& path) {
  std::vector<uint8_t> bytes = read_file_bytes(path);
  return parse_splat(bytes.data(), bytes.size(), path);
}

void write_splat(const std::string& path, const GaussianScene& scene, std::vector<std::string>* notes) {
  std::vector<uint8_t> bytes;
  try {
    bytes = serialize_splat(scene, notes);
  } catch (const Error& e) {
    throw Error(path, e.what());
  }
  write_file_atomic(path, bytes);
}

}  // namespace isegman
