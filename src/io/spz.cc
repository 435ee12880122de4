#include "io/spz.h"

#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/sh.h"

namespace isegman {
namespace {

constexpr uint32_t kMagic = 0x5053474e;  // "NGSP" little-endian
constexpr float kColorScale = 0.15f;
constexpr uint8_t kFlagAntialiased = 0x1, kFlagExtensions = 0x2;
constexpr size_t kLegacyHeader = 16, kV4Header = 32;
// SPZ allows degree 4; isegman stops at 3.
constexpr int kShDim[5] = {0, 3, 8, 15, 24};

uint32_t le32(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }
uint64_t le64(const uint8_t* p) { return uint64_t(le32(p)) | uint64_t(le32(p + 4)) << 32; }
void put32(std::vector<uint8_t>& o, uint32_t v) {
  for (int i = 0; i < 4; ++i) o.push_back(uint8_t(v >> (8 * i)));
}
void put64(std::vector<uint8_t>& o, uint64_t v) {
  put32(o, uint32_t(v));
  put32(o, uint32_t(v >> 32));
}
uint8_t to_u8(float x) { return uint8_t(std::clamp(std::round(x), 0.0f, 255.0f)); }

// Sign of SH basis function k under (x, y, z) -> (x, -y, -z): +1 or -1. Taken from the
// basis itself so it cannot disagree with the renderer's convention.
const float* sh_flip_signs() {
  static float s[16];
  static bool init = [] {
    float a[16], b[16];
    const float x = 0.3f, y = 0.5f, z = 0.7f;  // any direction with no zero component
    sh_basis(3, x, y, z, a);
    sh_basis(3, x, -y, -z, b);
    for (int k = 0; k < 16; ++k) s[k] = (a[k] * b[k] < 0) ? -1.0f : 1.0f;
    return true;
  }();
  (void)init;
  return s;
}

float half_to_float(uint16_t h) {
  const int sign = h >> 15, exp = (h >> 10) & 31, mant = h & 1023;
  float v;
  if (exp == 0) v = std::ldexp(float(mant), -24);
  else if (exp == 31) v = mant ? NAN : INFINITY;
  else v = std::ldexp(float(mant | 1024), exp - 25);
  return sign ? -v : v;
}

// Inflates a gzip stream, refusing to grow past `limit` bytes.
std::vector<uint8_t> gunzip(const uint8_t* data, size_t size, size_t limit, const std::string& source) {
  z_stream zs{};
  if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) throw Error(source, "cannot start gzip decompression");
  std::vector<uint8_t> out;
  zs.next_in = const_cast<Bytef*>(data);
  zs.avail_in = uInt(std::min<size_t>(size, 0x7fffffff));
  int rc = Z_OK;
  uint8_t buf[65536];
  while (rc != Z_STREAM_END) {
    zs.next_out = buf;
    zs.avail_out = sizeof(buf);
    rc = inflate(&zs, Z_NO_FLUSH);
    if (rc != Z_OK && rc != Z_STREAM_END) {
      inflateEnd(&zs);
      throw Error(source, rc == Z_BUF_ERROR ? "truncated .spz: the gzip stream ends early"
                                            : "corrupt .spz: gzip data error");
    }
    out.insert(out.end(), buf, buf + (sizeof(buf) - zs.avail_out));
    if (out.size() > limit) {
      inflateEnd(&zs);
      throw Error(source, "corrupt .spz: decompressed data is larger than its header announces");
    }
  }
  inflateEnd(&zs);
  return out;
}

std::vector<uint8_t> gzip(const std::vector<uint8_t>& in) {
  z_stream zs{};
  if (deflateInit2(&zs, 9, Z_DEFLATED, 16 + MAX_WBITS, 9, Z_DEFAULT_STRATEGY) != Z_OK)
    throw Error("spz output", "cannot start gzip compression");
  std::vector<uint8_t> out(deflateBound(&zs, uLong(in.size())) + 64);
  zs.next_in = const_cast<Bytef*>(in.data());
  zs.avail_in = uInt(in.size());
  zs.next_out = out.data();
  zs.avail_out = uInt(out.size());
  const int rc = deflate(&zs, Z_FINISH);
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw Error("spz output", "gzip compression failed");
  out.resize(zs.total_out);
  return out;
}

// The attribute arrays of one file, before dequantisation.
struct Packed {
  uint32_t version = 0, n = 0;
  int sh_degree = 0, fractional_bits = 0;
  const uint8_t *pos = nullptr, *alpha = nullptr, *color = nullptr, *scale = nullptr, *rot = nullptr, *sh = nullptr;
};

size_t position_bytes(uint32_t version) { return version == 1 ? 6 : 9; }
size_t rotation_bytes(uint32_t version) { return version >= 3 ? 4 : 3; }

GaussianScene unpack(const Packed& p, const std::string& source, std::vector<std::string>* notes) {
  const int degree = std::min(p.sh_degree, 3);
  if (p.sh_degree > 3 && notes)
    notes->push_back(source + ": SH degree " + std::to_string(p.sh_degree) + " read as degree 3 (band 4 dropped)");
  const int dim = kShDim[p.sh_degree];
  const int keep = kShDim[degree];
  GaussianScene s;
  s.resize(p.n, degree);
  const int K = s.coeffs();
  const float* flip = sh_flip_signs();
  const float fixed_scale = 1.0f / float(1u << std::min(p.fractional_bits, 31));
  for (size_t i = 0; i < p.n; ++i) {
    float xyz[3];
    if (p.version == 1) {
      for (int a = 0; a < 3; ++a) {
        const uint8_t* h = p.pos + 6 * i + 2 * a;
        xyz[a] = half_to_float(uint16_t(h[0] | h[1] << 8));
      }
    } else {
      for (int a = 0; a < 3; ++a) {
        const uint8_t* q = p.pos + 9 * i + 3 * a;
        int32_t v = int32_t(q[0] | q[1] << 8 | q[2] << 16);
        if (v & 0x800000) v -= 0x1000000;  // sign-extend 24 bits
        xyz[a] = float(v) * fixed_scale;
      }
    }
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(xyz[a])) throw Error(source, "Gaussian " + std::to_string(i) + " has a non-finite position");
    }
    // RUB -> RDF.
    s.positions[3 * i] = xyz[0];
    s.positions[3 * i + 1] = -xyz[1];
    s.positions[3 * i + 2] = -xyz[2];
    for (int a = 0; a < 3; ++a) s.scales[3 * i + a] = float(p.scale[3 * i + a]) / 16.0f - 10.0f;
    // Alpha 0 and 255 would be infinite logits: read them half a step inside.
    const float al = std::clamp(float(p.alpha[i]), 0.5f, 254.5f) / 255.0f;
    s.opacity[i] = std::log(al / (1.0f - al));
    float* c = s.sh_of(i);
    for (int ch = 0; ch < 3; ++ch) c[ch] = (float(p.color[3 * i + ch]) / 255.0f - 0.5f) / kColorScale;
    const uint8_t* sh = p.sh + size_t(i) * dim * 3;
    for (int k = 0; k < keep; ++k)
      for (int ch = 0; ch < 3; ++ch) c[3 * (k + 1) + ch] = flip[k + 1] * (float(sh[3 * k + ch]) - 128.0f) / 128.0f;
    (void)K;
    // Rotation in SPZ order (x, y, z, w).
    float q[4];
    if (p.version >= 3) {
      uint32_t comp = le32(p.rot + 4 * i);
      const int largest = int(comp >> 30);
      float sum = 0;
      for (int k = 3; k >= 0; --k) {
        if (k == largest) continue;
        const uint32_t mag = comp & 511u, neg = (comp >> 9) & 1u;
        comp >>= 10;
        q[k] = float(M_SQRT1_2) * float(mag) / 511.0f * (neg ? -1.0f : 1.0f);
        sum += q[k] * q[k];
      }
      q[largest] = std::sqrt(std::max(0.0f, 1.0f - sum));
    } else {
      float sum = 0;
      for (int k = 0; k < 3; ++k) {
        q[k] = float(p.rot[3 * i + k]) / 127.5f - 1.0f;
        sum += q[k] * q[k];
      }
      q[3] = std::sqrt(std::max(0.0f, 1.0f - sum));
    }
    // RUB -> RDF: conjugating by the 180-degree turn about x negates y and z.
    s.rotations[4 * i] = q[3];
    s.rotations[4 * i + 1] = q[0];
    s.rotations[4 * i + 2] = -q[1];
    s.rotations[4 * i + 3] = -q[2];
  }
  return s;
}

