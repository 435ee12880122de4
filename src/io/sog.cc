#include "io/sog.h"

#include <webp/decode.h>
#include <webp/encode.h>
#include <zip.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <numeric>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/atomic_file.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace isegman {
namespace {

using FileGetter = std::function<std::vector<uint8_t>(const std::string&)>;

struct Image {
  int w = 0, h = 0;
  std::vector<uint8_t> rgba;
};

Image decode_webp(const std::vector<uint8_t>& bytes, const std::string& what, size_t count, const std::string& source) {
  Image im;
  if (!WebPGetInfo(bytes.data(), bytes.size(), &im.w, &im.h))
    throw Error(source, what + ": not a valid WebP image");
  if (size_t(im.w) * size_t(im.h) > (size_t(1) << 26))
    throw Error(source, what + ": " + std::to_string(im.w) + "x" + std::to_string(im.h) + " pixels is too large");
  if (size_t(im.w) * size_t(im.h) < count)
    throw Error(source, what + ": " + std::to_string(im.w) + "x" + std::to_string(im.h) + " pixels, fewer than the " +
                            std::to_string(count) + " Gaussians of meta.json");
  uint8_t* px = WebPDecodeRGBA(bytes.data(), bytes.size(), &im.w, &im.h);
  if (!px) throw Error(source, what + ": WebP decoding failed");
  im.rgba.assign(px, px + size_t(im.w) * im.h * 4);
  WebPFree(px);
  return im;
}

std::vector<float> codebook(const json& j, const std::string& field, const std::string& source) {
  if (!j.is_object() || !j.contains("codebook") || !j["codebook"].is_array() || j["codebook"].size() != 256)
    throw Error(source, "meta.json: " + field + ".codebook must be an array of 256 numbers");
  std::vector<float> c;
  for (const auto& v : j["codebook"]) {
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      throw Error(source, "meta.json: " + field + ".codebook holds a value that is not a finite number");
    c.push_back(v.get<float>());
  }
  return c;
}

std::string file_name(const json& j, size_t k, const std::string& field, const std::string& source) {
  if (!j.is_object() || !j.contains("files") || !j["files"].is_array() || j["files"].size() <= k || !j["files"][k].is_string())
    throw Error(source, "meta.json: " + field + ".files needs " + std::to_string(k + 1) + " file name(s)");
  return j["files"][k].get<std::string>();
}

GaussianScene decode(const FileGetter& get, const std::string& source) {
  const std::vector<uint8_t> mb = get("meta.json");
  json meta = json::parse(mb.begin(), mb.end(), nullptr, false);
  if (meta.is_discarded() || !meta.is_object()) throw Error(source, "meta.json is not a JSON object");
  if (!meta.contains("version"))
    throw Error(source, "SOG version 1 (meta.json without \"version\") is not supported; re-export with splat-transform");
  if (!meta["version"].is_number_integer() || meta["version"].get<long long>() != 2)
    throw Error(source, "unsupported SOG version " + meta["version"].dump() + " (reads version 2)");
  if (!meta.contains("count") || !meta["count"].is_number_unsigned() || meta["count"].get<unsigned long long>() == 0 ||
      meta["count"].get<unsigned long long>() > (1ull << 26))
    throw Error(source, "meta.json: count must be a positive integer");
  const size_t n = meta["count"].get<size_t>();
  for (const char* f : {"means", "scales", "quats", "sh0"})
    if (!meta.contains(f) || !meta[f].is_object()) throw Error(source, std::string("meta.json lacks the \"") + f + "\" object");
  const json& jm = meta["means"];
  double mins[3], maxs[3];
  for (const char* f : {"mins", "maxs"})
    if (!jm.contains(f) || !jm[f].is_array() || jm[f].size() != 3)
      throw Error(source, std::string("meta.json: means.") + f + " must hold 3 numbers");
  for (int a = 0; a < 3; ++a) {
    if (!jm["mins"][a].is_number() || !jm["maxs"][a].is_number()) throw Error(source, "meta.json: means ranges must be numbers");
    mins[a] = jm["mins"][a].get<double>();
    maxs[a] = jm["maxs"][a].get<double>();
    if (!std::isfinite(mins[a]) || !std::isfinite(maxs[a]) || std::fabs(mins[a]) > 80 || std::fabs(maxs[a]) > 80)
      throw Error(source, "meta.json: means ranges out of bounds");
  }
  int degree = 0;
  const json* jn = meta.contains("shN") && !meta["shN"].is_null() ? &meta["shN"] : nullptr;
  if (jn) {
    if (!jn->is_object() || !jn->contains("bands") || !(*jn)["bands"].is_number_integer())
      throw Error(source, "meta.json: shN.bands must be 1, 2 or 3");
    degree = (*jn)["bands"].get<int>();
    if (degree < 0 || degree > 3) throw Error(source, "meta.json: shN.bands must be 1, 2 or 3");
  }
  GaussianScene s;
  s.resize(n, degree);
  const int K = s.coeffs();

  const Image lo = decode_webp(get(file_name(jm, 0, "means", source)), "means low bytes", n, source);
  const Image hi = decode_webp(get(file_name(jm, 1, "means", source)), "means high bytes", n, source);
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      const double q = double(lo.rgba[4 * i + a] | hi.rgba[4 * i + a] << 8) / 65535.0;
      const double range = (maxs[a] - mins[a]) != 0 ? maxs[a] - mins[a] : 1.0;
      const double v = mins[a] + range * q;
      const double e = std::exp(std::fabs(v)) - 1.0;  // inverse of sign(x) ln(|x| + 1)
      s.positions[3 * i + a] = float(v < 0 ? -e : e);
    }

