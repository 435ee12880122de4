#include "io/ply.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"
#include "io/atomic_file.h"
#include "io/mapped_file.h"

namespace isegman {
namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool parse_type(const std::string& s, PlyType& t, int& size) {
  static const std::map<std::string, std::pair<PlyType, int>> types = {
      {"char", {PlyType::Int8, 1}},     {"int8", {PlyType::Int8, 1}},       {"uchar", {PlyType::UInt8, 1}},
      {"uint8", {PlyType::UInt8, 1}},   {"short", {PlyType::Int16, 2}},     {"int16", {PlyType::Int16, 2}},
      {"ushort", {PlyType::UInt16, 2}}, {"uint16", {PlyType::UInt16, 2}},   {"int", {PlyType::Int32, 4}},
      {"int32", {PlyType::Int32, 4}},   {"uint", {PlyType::UInt32, 4}},     {"uint32", {PlyType::UInt32, 4}},
      {"float", {PlyType::Float32, 4}}, {"float32", {PlyType::Float32, 4}}, {"double", {PlyType::Float64, 8}},
      {"float64", {PlyType::Float64, 8}}};
  auto it = types.find(s);
  if (it == types.end()) return false;
  t = it->second.first;
  size = it->second.second;
  return true;
}

struct Property {
  std::string name, type_name;
  PlyType type = PlyType::Float32;
  int size = 4;
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;
  int count_size = 1;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
};

enum class Format { Ascii, BinaryLE, BinaryBE };

// Reads one scalar of `t` from raw bytes as double (byte-swapping for big endian).
double load_scalar(const uint8_t* p, PlyType t, bool swap) {
  uint8_t b[8];
  int n = 1;
  switch (t) {
    case PlyType::Int8: case PlyType::UInt8: n = 1; break;
    case PlyType::Int16: case PlyType::UInt16: n = 2; break;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: n = 4; break;
    case PlyType::Float64: n = 8; break;
  }
  for (int i = 0; i < n; ++i) b[i] = swap ? p[n - 1 - i] : p[i];
  switch (t) {
    case PlyType::Int8: return double(int8_t(b[0]));
    case PlyType::UInt8: return double(b[0]);
    case PlyType::Int16: { int16_t v; std::memcpy(&v, b, 2); return v; }
    case PlyType::UInt16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
    case PlyType::Int32: { int32_t v; std::memcpy(&v, b, 4); return v; }
    case PlyType::UInt32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
    case PlyType::Float32: { float v; std::memcpy(&v, b, 4); return v; }
    case PlyType::Float64: { double v; std::memcpy(&v, b, 8); return v; }
  }
  return 0;
}

// Stores `v` as type `t` in little-endian bytes (for extras read from ASCII/BE files).
void store_scalar(double v, PlyType t, uint8_t* out) {
  switch (t) {
    case PlyType::Int8: { int8_t x = int8_t(v); std::memcpy(out, &x, 1); break; }
    case PlyType::UInt8: { uint8_t x = uint8_t(v); std::memcpy(out, &x, 1); break; }
    case PlyType::Int16: { int16_t x = int16_t(v); std::memcpy(out, &x, 2); break; }
    case PlyType::UInt16: { uint16_t x = uint16_t(v); std::memcpy(out, &x, 2); break; }
    case PlyType::Int32: { int32_t x = int32_t(v); std::memcpy(out, &x, 4); break; }
    case PlyType::UInt32: { uint32_t x = uint32_t(v); std::memcpy(out, &x, 4); break; }
    case PlyType::Float32: { float x = float(v); std::memcpy(out, &x, 4); break; }
    case PlyType::Float64: { std::memcpy(out, &v, 8); break; }
  }
}

// Where each vertex property goes in the scene.
enum class Target { Position, Normal, Dc, Rest, Opacity, Scale, Rot, Extra, Dropped };
struct Slot {
  Target target = Target::Dropped;
  int index = 0;  // component / coefficient / extra index
};

bool parse_indexed(const std::string& name, const std::string& prefix, int& index) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return false;
  const char* b = name.data() + prefix.size();
  const char* e = name.data() + name.size();
  auto r = std::from_chars(b, e, index);
  return r.ec == std::errc() && r.ptr == e && index >= 0;
}