// Bytes per Gaussian of each attribute, in file order.
void attribute_sizes(uint32_t version, int sh_degree, size_t sizes[6]) {
  sizes[0] = position_bytes(version);
  sizes[1] = 1;
  sizes[2] = 3;
  sizes[3] = 3;
  sizes[4] = rotation_bytes(version);
  sizes[5] = size_t(kShDim[sh_degree]) * 3;
}

GaussianScene parse_legacy(const uint8_t* data, size_t size, const std::string& source,
                           std::vector<std::string>* notes) {
  // Inflate the header first to bound the rest by what it announces.
  std::vector<uint8_t> head;
  {
    z_stream zs{};
    if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) throw Error(source, "cannot start gzip decompression");
    head.resize(kLegacyHeader);
    zs.next_in = const_cast<Bytef*>(data);
    zs.avail_in = uInt(std::min<size_t>(size, 0x7fffffff));
    zs.next_out = head.data();
    zs.avail_out = uInt(head.size());
    int rc = Z_OK;
    while (zs.avail_out > 0 && (rc == Z_OK)) rc = inflate(&zs, Z_NO_FLUSH);
    const size_t got = kLegacyHeader - zs.avail_out;
    inflateEnd(&zs);
    if (got < kLegacyHeader)
      throw Error(source, rc == Z_DATA_ERROR ? "corrupt .spz: gzip data error" : "truncated .spz: no complete 16-byte header");
  }
  if (le32(head.data()) != kMagic) throw Error(source, "not an .spz file: the gzip stream does not start with NGSP");
  Packed p;
  p.version = le32(head.data() + 4);
  p.n = le32(head.data() + 8);
  p.sh_degree = head[12];
  p.fractional_bits = head[13];
  const uint8_t flags = head[14];
  if (p.version < 1 || p.version > 3)
    throw Error(source, "unsupported .spz version " + std::to_string(p.version) + " in a gzip stream (expected 1-3)");
  if (p.sh_degree > 4) throw Error(source, "invalid .spz SH degree " + std::to_string(p.sh_degree) + " (0-4)");
  if (p.fractional_bits > 24) throw Error(source, "invalid .spz fractional bits " + std::to_string(p.fractional_bits));
  size_t sizes[6];
  attribute_sizes(p.version, p.sh_degree, sizes);
  size_t per = 0;
  for (size_t s : sizes) per += s;
  // Even a maximal zlib ratio (~1032:1) cannot announce more than this.
  if (p.n == 0) throw Error(source, ".spz holds no Gaussians");
  if (uint64_t(p.n) * per > uint64_t(size) * 1100 + (1u << 20))
    throw Error(source, "corrupt .spz: " + std::to_string(p.n) + " Gaussians cannot fit in " + std::to_string(size) + " bytes");
  const size_t payload = size_t(p.n) * per;
  // Extension records (flag 0x2) sit between the header and the attributes; up to 1 MiB.
  const size_t limit = kLegacyHeader + payload + ((flags & kFlagExtensions) ? (1u << 20) : 0) + 65536;
  const std::vector<uint8_t> raw = gunzip(data, size, limit, source);
  if (raw.size() < kLegacyHeader + payload)
    throw Error(source, "truncated .spz: " + std::to_string(raw.size()) + " bytes after decompression, " +
                            std::to_string(kLegacyHeader + payload) + " needed for " + std::to_string(p.n) + " Gaussians");
  size_t off = kLegacyHeader;
  if (flags & kFlagExtensions) {
    off = raw.size() - payload;
    if (notes) notes->push_back(source + ": .spz extension records ignored");
  } else if (raw.size() > kLegacyHeader + payload && notes) {
    notes->push_back(source + ": " + std::to_string(raw.size() - kLegacyHeader - payload) + " trailing bytes ignored");
  }
  const uint8_t* b = raw.data() + off;
  p.pos = b; b += p.n * sizes[0];
  p.alpha = b; b += p.n * sizes[1];
  p.color = b; b += p.n * sizes[2];
  p.scale = b; b += p.n * sizes[3];
  p.rot = b; b += p.n * sizes[4];
  p.sh = b;
  if ((flags & kFlagAntialiased) && notes) notes->push_back(source + ": trained with antialiasing (flag not kept)");
  return unpack(p, source, notes);
}