  const Image qi = decode_webp(get(file_name(meta["quats"], 0, "quats", source)), "quats", n, source);
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* p = &qi.rgba[4 * i];
    float* r = &s.rotations[4 * i];
    if (p[3] < 252) throw Error(source, "quats: pixel " + std::to_string(i) + " has an invalid largest-component tag");
    const int largest = p[3] - 252;
    float sum = 0;
    for (int k = 0, j = 0; k < 4; ++k) {
      if (k == largest) continue;
      r[k] = (float(p[j++]) / 255.0f * 2.0f - 1.0f) / float(M_SQRT2);
      sum += r[k] * r[k];
    }
    r[largest] = std::sqrt(std::max(0.0f, 1.0f - sum));
  }

  const std::vector<float> sc = codebook(meta["scales"], "scales", source);
  const Image si = decode_webp(get(file_name(meta["scales"], 0, "scales", source)), "scales", n, source);
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) s.scales[3 * i + a] = sc[si.rgba[4 * i + a]];

  const std::vector<float> cc = codebook(meta["sh0"], "sh0", source);
  const Image ci = decode_webp(get(file_name(meta["sh0"], 0, "sh0", source)), "sh0", n, source);
  for (size_t i = 0; i < n; ++i) {
    for (int ch = 0; ch < 3; ++ch) s.sh_of(i)[ch] = cc[ci.rgba[4 * i + ch]];
    // Alpha bytes 0 and 255 would be infinite logits: read them half a step inside.
    const float al = std::clamp(float(ci.rgba[4 * i + 3]), 0.5f, 254.5f) / 255.0f;
    s.opacity[i] = std::log(al / (1.0f - al));
  }

  if (degree > 0) {
    const int per = K - 1;
    const std::vector<float> nc = codebook(*jn, "shN", source);
    if (!jn->contains("count") || !(*jn)["count"].is_number_unsigned())
      throw Error(source, "meta.json: shN.count must be a non-negative integer");
    const size_t palette = (*jn)["count"].get<size_t>();
    const Image cent = decode_webp(get(file_name(*jn, 0, "shN", source)), "shN centroids", 0, source);
    const Image lab = decode_webp(get(file_name(*jn, 1, "shN", source)), "shN labels", n, source);
    if (cent.w != 64 * per)
      throw Error(source, "shN centroids: width " + std::to_string(cent.w) + ", expected " + std::to_string(64 * per));
    if (size_t(cent.h) * 64 < palette) throw Error(source, "shN centroids: too few rows for shN.count");
    for (size_t i = 0; i < n; ++i) {
      const size_t label = lab.rgba[4 * i] | lab.rgba[4 * i + 1] << 8;
      if (label >= palette)
        throw Error(source, "shN labels: Gaussian " + std::to_string(i) + " names palette entry " + std::to_string(label) +
                                " of " + std::to_string(palette));
      float* c = s.sh_of(i);
      for (int k = 0; k < per; ++k) {
        const size_t x = (label % 64) * per + k, y = label / 64;
        const uint8_t* p = &cent.rgba[4 * (y * cent.w + x)];
        for (int ch = 0; ch < 3; ++ch) c[3 * (k + 1) + ch] = nc[p[ch]];
      }
    }
  }
  s.validate(source);
  return s;
}