class AsciiTokens {
 public:
  AsciiTokens(const uint8_t* p, const uint8_t* end, const std::string& src) : p_(p), end_(end), src_(src) {}
  double next(const char* what) {
    while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\n' || *p_ == '\r')) ++p_;
    if (p_ >= end_) throw Error(src_, std::string("truncated ASCII data while reading ") + what);
    const uint8_t* start = p_;
    while (p_ < end_ && !(*p_ == ' ' || *p_ == '\t' || *p_ == '\n' || *p_ == '\r')) ++p_;
    std::string tok(reinterpret_cast<const char*>(start), size_t(p_ - start));
    char* endp = nullptr;
    double v = std::strtod(tok.c_str(), &endp);
    if (tok.empty() || *endp != '\0') throw Error(src_, "'" + tok + "' is not a number (reading " + what + ")");
    return v;
  }

 private:
  const uint8_t* p_;
  const uint8_t* end_;
  const std::string& src_;
};

}  // namespace

GaussianScene parse_ply(const uint8_t* data, size_t size, const std::string& src, PlyReadReport* report,
                        const std::function<void(size_t, size_t)>& parsed) {
  // ---- header ----
  size_t pos = 0;
  auto next_line = [&](std::string& line) -> bool {
    if (pos >= size) return false;
    size_t e = pos;
    while (e < size && data[e] != '\n') ++e;
    if (e >= size) return false;  // the header must end with a newline
    line.assign(reinterpret_cast<const char*>(data + pos), e - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = e + 1;
    return true;
  };
  std::string line;
  if (size < 4 || std::memcmp(data, "ply", 3) != 0 || !next_line(line) || line != "ply")
    throw Error(src, "not a PLY file (missing 'ply' magic line)");
  Format format = Format::BinaryLE;
  bool have_format = false, have_end = false;
  std::vector<Element> elements;
  while (next_line(line)) {
    if (pos > (1u << 20)) break;
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    if (kw.empty() || kw == "comment" || kw == "obj_info") continue;
    if (kw == "format") {
      std::string f, ver;
      ls >> f >> ver;
      if (f == "ascii") format = Format::Ascii;
      else if (f == "binary_little_endian") format = Format::BinaryLE;
      else if (f == "binary_big_endian") format = Format::BinaryBE;
      else throw Error(src, "unknown PLY format '" + f + "'");
      have_format = true;
    } else if (kw == "element") {
      Element e;
      std::string count;
      ls >> e.name >> count;
      auto r = std::from_chars(count.data(), count.data() + count.size(), e.count);
      if (e.name.empty() || r.ec != std::errc() || r.ptr != count.data() + count.size())
        throw Error(src, "malformed element line '" + line + "'");
      elements.push_back(e);
    } else if (kw == "property") {
      if (elements.empty()) throw Error(src, "property before any element: '" + line + "'");
      Property p;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, vt;
        ls >> ct >> vt >> p.name;
        p.is_list = true;
        if (!parse_type(ct, p.count_type, p.count_size) || !parse_type(vt, p.type, p.size) ||
            p.count_type == PlyType::Float32 || p.count_type == PlyType::Float64)
          throw Error(src, "bad list property types in '" + line + "'");
        p.type_name = vt;
      } else {
        ls >> p.name;
        if (!parse_type(t, p.type, p.size)) throw Error(src, "unknown property type '" + t + "' in '" + line + "'");
        p.type_name = t;
      }
      if (p.name.empty()) throw Error(src, "property without a name: '" + line + "'");
      for (const auto& q : elements.back().props)
        if (q.name == p.name) throw Error(src, "duplicate property '" + p.name + "'");
      elements.back().props.push_back(p);
    } else if (kw == "end_header") {
      have_end = true;
      break;
    } else {
      throw Error(src, "unexpected header line '" + line + "'");
    }
  }
  if (!have_end) throw Error(src, "PLY header has no end_header line (truncated or not a PLY file)");
  if (!have_format) throw Error(src, "PLY header has no format line");

  size_t vi = elements.size();
  for (size_t i = 0; i < elements.size(); ++i)
    if (elements[i].name == "vertex") { vi = i; break; }
  if (vi == elements.size()) throw Error(src, "no 'vertex' element: not a Gaussian splat PLY");
  const Element& vert = elements[vi];
  if (vert.count == 0) throw Error(src, "the vertex element is empty: the scene has no Gaussians");

  // ---- map properties ----
  std::vector<Slot> slots(vert.props.size());
  int rest_count = 0;
  bool seen_pos[3] = {}, seen_nrm[3] = {}, seen_dc[3] = {}, seen_scale[3] = {}, seen_rot[4] = {}, seen_op = false;
  std::vector<int> rest_seen;
  GaussianScene scene;
  std::vector<const Property*> extra_props;
  for (size_t k = 0; k < vert.props.size(); ++k) {
    const Property& p = vert.props[k];
    Slot s;
    int idx = 0;
    if (p.name == "x" || p.name == "y" || p.name == "z") { s = {Target::Position, p.name[0] - 'x'}; seen_pos[s.index] = true; }
    else if (p.name == "nx" || p.name == "ny" || p.name == "nz") { s = {Target::Normal, p.name[1] - 'x'}; seen_nrm[s.index] = true; }
    else if (parse_indexed(p.name, "f_dc_", idx) && idx < 3) { s = {Target::Dc, idx}; seen_dc[idx] = true; }
    else if (parse_indexed(p.name, "f_rest_", idx)) { s = {Target::Rest, idx}; rest_seen.push_back(idx); ++rest_count; }
    else if (p.name == "opacity") { s = {Target::Opacity, 0}; seen_op = true; }
    else if (parse_indexed(p.name, "scale_", idx) && idx < 3) { s = {Target::Scale, idx}; seen_scale[idx] = true; }
    else if (parse_indexed(p.name, "rot_", idx) && idx < 4) { s = {Target::Rot, idx}; seen_rot[idx] = true; }
    else if (p.is_list) {
      s = {Target::Dropped, 0};
      if (report) report->notes.push_back("dropped list property '" + p.name + "' (per-vertex lists are not kept)");
    } else {
      s = {Target::Extra, int(extra_props.size())};
      extra_props.push_back(&p);
    }
    if (s.target != Target::Extra && s.target != Target::Dropped) {
      if (p.is_list) throw Error(src, "property '" + p.name + "' is a list; expected a float scalar");
      if (p.type != PlyType::Float32 && p.type != PlyType::Float64)
        throw Error(src, "property '" + p.name + "' has type " + p.type_name + "; expected float");
    }
    slots[k] = s;
  }
  auto require = [&](const bool* seen, int n, const char* names) {
    for (int i = 0; i < n; ++i)
      if (!seen[i]) throw Error(src, std::string("missing required properties ") + names + ": not a 3DGS PLY");
  };
  require(seen_pos, 3, "x, y, z");
  require(seen_dc, 3, "f_dc_0..2");
  require(&seen_op, 1, "opacity");
  require(seen_scale, 3, "scale_0..2");
  require(seen_rot, 4, "rot_0..3");
  const bool have_normals = seen_nrm[0] && seen_nrm[1] && seen_nrm[2];
  if (!have_normals && (seen_nrm[0] || seen_nrm[1] || seen_nrm[2]))
    throw Error(src, "incomplete normals: need all of nx, ny, nz or none");
  int degree = -1;
  for (int d = 0; d <= 3; ++d)
    if (rest_count == 3 * (sh_coeff_count(d) - 1)) degree = d;
  if (degree < 0)
    throw Error(src, std::to_string(rest_count) + " f_rest_* properties: expected 0, 9, 24 or 45 (SH degree 0..3)");
  std::sort(rest_seen.begin(), rest_seen.end());
  for (int i = 0; i < rest_count; ++i)
    if (rest_seen[i] != i) throw Error(src, "f_rest_* properties are not numbered 0.." + std::to_string(rest_count - 1));

  // ---- sizes: refuse counts the file cannot hold before allocating anything ----
  const bool binary = format != Format::Ascii;
  const bool swap = format == Format::BinaryBE;
  bool fixed_stride = true;
  size_t stride = 0;
  for (const auto& p : vert.props) {
    if (p.is_list) fixed_stride = false;
    stride += p.size;
  }
  const size_t remaining = size - pos;
  const size_t min_row = binary ? std::max<size_t>(stride, 1) : 2 * vert.props.size();
  if (vert.count > remaining / min_row + 1)
    throw Error(src, "truncated: header declares " + std::to_string(vert.count) + " Gaussians but only " +
                         std::to_string(remaining) + " bytes of data follow");
  const size_t n = size_t(vert.count);
  scene.resize(n, degree);
  if (have_normals) scene.normals.assign(3 * n, 0.f);
  for (const Property* p : extra_props) {
    ExtraProperty e;
    e.name = p->name;
    e.type = p->type_name;
    e.size = p->size;
    e.data.assign(n * p->size, 0);
    scene.extras.push_back(std::move(e));
  }
  const int rest_per_channel = sh_coeff_count(degree) - 1;
  const int K = sh_coeff_count(degree);

  auto store = [&](size_t i, const Slot& s, double v) {
    switch (s.target) {
      case Target::Position: scene.positions[3 * i + s.index] = float(v); break;
      case Target::Normal: scene.normals[3 * i + s.index] = float(v); break;
      case Target::Dc: scene.sh[(i * K) * 3 + s.index] = float(v); break;
      case Target::Rest: {
        // f_rest is channel-major: index = channel * (K-1) + (coefficient-1).
        int channel = s.index / rest_per_channel, coeff = 1 + s.index % rest_per_channel;
        scene.sh[(i * K + coeff) * 3 + channel] = float(v);
        break;
      }
      case Target::Opacity: scene.opacity[i] = float(v); break;
      case Target::Scale: scene.scales[3 * i + s.index] = float(v); break;
      case Target::Rot: scene.rotations[4 * i + s.index] = float(v); break;
      default: break;
    }
  };

  // ---- data ----
  const uint8_t* p = data + pos;
  const uint8_t* end = data + size;
  if (binary) {
    // Skip elements stored before the vertices (a count the file cannot hold is refused
    // before walking it, and elements without properties take no bytes at all).
    auto skip_element = [&](size_t e) {
      if (elements[e].props.empty()) return;
      size_t min_record = 0;
      for (const auto& q : elements[e].props) min_record += q.is_list ? q.count_size : q.size;
      if (elements[e].count > uint64_t(end - p) / min_record)
        throw Error(src, "truncated: element '" + elements[e].name + "' declares " + std::to_string(elements[e].count) +
                             " rows, more than the file holds");
      for (uint64_t r = 0; r < elements[e].count; ++r)
        for (const auto& q : elements[e].props) {
          if (q.is_list) {
            if (end - p < q.count_size) throw Error(src, "truncated in element '" + elements[e].name + "'");
            double c = load_scalar(p, q.count_type, swap);
            p += q.count_size;
            if (c < 0 || c * q.size > double(end - p)) throw Error(src, "truncated in element '" + elements[e].name + "'");
            p += size_t(c) * q.size;
          } else {
            if (end - p < q.size) throw Error(src, "truncated in element '" + elements[e].name + "'");
            p += q.size;
          }
        }
    };
    for (size_t e = 0; e < vi; ++e) skip_element(e);
    if (fixed_stride && size_t(end - p) < n * stride)
      throw Error(src, "truncated: expected " + std::to_string(n * stride) + " bytes of Gaussian data, found " +
                           std::to_string(end - p));
    // Fixed-size records (the usual case): in parallel, in blocks of rows, each block's
    // bytes handed to `parsed` once it is stored.
    auto store_row = [&](size_t i, const uint8_t* row) {
      for (size_t k = 0; k < vert.props.size(); ++k) {
        const Property& q = vert.props[k];
        const Slot& s = slots[k];
        if (s.target == Target::Extra) {
          uint8_t* dst = scene.extras[s.index].data.data() + i * q.size;
          for (int b = 0; b < q.size; ++b) dst[b] = swap ? row[q.size - 1 - b] : row[b];
        } else if (q.type == PlyType::Float32 && !swap) {
          float v;
          std::memcpy(&v, row, 4);  // float -> double -> float is exact
          store(i, s, v);
        } else {
          store(i, s, load_scalar(row, q.type, swap));
        }
        row += q.size;
      }
    };
    if (fixed_stride) {
      const uint8_t* base = p;
      parallel_chunks(n, 65536, 0, [&](size_t, size_t a, size_t e) {
        for (size_t i = a; i < e; ++i) store_row(i, base + i * stride);
        if (parsed) parsed(size_t(base - data) + a * stride, (e - a) * stride);
      });
      p = base + n * stride;
    }
    for (size_t i = 0; i < n && !fixed_stride; ++i) {
      for (size_t k = 0; k < vert.props.size(); ++k) {
        const Property& q = vert.props[k];
        if (q.is_list) {
          if (end - p < q.count_size) throw Error(src, "truncated at Gaussian " + std::to_string(i));
          double c = load_scalar(p, q.count_type, swap);
          p += q.count_size;
          if (c < 0 || c * q.size > double(end - p)) throw Error(src, "truncated at Gaussian " + std::to_string(i));
          p += size_t(c) * q.size;
          continue;
        }
        if (end - p < q.size) throw Error(src, "truncated at Gaussian " + std::to_string(i));
        const Slot& s = slots[k];
        if (s.target == Target::Extra) {
          uint8_t* dst = scene.extras[s.index].data.data() + i * q.size;
          for (int b = 0; b < q.size; ++b) dst[b] = swap ? p[q.size - 1 - b] : p[b];
        } else if (q.type == PlyType::Float32 && !swap) {
          float v;
          std::memcpy(&v, p, 4);  // float -> double -> float is exact
          store(i, s, v);
        } else {
          store(i, s, load_scalar(p, q.type, swap));
        }
        p += q.size;
      }
    }
    for (size_t e = vi + 1; e < elements.size(); ++e) skip_element(e);
    // Bytes after the last element are not part of any PLY: a corrupt or concatenated file.
    if (p != end)
      throw Error(src, std::to_string(end - p) + " trailing bytes after the end of the PLY data (the header "
                       "declares " + std::to_string(n) + " Gaussians); the file is corrupt or has data appended");
  } else {
    AsciiTokens tok(p, end, src);
    // Skip elements stored before the vertices (each ASCII value takes at least 2 bytes).
    for (size_t e = 0; e < vi; ++e) {
      if (elements[e].props.empty()) continue;
      if (elements[e].count > uint64_t(end - p) / (2 * elements[e].props.size()))
        throw Error(src, "truncated: element '" + elements[e].name + "' declares " + std::to_string(elements[e].count) +
                             " rows, more than the file holds");
      for (uint64_t r = 0; r < elements[e].count; ++r)
        for (const auto& q : elements[e].props) {
          if (q.is_list) {
            double c = tok.next("a list count");
            if (c < 0 || c > 1e9) throw Error(src, "bad list count");
            for (size_t j = 0; j < size_t(c); ++j) tok.next("a list item");
          } else {
            tok.next(elements[e].name.c_str());
          }
        }
    }
    for (size_t i = 0; i < n; ++i)
      for (size_t k = 0; k < vert.props.size(); ++k) {
        const Property& q = vert.props[k];
        if (q.is_list) {
          double c = tok.next("a list count");
          if (c < 0 || c > 1e9) throw Error(src, "bad list count at Gaussian " + std::to_string(i));
          for (size_t j = 0; j < size_t(c); ++j) tok.next("a list item");
          continue;
        }
        double v = tok.next(q.name.c_str());
        const Slot& s = slots[k];
        if (s.target == Target::Extra) store_scalar(v, q.type, scene.extras[s.index].data.data() + i * q.size);
        else store(i, s, v);
      }
  }
  scene.validate(src);
  if (report && !have_normals) report->notes.push_back("no normals in the file (they are optional and unused)");
  return scene;
}