GaussianScene parse_v4(const uint8_t* data, size_t size, const std::string& source, std::vector<std::string>* notes) {
  if (size < kV4Header) throw Error(source, "truncated .spz: " + std::to_string(size) + " bytes, the v4 header needs 32");
  Packed p;
  p.version = le32(data + 4);
  p.n = le32(data + 8);
  p.sh_degree = data[12];
  p.fractional_bits = data[13];
  const uint8_t flags = data[14];
  const unsigned streams = data[15];
  const uint32_t toc = le32(data + 16);
  if (p.version < 4) throw Error(source, "corrupt .spz: an uncompressed NGSP header must be version 4 or later");
  if (p.version > 4) throw Error(source, "unsupported .spz version " + std::to_string(p.version) + " (reads 1-4)");
  if (p.sh_degree > 4) throw Error(source, "invalid .spz SH degree " + std::to_string(p.sh_degree) + " (0-4)");
  if (p.fractional_bits > 24) throw Error(source, "invalid .spz fractional bits " + std::to_string(p.fractional_bits));
  if (p.n == 0) throw Error(source, ".spz holds no Gaussians");
  size_t sizes[6];
  attribute_sizes(p.version, p.sh_degree, sizes);
  const unsigned needed = sizes[5] ? 6 : 5;
  if (streams < needed)
    throw Error(source, "corrupt .spz: " + std::to_string(streams) + " streams, " + std::to_string(needed) + " needed");
  // zstd cannot expand beyond 32768:1 (a 4-byte RLE block per 128 KiB), so the file size
  // bounds the positions stream (9 bytes a Gaussian) and with it what is allocated. (The
  // reference reader assumes 1024:1, which refuses scenes of identical Gaussians.)
  if (uint64_t(p.n) * 9 > uint64_t(size) * 32768 + 4096)
    throw Error(source, "corrupt .spz: " + std::to_string(p.n) + " Gaussians cannot fit in " + std::to_string(size) + " bytes");
  if (toc < kV4Header || toc > size || (size - toc) / 16 < streams)
    throw Error(source, "truncated .spz: the table of contents lies outside the file");
  if (flags & kFlagExtensions && toc > kV4Header && notes) notes->push_back(source + ": .spz extension records ignored");
  std::vector<std::vector<uint8_t>> out(6);
  size_t off = size_t(toc) + size_t(streams) * 16;
  for (unsigned k = 0; k < streams; ++k) {
    const uint64_t csize = le64(data + toc + 16 * k), usize = le64(data + toc + 16 * k + 8);
    if (csize > size - std::min(off, size) || off > size)
      throw Error(source, "truncated .spz: stream " + std::to_string(k) + " runs past the end of the file");
    if (k < 6) {
      const uint64_t want = uint64_t(p.n) * sizes[k];
      if (usize != want)
        throw Error(source, "corrupt .spz: stream " + std::to_string(k) + " holds " + std::to_string(usize) +
                                " bytes, " + std::to_string(want) + " expected for " + std::to_string(p.n) + " Gaussians");
      const unsigned long long declared = ZSTD_getFrameContentSize(data + off, size_t(csize));
      if (declared != ZSTD_CONTENTSIZE_UNKNOWN && declared != want)
        throw Error(source, "corrupt .spz: stream " + std::to_string(k) + " is not a zstd frame of " +
                                std::to_string(want) + " bytes");
      if (declared == ZSTD_CONTENTSIZE_UNKNOWN && want > uint64_t(csize) * 32768 + 4096)
        throw Error(source, "corrupt .spz: stream " + std::to_string(k) + " is too small for its size");
      out[k].resize(size_t(want));
      const size_t got = ZSTD_decompress(out[k].data(), out[k].size(), data + off, size_t(csize));
      if (ZSTD_isError(got) || got != want)
        throw Error(source, "corrupt .spz: stream " + std::to_string(k) + ": " +
                                (ZSTD_isError(got) ? ZSTD_getErrorName(got) : "short zstd data"));
    }
    off += size_t(csize);
  }
  p.pos = out[0].data();
  p.alpha = out[1].data();
  p.color = out[2].data();
  p.scale = out[3].data();
  p.rot = out[4].data();
  p.sh = out[5].data();
  return unpack(p, source, notes);
}

}  // namespace