// Reads member `name` of an open zip archive, refusing members larger than `limit`.
std::vector<uint8_t> zip_member(zip_t* z, const std::string& name, const std::string& source) {
  const zip_int64_t idx = zip_name_locate(z, name.c_str(), 0);
  if (idx < 0) throw Error(source, "the .sog archive has no member '" + name + "'");
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat_index(z, zip_uint64_t(idx), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
    throw Error(source, "cannot read the size of '" + name + "' in the .sog archive");
  if (st.size > (1ull << 28)) throw Error(source, "'" + name + "' in the .sog archive is larger than 256 MiB");
  // Deflate expands at most ~1032:1: a larger claim is a corrupt directory.
  if ((st.valid & ZIP_STAT_COMP_SIZE) && st.size > st.comp_size * 1100 + (1u << 16))
    throw Error(source, "'" + name + "' in the .sog archive claims more data than it can hold");
  zip_file_t* f = zip_fopen_index(z, zip_uint64_t(idx), 0);
  if (!f) throw Error(source, "cannot open '" + name + "' in the .sog archive: " + zip_strerror(z));
  std::vector<uint8_t> out(size_t(st.size));
  const zip_int64_t got = out.empty() ? 0 : zip_fread(f, out.data(), out.size());
  zip_fclose(f);
  if (got != zip_int64_t(out.size()))
    throw Error(source, "'" + name + "' in the .sog archive is truncated or corrupt");
  return out;
}

}  // namespace

bool is_sog_dir(const std::string& path) {
  std::error_code ec;
  const fs::path meta = fs::path(path) / "meta.json";
  if (!fs::is_directory(path, ec) || !fs::is_regular_file(meta, ec)) return false;
  // A trained scene's folder may hold a meta.json of its own (a trainer's notes, as the
  // fixtures do): it is SOG only without a point_cloud and when its meta.json is SOG's
  // (it has "means"). One that does not parse is left to the SOG reader to report.
  if (fs::exists(fs::path(path) / "point_cloud", ec)) return false;
  const uintmax_t size = fs::file_size(meta, ec);
  if (ec || size > (64u << 20)) return true;
  const std::vector<uint8_t> bytes = read_file_bytes(meta.string());
  const json j = json::parse(bytes.begin(), bytes.end(), nullptr, false);
  return j.is_discarded() || !j.is_object() || j.contains("means");
}

bool looks_like_zip(const uint8_t* data, size_t size) {
  return size >= 4 && data[0] == 'P' && data[1] == 'K' && data[2] == 3 && data[3] == 4;
}

GaussianScene parse_sog_zip(const uint8_t* data, size_t size, const std::string& source) {
  zip_error_t err;
  zip_error_init(&err);
  zip_source_t* src = zip_source_buffer_create(data, size, 0, &err);
  if (!src) throw Error(source, "cannot read the .sog archive");
  zip_t* z = zip_open_from_source(src, ZIP_RDONLY, &err);
  if (!z) {
    zip_source_free(src);
    const std::string msg = zip_error_strerror(&err);
    zip_error_fini(&err);
    throw Error(source, "not a readable .sog (zip) archive: " + msg);
  }
  zip_error_fini(&err);
  try {
    GaussianScene s = decode([&](const std::string& name) { return zip_member(z, name, source); }, source);
    zip_discard(z);
    return s;
  } catch (...) {
    zip_discard(z);
    throw;
  }
}

