#include "server/scene_binary.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/sh.h"

namespace isegman::server {

namespace {

template <typename T>
void put(std::vector<uint8_t>& out, size_t& at, T v) {
  std::memcpy(out.data() + at, &v, sizeof(T));  // x86/ARM are little-endian, as the page reads
  at += sizeof(T);
}

void put_header(std::vector<uint8_t>& out, const char magic[4], uint32_t version, uint32_t count, uint32_t third,
                uint64_t a, uint64_t b) {
  size_t at = 0;
  std::memcpy(out.data(), magic, 4);
  at = 4;
  put<uint32_t>(out, at, version);
  put<uint32_t>(out, at, count);
  put<uint32_t>(out, at, third);
  put<uint64_t>(out, at, a);
  put<uint64_t>(out, at, b);
}

uint8_t unit_byte(double v) { return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

}  // namespace

std::vector<uint8_t> pack_splats(const GaussianScene& scene, uint64_t fingerprint) {
  const size_t n = scene.size();
  const int k = scene.coeffs();
  const uint32_t degree = uint32_t(scene.sh_degree), rest = uint32_t(3 * (k - 1));
  std::vector<uint8_t> out(kSceneBinaryHeaderBytes + n * kSplatRecordBytes + kColourRangeBytes +
                           (degree > 0 ? kShScalesBytes + n * rest : 0));
  put_header(out, "ISGS", 3, uint32_t(n), kSplatRecordBytes, fingerprint, uint64_t(degree) | uint64_t(rest) << 32);
  auto base = [&](size_t i, int c) { return 0.5 + kShC0 * double(scene.sh[i * size_t(k) * 3 + size_t(c)]); };
  double lo = 0, hi = 1;
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      if (const double v = base(i, c); std::isfinite(v)) {
        if (degree > 0) lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  lo = double(float(std::max(lo, double(kColourLow))));  // as the page reads them
  hi = double(float(std::min(hi, double(kColourHigh))));
  size_t at = kSceneBinaryHeaderBytes;
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) put<float>(out, at, scene.positions[3 * i + c]);
    for (int c = 0; c < 3; ++c) out[at++] = unit_byte((base(i, c) - lo) / (hi - lo));
    out[at++] = unit_byte(scene.activated_opacity(i));
    // Sigma = M M^T with M = R S (the 3DGS computeCov3D).
    const Mat3 r = scene.rotation(i).to_matrix();
    const Vec3 s = scene.scale(i);
    double m[3][3];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) m[a][b] = r.m[a][b] * s[b];
    auto cov = [&](int a, int b) { return m[a][0] * m[b][0] + m[a][1] * m[b][1] + m[a][2] * m[b][2]; };
    put<float>(out, at, float(cov(0, 0)));
    put<float>(out, at, float(cov(0, 1)));
    put<float>(out, at, float(cov(0, 2)));
    put<float>(out, at, float(cov(1, 1)));
    put<float>(out, at, float(cov(1, 2)));
    put<float>(out, at, float(cov(2, 2)));
  }
  put<float>(out, at, float(lo));
  put<float>(out, at, float(hi));
  if (degree == 0) return out;
  // Band b holds coefficients b^2 .. (b+1)^2 - 1.
  float scale[4] = {0, 0, 0, 0};
  auto band = [](int c) { return c < 4 ? 1 : c < 9 ? 2 : 3; };
  for (size_t i = 0; i < n; ++i) {
    const float* c = scene.sh_of(i);
    for (int j = 3; j < 3 * k; ++j)
      if (std::isfinite(c[j])) scale[band(j / 3)] = std::max(scale[band(j / 3)], std::abs(c[j]));
  }
  for (int b = 1; b <= 3; ++b) put<float>(out, at, scale[b]);
  put<float>(out, at, 0.f);
  for (size_t i = 0; i < n; ++i) {
    const float* c = scene.sh_of(i);
    for (int j = 3; j < 3 * k; ++j) {
      const float s = scale[band(j / 3)];
      const float v = s > 0 && std::isfinite(c[j]) ? c[j] / s : 0.f;
      out[at++] = uint8_t(std::lround(std::clamp(v, -1.f, 1.f) * 127.f) + 128);
    }
  }
  return out;
}

std::vector<uint8_t> pack_selection(const std::vector<bool>& selected, const std::vector<bool>& hidden,
                                    uint64_t fingerprint, uint64_t revision) {
  const size_t n = selected.size();
  std::vector<uint8_t> out(kSceneBinaryHeaderBytes + n);
  uint32_t hidden_count = 0;
  for (size_t i = 0; i < n; ++i) {
    const bool h = i < hidden.size() && hidden[i];
    hidden_count += h;
    out[kSceneBinaryHeaderBytes + i] = uint8_t((selected[i] ? 1 : 0) | (h ? 2 : 0));
  }
  put_header(out, "ISGM", 1, uint32_t(n), hidden_count, fingerprint, revision);
  return out;
}

}  // namespace isegman::server