GaussianScene flip_y_z(const GaussianScene& scene) {
  GaussianScene s = scene;
  const float* flip = sh_flip_signs();
  const int K = s.coeffs();
  for (size_t i = 0; i < s.size(); ++i) {
    s.positions[3 * i + 1] = -s.positions[3 * i + 1];
    s.positions[3 * i + 2] = -s.positions[3 * i + 2];
    s.rotations[4 * i + 2] = -s.rotations[4 * i + 2];
    s.rotations[4 * i + 3] = -s.rotations[4 * i + 3];
    float* c = s.sh_of(i);
    for (int k = 1; k < K; ++k)
      for (int ch = 0; ch < 3; ++ch) c[3 * k + ch] *= flip[k];
  }
  if (!s.normals.empty())
    for (size_t i = 0; i < s.size(); ++i) {
      s.normals[3 * i + 1] = -s.normals[3 * i + 1];
      s.normals[3 * i + 2] = -s.normals[3 * i + 2];
    }
  return s;
}

bool looks_like_spz(const uint8_t* data, size_t size) {
  return (size >= 2 && data[0] == 0x1f && data[1] == 0x8b) || (size >= 4 && le32(data) == kMagic);
}

GaussianScene parse_spz(const uint8_t* data, size_t size, const std::string& source, std::vector<std::string>* notes) {
  if (size == 0) throw Error(source, "empty .spz file");
  if (size >= 4 && le32(data) == kMagic) return parse_v4(data, size, source, notes);
  if (size >= 2 && data[0] == 0x1f && data[1] == 0x8b) return parse_legacy(data, size, source, notes);
  throw Error(source, "not an .spz file: neither gzip data nor an NGSP header");
}