GaussianScene read_sog_dir(const std::string& dir) {
  return decode(
      [&](const std::string& name) {
        // Members are named by the untrusted meta.json: plain names inside the folder only.
        if (name.empty() || name.find('/') != std::string::npos || name.find('\\') != std::string::npos || name == "." ||
            name == "..")
          throw Error(dir, "meta.json names a file outside its folder: '" + name + "'");
        return read_file_bytes((fs::path(dir) / name).string());
      },
      dir);
}

namespace {

// 256 centroids for `values` by 1-D k-means on sorted data. Half start at quantiles, half
// evenly over the range: rare values in the tails (the few large Gaussians of a scene)
// matter on screen, and quantiles alone leave them far from any centroid.
std::vector<float> codebook_kmeans(std::vector<float> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  std::vector<double> c(256);
  for (int k = 0; k < 128; ++k) {
    c[k] = v[std::min(n - 1, size_t((k + 0.5) / 128.0 * n))];
    c[128 + k] = v.front() + (double(v.back()) - v.front()) * k / 127.0;
  }
  std::sort(c.begin(), c.end());
  for (int it = 0; it < 12; ++it) {
    std::vector<double> sum(256, 0.0);
    std::vector<size_t> cnt(256, 0);
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
      while (k + 1 < 256 && double(v[i]) > 0.5 * (c[k] + c[k + 1])) ++k;
      sum[k] += v[i];
      ++cnt[k];
    }
    for (int j = 0; j < 256; ++j)
      if (cnt[j]) c[j] = sum[j] / double(cnt[j]);
    std::sort(c.begin(), c.end());
  }
  return std::vector<float>(c.begin(), c.end());
}

uint8_t nearest(const std::vector<float>& cb, float x) {
  const auto it = std::lower_bound(cb.begin(), cb.end(), x);
  size_t k = size_t(it - cb.begin());
  if (k == cb.size()) return uint8_t(k - 1);
  if (k > 0 && (x - cb[k - 1]) <= (cb[k] - x)) --k;
  return uint8_t(k);
}

std::vector<uint8_t> encode_webp(const std::vector<uint8_t>& rgba, int w, int h) {
  WebPConfig config;
  WebPPicture pic;
  if (!WebPConfigInit(&config) || !WebPPictureInit(&pic)) throw Error("sog output", "libwebp version mismatch");
  config.lossless = 1;
  config.exact = 1;  // keep RGB under alpha 0 (sh0 stores colours there)
  config.method = 4;
  config.quality = 75;
  pic.use_argb = 1;
  pic.width = w;
  pic.height = h;
  WebPMemoryWriter writer;
  WebPMemoryWriterInit(&writer);
  pic.writer = WebPMemoryWrite;
  pic.custom_ptr = &writer;
  if (!WebPPictureImportRGBA(&pic, rgba.data(), w * 4)) {
    WebPPictureFree(&pic);
    throw Error("sog output", "WebP import failed");
  }
  const int ok = WebPEncode(&config, &pic);
  WebPPictureFree(&pic);
  std::vector<uint8_t> out(writer.mem, writer.mem + writer.size);
  WebPMemoryWriterClear(&writer);
  if (!ok) throw Error("sog output", "WebP encoding failed");
  return out;
}

