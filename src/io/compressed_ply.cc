#include "io/compressed_ply.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <sstream>

#include "core/error.h"
#include "core/sh.h"

namespace isegman {
namespace {

constexpr size_t kChunk = 256;
const char* const kChunkProps[] = {"min_x", "min_y", "min_z", "max_x", "max_y", "max_z",
                                   "min_scale_x", "min_scale_y", "min_scale_z",
                                   "max_scale_x", "max_scale_y", "max_scale_z"};
const char* const kColorProps[] = {"min_r", "min_g", "min_b", "max_r", "max_g", "max_b"};
const char* const kVertexProps[] = {"packed_position", "packed_rotation", "packed_scale", "packed_color"};

struct Property {
  std::string name, type;
  size_t offset = 0;
};
struct Element {
  std::string name;
  size_t count = 0, stride = 0, start = 0;
  std::vector<Property> props;
  const Property* find(const std::string& n) const {
    for (const auto& p : props)
      if (p.name == n) return &p;
    return nullptr;
  }
};

size_t type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

// Parses the header; `body` receives the offset of the first data byte.
std::vector<Element> parse_header(const uint8_t* data, size_t size, const std::string& source, size_t& body) {
  const size_t limit = std::min<size_t>(size, 1 << 16);
  const std::string head(reinterpret_cast<const char*>(data), limit);
  const size_t end = head.find("end_header");
  if (head.compare(0, 3, "ply") != 0 || end == std::string::npos)
    throw Error(source, "not a PLY file (no 'ply' ... 'end_header' header)");
  size_t eol = head.find('\n', end);
  if (eol == std::string::npos) throw Error(source, "truncated PLY header");
  body = eol + 1;
  std::istringstream in(head.substr(0, end));
  std::string line;
  std::vector<Element> elements;
  bool format_ok = false;
  std::getline(in, line);
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    if (kw.empty() || kw == "comment" || kw == "obj_info") continue;
    if (kw == "format") {
      std::string f, v;
      ls >> f >> v;
      if (f != "binary_little_endian")
        throw Error(source, "compressed PLY must be binary_little_endian, not '" + f + "'");
      format_ok = true;
    } else if (kw == "element") {
      Element e;
      long long n = -1;
      ls >> e.name >> n;
      if (!ls || n < 0) throw Error(source, "bad PLY element line: '" + line + "'");
      e.count = size_t(n);
      elements.push_back(e);
    } else if (kw == "property") {
      if (elements.empty()) throw Error(source, "PLY property before any element");
      Property p;
      ls >> p.type >> p.name;
      if (p.type == "list") throw Error(source, "unexpected list property in a compressed PLY");
      const size_t ts = type_size(p.type);
      if (!ts) throw Error(source, "unknown PLY property type '" + p.type + "'");
      Element& e = elements.back();
      p.offset = e.stride;
      e.stride += ts;
      e.props.push_back(p);
    } else {
      throw Error(source, "unexpected PLY header line: '" + line + "'");
    }
  }
  if (!format_ok) throw Error(source, "PLY header has no format line");
  size_t at = body;
  for (auto& e : elements) {
    e.start = at;
    if (e.stride && e.count > (size - std::min(at, size)) / e.stride)
      throw Error(source, "truncated compressed PLY: element '" + e.name + "' (" + std::to_string(e.count) +
                              " rows) runs past the end of the file");
    at += e.count * e.stride;
  }
  return elements;
}

float rd_f32(const uint8_t* p) {
  uint32_t u = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}
uint32_t rd_u32(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }

float unorm(uint32_t v, int bits) { return float(v & ((1u << bits) - 1)) / float((1u << bits) - 1); }
uint32_t pack_unorm(double t, int bits) {
  const double m = double((1u << bits) - 1);
  return uint32_t(std::clamp(std::floor(t * m + 0.5), 0.0, m));
}
float lerp(float a, float b, float t) { return a * (1 - t) + b * t; }

const Element* find_element(const std::vector<Element>& es, const std::string& n) {
  for (const auto& e : es)
    if (e.name == n) return &e;
  return nullptr;
}

uint64_t spread3(uint32_t v) {  // 21 bits -> every third bit
  uint64_t x = v & 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

}  // namespace

bool is_compressed_ply(const uint8_t* data, size_t size) {
  if (size < 4 || std::memcmp(data, "ply", 3) != 0) return false;
  const std::string head(reinterpret_cast<const char*>(data), std::min<size_t>(size, 1 << 16));
  const size_t end = head.find("end_header");
  return end != std::string::npos && head.substr(0, end).find("packed_position") != std::string::npos;
}

GaussianScene parse_compressed_ply(const uint8_t* data, size_t size, const std::string& source) {
  size_t body = 0;
  const std::vector<Element> es = parse_header(data, size, source, body);
  const Element* chunk = find_element(es, "chunk");
  const Element* vert = find_element(es, "vertex");
  const Element* shel = find_element(es, "sh");
  if (!chunk || !vert) throw Error(source, "compressed PLY needs 'chunk' and 'vertex' elements");
  for (const auto& e : es)
    if (e.name != "chunk" && e.name != "vertex" && e.name != "sh")
      throw Error(source, "unexpected element '" + e.name + "' in a compressed PLY");
  const size_t n = vert->count;
  if (n == 0) throw Error(source, "compressed PLY holds no Gaussians");
  if (chunk->count != (n + kChunk - 1) / kChunk)
    throw Error(source, "compressed PLY has " + std::to_string(chunk->count) + " chunks for " + std::to_string(n) +
                            " Gaussians (expected " + std::to_string((n + kChunk - 1) / kChunk) + ")");
  std::vector<const Property*> cp, cc, vp;
  for (const char* name : kChunkProps) {
    const Property* p = chunk->find(name);
    if (!p || p->type.rfind("float", 0) != 0 || type_size(p->type) != 4)
      throw Error(source, std::string("compressed PLY chunk element lacks float property ") + name);
    cp.push_back(p);
  }
  for (const char* name : kColorProps) cc.push_back(chunk->find(name));
  const bool chunk_colors = cc[0] != nullptr;
  for (const Property* p : cc)
    if ((p != nullptr) != chunk_colors || (p && type_size(p->type) != 4))
      throw Error(source, "compressed PLY chunk colour ranges are incomplete");
  for (const char* name : kVertexProps) {
    const Property* p = vert->find(name);
    if (!p || type_size(p->type) != 4 || p->type == "float" || p->type == "float32")
      throw Error(source, std::string("compressed PLY vertex element lacks uint property ") + name);
    vp.push_back(p);
  }
  int degree = 0;
  if (shel) {
    const size_t k = shel->props.size();
    degree = k == 9 ? 1 : k == 24 ? 2 : k == 45 ? 3 : -1;
    if (degree < 0) throw Error(source, "compressed PLY sh element has " + std::to_string(k) + " properties (9, 24 or 45)");
    if (shel->count != n) throw Error(source, "compressed PLY sh element count differs from the vertex count");
    if (shel->stride != k) throw Error(source, "compressed PLY sh properties must be uchar");
  }
  GaussianScene s;
  s.resize(n, degree);
  const int K = s.coeffs();
  const float norm = std::sqrt(2.0f);
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* c = data + chunk->start + (i / kChunk) * chunk->stride;
    float r[12];
    for (int k = 0; k < 12; ++k) r[k] = rd_f32(c + cp[k]->offset);
    const uint8_t* v = data + vert->start + i * vert->stride;
    const uint32_t pp = rd_u32(v + vp[0]->offset), pr = rd_u32(v + vp[1]->offset), ps = rd_u32(v + vp[2]->offset),
                   pc = rd_u32(v + vp[3]->offset);
    const float t[3] = {unorm(pp >> 21, 11), unorm(pp >> 11, 10), unorm(pp, 11)};
    const float u[3] = {unorm(ps >> 21, 11), unorm(ps >> 11, 10), unorm(ps, 11)};
    for (int a = 0; a < 3; ++a) {
      s.positions[3 * i + a] = lerp(r[a], r[3 + a], t[a]);
      s.scales[3 * i + a] = lerp(r[6 + a], r[9 + a], u[a]);
    }
    float* sh = s.sh_of(i);
    for (int ch = 0; ch < 3; ++ch) {
      float col = unorm(pc >> (24 - 8 * ch), 8);
      if (chunk_colors) col = lerp(rd_f32(c + cc[ch]->offset), rd_f32(c + cc[3 + ch]->offset), col);
      sh[ch] = (col - 0.5f) / kShC0;
    }
    // Alpha bytes 0 and 255 would be infinite logits: read them half a step inside.
    const float al = std::clamp(float(pc & 255u), 0.5f, 254.5f) / 255.0f;
    s.opacity[i] = std::log(al / (1.0f - al));
    // Rotation components in PLY order (rot_0..rot_3 = w x y z).
    const float a0 = (unorm(pr >> 20, 10) - 0.5f) * norm, a1 = (unorm(pr >> 10, 10) - 0.5f) * norm,
                a2 = (unorm(pr, 10) - 0.5f) * norm;
    const float m = std::sqrt(std::max(0.0f, 1.0f - (a0 * a0 + a1 * a1 + a2 * a2)));
    const float others[3] = {a0, a1, a2};
    const int largest = int(pr >> 30);
    for (int k = 0, j = 0; k < 4; ++k) s.rotations[4 * i + k] = (k == largest) ? m : others[j++];
    if (shel) {
      const uint8_t* b = data + shel->start + i * shel->stride;
      const int per = K - 1;
      // f_rest_j is channel-major: j = channel * per + coefficient.
      for (const Property& p : shel->props) {
        int j = -1;
        if (std::sscanf(p.name.c_str(), "f_rest_%d", &j) != 1 || j < 0 || j >= 3 * per)
          throw Error(source, "unexpected sh property '" + p.name + "'");
        const uint8_t q = b[p.offset];
        const float nv = q == 0 ? 0.0f : q == 255 ? 1.0f : (float(q) + 0.5f) / 256.0f;
        sh[3 * (1 + j % per) + j / per] = (nv - 0.5f) * 8.0f;
      }
    }
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(s.positions[3 * i + a]) || !std::isfinite(s.scales[3 * i + a]))
        throw Error(source, "Gaussian " + std::to_string(i) + " has a non-finite chunk range");
    for (int ch = 0; ch < 3; ++ch)
      if (!std::isfinite(sh[ch])) throw Error(source, "Gaussian " + std::to_string(i) + " has a non-finite colour range");
  }
  return s;
}