std::vector<uint8_t> serialize_spz(const GaussianScene& scene, const SpzWriteOptions& options,
                                   std::vector<std::string>* notes) {
  scene.validate("spz output");
  const size_t n = scene.size();
  if (n == 0) throw Error("spz output", "the scene has no Gaussians");
  if (n > 0xffffffffu) throw Error("spz output", "too many Gaussians for .spz");
  const uint32_t version = uint32_t(options.version);
  if (version < 2 || version > 4) throw Error("spz output", "can write .spz versions 2-4, not " + std::to_string(version));
  // 12 fractional bits (1/4096) as the reference writer, fewer when the scene is too large
  // for 24 bits: readers take the count from the header.
  double max_abs = 0;
  for (float v : scene.positions) max_abs = std::max(max_abs, double(std::fabs(v)));
  int fb = 12;
  while (fb > 0 && max_abs * double(1 << fb) > double((1 << 23) - 1)) --fb;
  if (max_abs * double(1 << fb) > double((1 << 23) - 1))
    throw Error("spz output", "positions up to " + std::to_string(max_abs) + " do not fit .spz's 24-bit fixed point");
  if (fb < 12 && notes)
    notes->push_back(".spz: positions stored with " + std::to_string(fb) + " fractional bits (the scene spans up to " +
                     std::to_string(max_abs) + ")");
  const int degree = scene.sh_degree, dim = kShDim[degree], K = scene.coeffs();
  size_t sizes[6];
  attribute_sizes(version, degree, sizes);
  std::vector<std::vector<uint8_t>> a(6);
  for (int k = 0; k < 6; ++k) a[k].resize(n * sizes[k]);
  const float* flip = sh_flip_signs();
  const float fixed = float(1 << fb);
  size_t clamped_scale = 0, clamped_colour = 0, clamped_sh = 0;
  for (size_t i = 0; i < n; ++i) {
    // RDF -> RUB.
    const float xyz[3] = {scene.positions[3 * i], -scene.positions[3 * i + 1], -scene.positions[3 * i + 2]};
    for (int c = 0; c < 3; ++c) {
      const int32_t v = int32_t(std::lround(double(xyz[c]) * fixed));
      for (int b = 0; b < 3; ++b) a[0][9 * i + 3 * c + b] = uint8_t(uint32_t(v) >> (8 * b));
    }
    a[1][i] = to_u8(255.0f * sigmoid(scene.opacity[i]));
    const float* c = scene.sh_of(i);
    for (int ch = 0; ch < 3; ++ch) {
      const float v = c[ch] * (kColorScale * 255.0f) + 127.5f;
      if (v < -0.5f || v > 255.5f) ++clamped_colour;
      a[2][3 * i + ch] = to_u8(v);
    }
    for (int k = 0; k < 3; ++k) {
      const float v = (scene.scales[3 * i + k] + 10.0f) * 16.0f;
      if (v < -0.5f || v > 255.5f) ++clamped_scale;
      a[3][3 * i + k] = to_u8(v);
    }
    // Rotation: normalise, RDF -> RUB (w, x, -y, -z), SPZ order x y z w.
    const Quat qn = scene.rotation(i).normalized();
    float q[4] = {float(qn.x), float(-qn.y), float(-qn.z), float(qn.w)};
    if (version >= 3) {
      int largest = 0;
      for (int k = 1; k < 4; ++k)
        if (std::fabs(q[k]) > std::fabs(q[largest])) largest = k;
      const bool negate = q[largest] < 0;  // -q is the same rotation: make the largest positive
      uint32_t comp = uint32_t(largest);
      for (int k = 0; k < 4; ++k) {
        if (k == largest) continue;
        const uint32_t neg = uint32_t((q[k] < 0) != negate);
        const uint32_t mag = std::min<uint32_t>(511u, uint32_t(511.0f * (std::fabs(q[k]) / float(M_SQRT1_2)) + 0.5f));
        comp = (comp << 10) | (neg << 9) | mag;
      }
      for (int b = 0; b < 4; ++b) a[4][4 * i + b] = uint8_t(comp >> (8 * b));
    } else {
      const float sgn = q[3] < 0 ? -1.0f : 1.0f;  // w is rebuilt as non-negative
      for (int k = 0; k < 3; ++k) a[4][3 * i + k] = to_u8(sgn * q[k] * 127.5f + 127.5f);
    }
    for (int k = 0; k < dim && k + 1 < K; ++k) {
      const int bucket = k < 3 ? 8 : 16;  // 5 bits for degree 1, 4 bits above
      for (int ch = 0; ch < 3; ++ch) {
        const float x = flip[k + 1] * c[3 * (k + 1) + ch];
        int qv = int(std::lround(x * 128.0f)) + 128;
        qv = (qv + bucket / 2) / bucket * bucket;
        if (qv < 0 || qv > 255) ++clamped_sh;
        a[5][size_t(i) * dim * 3 + 3 * k + ch] = uint8_t(std::clamp(qv, 0, 255));
      }
    }
  }
  if (notes) {
    if (clamped_scale) notes->push_back(".spz: " + std::to_string(clamped_scale) + " log-scales outside [-10, 6] were clamped");
    if (clamped_colour) notes->push_back(".spz: " + std::to_string(clamped_colour) + " base colours outside its range were clamped");
    if (clamped_sh) notes->push_back(".spz: " + std::to_string(clamped_sh) + " SH coefficients outside [-1, 1] were clamped");
    if (!scene.extras.empty()) notes->push_back(".spz has no room for extra properties: they were dropped");
  }
  std::vector<uint8_t> out;
  if (version <= 3) {
    std::vector<uint8_t> raw;
    put32(raw, kMagic);
    put32(raw, version);
    put32(raw, uint32_t(n));
    raw.push_back(uint8_t(degree));
    raw.push_back(uint8_t(fb));
    raw.push_back(0);
    raw.push_back(0);
    for (const auto& v : a) raw.insert(raw.end(), v.begin(), v.end());
    return gzip(raw);
  }
  const unsigned streams = dim ? 6 : 5;  // the reference writer skips an empty SH stream
  std::vector<std::vector<uint8_t>> z(streams);
  for (unsigned k = 0; k < streams; ++k) {
    z[k].resize(ZSTD_compressBound(a[k].size()));
    const size_t got = ZSTD_compress(z[k].data(), z[k].size(), a[k].data(), a[k].size(), 12);
    if (ZSTD_isError(got)) throw Error("spz output", std::string("zstd compression failed: ") + ZSTD_getErrorName(got));
    z[k].resize(got);
  }
  put32(out, kMagic);
  put32(out, version);
  put32(out, uint32_t(n));
  out.push_back(uint8_t(degree));
  out.push_back(uint8_t(fb));
  out.push_back(0);
  out.push_back(uint8_t(streams));
  put32(out, uint32_t(kV4Header));
  out.resize(kV4Header, 0);
  for (unsigned k = 0; k < streams; ++k) {
    put64(out, z[k].size());
    put64(out, a[k].size());
  }
  for (const auto& v : z) out.insert(out.end(), v.begin(), v.end());
  return out;
}

}  // namespace isegman