std::vector<uint8_t> zip_files(const std::vector<std::pair<std::string, std::vector<uint8_t>>>& files) {
  zip_error_t err;
  zip_error_init(&err);
  zip_source_t* src = zip_source_buffer_create(nullptr, 0, 0, &err);
  if (!src) throw Error("sog output", "cannot create a zip buffer");
  zip_t* z = zip_open_from_source(src, ZIP_TRUNCATE, &err);
  if (!z) {
    zip_source_free(src);
    throw Error("sog output", "cannot create a zip archive");
  }
  zip_source_keep(src);
  for (const auto& f : files) {
    zip_source_t* fs = zip_source_buffer(z, f.second.data(), f.second.size(), 0);
    const zip_int64_t idx = fs ? zip_file_add(z, f.first.c_str(), fs, ZIP_FL_ENC_UTF_8) : -1;
    if (idx < 0) {
      if (fs) zip_source_free(fs);
      zip_discard(z);
      zip_source_free(src);
      throw Error("sog output", "cannot add " + f.first + " to the zip archive");
    }
    // WebP is already compressed; meta.json (codebooks as text) deflates well.
    zip_set_file_compression(z, zip_uint64_t(idx), f.first == "meta.json" ? ZIP_CM_DEFLATE : ZIP_CM_STORE, 0);
  }
  if (zip_close(z) != 0) {
    zip_discard(z);
    zip_source_free(src);
    throw Error("sog output", "cannot finish the zip archive");
  }
  zip_stat_t st;
  std::vector<uint8_t> out;
  if (zip_source_stat(src, &st) == 0 && zip_source_open(src) == 0) {
    out.resize(size_t(st.size));
    const zip_int64_t got = zip_source_read(src, out.data(), out.size());
    zip_source_close(src);
    if (got != zip_int64_t(out.size())) out.clear();
  }
  zip_source_free(src);
  if (out.empty()) throw Error("sog output", "cannot read the zip archive back");
  return out;
}

// Palette of SH vectors (dim floats each) with at most 65536 entries; `labels` gets each
// Gaussian's entry.
std::vector<float> sh_palette(const GaussianScene& s, int dim, std::vector<uint32_t>& labels, bool& exact) {
  const size_t n = s.size();
  auto vec = [&](size_t i, int d) { return s.sh_of(i)[3 + d]; };  // coefficient-major, channel inner
  labels.resize(n);
  if (n <= 65536) {
    exact = true;
    std::vector<float> p(n * dim);
    for (size_t i = 0; i < n; ++i) {
      labels[i] = uint32_t(i);
      for (int d = 0; d < dim; ++d) p[i * dim + d] = vec(i, d);
    }
    return p;
  }
  exact = false;
  // Principal direction of the SH vectors (power iteration), to order them.
  std::vector<double> mean(dim, 0.0), dir(dim, 1.0 / std::sqrt(double(dim)));
  for (size_t i = 0; i < n; ++i)
    for (int d = 0; d < dim; ++d) mean[d] += vec(i, d) / double(n);
  for (int it = 0; it < 8; ++it) {
    std::vector<double> next(dim, 0.0);
    for (size_t i = 0; i < n; i += 7) {
      double dot = 0;
      for (int d = 0; d < dim; ++d) dot += (vec(i, d) - mean[d]) * dir[d];
      for (int d = 0; d < dim; ++d) next[d] += dot * (vec(i, d) - mean[d]);
    }
    double nn = 0;
    for (double x : next) nn += x * x;
    nn = std::sqrt(nn);
    if (!(nn > 0)) break;
    for (int d = 0; d < dim; ++d) dir[d] = next[d] / nn;
  }
  std::vector<double> proj(n);
  for (size_t i = 0; i < n; ++i) {
    double dot = 0;
    for (int d = 0; d < dim; ++d) dot += (vec(i, d) - mean[d]) * dir[d];
    proj[i] = dot;
  }
  std::vector<uint32_t> ord(n);
  std::iota(ord.begin(), ord.end(), 0u);
  std::sort(ord.begin(), ord.end(), [&](uint32_t a, uint32_t b) { return proj[a] < proj[b]; });
  const size_t P = 65536;
  std::vector<float> c(P * dim);
  for (size_t k = 0; k < P; ++k) {  // start: evenly spaced along the principal direction
    const size_t i = ord[(k * n) / P];
    for (int d = 0; d < dim; ++d) c[k * dim + d] = vec(i, d);
  }
  // Gaussian at rank r starts next to centroid r * P / n; search a window around it.
  const long W = 48;
  for (int it = 0; it < 3; ++it) {
    for (size_t r = 0; r < n; ++r) {
      const size_t i = ord[r];
      const long centre = long((r * P) / n);
      double best = 1e300;
      uint32_t bk = uint32_t(centre);
      for (long k = std::max(0L, centre - W); k <= std::min(long(P) - 1, centre + W); ++k) {
        double dist = 0;
        for (int d = 0; d < dim && dist < best; ++d) {
          const double e = vec(i, d) - c[k * dim + d];
          dist += e * e;
        }
        if (dist < best) {
          best = dist;
          bk = uint32_t(k);
        }
      }
      labels[i] = bk;
    }
    std::vector<double> sum(P * dim, 0.0);
    std::vector<uint32_t> cnt(P, 0);
    for (size_t i = 0; i < n; ++i) {
      ++cnt[labels[i]];
      for (int d = 0; d < dim; ++d) sum[labels[i] * dim + d] += vec(i, d);
    }
    for (size_t k = 0; k < P; ++k)
      if (cnt[k])
        for (int d = 0; d < dim; ++d) c[k * dim + d] = float(sum[k * dim + d] / cnt[k]);
  }
  return c;
}

}  // namespace

