#include "core/scene.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "core/error.h"

namespace isegman {

void GaussianScene::resize(size_t n, int degree) {
  sh_degree = degree;
  positions.assign(3 * n, 0.f);
  normals.clear();
  sh.assign(n * sh_coeff_count(degree) * 3, 0.f);
  opacity.assign(n, 0.f);
  scales.assign(3 * n, 0.f);
  rotations.assign(4 * n, 0.f);
  for (size_t i = 0; i < n; ++i) rotations[4 * i] = 1.f;
  extras.clear();
}

void GaussianScene::append_from(const GaussianScene& o, size_t i) {
  if (o.sh_degree != sh_degree) throw Error("append_from: SH degrees differ");
  positions.insert(positions.end(), o.positions.begin() + 3 * i, o.positions.begin() + 3 * i + 3);
  if (!normals.empty() || (size() == 0 && !o.normals.empty())) {
    if (o.normals.empty()) normals.insert(normals.end(), 3, 0.f);
    else normals.insert(normals.end(), o.normals.begin() + 3 * i, o.normals.begin() + 3 * i + 3);
  }
  const size_t k = o.coeffs() * 3;
  sh.insert(sh.end(), o.sh.begin() + i * k, o.sh.begin() + (i + 1) * k);
  opacity.push_back(o.opacity[i]);
  scales.insert(scales.end(), o.scales.begin() + 3 * i, o.scales.begin() + 3 * i + 3);
  rotations.insert(rotations.end(), o.rotations.begin() + 4 * i, o.rotations.begin() + 4 * i + 4);
  // Extras only survive when both scenes carry the same ones.
  if (!extras.empty()) {
    bool same = extras.size() == o.extras.size();
    for (size_t e = 0; same && e < extras.size(); ++e)
      same = extras[e].name == o.extras[e].name && extras[e].size == o.extras[e].size;
    if (!same) {
      extras.clear();
    } else {
      for (size_t e = 0; e < extras.size(); ++e) {
        const auto& src = o.extras[e];
        extras[e].data.insert(extras[e].data.end(), src.data.begin() + i * src.size,
                              src.data.begin() + (i + 1) * src.size);
      }
    }
  }
}

GaussianScene GaussianScene::subset(const std::vector<bool>& keep) const {
  if (keep.size() != size()) throw Error("subset: mask size does not match the scene");
  GaussianScene out;
  out.sh_degree = sh_degree;
  const size_t k = coeffs() * 3;
  for (const auto& e : extras) {
    ExtraProperty ne = e;
    ne.data.clear();
    out.extras.push_back(ne);
  }
  for (size_t i = 0; i < size(); ++i) {
    if (!keep[i]) continue;
    out.positions.insert(out.positions.end(), positions.begin() + 3 * i, positions.begin() + 3 * i + 3);
    if (!normals.empty())
      out.normals.insert(out.normals.end(), normals.begin() + 3 * i, normals.begin() + 3 * i + 3);
    out.sh.insert(out.sh.end(), sh.begin() + i * k, sh.begin() + (i + 1) * k);
    out.opacity.push_back(opacity[i]);
    out.scales.insert(out.scales.end(), scales.begin() + 3 * i, scales.begin() + 3 * i + 3);
    out.rotations.insert(out.rotations.end(), rotations.begin() + 4 * i, rotations.begin() + 4 * i + 4);
    for (size_t e = 0; e < extras.size(); ++e)
      out.extras[e].data.insert(out.extras[e].data.end(), extras[e].data.begin() + i * extras[e].size,
                                extras[e].data.begin() + (i + 1) * extras[e].size);
  }
  return out;
}

namespace {
void check_finite(const std::vector<float>& v, int stride, const char* what, const std::string& src) {
  for (size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      throw Error(src, std::string("Gaussian ") + std::to_string(i / stride) + " has a non-finite " + what);
}
}  // namespace

void GaussianScene::validate(const std::string& src) const {
  const size_t n = size();
  if (sh_degree < 0 || sh_degree > 3) throw Error(src, "SH degree " + std::to_string(sh_degree) + " is not in 0..3");
  if (positions.size() != 3 * n || scales.size() != 3 * n || rotations.size() != 4 * n ||
      sh.size() != n * coeffs() * 3 || (!normals.empty() && normals.size() != 3 * n))
    throw Error(src, "inconsistent Gaussian array sizes");
  for (const auto& e : extras)
    if (e.data.size() != n * size_t(e.size)) throw Error(src, "extra property '" + e.name + "' has the wrong length");
  check_finite(positions, 3, "position", src);
  check_finite(scales, 3, "scale", src);
  check_finite(rotations, 4, "rotation", src);
  check_finite(opacity, 1, "opacity", src);
  check_finite(sh, coeffs() * 3, "colour coefficient", src);
  for (size_t i = 0; i < n; ++i) {
    const float* q = &rotations[4 * i];
    if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0)
      throw Error(src, "Gaussian " + std::to_string(i) + " has a zero rotation quaternion");
  }
}

void GaussianScene::bounds(Vec3& lo, Vec3& hi) const {
  const double inf = std::numeric_limits<double>::infinity();
  lo = {inf, inf, inf};
  hi = {-inf, -inf, -inf};
  for (size_t i = 0; i < size(); ++i)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min<double>(lo[a], positions[3 * i + a]);
      hi[a] = std::max<double>(hi[a], positions[3 * i + a]);
    }
}

namespace {
void fnv(uint64_t& h, const void* data, size_t bytes) {
  const auto* p = static_cast<const uint8_t*>(data);
  for (size_t i = 0; i < bytes; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
}

// xxHash64's primes and round (acc = rotl(acc + word * P2, 31) * P1) in four independent
// lanes, so the multiplies overlap; the lanes, the length and the tail bytes are folded in
// after, then mixed by SplitMix64's finaliser.
constexpr uint64_t kP1 = 0x9E3779B185EBCA87ull, kP2 = 0xC2B2AE3D27D4EB4Full;
uint64_t rotl(uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
uint64_t finalise(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
void hash_words(uint64_t& h, const void* data, size_t bytes) {
  const auto* p = static_cast<const uint8_t*>(data);
  uint64_t lane[4] = {h + kP1 + kP2, h + kP2, h, h - kP1};
  size_t i = 0;
  for (; i + 32 <= bytes; i += 32)
    for (int j = 0; j < 4; ++j) {
      uint64_t w;
      std::memcpy(&w, p + i + 8 * j, 8);
      lane[j] = rotl(lane[j] + w * kP2, 31) * kP1;
    }
  uint64_t out = h ^ (bytes * kP1);
  for (int j = 0; j < 4; ++j) out = rotl(out ^ lane[j], 27) * kP1 + kP2;
  for (; i < bytes; ++i) out = (out ^ p[i]) * 1099511628211ull;
  h = finalise(out);
}

// Folds the count, the SH degree and every parameter array into one hash, in that order.
template <class Fold>
uint64_t fold_scene(const GaussianScene& g, Fold fold) {
  uint64_t h = 1469598103934665603ull;
  const uint64_t n = g.size();
  fold(h, &n, sizeof n);
  fold(h, &g.sh_degree, sizeof g.sh_degree);
  for (const std::vector<float>* v : {&g.positions, &g.sh, &g.opacity, &g.scales, &g.rotations})
    fold(h, v->data(), v->size() * 4);
  return h;
}
}  // namespace

uint64_t GaussianScene::fingerprint() const { return fold_scene(*this, hash_words); }

uint64_t GaussianScene::legacy_fingerprint() const { return fold_scene(*this, fnv); }

}  // namespace isegman