std::vector<uint8_t> serialize_compressed_ply(const GaussianScene& scene, bool spatial_order,
                                              std::vector<uint32_t>* order_out, std::vector<std::string>* notes) {
  scene.validate("compressed PLY output");
  const size_t n = scene.size();
  if (n == 0) throw Error("compressed PLY output", "the scene has no Gaussians");
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  if (spatial_order) {
    Vec3 lo, hi;
    scene.bounds(lo, hi);
    const double ext[3] = {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}, l0[3] = {lo.x, lo.y, lo.z};
    std::vector<uint64_t> code(n);
    for (size_t i = 0; i < n; ++i) {
      uint64_t c = 0;
      for (int a = 0; a < 3; ++a) {
        const double t = ext[a] > 0 ? (scene.positions[3 * i + a] - l0[a]) / ext[a] : 0.0;
        c |= spread3(uint32_t(std::clamp(t, 0.0, 1.0) * 2097151.0)) << (2 - a);
      }
      code[i] = c;
    }
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return code[a] < code[b]; });
    if (notes) notes->push_back("compressed PLY: Gaussians written in Morton order of their centres (as SuperSplat does)");
  }
  const int degree = scene.sh_degree, K = scene.coeffs(), per = K - 1;
  std::ostringstream h;
  const size_t chunks = (n + kChunk - 1) / kChunk;
  h << "ply\nformat binary_little_endian 1.0\ncomment written by isegman\n";
  h << "element chunk " << chunks << "\n";
  for (const char* p : kChunkProps) h << "property float " << p << "\n";
  for (const char* p : kColorProps) h << "property float " << p << "\n";
  h << "element vertex " << n << "\n";
  for (const char* p : kVertexProps) h << "property uint " << p << "\n";
  if (degree > 0) {
    h << "element sh " << n << "\n";
    for (int j = 0; j < 3 * per; ++j) h << "property uchar f_rest_" << j << "\n";
  }
  h << "end_header\n";
  const std::string hs = h.str();
  std::vector<uint8_t> out(hs.begin(), hs.end());
  const size_t chunk_at = out.size(), vert_at = chunk_at + chunks * 18 * 4, sh_at = vert_at + n * 16;
  out.resize(sh_at + (degree > 0 ? n * 3 * per : 0));
  auto put_f = [&](size_t at, float v) { std::memcpy(out.data() + at, &v, 4); };  // little-endian host
  auto put_u = [&](size_t at, uint32_t v) {
    for (int b = 0; b < 4; ++b) out[at + b] = uint8_t(v >> (8 * b));
  };
  size_t clamped_sh = 0;
  for (size_t c = 0; c < chunks; ++c) {
    const size_t b = c * kChunk, e = std::min(n, b + kChunk);
    float mn[9], mx[9];  // position, log-scale (clamped to +-20 as SuperSplat), colour
    std::fill(mn, mn + 9, INFINITY);
    std::fill(mx, mx + 9, -INFINITY);
    auto value = [&](size_t i, int k) -> float {
      if (k < 3) return scene.positions[3 * i + k];
      if (k < 6) return std::clamp(scene.scales[3 * i + k - 3], -20.0f, 20.0f);
      return sh_dc_to_rgb(scene.sh_of(i)[k - 6]);
    };
    for (size_t j = b; j < e; ++j)
      for (int k = 0; k < 9; ++k) {
        const float v = value(order[j], k);
        mn[k] = std::min(mn[k], v);
        mx[k] = std::max(mx[k], v);
      }
    const size_t at = chunk_at + c * 18 * 4;
    for (int a = 0; a < 3; ++a) {
      put_f(at + 4 * a, mn[a]);
      put_f(at + 4 * (3 + a), mx[a]);
      put_f(at + 4 * (6 + a), mn[3 + a]);
      put_f(at + 4 * (9 + a), mx[3 + a]);
      put_f(at + 4 * (12 + a), mn[6 + a]);
      put_f(at + 4 * (15 + a), mx[6 + a]);
    }
    auto frac = [&](float v, int k) { return mx[k] > mn[k] ? (double(v) - mn[k]) / (double(mx[k]) - mn[k]) : 0.0; };
    for (size_t j = b; j < e; ++j) {
      const size_t i = order[j];
      const uint32_t pp = pack_unorm(frac(value(i, 0), 0), 11) << 21 | pack_unorm(frac(value(i, 1), 1), 10) << 11 |
                          pack_unorm(frac(value(i, 2), 2), 11);
      const uint32_t ps = pack_unorm(frac(value(i, 3), 3), 11) << 21 | pack_unorm(frac(value(i, 4), 4), 10) << 11 |
                          pack_unorm(frac(value(i, 5), 5), 11);
      const double alpha = sigmoid(double(scene.opacity[i]));
      const uint32_t pc = pack_unorm(frac(value(i, 6), 6), 8) << 24 | pack_unorm(frac(value(i, 7), 7), 8) << 16 |
                          pack_unorm(frac(value(i, 8), 8), 8) << 8 | pack_unorm(alpha, 8);
      const Quat q = scene.rotation(i).normalized();
      double qv[4] = {q.w, q.x, q.y, q.z};
      int largest = 0;
      for (int k = 1; k < 4; ++k)
        if (std::fabs(qv[k]) > std::fabs(qv[largest])) largest = k;
      if (qv[largest] < 0)
        for (double& x : qv) x = -x;  // -q is the same rotation: make the largest positive
      uint32_t pr = uint32_t(largest);
      for (int k = 0; k < 4; ++k)
        if (k != largest) pr = pr << 10 | pack_unorm(qv[k] / std::sqrt(2.0) + 0.5, 10);
      const size_t va = vert_at + j * 16;
      put_u(va, pp);
      put_u(va + 4, pr);
      put_u(va + 8, ps);
      put_u(va + 12, pc);
      if (degree > 0) {
        const float* sh = scene.sh_of(i);
        for (int ch = 0; ch < 3; ++ch)
          for (int k = 0; k < per; ++k) {
            const double nv = double(sh[3 * (k + 1) + ch]) / 8.0 + 0.5;
            if (nv < 0 || nv > 1) ++clamped_sh;
            out[sh_at + j * 3 * per + ch * per + k] = uint8_t(std::clamp(std::floor(nv * 256.0), 0.0, 255.0));
          }
      }
    }
  }
  if (notes) {
    if (clamped_sh) notes->push_back("compressed PLY: " + std::to_string(clamped_sh) + " SH coefficients outside [-4, 4] were clamped");
    if (!scene.extras.empty()) notes->push_back("compressed PLY has no room for extra properties: they were dropped");
  }
  if (order_out) *order_out = std::move(order);
  return out;
}

}  // namespace isegman
