#include "io/sog.h"

#include <webp/decode.h>
#include <zip.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>

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
      meta["count"].get<unsigned long long>() > (1ull << 28))
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
  if (st.size > (1ull << 30)) throw Error(source, "'" + name + "' in the .sog archive is larger than 1 GiB");
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
  return fs::is_directory(path, ec) && fs::is_regular_file(fs::path(path) / "meta.json", ec);
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

}  // namespace isegman