std::vector<uint8_t> serialize_sog(const GaussianScene& scene, std::vector<std::string>* notes) {
  scene.validate("sog output");
  const size_t n = scene.size();
  if (n == 0) throw Error("sog output", "the scene has no Gaussians");
  const int w = int(std::ceil(std::sqrt(double(n)))), h = int((n + w - 1) / w);
  auto image = [&]() { return std::vector<uint8_t>(size_t(w) * h * 4, 0); };
  json meta;
  meta["version"] = 2;
  meta["asset"] = {{"generator", "isegman"}};
  meta["count"] = n;
  meta["antialias"] = false;
  std::vector<std::pair<std::string, std::vector<uint8_t>>> files;

  // Means: 16-bit fractions of sign(x) ln(|x| + 1) between per-axis mins and maxs.
  double mins[3] = {1e300, 1e300, 1e300}, maxs[3] = {-1e300, -1e300, -1e300};
  auto logt = [](double x) { return x < 0 ? -std::log1p(-x) : std::log1p(x); };
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      const double v = logt(scene.positions[3 * i + a]);
      mins[a] = std::min(mins[a], v);
      maxs[a] = std::max(maxs[a], v);
    }
  std::vector<uint8_t> lo = image(), hi = image();
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      const double range = maxs[a] > mins[a] ? maxs[a] - mins[a] : 1.0;
      const double t = (logt(scene.positions[3 * i + a]) - mins[a]) / range;
      const uint32_t q = uint32_t(std::clamp(std::lround(t * 65535.0), 0L, 65535L));
      lo[4 * i + a] = uint8_t(q & 255);
      hi[4 * i + a] = uint8_t(q >> 8);
    }
    lo[4 * i + 3] = hi[4 * i + 3] = 255;
  }
  meta["means"] = {{"mins", json::array({mins[0], mins[1], mins[2]})}, {"maxs", json::array({maxs[0], maxs[1], maxs[2]})},
                   {"files", json::array({"means_l.webp", "means_u.webp"})}};
  files.push_back({"means_l.webp", encode_webp(lo, w, h)});
  files.push_back({"means_u.webp", encode_webp(hi, w, h)});

  // Quaternions (w x y z): the three smaller components, the largest made positive.
  std::vector<uint8_t> qi = image();
  for (size_t i = 0; i < n; ++i) {
    const Quat q = scene.rotation(i).normalized();
    double v[4] = {q.w, q.x, q.y, q.z};
    int largest = 0;
    for (int k = 1; k < 4; ++k)
      if (std::fabs(v[k]) > std::fabs(v[largest])) largest = k;
    if (v[largest] < 0)
      for (double& x : v) x = -x;
    for (int k = 0, j = 0; k < 4; ++k)
      if (k != largest)
        qi[4 * i + j++] = uint8_t(std::clamp(std::lround((v[k] * M_SQRT2 * 0.5 + 0.5) * 255.0), 0L, 255L));
    qi[4 * i + 3] = uint8_t(252 + largest);
  }
  meta["quats"] = {{"files", json::array({"quats.webp"})}};
  files.push_back({"quats.webp", encode_webp(qi, w, h)});

  // Scales and colours through 256-entry codebooks.
  const std::vector<float> scb = codebook_kmeans(scene.scales);
  std::vector<uint8_t> si = image();
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) si[4 * i + a] = nearest(scb, scene.scales[3 * i + a]);
    si[4 * i + 3] = 255;
  }
  meta["scales"] = {{"codebook", scb}, {"files", json::array({"scales.webp"})}};
  files.push_back({"scales.webp", encode_webp(si, w, h)});
  std::vector<float> dc(3 * n);
  for (size_t i = 0; i < n; ++i)
    for (int ch = 0; ch < 3; ++ch) dc[3 * i + ch] = scene.sh_of(i)[ch];
  const std::vector<float> ccb = codebook_kmeans(dc);
  std::vector<uint8_t> ci = image();
  for (size_t i = 0; i < n; ++i) {
    for (int ch = 0; ch < 3; ++ch) ci[4 * i + ch] = nearest(ccb, dc[3 * i + ch]);
    ci[4 * i + 3] = uint8_t(std::clamp(std::lround(255.0 * sigmoid(double(scene.opacity[i]))), 0L, 255L));
  }
  meta["sh0"] = {{"codebook", ccb}, {"files", json::array({"sh0.webp"})}};
  files.push_back({"sh0.webp", encode_webp(ci, w, h)});

  if (scene.sh_degree > 0) {
    const int per = scene.coeffs() - 1, dim = 3 * per;
    std::vector<uint32_t> labels;
    bool exact = false;
    const std::vector<float> pal = sh_palette(scene, dim, labels, exact);
    const size_t P = pal.size() / dim;
    const std::vector<float> ncb = codebook_kmeans(pal);
    const int cw = 64 * per, ch_rows = int((P + 63) / 64);
    std::vector<uint8_t> cent(size_t(cw) * ch_rows * 4, 0);
    for (size_t k = 0; k < P; ++k)
      for (int j = 0; j < per; ++j) {
        uint8_t* p = &cent[4 * ((k / 64) * cw + (k % 64) * per + j)];
        for (int c = 0; c < 3; ++c) p[c] = nearest(ncb, pal[k * dim + 3 * j + c]);
        p[3] = 255;
      }
    std::vector<uint8_t> li = image();
    for (size_t i = 0; i < n; ++i) {
      li[4 * i] = uint8_t(labels[i] & 255);
      li[4 * i + 1] = uint8_t(labels[i] >> 8);
      li[4 * i + 3] = 255;
    }
    meta["shN"] = {{"count", P}, {"bands", scene.sh_degree}, {"codebook", ncb},
                   {"files", json::array({"shN_centroids.webp", "shN_labels.webp"})}};
    files.push_back({"shN_centroids.webp", encode_webp(cent, cw, ch_rows)});
    files.push_back({"shN_labels.webp", encode_webp(li, w, h)});
    if (notes && !exact)
      notes->push_back(".sog: SH bands of " + std::to_string(n) +
                       " Gaussians share a 65536-entry palette (approximate k-means)");
  }
  if (notes && !scene.extras.empty()) notes->push_back(".sog has no room for extra properties: they were dropped");
  const std::string m = meta.dump();
  files.insert(files.begin(), {"meta.json", std::vector<uint8_t>(m.begin(), m.end())});
  return zip_files(files);
}

}  // namespace isegman