GaussianScene read_ply(const std::string& path, PlyReadReport* report) {
  // Mapped, not read: the parse drops what it has stored, so the file and the scene are
  // never both in memory.
  const MappedFile file(path);
  return parse_ply(file.data(), file.size(), path, report,
                   [&](size_t offset, size_t length) { file.release(offset, length); });
}

std::vector<uint8_t> serialize_ply(const GaussianScene& s) {
  const size_t n = s.size();
  const int K = s.coeffs();
  std::ostringstream h;
  h << "ply\nformat binary_little_endian 1.0\ncomment written by isegman\nelement vertex " << n << "\n";
  for (const char* name : {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"})
    h << "property float " << name << "\n";
  for (int i = 0; i < 3 * (K - 1); ++i) h << "property float f_rest_" << i << "\n";
  h << "property float opacity\n";
  for (int i = 0; i < 3; ++i) h << "property float scale_" << i << "\n";
  for (int i = 0; i < 4; ++i) h << "property float rot_" << i << "\n";
  size_t extra_bytes = 0;
  for (const auto& e : s.extras) {
    h << "property " << e.type << " " << e.name << "\n";
    extra_bytes += e.size;
  }
  h << "end_header\n";
  const std::string header = h.str();
  const size_t floats = 3 + 3 + 3 * K + 1 + 3 + 4;
  const size_t stride = floats * 4 + extra_bytes;
  std::vector<uint8_t> out(header.size() + n * stride);
  std::memcpy(out.data(), header.data(), header.size());
  uint8_t* row = out.data() + header.size();
  std::vector<float> rec(floats);
  for (size_t i = 0; i < n; ++i, row += stride) {
    size_t k = 0;
    for (int a = 0; a < 3; ++a) rec[k++] = s.positions[3 * i + a];
    for (int a = 0; a < 3; ++a) rec[k++] = s.normals.empty() ? 0.f : s.normals[3 * i + a];
    const float* sh = s.sh_of(i);
    for (int c = 0; c < 3; ++c) rec[k++] = sh[c];
    for (int c = 0; c < 3; ++c)
      for (int j = 1; j < K; ++j) rec[k++] = sh[3 * j + c];
    rec[k++] = s.opacity[i];
    for (int a = 0; a < 3; ++a) rec[k++] = s.scales[3 * i + a];
    for (int a = 0; a < 4; ++a) rec[k++] = s.rotations[4 * i + a];
    std::memcpy(row, rec.data(), floats * 4);
    uint8_t* ex = row + floats * 4;
    for (const auto& e : s.extras) {
      std::memcpy(ex, e.data.data() + i * e.size, e.size);
      ex += e.size;
    }
  }
  return out;
}

void write_ply(const std::string& path, const GaussianScene& scene) {
  if (scene.size() == 0) throw Error(path, "refusing to write a scene with no Gaussians (viewers cannot open it)");
  scene.validate(path);
  write_file_atomic(path, serialize_ply(scene));
}

}  // namespace isegman
