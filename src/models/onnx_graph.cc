// The ONNX executor: one function per operator on ATen tensors, a load-time pass that folds
// constant subgraphs, and a run loop that frees every intermediate after its last use.
#include "models/onnx_graph.h"

#include <ATen/ATen.h>
#include <ATen/Parallel.h>
#include <c10/core/InferenceMode.h>

#include <malloc.h>

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <deque>
#include <functional>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <unordered_map>

#include "core/error.h"
#include "models/gemm.h"
#include "models/kernels.h"
#include "models/tensor_memory.h"

namespace isegman::models {

void configure_threads(int threads) {
  static std::once_flag once;
  std::call_once(once, [threads] {
    // Keep freed tensor memory in the heap: otherwise every large intermediate is a fresh
    // mmap whose pages the kernel faults in and zeroes again (a third of the encoder's time).
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    // libgomp reads OMP_WAIT_POLICY once, when the process starts. With its default (spinning
    // workers) two threads on a 2-core VM run up to 10x slower as soon as anything else wants
    // a core, so more than one thread is the default only when the policy is PASSIVE.
    const char* policy = std::getenv("OMP_WAIT_POLICY");
    bool passive = policy && (std::string(policy) == "PASSIVE" || std::string(policy) == "passive");
    int cores = int(std::max(1u, std::thread::hardware_concurrency()));
    int n = threads > 0 ? threads : (passive ? cores : 1);
    at::set_num_threads(n);
  });
}

void limit_threads_of_this_thread(int threads) {
  if (threads < 1) throw Error("limit_threads_of_this_thread: needs at least one thread");
  omp_set_num_threads(threads);
}

int threads_of_this_thread() { return omp_get_max_threads(); }

namespace {

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double cpu_ms() {  // CPU time of the whole process (every thread)
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

// An operator-level failure; the run loop adds the model file and the node.
struct OpError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Ctx {
  const Node& node;
  int64_t opset;
  std::vector<at::Tensor> in;   // undefined where an optional input is omitted
  std::vector<at::Tensor> out;  // one per node output

  bool has(size_t i) const { return i < in.size() && in[i].defined(); }
  const at::Tensor& input(size_t i) const {
    if (!has(i)) throw OpError("missing required input " + std::to_string(i));
    return in[i];
  }
};

using OpFn = std::function<void(Ctx&)>;

at::ScalarType to_scalar_type(DType t) {
  switch (t) {
    case DType::Float32: return at::kFloat;
    case DType::Float64: return at::kDouble;
    case DType::Float16: return at::kHalf;
    case DType::Int8: return at::kChar;
    case DType::UInt8: return at::kByte;
    case DType::Int32: return at::kInt;
    case DType::Int64: return at::kLong;
    case DType::Bool: return at::kBool;
  }
  return at::kFloat;
}

DType to_dtype(at::ScalarType t) {
  switch (t) {
    case at::kFloat: return DType::Float32;
    case at::kDouble: return DType::Float64;
    case at::kHalf: return DType::Float16;
    case at::kChar: return DType::Int8;
    case at::kByte: return DType::UInt8;
    case at::kInt: return DType::Int32;
    case at::kLong: return DType::Int64;
    case at::kBool: return DType::Bool;
    default: break;
  }
  throw OpError(std::string("tensor type ") + c10::toString(t) + " has no ONNX equivalent here");
}

// ONNX TensorProto.DataType code -> ATen type (for Cast's `to`).
at::ScalarType onnx_code_to_scalar_type(int64_t code) {
  switch (code) {
    case 1: return at::kFloat;
    case 2: return at::kByte;
    case 3: return at::kChar;
    case 5: return at::kShort;
    case 6: return at::kInt;
    case 7: return at::kLong;
    case 9: return at::kBool;
    case 10: return at::kHalf;
    case 11: return at::kDouble;
    case 16: return at::kBFloat16;
    default: break;
  }
  throw OpError("unsupported element type code " + std::to_string(code));
}

at::Tensor to_aten(const HostTensor& h) {
  auto keep = h.bytes;
  std::vector<int64_t> shape = h.shape;
  if (keep->empty()) return at::empty(shape, at::TensorOptions().dtype(to_scalar_type(h.dtype)));
  return at::from_blob(
      keep->data(), shape, [keep](void*) mutable { keep.reset(); },
      at::TensorOptions().dtype(to_scalar_type(h.dtype)));
}

HostTensor to_host(const at::Tensor& t0) {
  at::Tensor t = t0.contiguous();
  HostTensor h(to_dtype(t.scalar_type()), t.sizes().vec());
  if (h.numel() > 0) std::memcpy(h.bytes->data(), t.data_ptr(), h.bytes->size());
  return h;
}

std::vector<int64_t> ints_of(const at::Tensor& t) {
  at::Tensor c = t.to(at::kLong).contiguous().reshape({-1});
  const int64_t* p = c.data_ptr<int64_t>();
  return std::vector<int64_t>(p, p + c.numel());
}

double scalar_of(const at::Tensor& t) {
  if (t.numel() != 1) throw OpError("expected a single-element tensor, got " + std::to_string(t.numel()) + " elements");
  return t.to(at::kDouble).reshape({-1})[0].item<double>();
}

int64_t norm_axis(int64_t axis, int64_t rank) {
  int64_t a = axis < 0 ? axis + rank : axis;
  if (a < 0 || a >= std::max<int64_t>(rank, 1))
    throw OpError("axis " + std::to_string(axis) + " out of range for rank " + std::to_string(rank));
  return a;
}

std::string shape_str(at::IntArrayRef s) {
  std::ostringstream o;
  o << "[";
  for (size_t i = 0; i < s.size(); ++i) o << (i ? "," : "") << s[i];
  o << "]";
  return o.str();
}

std::vector<int64_t> broadcast_shapes(std::vector<int64_t> a, std::vector<int64_t> b) {
  if (a.size() < b.size()) std::swap(a, b);
  b.insert(b.begin(), a.size() - b.size(), 1);
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i] == b[i] || b[i] == 1) continue;
    if (a[i] == 1) { a[i] = b[i]; continue; }
    throw OpError("shapes cannot be broadcast: " + shape_str(a) + " vs " + shape_str(b));
  }
  return a;
}

// ---------------------------------------------------------------- elementwise

void unary(std::map<std::string, OpFn>& r, const std::string& name, at::Tensor (*f)(const at::Tensor&)) {
  r[name] = [f](Ctx& c) { c.out = {f(c.input(0))}; };
}

template <class F>
void binary(std::map<std::string, OpFn>& r, const std::string& name, F f) {
  r[name] = [f](Ctx& c) { c.out = {f(c.input(0), c.input(1))}; };
}

at::Tensor onnx_div(const at::Tensor& a, const at::Tensor& b) {
  if (at::isIntegralType(a.scalar_type(), true) && at::isIntegralType(b.scalar_type(), true))
    return at::div(a, b, "trunc");
  return at::div(a, b);
}

at::Tensor onnx_pow(const at::Tensor& a, const at::Tensor& b) {
  if (b.numel() == 1 && at::isFloatingType(a.scalar_type())) {
    double e = scalar_of(b);
    if (e == 2.0) return a * a;
    if (e == 0.5) return at::sqrt(a);
    if (e == 1.0) return a.clone();
    return at::pow(a, e);
  }
  return at::pow(a, b).to(a.scalar_type());
}

// ---------------------------------------------------------------- reductions

std::vector<int64_t> reduce_axes(const Ctx& c, bool& reduce_all) {
  std::vector<int64_t> axes;
  if (c.node.has("axes")) axes = c.node.get_ints("axes", {});
  else if (c.has(1)) axes = ints_of(c.input(1));
  reduce_all = axes.empty();
  if (reduce_all && c.node.get_int("noop_with_empty_axes", 0)) reduce_all = false;
  int64_t rank = c.input(0).dim();
  for (auto& a : axes) a = norm_axis(a, rank);
  return axes;
}

template <class F>
OpFn reduce_op(F f) {
  return [f](Ctx& c) {
    bool all = false;
    std::vector<int64_t> axes = reduce_axes(c, all);
    const at::Tensor& x = c.input(0);
    bool keep = c.node.get_int("keepdims", 1) != 0;
    if (all) {
      axes.resize(x.dim());
      for (int64_t i = 0; i < x.dim(); ++i) axes[i] = i;
    }
    if (axes.empty()) { c.out = {x}; return; }
    c.out = {f(x, axes, keep)};
  };
}

// ---------------------------------------------------------------- resize

// Source coordinate of output index `o` along an axis, per ONNX's coordinate_transformation_mode.
double resize_source(const std::string& mode, double o, double scale, int64_t in, int64_t out) {
  if (mode == "half_pixel") return (o + 0.5) / scale - 0.5;
  if (mode == "pytorch_half_pixel") return out > 1 ? (o + 0.5) / scale - 0.5 : 0.0;
  if (mode == "align_corners") return out == 1 ? 0.0 : o * double(in - 1) / double(out - 1);
  if (mode == "asymmetric") return o / scale;
  if (mode == "tf_half_pixel_for_nn") return (o + 0.5) / scale;
  if (mode == "half_pixel_symmetric") {
    double adj = double(out) / (scale * double(in));
    double centre = double(in) / 2.0;
    double offset = centre * (1 - adj);
    return offset + (o + 0.5) / scale - 0.5;
  }
  throw OpError("coordinate_transformation_mode '" + mode + "' is not supported");
}

void op_resize(Ctx& c) {
  const at::Tensor& x = c.input(0);
  std::string mode = c.node.get_string("mode", "nearest");
  std::string coord = c.node.get_string("coordinate_transformation_mode", c.opset >= 11 ? "half_pixel" : "asymmetric");
  std::string nearest = c.node.get_string("nearest_mode", "round_prefer_floor");
  if (c.node.get_int("antialias", 0)) throw OpError("antialias=1 is not supported");
  if (c.node.has("axes")) throw OpError("the axes attribute is not supported");
  int64_t rank = x.dim();
  std::vector<double> scales(rank, 1.0);
  std::vector<int64_t> sizes(rank);
  size_t scales_index = c.opset >= 11 ? 2 : 1, sizes_index = 3;
  if (c.has(sizes_index) && c.input(sizes_index).numel() > 0) {
    sizes = ints_of(c.input(sizes_index));
    if (int64_t(sizes.size()) != rank) throw OpError("sizes has the wrong length");
    for (int64_t i = 0; i < rank; ++i) scales[i] = double(sizes[i]) / double(x.size(i));
  } else if (c.has(scales_index) && c.input(scales_index).numel() > 0) {
    at::Tensor s = c.input(scales_index).to(at::kDouble).contiguous();
    if (s.numel() != rank) throw OpError("scales has the wrong length");
    for (int64_t i = 0; i < rank; ++i) {
      scales[i] = s.data_ptr<double>()[i];
      sizes[i] = int64_t(std::floor(double(x.size(i)) * scales[i]));
    }
  } else {
    throw OpError("neither scales nor sizes given");
  }
  if (mode != "linear" && mode != "nearest") throw OpError("mode '" + mode + "' is not supported");
  if (mode == "linear" && rank == 4 && x.scalar_type() == at::kFloat && sizes[0] == x.size(0) && sizes[1] == x.size(1) &&
      (coord == "half_pixel" || coord == "align_corners" || (coord == "pytorch_half_pixel" && sizes[2] > 1 && sizes[3] > 1))) {
    // ATen's bilinear kernel computes the same source positions (clamped like ONNX Runtime).
    c.out = {at::upsample_bilinear2d(x, {sizes[2], sizes[3]}, coord == "align_corners", scales[2], scales[3])};
    return;
  }
  at::Tensor y = x;
  bool is_float = at::isFloatingType(x.scalar_type());
  for (int64_t axis = 0; axis < rank; ++axis) {
    int64_t in = x.size(axis), out = sizes[axis];
    if (in == out && scales[axis] == 1.0) continue;
    std::vector<int64_t> i0(out), i1(out);
    std::vector<float> w(out);
    for (int64_t o = 0; o < out; ++o) {
      double s = resize_source(coord, double(o), scales[axis], in, out);
      if (mode == "linear") {
        s = std::min(std::max(s, 0.0), double(in - 1));
        int64_t a = int64_t(std::floor(s));
        i0[o] = a;
        i1[o] = std::min(a + 1, in - 1);
        w[o] = float(s - double(a));
      } else {
        double r;
        if (nearest == "floor") r = std::floor(s);
        else if (nearest == "ceil") r = std::ceil(s);
        else if (nearest == "round_prefer_ceil") r = std::floor(s + 0.5);
        else if (nearest == "round_prefer_floor") r = (s - std::floor(s) == 0.5) ? std::floor(s) : std::round(s);
        else throw OpError("nearest_mode '" + nearest + "' is not supported");
        i0[o] = std::min(std::max<int64_t>(int64_t(r), 0), in - 1);
      }
    }
    at::Tensor idx0 = at::tensor(i0, at::kLong);
    if (mode == "nearest") {
      y = at::index_select(y, axis, idx0);
      continue;
    }
    if (!is_float) throw OpError("linear resize of a non-float tensor is not supported");
    std::vector<int64_t> wshape(rank, 1);
    wshape[axis] = out;
    at::Tensor wt = at::tensor(w, at::kFloat).to(x.scalar_type()).reshape(wshape);
    at::Tensor a = at::index_select(y, axis, idx0);
    at::Tensor b = at::index_select(y, axis, at::tensor(i1, at::kLong));
    y = at::lerp(a, b, wt);
  }
  c.out = {y.contiguous()};
}

// ---------------------------------------------------------------- convolution

void conv_pads(const Ctx& c, const at::Tensor& x, const std::vector<int64_t>& kernel, const std::vector<int64_t>& strides,
               const std::vector<int64_t>& dilations, std::vector<int64_t>& begin, std::vector<int64_t>& end) {
  size_t k = kernel.size();
  std::string auto_pad = c.node.get_string("auto_pad", "NOTSET");
  begin.assign(k, 0);
  end.assign(k, 0);
  if (auto_pad == "NOTSET") {
    std::vector<int64_t> pads = c.node.get_ints("pads", std::vector<int64_t>(2 * k, 0));
    if (pads.size() != 2 * k) throw OpError("pads has the wrong length");
    for (size_t i = 0; i < k; ++i) begin[i] = pads[i], end[i] = pads[i + k];
  } else if (auto_pad == "SAME_UPPER" || auto_pad == "SAME_LOWER") {
    for (size_t i = 0; i < k; ++i) {
      int64_t in = x.size(2 + i);
      int64_t out = (in + strides[i] - 1) / strides[i];
      int64_t total = std::max<int64_t>(0, (out - 1) * strides[i] + (kernel[i] - 1) * dilations[i] + 1 - in);
      int64_t small = total / 2, big = total - small;
      begin[i] = auto_pad == "SAME_UPPER" ? small : big;
      end[i] = auto_pad == "SAME_UPPER" ? big : small;
    }
  } else if (auto_pad != "VALID") {
    throw OpError("auto_pad '" + auto_pad + "' is not supported");
  }
}

// Depthwise convolution (one filter per channel), direct loops parallel over channels:
// ATen's CPU path without oneDNN would run one tiny convolution per group.
at::Tensor depthwise_conv2d(const at::Tensor& x0, const at::Tensor& w0, const at::Tensor& b0, const std::vector<int64_t>& stride,
                            const std::vector<int64_t>& pad, const std::vector<int64_t>& dil) {
  at::Tensor x = x0.contiguous(), w = w0.contiguous();
  int64_t n = x.size(0), ch = x.size(1), h = x.size(2), wd = x.size(3);
  int64_t kh = w.size(2), kw = w.size(3);
  int64_t oh = (h + 2 * pad[0] - dil[0] * (kh - 1) - 1) / stride[0] + 1;
  int64_t ow = (wd + 2 * pad[1] - dil[1] * (kw - 1) - 1) / stride[1] + 1;
  if (oh <= 0 || ow <= 0) throw OpError("depthwise convolution output would be empty");
  at::Tensor y = at::empty({n, ch, oh, ow}, x.options());
  const float* xp = x.data_ptr<float>();
  const float* wp = w.data_ptr<float>();
  at::Tensor b = b0.defined() ? b0.contiguous() : at::Tensor();
  const float* bp = b.defined() ? b.data_ptr<float>() : nullptr;
  float* yp = y.data_ptr<float>();
  int64_t sy = stride[0], sx = stride[1], py = pad[0], px = pad[1], dy = dil[0], dx = dil[1];
  // 3x3 taps, dilation 1 (all of TinyViT's): an output row whose three input rows lie inside
  // the image sums, for the columns whose taps all lie inside the row, its nine taps in a
  // register (the order below: the same sums) instead of nine passes over the row in memory.
  const bool three = kh == 3 && kw == 3 && dy == 1 && dx == 1;
  const int64_t inner_lo = three ? std::min(ow, (px + sx - 1) / sx) : 0;
  const int64_t inner_hi = three && wd - 3 + px >= 0 ? std::max(inner_lo, std::min(ow, (wd - 3 + px) / sx + 1)) : inner_lo;
  at::parallel_for(0, n * ch, 1, [&](int64_t begin, int64_t end) {
    for (int64_t nc = begin; nc < end; ++nc) {
      int64_t c = nc % ch;
      const float* in = xp + nc * h * wd;
      const float* k = wp + c * kh * kw;
      float* out = yp + nc * oh * ow;
      float bias = bp ? bp[c] : 0.f;
      for (int64_t oy = 0; oy < oh; ++oy) {
        float* o = out + oy * ow;
        const int64_t iy0 = oy * sy - py;
        if (three && iy0 >= 0 && iy0 + 2 < h && inner_hi > inner_lo) {
          const float* r0 = in + iy0 * wd;
          const float* r1 = r0 + wd;
          const float* r2 = r1 + wd;
          const float k0 = k[0], k1 = k[1], k2 = k[2], k3 = k[3], k4 = k[4], k5 = k[5], k6 = k[6], k7 = k[7], k8 = k[8];
          auto tap_sum = [&](int64_t i) {
            float acc = bias;
            acc += k0 * r0[i];
            acc += k1 * r0[i + 1];
            acc += k2 * r0[i + 2];
            acc += k3 * r1[i];
            acc += k4 * r1[i + 1];
            acc += k5 * r1[i + 2];
            acc += k6 * r2[i];
            acc += k7 * r2[i + 1];
            acc += k8 * r2[i + 2];
            return acc;
          };
          if (sx == 1)
            for (int64_t ox = inner_lo; ox < inner_hi; ++ox) o[ox] = tap_sum(ox - px);
          else
            for (int64_t ox = inner_lo; ox < inner_hi; ++ox) o[ox] = tap_sum(ox * sx - px);
          // The columns at the row's ends, tap by tap as below.
          for (int64_t ox = 0; ox < ow; ++ox) {
            if (ox == inner_lo) ox = inner_hi;
            if (ox >= ow) break;
            float acc = bias;
            for (int64_t ky = 0; ky < 3; ++ky)
              for (int64_t kx = 0; kx < 3; ++kx) {
                const int64_t ix = ox * sx - px + kx;
                if (ix >= 0 && ix < wd) acc += k[ky * 3 + kx] * in[(iy0 + ky) * wd + ix];
              }
            o[ox] = acc;
          }
          continue;
        }
        for (int64_t ox = 0; ox < ow; ++ox) o[ox] = bias;
        for (int64_t ky = 0; ky < kh; ++ky) {
          int64_t iy = oy * sy - py + ky * dy;
          if (iy < 0 || iy >= h) continue;
          const float* irow = in + iy * wd;
          for (int64_t kx = 0; kx < kw; ++kx) {
            float wv = k[ky * kw + kx];
            int64_t off = kx * dx - px;
            // Output columns whose input column lies inside the row.
            int64_t lo = off < 0 ? (-off + sx - 1) / sx : 0;
            int64_t hi = std::min(ow, (wd - off + sx - 1) / sx);
            if (sx == 1) {
              const float* src = irow + off;
              for (int64_t ox = lo; ox < hi; ++ox) o[ox] += wv * src[ox];
            } else {
              for (int64_t ox = lo; ox < hi; ++ox) o[ox] += wv * irow[ox * sx + off];
            }
          }
        }
      }
    }
  });
  return y;
}

void op_conv(Ctx& c) {
  at::Tensor x = c.input(0);
  const at::Tensor& w = c.input(1);
  at::Tensor b = c.has(2) ? c.in[2] : at::Tensor();
  int64_t k = w.dim() - 2;
  if (x.dim() != w.dim()) throw OpError("input rank " + std::to_string(x.dim()) + " does not match weight rank " + std::to_string(w.dim()));
  std::vector<int64_t> kernel(w.sizes().begin() + 2, w.sizes().end());
  std::vector<int64_t> strides = c.node.get_ints("strides", std::vector<int64_t>(k, 1));
  std::vector<int64_t> dilations = c.node.get_ints("dilations", std::vector<int64_t>(k, 1));
  int64_t group = c.node.get_int("group", 1);
  std::vector<int64_t> begin, end;
  conv_pads(c, x, kernel, strides, dilations, begin, end);
  std::vector<int64_t> padding(k, 0);
  if (begin == end) {
    padding = begin;
  } else {
    std::vector<int64_t> tp;
    for (int64_t i = k - 1; i >= 0; --i) tp.push_back(begin[i]), tp.push_back(end[i]);
    x = at::constant_pad_nd(x, tp, 0);
  }
  if (x.size(1) != w.size(1) * group)
    throw OpError("input has " + std::to_string(x.size(1)) + " channels, weight expects " + std::to_string(w.size(1) * group));
  bool unit = true;
  for (int64_t i = 0; i < k; ++i) unit = unit && strides[i] == 1 && dilations[i] == 1;
  if (k == 2 && group == 1 && unit && kernel[0] == 1 && kernel[1] == 1 && padding[0] == 0 && padding[1] == 0) {
    c.out = {conv1x1(x, w, b)};
    return;
  }
  if (k == 2 && group > 1 && group == x.size(1) && w.size(0) == group && w.size(1) == 1 &&
      x.scalar_type() == at::kFloat && w.scalar_type() == at::kFloat) {
    c.out = {depthwise_conv2d(x, w, b, strides, padding, dilations)};
    return;
  }
  std::vector<int64_t> output_padding(k, 0);
  c.out = {at::convolution(x, w, b, strides, padding, dilations, false, output_padding, group)};
}

void op_conv_transpose(Ctx& c) {
  const at::Tensor& x = c.input(0);
  const at::Tensor& w = c.input(1);
  at::Tensor b = c.has(2) ? c.in[2] : at::Tensor();
  int64_t k = w.dim() - 2;
  std::vector<int64_t> kernel(w.sizes().begin() + 2, w.sizes().end());
  std::vector<int64_t> strides = c.node.get_ints("strides", std::vector<int64_t>(k, 1));
  std::vector<int64_t> dilations = c.node.get_ints("dilations", std::vector<int64_t>(k, 1));
  std::vector<int64_t> out_pad = c.node.get_ints("output_padding", std::vector<int64_t>(k, 0));
  int64_t group = c.node.get_int("group", 1);
  std::vector<int64_t> pads = c.node.get_ints("pads", std::vector<int64_t>(2 * k, 0));
  std::string auto_pad = c.node.get_string("auto_pad", "NOTSET");
  if (c.node.has("output_shape") || (auto_pad != "NOTSET" && auto_pad != "VALID"))
    throw OpError("output_shape / auto_pad are not supported");
  std::vector<int64_t> begin(pads.begin(), pads.begin() + k), end(pads.begin() + k, pads.end());
  bool shuffle = k == 2 && group == 1 && x.scalar_type() == at::kFloat;
  for (int64_t i = 0; i < k; ++i)
    shuffle = shuffle && kernel[i] == strides[i] && dilations[i] == 1 && begin[i] == 0 && end[i] == 0 && out_pad[i] == 0;
  if (shuffle) {
    c.out = {conv_transpose_blocks(x, w, b)};  // non-overlapping kernels: a matrix product
    return;
  }
  if (begin == end) {
    c.out = {at::convolution(x, w, b, strides, begin, dilations, true, out_pad, group)};
    return;
  }
  // Asymmetric pads: compute the full result and crop it.
  at::Tensor full = at::convolution(x, w, {}, strides, std::vector<int64_t>(k, 0), dilations, true, out_pad, group);
  at::Tensor y = full;
  for (int64_t i = 0; i < k; ++i) {
    int64_t len = full.size(2 + i) - begin[i] - end[i];
    y = y.narrow(2 + i, begin[i], len);
  }
  if (b.defined()) {
    std::vector<int64_t> bs(y.dim(), 1);
    bs[1] = b.numel();
    y = y + b.reshape(bs);
  }
  c.out = {y.contiguous()};
}

// ---------------------------------------------------------------- shapes and indexing

void op_slice(Ctx& c) {
  const at::Tensor& x = c.input(0);
  std::vector<int64_t> starts, ends, axes, steps;
  if (c.opset < 10) {
    starts = c.node.get_ints("starts", {});
    ends = c.node.get_ints("ends", {});
    axes = c.node.get_ints("axes", {});
  } else {
    starts = ints_of(c.input(1));
    ends = ints_of(c.input(2));
    if (c.has(3)) axes = ints_of(c.in[3]);
    if (c.has(4)) steps = ints_of(c.in[4]);
  }
  if (axes.empty())
    for (size_t i = 0; i < starts.size(); ++i) axes.push_back(int64_t(i));
  if (steps.empty()) steps.assign(starts.size(), 1);
  if (ends.size() != starts.size() || axes.size() != starts.size() || steps.size() != starts.size())
    throw OpError("starts/ends/axes/steps lengths differ");
  at::Tensor y = x;
  for (size_t i = 0; i < starts.size(); ++i) {
    int64_t axis = norm_axis(axes[i], x.dim());
    int64_t dim = x.size(axis), step = steps[i];
    if (step == 0) throw OpError("step 0");
    int64_t s = starts[i], e = ends[i];
    if (s < 0) s += dim;
    if (e < 0) e += dim;
    if (step > 0) {
      s = std::clamp<int64_t>(s, 0, dim);
      e = std::clamp<int64_t>(e, 0, dim);
      y = at::slice(y, axis, s, std::max(s, e), step);
    } else {
      s = std::clamp<int64_t>(s, 0, dim - 1);
      e = std::clamp<int64_t>(e, -1, dim - 1);
      std::vector<int64_t> idx;
      for (int64_t j = s; j > e; j += step) idx.push_back(j);
      y = at::index_select(y, axis, at::tensor(idx, at::kLong));
    }
  }
  c.out = {y};
}

void op_gather(Ctx& c) {
  const at::Tensor& x = c.input(0);
  int64_t axis = norm_axis(c.node.get_int("axis", 0), x.dim());
  at::Tensor idx = c.input(1).to(at::kLong);
  idx = at::where(idx < 0, idx + x.size(axis), idx);
  std::vector<int64_t> shape(x.sizes().begin(), x.sizes().begin() + axis);
  for (int64_t d : idx.sizes()) shape.push_back(d);
  for (int64_t i = axis + 1; i < x.dim(); ++i) shape.push_back(x.size(i));
  c.out = {at::index_select(x, axis, idx.reshape({-1})).reshape(shape)};
}

void op_reshape(Ctx& c) {
  const at::Tensor& x = c.input(0);
  std::vector<int64_t> shape = c.opset >= 5 ? ints_of(c.input(1)) : c.node.get_ints("shape", {});
  bool allowzero = c.node.get_int("allowzero", 0) != 0;
  for (size_t i = 0; i < shape.size(); ++i)
    if (shape[i] == 0 && !allowzero) {
      if (int64_t(i) >= x.dim()) throw OpError("shape has 0 at an axis the input lacks");
      shape[i] = x.size(int64_t(i));
    }
  try {
    c.out = {x.reshape(shape)};
  } catch (const c10::Error&) {
    throw OpError("cannot reshape " + shape_str(x.sizes()) + " to " + shape_str(shape));
  }
}

void op_unsqueeze(Ctx& c) {
  at::Tensor x = c.input(0);
  std::vector<int64_t> axes = c.opset >= 13 ? ints_of(c.input(1)) : c.node.get_ints("axes", {});
  int64_t out_rank = x.dim() + int64_t(axes.size());
  for (auto& a : axes) a = norm_axis(a, out_rank);
  std::sort(axes.begin(), axes.end());
  for (int64_t a : axes) x = x.unsqueeze(a);
  c.out = {x};
}

void op_squeeze(Ctx& c) {
  at::Tensor x = c.input(0);
  std::vector<int64_t> axes;
  if (c.opset >= 13) {
    if (c.has(1)) axes = ints_of(c.in[1]);
  } else {
    axes = c.node.get_ints("axes", {});
  }
  if (axes.empty()) {
    std::vector<int64_t> shape;
    for (int64_t d : x.sizes())
      if (d != 1) shape.push_back(d);
    c.out = {x.reshape(shape)};
    return;
  }
  for (auto& a : axes) a = norm_axis(a, x.dim());
  std::sort(axes.rbegin(), axes.rend());
  for (int64_t a : axes) {
    if (x.size(a) != 1) throw OpError("cannot squeeze axis " + std::to_string(a) + " of size " + std::to_string(x.size(a)));
    x = x.squeeze(a);
  }
  c.out = {x};
}

void op_transpose(Ctx& c) {
  const at::Tensor& x = c.input(0);
  std::vector<int64_t> perm = c.node.get_ints("perm", {});
  if (perm.empty())
    for (int64_t i = x.dim() - 1; i >= 0; --i) perm.push_back(i);
  if (int64_t(perm.size()) != x.dim()) throw OpError("perm length does not match rank " + std::to_string(x.dim()));
  // A large swap of the last two axes (SAM's decoder: the image embedding as [1, 4096, 256]
  // tokens) is copied once: elementwise ops, layer norms and linears read it several times,
  // each far slower on the transposed view (and adds pass its strides on to their results).
  bool swap_last = x.dim() >= 2 && x.scalar_type() == at::kFloat && x.is_contiguous() && x.numel() >= (1 << 16) &&
                   perm[size_t(x.dim() - 1)] == x.dim() - 2 && perm[size_t(x.dim() - 2)] == x.dim() - 1;
  for (int64_t i = 0; i + 2 < x.dim(); ++i) swap_last = swap_last && perm[size_t(i)] == i;
  if (swap_last) {
    c.out = {transpose_last_two(x)};
    return;
  }
  c.out = {x.permute(perm)};
}

void op_concat(Ctx& c) {
  std::vector<at::Tensor> parts;
  for (const auto& t : c.in)
    if (t.defined()) parts.push_back(t);
  if (parts.empty()) throw OpError("no inputs");
  int64_t axis = norm_axis(c.node.get_int("axis", 0), parts[0].dim());
  // ONNX allows empty tensors of any type among the parts (e.g. empty shape vectors).
  at::ScalarType type = parts[0].scalar_type();
  for (auto& p : parts)
    if (p.scalar_type() != type) p = p.to(type);
  c.out = {at::cat(parts, axis)};
}

void op_split(Ctx& c) {
  const at::Tensor& x = c.input(0);
  int64_t axis = norm_axis(c.node.get_int("axis", 0), x.dim());
  std::vector<int64_t> split;
  if (c.node.has("split")) split = c.node.get_ints("split", {});
  else if (c.has(1)) split = ints_of(c.in[1]);
  size_t n = c.node.outputs.size();
  if (split.empty()) {
    int64_t parts = c.node.has("num_outputs") ? c.node.get_int("num_outputs", 1) : int64_t(n);
    int64_t each = (x.size(axis) + parts - 1) / parts;
    for (int64_t i = 0, left = x.size(axis); i < parts; ++i, left -= each) split.push_back(std::min(each, left));
  }
  int64_t total = 0;
  for (int64_t s : split) total += s;
  if (total != x.size(axis)) throw OpError("split sizes do not add up to the axis size " + std::to_string(x.size(axis)));
  std::vector<at::Tensor> parts = at::split_with_sizes(x, split, axis);
  c.out.assign(parts.begin(), parts.end());
}

void op_expand(Ctx& c) {
  const at::Tensor& x = c.input(0);
  std::vector<int64_t> shape = broadcast_shapes(x.sizes().vec(), ints_of(c.input(1)));
  c.out = {x.expand(shape)};
}

void op_tile(Ctx& c) {
  std::vector<int64_t> reps = ints_of(c.input(1));
  if (int64_t(reps.size()) != c.input(0).dim()) throw OpError("repeats length does not match the rank");
  c.out = {c.input(0).repeat(reps)};
}

void op_shape(Ctx& c) {
  std::vector<int64_t> s = c.input(0).sizes().vec();
  int64_t r = int64_t(s.size());
  int64_t start = c.node.get_int("start", 0), end = c.node.get_int("end", r);
  if (start < 0) start += r;
  if (end < 0) end += r;
  start = std::clamp<int64_t>(start, 0, r);
  end = std::clamp<int64_t>(end, start, r);
  c.out = {at::tensor(std::vector<int64_t>(s.begin() + start, s.begin() + end), at::kLong)};
}

at::Tensor tensor_attr(const Node& n, const std::string& a) { return to_aten(n.attrs.at(a).t).clone(); }

void op_constant(Ctx& c) {
  const Node& n = c.node;
  if (n.has("value")) c.out = {tensor_attr(n, "value")};
  else if (n.has("value_float")) c.out = {at::scalar_tensor(n.get_float("value_float", 0), at::kFloat)};
  else if (n.has("value_int")) c.out = {at::scalar_tensor(n.get_int("value_int", 0), at::kLong)};
  else if (n.has("value_floats")) c.out = {at::tensor(n.attrs.at("value_floats").floats, at::kFloat)};
  else if (n.has("value_ints")) c.out = {at::tensor(n.attrs.at("value_ints").ints, at::kLong)};
  else throw OpError("no supported value attribute");
}

void op_constant_of_shape(Ctx& c) {
  std::vector<int64_t> shape = ints_of(c.input(0));
  at::Tensor v = c.node.has("value") ? tensor_attr(c.node, "value") : at::zeros({1}, at::kFloat);
  c.out = {at::full(shape, v.reshape({-1})[0].item(), at::TensorOptions().dtype(v.scalar_type()))};
}

void op_range(Ctx& c) {
  const at::Tensor& start = c.input(0);
  at::ScalarType t = start.scalar_type();
  if (at::isIntegralType(t, false)) {
    int64_t s = int64_t(scalar_of(start)), l = int64_t(scalar_of(c.input(1))), d = int64_t(scalar_of(c.input(2)));
    if (d == 0) throw OpError("delta 0");
    int64_t n = std::max<int64_t>(0, (l - s + d + (d > 0 ? -1 : 1)) / d);
    c.out = {(at::arange(n, at::kLong) * d + s).to(t)};
  } else {
    double s = scalar_of(start), l = scalar_of(c.input(1)), d = scalar_of(c.input(2));
    int64_t n = std::max<int64_t>(0, int64_t(std::ceil((l - s) / d)));
    c.out = {(at::arange(n, at::kDouble) * d + s).to(t)};
  }
}

void op_one_hot(Ctx& c) {
  at::Tensor idx = c.input(0).to(at::kLong);
  int64_t depth = int64_t(scalar_of(c.input(1)));
  const at::Tensor& values = c.input(2);
  idx = at::where(idx < 0, idx + depth, idx);
  at::Tensor hot = idx.unsqueeze(-1) == at::arange(depth, at::kLong);
  at::Tensor v = values.reshape({-1});
  at::Tensor y = at::where(hot, v[1], v[0]);
  int64_t axis = c.node.get_int("axis", -1);
  int64_t rank = y.dim();
  axis = norm_axis(axis, rank);
  if (axis != rank - 1) y = y.movedim(rank - 1, axis);
  c.out = {y.contiguous()};
}

void op_pad(Ctx& c) {
  const at::Tensor& x = c.input(0);
  std::string mode = c.node.get_string("mode", "constant");
  std::vector<int64_t> pads;
  double value = 0;
  std::vector<int64_t> axes;
  if (c.opset >= 11) {
    pads = ints_of(c.input(1));
    if (c.has(2) && c.in[2].numel() > 0) value = scalar_of(c.in[2]);
    if (c.has(3)) axes = ints_of(c.in[3]);
  } else {
    pads = c.node.get_ints("pads", {});
    value = c.node.get_float("value", 0);
  }
  int64_t r = x.dim();
  if (axes.empty())
    for (int64_t i = 0; i < r; ++i) axes.push_back(i);
  if (pads.size() != 2 * axes.size()) throw OpError("pads has the wrong length");
  std::vector<int64_t> begin(r, 0), end(r, 0);
  for (size_t i = 0; i < axes.size(); ++i) {
    int64_t a = norm_axis(axes[i], r);
    begin[a] = pads[i];
    end[a] = pads[i + axes.size()];
  }
  // ATen wants pairs from the last axis backwards; trim leading all-zero axes.
  int64_t first = 0;
  while (first < r && begin[first] == 0 && end[first] == 0) ++first;
  std::vector<int64_t> tp;
  for (int64_t i = r - 1; i >= first; --i) tp.push_back(begin[i]), tp.push_back(end[i]);
  if (tp.empty()) { c.out = {x}; return; }
  if (mode == "constant") c.out = {at::constant_pad_nd(x, tp, value)};
  else if (mode == "reflect") c.out = {at::pad(x, tp, "reflect")};
  else if (mode == "edge") c.out = {at::pad(x, tp, "replicate")};
  else throw OpError("mode '" + mode + "' is not supported");
}

// ---------------------------------------------------------------- neural-network ops

void op_matmul(Ctx& c) { c.out = {batched_matmul(c.input(0), c.input(1))}; }

void op_gemm(Ctx& c) {
  const at::Tensor& a = c.input(0);
  const at::Tensor& b = c.input(1);
  bool ta = c.node.get_int("transA", 0) != 0, tb = c.node.get_int("transB", 0) != 0;
  float alpha = c.node.get_float("alpha", 1.0f), beta = c.node.get_float("beta", 1.0f);
  if (a.dim() != 2 || b.dim() != 2) throw OpError("Gemm needs 2-D inputs");
  if (a.scalar_type() != at::kFloat || b.scalar_type() != at::kFloat) {
    at::Tensor at = ta ? a.t() : a, bt = tb ? b.t() : b;
    at::Tensor y = at::mm(at, bt) * alpha;
    c.out = {c.has(2) ? y + c.in[2] * beta : y};
    return;
  }
  at::Tensor A = a.contiguous(), B = b.contiguous();
  int64_t m = ta ? A.size(1) : A.size(0), k = ta ? A.size(0) : A.size(1);
  int64_t n = tb ? B.size(0) : B.size(1), kb = tb ? B.size(1) : B.size(0);
  if (k != kb) throw OpError("inner dimensions differ");
  at::Tensor y = at::empty({m, n}, A.options());
  float accumulate = 0.0f;
  if (c.has(2) && beta != 0.0f) {
    y.copy_(c.in[2].expand({m, n}));
    if (beta != 1.0f) y.mul_(beta);
    accumulate = 1.0f;
  }
  if (k == 0) {
    if (accumulate == 0.0f) y.zero_();
  } else {
    sgemm(ta, tb, m, n, k, alpha, A.data_ptr<float>(), A.size(1), B.data_ptr<float>(), B.size(1), accumulate,
          y.data_ptr<float>(), n);
  }
  c.out = {y};
}

// ONNX Softmax / LogSoftmax: from opset 13 over one axis; before, over the flattened axes
// from `axis` on (the same thing when axis is the last one).
at::Tensor onnx_softmax(const at::Tensor& x, int64_t axis_attr, int64_t opset, bool log) {
  int64_t axis = norm_axis(axis_attr, x.dim());
  if (opset >= 13 || axis == x.dim() - 1) return log ? at::log_softmax(x, axis) : at::softmax(x, axis);
  int64_t rows = 1;
  for (int64_t i = 0; i < axis; ++i) rows *= x.size(i);
  at::Tensor f = x.reshape({rows, -1});
  return (log ? at::log_softmax(f, 1) : at::softmax(f, 1)).reshape(x.sizes());
}

void op_softmax(Ctx& c, bool log) {
  c.out = {onnx_softmax(c.input(0), c.node.get_int("axis", c.opset >= 13 ? -1 : 1), c.opset, log)};
}

void op_layer_norm(Ctx& c) {
  const at::Tensor& x = c.input(0);
  int64_t axis = norm_axis(c.node.get_int("axis", -1), x.dim());
  double eps = c.node.get_float("epsilon", 1e-5f);
  std::vector<int64_t> shape(x.sizes().begin() + axis, x.sizes().end());
  at::Tensor scale = c.input(1);
  at::Tensor bias = c.has(2) ? c.in[2] : at::Tensor();
  if (scale.sizes().vec() != shape) scale = scale.expand(shape).contiguous();
  if (bias.defined() && bias.sizes().vec() != shape) bias = bias.expand(shape).contiguous();
  c.out.assign(c.node.outputs.size(), at::Tensor());
  c.out[0] = at::layer_norm(x, shape, scale, bias, eps);
  if (c.node.outputs.size() > 1) {
    std::vector<int64_t> dims;
    for (int64_t i = axis; i < x.dim(); ++i) dims.push_back(i);
    at::Tensor mean = x.mean(dims, true);
    c.out[1] = mean;
    if (c.node.outputs.size() > 2) c.out[2] = at::rsqrt((x - mean).pow(2).mean(dims, true) + eps);
  }
}

void op_batch_norm(Ctx& c) {
  c.out = {at::batch_norm(c.input(0), c.input(1), c.input(2), c.input(3), c.input(4), false, 0.0,
                          c.node.get_float("epsilon", 1e-5f), false)};
}

void op_instance_norm(Ctx& c) {
  c.out = {at::instance_norm(c.input(0), c.input(1), c.input(2), {}, {}, true, 0.0, c.node.get_float("epsilon", 1e-5f),
                             false)};
}

void op_clip(Ctx& c) {
  at::Tensor x = c.input(0);
  if (c.opset >= 11) {
    if (c.has(1)) x = at::maximum(x, c.in[1].to(x.scalar_type()));
    if (c.has(2)) x = at::minimum(x, c.in[2].to(x.scalar_type()));
  } else {
    x = at::clamp(x, c.node.get_float("min", -INFINITY), c.node.get_float("max", INFINITY));
  }
  c.out = {x};
}

void op_argmax(Ctx& c, bool is_max) {
  at::Tensor x = c.input(0);
  int64_t axis = norm_axis(c.node.get_int("axis", 0), x.dim());
  bool keep = c.node.get_int("keepdims", 1) != 0;
  if (c.node.get_int("select_last_index", 0)) {
    at::Tensor flipped = x.flip(axis);
    at::Tensor i = is_max ? at::argmax(flipped, axis, keep) : at::argmin(flipped, axis, keep);
    c.out = {x.size(axis) - 1 - i};
    return;
  }
  c.out = {is_max ? at::argmax(x, axis, keep) : at::argmin(x, axis, keep)};
}

void op_cast(Ctx& c) { c.out = {c.input(0).to(onnx_code_to_scalar_type(c.node.get_int("to", 1)))}; }

template <class F>
OpFn variadic(F f) {
  return [f](Ctx& c) {
    at::Tensor acc = c.input(0);
    for (size_t i = 1; i < c.in.size(); ++i)
      if (c.in[i].defined()) acc = f(acc, c.in[i]);
    c.out = {acc};
  };
}

const std::map<std::string, OpFn>& registry() {
  static const std::map<std::string, OpFn> reg = [] {
    std::map<std::string, OpFn> r;
    binary(r, "Add", [](const at::Tensor& a, const at::Tensor& b) { return a + b; });
    binary(r, "Sub", [](const at::Tensor& a, const at::Tensor& b) { return a - b; });
    binary(r, "Mul", [](const at::Tensor& a, const at::Tensor& b) { return a * b; });
    binary(r, "Div", onnx_div);
    binary(r, "Pow", onnx_pow);
    binary(r, "Equal", [](const at::Tensor& a, const at::Tensor& b) { return at::eq(a, b); });
    binary(r, "Less", [](const at::Tensor& a, const at::Tensor& b) { return at::lt(a, b); });
    binary(r, "LessOrEqual", [](const at::Tensor& a, const at::Tensor& b) { return at::le(a, b); });
    binary(r, "Greater", [](const at::Tensor& a, const at::Tensor& b) { return at::gt(a, b); });
    binary(r, "GreaterOrEqual", [](const at::Tensor& a, const at::Tensor& b) { return at::ge(a, b); });
    binary(r, "And", [](const at::Tensor& a, const at::Tensor& b) { return at::logical_and(a, b); });
    binary(r, "Or", [](const at::Tensor& a, const at::Tensor& b) { return at::logical_or(a, b); });
    binary(r, "Xor", [](const at::Tensor& a, const at::Tensor& b) { return at::logical_xor(a, b); });
    r["Mod"] = [](Ctx& c) {
      c.out = {c.node.get_int("fmod", 0) ? at::fmod(c.input(0), c.input(1)) : at::remainder(c.input(0), c.input(1))};
    };
    r["Max"] = variadic([](const at::Tensor& a, const at::Tensor& b) { return at::maximum(a, b); });
    r["Min"] = variadic([](const at::Tensor& a, const at::Tensor& b) { return at::minimum(a, b); });
    r["Sum"] = variadic([](const at::Tensor& a, const at::Tensor& b) { return a + b; });
    r["Mean"] = [](Ctx& c) {
      at::Tensor acc = c.input(0);
      for (size_t i = 1; i < c.in.size(); ++i) acc = acc + c.in[i];
      c.out = {acc / double(c.in.size())};
    };
    unary(r, "Sqrt", at::sqrt);
    unary(r, "Erf", at::erf);
    unary(r, "Exp", at::exp);
    unary(r, "Log", at::log);
    unary(r, "Sin", at::sin);
    unary(r, "Cos", at::cos);
    unary(r, "Tan", at::tan);
    unary(r, "Atan", at::atan);
    unary(r, "Tanh", at::tanh);
    unary(r, "Sigmoid", at::sigmoid);
    unary(r, "Relu", at::relu);
    unary(r, "Abs", at::abs);
    unary(r, "Neg", at::neg);
    unary(r, "Floor", at::floor);
    unary(r, "Ceil", at::ceil);
    unary(r, "Round", at::round);
    unary(r, "Reciprocal", at::reciprocal);
    unary(r, "Not", at::logical_not);
    unary(r, "Sign", at::sign);
    unary(r, "IsNaN", at::isnan);
    unary(r, "Softplus", [](const at::Tensor& x) { return at::softplus(x); });
    unary(r, "Softsign", [](const at::Tensor& x) { return x / (at::abs(x) + 1); });
    unary(r, "HardSwish", [](const at::Tensor& x) { return at::hardswish(x); });
    r["Identity"] = [](Ctx& c) { c.out = {c.input(0)}; };
    r["Dropout"] = [](Ctx& c) {
      c.out = {c.input(0)};
      if (c.node.outputs.size() > 1) c.out.push_back(at::ones(c.input(0).sizes(), at::kBool));
    };
    r["LeakyRelu"] = [](Ctx& c) { c.out = {at::leaky_relu(c.input(0), c.node.get_float("alpha", 0.01f))}; };
    r["Elu"] = [](Ctx& c) { c.out = {at::elu(c.input(0), c.node.get_float("alpha", 1.0f))}; };
    r["HardSigmoid"] = [](Ctx& c) {
      c.out = {at::clamp(c.input(0) * c.node.get_float("alpha", 0.2f) + c.node.get_float("beta", 0.5f), 0, 1)};
    };
    r["Gelu"] = [](Ctx& c) {
      c.out = {at::gelu(c.input(0), c.node.get_string("approximate", "none") == "tanh" ? "tanh" : "none")};
    };
    r["Clip"] = op_clip;
    r["Cast"] = op_cast;
    r["CastLike"] = [](Ctx& c) { c.out = {c.input(0).to(c.input(1).scalar_type())}; };
    r["Where"] = [](Ctx& c) {
      at::Tensor a = c.input(1), b = c.input(2);
      c.out = {at::where(c.input(0).to(at::kBool), a, b.to(a.scalar_type()))};
    };

    r["ReduceMean"] = reduce_op([](const at::Tensor& x, at::IntArrayRef a, bool k) { return at::mean(x, a, k); });
    r["ReduceSum"] = reduce_op([](const at::Tensor& x, at::IntArrayRef a, bool k) { return at::sum(x, a, k, x.scalar_type()); });
    r["ReduceMax"] = reduce_op([](const at::Tensor& x, at::IntArrayRef a, bool k) { return at::amax(x, a, k); });
    r["ReduceMin"] = reduce_op([](const at::Tensor& x, at::IntArrayRef a, bool k) { return at::amin(x, a, k); });
    r["ReduceProd"] = reduce_op([](const at::Tensor& x, at::IntArrayRef a, bool k) {
      std::vector<int64_t> axes(a.begin(), a.end());
      std::sort(axes.rbegin(), axes.rend());
      at::Tensor y = x;
      for (int64_t ax : axes) y = at::prod(y, ax, k);
      return y;
    });
    r["ReduceL2"] = reduce_op([](const at::Tensor& x, at::IntArrayRef a, bool k) { return at::sqrt(at::sum(x * x, a, k)); });
    r["ArgMax"] = [](Ctx& c) { op_argmax(c, true); };
    r["ArgMin"] = [](Ctx& c) { op_argmax(c, false); };
    r["CumSum"] = [](Ctx& c) {
      if (c.node.get_int("exclusive", 0) || c.node.get_int("reverse", 0)) throw OpError("exclusive/reverse are not supported");
      c.out = {at::cumsum(c.input(0), norm_axis(int64_t(scalar_of(c.input(1))), c.input(0).dim()))};
    };

    r["Shape"] = op_shape;
    r["Size"] = [](Ctx& c) { c.out = {at::scalar_tensor(c.input(0).numel(), at::kLong)}; };
    r["Reshape"] = op_reshape;
    r["Flatten"] = [](Ctx& c) {
      const at::Tensor& x = c.input(0);
      int64_t axis = c.node.get_int("axis", 1);
      if (axis < 0) axis += x.dim();
      int64_t rows = 1;
      for (int64_t i = 0; i < axis; ++i) rows *= x.size(i);
      c.out = {x.reshape({rows, rows == 0 ? 0 : -1})};
    };
    r["Squeeze"] = op_squeeze;
    r["Unsqueeze"] = op_unsqueeze;
    r["Transpose"] = op_transpose;
    r["Concat"] = op_concat;
    r["Split"] = op_split;
    r["Slice"] = op_slice;
    r["Gather"] = op_gather;
    r["GatherElements"] = [](Ctx& c) {
      const at::Tensor& x = c.input(0);
      int64_t axis = norm_axis(c.node.get_int("axis", 0), x.dim());
      at::Tensor idx = c.input(1).to(at::kLong);
      idx = at::where(idx < 0, idx + x.size(axis), idx);
      c.out = {at::gather(x, axis, idx)};
    };
    r["Expand"] = op_expand;
    r["Tile"] = op_tile;
    r["Constant"] = op_constant;
    r["ConstantOfShape"] = op_constant_of_shape;
    r["Range"] = op_range;
    r["OneHot"] = op_one_hot;
    r["Pad"] = op_pad;
    r["Einsum"] = [](Ctx& c) {
      std::vector<at::Tensor> ins;
      for (const auto& t : c.in) ins.push_back(t);
      c.out = {at::einsum(c.node.get_string("equation", ""), ins)};
    };

    r["MatMul"] = op_matmul;
    r["Gemm"] = op_gemm;
    r["Conv"] = op_conv;
    r["ConvTranspose"] = op_conv_transpose;
    r["Softmax"] = [](Ctx& c) { op_softmax(c, false); };
    r["LogSoftmax"] = [](Ctx& c) { op_softmax(c, true); };
    r["LayerNormalization"] = op_layer_norm;
    r["BatchNormalization"] = op_batch_norm;
    r["InstanceNormalization"] = op_instance_norm;
    r["GlobalAveragePool"] = [](Ctx& c) {
      const at::Tensor& x = c.input(0);
      std::vector<int64_t> dims;
      for (int64_t i = 2; i < x.dim(); ++i) dims.push_back(i);
      c.out = {x.mean(dims, true)};
    };
    r["Resize"] = op_resize;
    return r;
  }();
  return reg;
}

// Internal operators the fusion pass creates (never read from files).
const OpFn& fused_linear() {
  // x @ W + b with W [K, N] constant and b [N]: one addmm over the flattened rows.
  static const OpFn fn = [](Ctx& c) {
    const at::Tensor& x = c.input(0);
    const at::Tensor& w = c.input(1);
    const at::Tensor& b = c.input(2);
    if (x.dim() < 2 || x.size(-1) != w.size(0)) throw OpError("linear: inner dimensions differ");
    if (x.scalar_type() != at::kFloat) throw OpError("linear: input is not float");
    c.out = {linear(x, w, b)};
  };
  return fn;
}

const OpFn& fused_attention() {
  // softmax(q @ kT (* or / scale) (+ bias)) @ v; inputs q, kT, v, scale (optional, one
  // element), bias (optional). Softmax over the last axis runs the fused kernel; any other
  // axis runs the original operators one by one.
  static const OpFn fn = [](Ctx& c) {
    const at::Tensor& q = c.input(0);
    const at::Tensor& kt = c.input(1);
    const at::Tensor& v = c.input(2);
    at::Tensor scale = c.has(3) ? c.in[3] : at::Tensor();
    at::Tensor bias = c.has(4) ? c.in[4] : at::Tensor();
    bool divide = c.node.get_int("divide", 0) != 0;
    int64_t axis_attr = c.node.get_int("softmax_axis", -1);
    int64_t rank = std::max({q.dim(), kt.dim(), bias.defined() ? bias.dim() : 0});
    bool fast = q.dim() >= 2 && kt.dim() >= 2 && v.dim() >= 2 && norm_axis(axis_attr, rank) == rank - 1 &&
                q.scalar_type() == at::kFloat && kt.scalar_type() == at::kFloat && v.scalar_type() == at::kFloat &&
                (!bias.defined() || bias.scalar_type() == at::kFloat) && (!scale.defined() || scale.numel() == 1);
    if (fast) {
      double s = scale.defined() ? scalar_of(scale) : 1.0;
      c.out = {attention(q, kt, v, divide ? 1.0 / s : s, bias)};
      return;
    }
    at::Tensor x = batched_matmul(q, kt);
    if (scale.defined()) x = divide ? onnx_div(x, scale) : x * scale;
    if (bias.defined()) x = x + bias;
    c.out = {batched_matmul(onnx_softmax(x, axis_attr, c.opset, false), v)};
  };
  return fn;
}

}  // namespace

struct OnnxGraph::Impl {
  OnnxModel model;
  uint64_t id = 0;  // unique in the process
  // Nodes left after folding, with inputs/outputs resolved to slots.
  struct Step {
    const Node* node;
    const OpFn* fn;
    std::vector<int> in, out;  // -1: omitted
    std::vector<int> release;  // slots whose last use is this step
  };
  std::vector<Step> steps;
  std::unordered_map<std::string, int> slot_of;
  std::vector<at::Tensor> constants;  // by slot; undefined for runtime values
  std::vector<std::pair<std::string, int>> input_slots, output_slots;
  int slots = 0;
  std::deque<Node> fused_nodes;  // nodes made by the fusion pass (stable addresses)

  bool const_scalar(int s, double v, double tol) const {
    if (s < 0 || !constants[s].defined() || constants[s].numel() != 1) return false;
    return std::fabs(constants[s].to(at::kDouble).reshape({-1})[0].item<double>() - v) < tol;
  }
  struct Fusion;
  void fuse();
  int64_t opset() const { return model.opset; }

  int slot(const std::string& name) {
    auto it = slot_of.find(name);
    if (it != slot_of.end()) return it->second;
    slot_of[name] = slots;
    constants.emplace_back();
    return slots++;
  }

  [[noreturn]] void fail(const Node& n, const std::string& problem, const std::vector<at::Tensor>& ins) const {
    std::ostringstream s;
    s << n.label() << ": " << problem << " (inputs:";
    for (size_t i = 0; i < ins.size(); ++i) {
      s << (i ? ", " : " ");
      if (!ins[i].defined()) s << "none";
      else s << c10::toString(ins[i].scalar_type()) << shape_str(ins[i].sizes());
    }
    s << ")";
    throw Error(model.path, s.str());
  }

  // Runs the steps marked in run_step (all when null) over env, freeing each value after its
  // last use unless marked in keep. `after` (optional) sees each step's outputs before that
  // (and may mark more of keep); returning false stops the run, and run_steps returns false.
  bool run_steps(std::vector<at::Tensor>& env, const std::vector<char>* run_step, const std::vector<char>* keep,
                 const std::function<bool(size_t)>& after = nullptr) const;
  // The constants with every graph input bound from feeds (all inputs given, no unknown ones).
  std::vector<at::Tensor> bind(const std::map<std::string, HostTensor>& feeds) const;
  std::map<std::string, HostTensor> outputs_of(const std::vector<at::Tensor>& env) const;

  void execute(const Node& n, const OpFn& fn, Ctx& ctx) const {
    try {
      fn(ctx);
    } catch (const OpError& e) {
      fail(n, e.what(), ctx.in);
    } catch (const c10::Error& e) {
      std::string msg = e.what_without_backtrace();
      fail(n, msg.substr(0, msg.find('\n')), ctx.in);
    } catch (const std::exception& e) {  // kernels.cc / gemm.cc (bad shapes, a failed sgemm)
      fail(n, e.what(), ctx.in);
    }
    if (ctx.out.size() < n.outputs.size()) fail(n, "produced fewer outputs than the node declares", ctx.in);
  }
};

OnnxGraph::OnnxGraph(const std::string& path, const OutputRule& rule) : impl_(std::make_unique<Impl>()) {
  static std::atomic<uint64_t> graphs{0};
  impl_->id = ++graphs;
  use_tensor_memory_pool();
  c10::InferenceMode guard;
  Impl& m = *impl_;
  m.model = load_onnx(path);
  const OutputChoice choice = rule ? rule(m.model) : OutputChoice{};
  for (const std::string& name : choice.taps) {
    bool produced = false;
    for (const Node& n : m.model.nodes)
      produced = produced || std::find(n.outputs.begin(), n.outputs.end(), name) != n.outputs.end();
    if (!produced) throw Error(path, "no node produces the value '" + name + "' asked to be returned");
    bool known = false;
    for (const auto& v : m.model.outputs) known = known || v.name == name;
    if (!known) m.model.outputs.push_back(ValueInfo{name, DType::Float32, {}, {}});
  }
  for (const std::string& name : choice.unread) {
    bool known = false;
    for (const auto& v : m.model.outputs) known = known || v.name == name;
    if (!known) throw Error(path, "the graph has no output '" + name + "' to leave unread");
  }
  const auto& reg = registry();
  for (const Node& n : m.model.nodes) {
    if (!(n.domain.empty() || n.domain == "ai.onnx") || !reg.count(n.op_type))
      throw Error(path, n.label() + ": unsupported operator" +
                            (n.domain.empty() ? std::string() : " (domain '" + n.domain + "')") +
                            "; the executor implements the ops listed in docs/sam.md");
    for (const auto& [name, a] : n.attrs)
      if (a.kind == Attribute::Kind::Graph) throw Error(path, n.label() + ": subgraph attributes are not supported");
  }
  for (auto& [name, t] : m.model.initializers) m.constants[m.slot(name)] = to_aten(t);
  m.model.initializers.clear();  // the ATen tensors share the bytes
  for (const auto& v : m.model.inputs) m.input_slots.emplace_back(v.name, m.slot(v.name));
  // Fold nodes whose inputs are all constants; keep the rest as steps.
  for (const Node& n : m.model.nodes) {
    const OpFn& fn = reg.at(n.op_type);
    std::vector<int> ins, outs;
    bool constant = true;
    for (const auto& name : n.inputs) {
      if (name.empty()) { ins.push_back(-1); continue; }
      int s = m.slot(name);
      ins.push_back(s);
      if (!m.constants[s].defined()) constant = false;
    }
    for (const auto& name : n.outputs) outs.push_back(name.empty() ? -1 : m.slot(name));
    if (constant) {
      Ctx ctx{n, m.model.opset, {}, {}};
      for (int s : ins) ctx.in.push_back(s < 0 ? at::Tensor() : m.constants[s]);
      m.execute(n, fn, ctx);
      for (size_t i = 0; i < outs.size(); ++i)
        if (outs[i] >= 0) m.constants[outs[i]] = ctx.out[i].contiguous();
      continue;
    }
    m.steps.push_back({&n, &fn, ins, outs, {}});
  }
  for (const auto& v : m.model.outputs)
    if (std::find(choice.unread.begin(), choice.unread.end(), v.name) == choice.unread.end())
      m.output_slots.emplace_back(v.name, m.slot(v.name));
  m.fuse();
  // Keep only the steps that some returned output needs.
  std::vector<char> needed(size_t(m.slots), 0);
  for (const auto& [name, s] : m.output_slots) needed[size_t(s)] = 1;
  std::vector<char> keep(m.steps.size(), 0);
  for (size_t i = m.steps.size(); i-- > 0;) {
    for (int s : m.steps[i].out) keep[i] = keep[i] || (s >= 0 && needed[size_t(s)]);
    if (keep[i])
      for (int s : m.steps[i].in)
        if (s >= 0) needed[size_t(s)] = 1;
  }
  size_t kept = 0;
  for (size_t i = 0; i < m.steps.size(); ++i)
    if (keep[i]) {
      if (kept != i) m.steps[kept] = std::move(m.steps[i]);
      ++kept;
    }
  m.steps.resize(kept);
  // Free each runtime value after its last use (graph outputs are kept).
  std::vector<int> last_use(m.slots, -1);
  for (size_t i = 0; i < m.steps.size(); ++i)
    for (int s : m.steps[i].in)
      if (s >= 0 && !m.constants[s].defined()) last_use[s] = int(i);
  for (const auto& [name, s] : m.output_slots) last_use[s] = -1;
  for (int s = 0; s < m.slots; ++s)
    if (last_use[s] >= 0) m.steps[last_use[s]].release.push_back(s);
  // Drop constants nothing uses any more (folded intermediates).
  std::vector<char> used(m.slots, 0);
  for (const auto& st : m.steps)
    for (int s : st.in)
      if (s >= 0) used[s] = 1;
  for (const auto& [name, s] : m.output_slots) used[s] = 1;
  for (int s = 0; s < m.slots; ++s)
    if (!used[s]) m.constants[s] = at::Tensor();
}

// ---------------------------------------------------------------- fusion pass
//
// Rewrites patterns that exporters spell out op by op into single kernels. Each fusion is
// one function below; a rewritten chain becomes one step in place of its last node, and
// only chains whose intermediates have no other consumer are rewritten.
// ISEGMAN_ONNX_NO_FUSION=1 turns every fusion off (tests compare both ways).

struct OnnxGraph::Impl::Fusion {
  Impl& g;
  std::vector<std::vector<int>> consumers;  // by slot: the steps that read it
  std::vector<int> producer;                // by slot: the step that writes it, or -1
  std::vector<char> is_output, dead;

  explicit Fusion(Impl& graph) : g(graph), consumers(graph.slots), producer(graph.slots, -1), is_output(graph.slots, 0),
                                 dead(graph.steps.size(), 0) {
    for (size_t i = 0; i < g.steps.size(); ++i) {
      for (int s : g.steps[i].in)
        if (s >= 0) consumers[s].push_back(int(i));
      for (int s : g.steps[i].out)
        if (s >= 0) producer[s] = int(i);
    }
    for (const auto& [name, s] : g.output_slots) is_output[s] = 1;
  }
  const std::string& op(int i) const { return g.steps[i].node->op_type; }
  int out(int i) const { return g.steps[i].out[0]; }
  // The one live consumer of an intermediate, or -1.
  int single(int s) const {
    if (s < 0 || is_output[s]) return -1;
    int found = -1;
    for (int c : consumers[s]) {
      if (dead[c] || c == found) continue;
      if (found >= 0) return -1;
      found = c;
    }
    return found;
  }
  // The other input of a binary step that reads s, or -2.
  int other(int i, int s) const {
    const auto& in = g.steps[i].in;
    if (in.size() != 2) return -2;
    return in[0] == s ? in[1] : in[1] == s ? in[0] : -2;
  }
  bool is_const(int s) const { return s >= 0 && g.constants[s].defined(); }
  const std::string& name_of(int s) const {  // a slot's value name (for fused nodes' labels)
    for (const auto& [name, slot] : g.slot_of)
      if (slot == s) return name;
    static const std::string none;
    return none;
  }
  // Replaces step `last` with a fused step and marks `gone` dead.
  void replace(int last, Node node, const OpFn& fn, const std::vector<int>& in, const std::vector<int>& gone) {
    node.outputs = {g.steps[last].node->outputs[0]};
    node.inputs.clear();
    for (int s : in) node.inputs.push_back(s < 0 ? std::string() : name_of(s));
    g.fused_nodes.push_back(std::move(node));
    g.steps[last] = Step{&g.fused_nodes.back(), &fn, in, {g.steps[last].out[0]}, {}};
    for (int i : gone) dead[i] = 1;
    for (int s : in)
      if (s >= 0) consumers[s].push_back(last);
  }

  void gelu();
  void layer_norm();
  void attention();
  void linear();
};

Node fused_node(const Node& from, const std::string& suffix, const std::string& op_type) {
  Node n;
  n.name = from.name + "+" + suffix;
  n.op_type = op_type;
  return n;
}

void OnnxGraph::Impl::fuse() {
  if (std::getenv("ISEGMAN_ONNX_NO_FUSION")) return;
  Fusion f(*this);
  f.gelu();
  f.layer_norm();
  f.attention();
  f.linear();
  std::vector<Step> kept;
  for (size_t i = 0; i < steps.size(); ++i)
    if (!f.dead[i]) kept.push_back(std::move(steps[i]));
  steps = std::move(kept);
}

// Exact (erf) GELU, x / sqrt(2) -> Erf -> +1 -> *x -> *0.5, into at::gelu: one pass over
// the tensor instead of five.
void OnnxGraph::Impl::Fusion::gelu() {
  const OpFn& fn = registry().at("Gelu");
  for (int e = 0; e < int(g.steps.size()); ++e) {
    if (dead[e] || op(e) != "Erf") continue;
    int scaled = g.steps[e].in[0];
    int d = scaled >= 0 ? producer[scaled] : -1;
    if (d < 0 || single(scaled) != e) continue;
    int x = -1;
    if (op(d) == "Div" && g.const_scalar(g.steps[d].in[1], std::sqrt(2.0), 1e-3)) x = g.steps[d].in[0];
    if (op(d) == "Mul" && g.const_scalar(g.steps[d].in[1], std::sqrt(0.5), 1e-3)) x = g.steps[d].in[0];
    if (x < 0) continue;
    int a = single(out(e));
    if (a < 0 || op(a) != "Add" || !g.const_scalar(other(a, out(e)), 1.0, 1e-6)) continue;
    int m1 = single(out(a));
    if (m1 < 0 || op(m1) != "Mul" || other(m1, out(a)) != x) continue;
    int m2 = single(out(m1));
    if (m2 < 0 || op(m2) != "Mul" || !g.const_scalar(other(m2, out(m1)), 0.5, 1e-6)) continue;
    replace(m2, fused_node(*g.steps[e].node, "gelu", "Gelu"), fn, {x}, {d, e, a, m1});
  }
}

// LayerNorm over the last axis, spelled out (opset < 17 exports): m = mean(x); d = x - m;
// v = mean(d^2); y = d / sqrt(v + eps) * gamma + beta, into at::layer_norm.
void OnnxGraph::Impl::Fusion::layer_norm() {
  const OpFn& fn = registry().at("LayerNormalization");
  auto last_axis_mean = [&](int i) {
    return op(i) == "ReduceMean" && g.steps[i].in.size() == 1 &&
           g.steps[i].node->get_ints("axes", {}) == std::vector<int64_t>{-1} && g.steps[i].node->get_int("keepdims", 1) == 1;
  };
  for (int r1 = 0; r1 < int(g.steps.size()); ++r1) {
    if (dead[r1] || !last_axis_mean(r1)) continue;
    int x = g.steps[r1].in[0];
    int sub = single(out(r1));
    if (sub < 0 || op(sub) != "Sub" || g.steps[sub].in[0] != x || g.steps[sub].in[1] != out(r1)) continue;
    int d = out(sub);
    if (is_output[d] || consumers[d].size() != 2) continue;
    int pw = consumers[d][0], dv = consumers[d][1];
    if (op(pw) != "Pow") std::swap(pw, dv);
    if (op(pw) != "Pow" || op(dv) != "Div" || g.steps[pw].in[0] != d || !g.const_scalar(g.steps[pw].in[1], 2.0, 1e-9) ||
        g.steps[dv].in[0] != d)
      continue;
    int r2 = single(out(pw));
    if (r2 < 0 || !last_axis_mean(r2)) continue;
    int add = single(out(r2));
    if (add < 0 || op(add) != "Add") continue;
    int eps_slot = other(add, out(r2));
    if (!is_const(eps_slot) || g.constants[eps_slot].numel() != 1) continue;
    int sq = single(out(add));
    if (sq < 0 || op(sq) != "Sqrt" || single(out(sq)) != dv || g.steps[dv].in[1] != out(sq)) continue;
    int mul = single(out(dv));
    if (mul < 0 || op(mul) != "Mul") continue;
    int gamma = other(mul, out(dv));
    if (!is_const(gamma) || g.constants[gamma].dim() != 1) continue;
    int badd = single(out(mul));
    int beta = badd >= 0 && op(badd) == "Add" ? other(badd, out(mul)) : -1;
    if (!is_const(beta) || g.constants[beta].dim() != 1 || g.constants[beta].size(0) != g.constants[gamma].size(0)) continue;
    Node n = fused_node(*g.steps[r1].node, "layernorm", "LayerNormalization");
    Attribute axis, eps;
    axis.kind = Attribute::Kind::Int;
    axis.i = -1;
    eps.kind = Attribute::Kind::Float;
    eps.f = float(g.constants[eps_slot].to(at::kDouble).reshape({-1})[0].item<double>());
    n.attrs["axis"] = axis;
    n.attrs["epsilon"] = eps;
    replace(badd, n, fn, {x, gamma, beta}, {r1, sub, pw, dv, r2, add, sq, mul});
  }
}

// Attention, MatMul(q, kT) -> [Mul or Div by a scalar] -> [Add bias] -> Softmax -> MatMul(., v),
// into one kernel that keeps each (window, head) score matrix in cache instead of writing
// the whole score tensor four times (TinyViT's windows, the SAM decoder's attention).
void OnnxGraph::Impl::Fusion::attention() {
  const OpFn& fn = fused_attention();
  for (int m1 = 0; m1 < int(g.steps.size()); ++m1) {
    if (dead[m1] || op(m1) != "MatMul") continue;
    std::vector<int> gone = {m1};
    int cur = out(m1), scale = -1, bias = -1;
    bool divide = false;
    int next = single(cur);
    if (next >= 0 && (op(next) == "Mul" || (op(next) == "Div" && g.steps[next].in[0] == cur))) {
      int s = other(next, cur);
      if (s >= 0 && (!is_const(s) || g.constants[s].numel() == 1)) {
        scale = s;
        divide = op(next) == "Div";
        gone.push_back(next);
        cur = out(next);
        next = single(cur);
      }
    }
    if (next >= 0 && op(next) == "Add") {
      bias = other(next, cur);
      if (bias < 0) continue;
      gone.push_back(next);
      cur = out(next);
      next = single(cur);
    }
    if (next < 0 || op(next) != "Softmax") continue;
    int softmax = next;
    gone.push_back(softmax);
    int m2 = single(out(softmax));
    if (m2 < 0 || op(m2) != "MatMul" || g.steps[m2].in[0] != out(softmax)) continue;
    // A runtime scale must be computed before the last MatMul runs; steps are in order.
    Node n = fused_node(*g.steps[m1].node, "attention", "FusedAttention");
    Attribute a;
    a.kind = Attribute::Kind::Int;
    a.i = divide;
    n.attrs["divide"] = a;
    a.i = g.steps[softmax].node->get_int("axis", g.opset() >= 13 ? -1 : 1);
    n.attrs["softmax_axis"] = a;
    replace(m2, n, fn, {g.steps[m1].in[0], g.steps[m1].in[1], g.steps[m2].in[1], scale, bias}, gone);
  }
}

// MatMul(x, W const 2-D) -> Add(b const 1-D) into one sgemm onto the bias rows.
void OnnxGraph::Impl::Fusion::linear() {
  for (int i = 0; i < int(g.steps.size()); ++i) {
    if (dead[i] || op(i) != "MatMul") continue;
    int w = g.steps[i].in[1];
    if (!is_const(w) || g.constants[w].dim() != 2 || g.constants[w].scalar_type() != at::kFloat) continue;
    int a = single(out(i));
    if (a < 0 || op(a) != "Add") continue;
    int b = other(a, out(i));
    if (!is_const(b) || g.constants[b].dim() != 1 || g.constants[b].size(0) != g.constants[w].size(1) ||
        g.constants[b].scalar_type() != at::kFloat)
      continue;
    replace(a, fused_node(*g.steps[i].node, "bias", "FusedLinear"), fused_linear(), {g.steps[i].in[0], w, b}, {i});
  }
}

OnnxGraph::~OnnxGraph() = default;

const std::string& OnnxGraph::path() const { return impl_->model.path; }
const std::vector<ValueInfo>& OnnxGraph::inputs() const { return impl_->model.inputs; }
const std::vector<ValueInfo>& OnnxGraph::outputs() const { return impl_->model.outputs; }
size_t OnnxGraph::node_count() const { return impl_->steps.size(); }

std::vector<std::string> OnnxGraph::op_types() const {
  std::set<std::string> s;
  for (const auto& st : impl_->steps) s.insert(st.node->op_type);
  return {s.begin(), s.end()};
}

std::vector<std::string> OnnxGraph::supported_ops() {
  std::vector<std::string> v;
  for (const auto& [name, fn] : registry()) v.push_back(name);
  return v;
}

namespace {

// Operators whose output is shape arithmetic when their inputs are: small integer values
// derived from tensor shapes (an export's broadcasts and tiles are made of them).
bool shape_arithmetic(const std::string& op) {
  static const std::set<std::string> ops = {"Gather", "Unsqueeze", "Squeeze", "Concat", "Slice", "Cast", "Reshape",
                                            "Equal", "Where", "Mul", "Add", "Sub", "Div", "OneHot", "ConstantOfShape",
                                            "Range", "Not", "Less", "Greater", "ReduceProd", "Identity", "Max", "Min",
                                            "Neg", "Floor", "Ceil"};
  return ops.count(op) != 0;
}

bool same_value(const at::Tensor& a, const at::Tensor& b) {
  if (!a.defined() || !b.defined()) return a.defined() == b.defined();
  if (a.scalar_type() != b.scalar_type() || a.sizes() != b.sizes()) return false;
  const at::Tensor ca = a.contiguous(), cb = b.contiguous();
  return std::memcmp(ca.data_ptr(), cb.data_ptr(), size_t(ca.numel()) * ca.element_size()) == 0;
}

}  // namespace

struct OnnxGraph::Stable {
  uint64_t graph = 0;                              // id() of the graph that made it
  std::map<std::string, HostTensor> inputs;        // the stable feeds (the caller's bytes)
  std::vector<char> done;                          // per step: computed here, skipped by run(feeds, stable)
  std::vector<std::pair<int, at::Tensor>> values;  // the slots the other steps (or the outputs) read
  // Shape arithmetic of the other inputs that the kept values were made with: per slot, the
  // value it had; a later run that computes another value there runs the whole graph.
  std::vector<std::pair<int, at::Tensor>> guards;
  mutable std::atomic<size_t> whole_runs{0};
};

bool OnnxGraph::Impl::run_steps(std::vector<at::Tensor>& env, const std::vector<char>* run_step,
                                const std::vector<char>* keep, const std::function<bool(size_t)>& after) const {
  // ISEGMAN_ONNX_PROFILE=1 prints the time spent per operator type after each run: wall
  // time and the process's CPU time (all threads; steadier than wall time on a shared machine).
  // ISEGMAN_ONNX_PROFILE=2 also prints every node with its input shapes and times.
  static const int profile = std::getenv("ISEGMAN_ONNX_PROFILE") ? std::atoi(std::getenv("ISEGMAN_ONNX_PROFILE")) : 0;
  struct OpTime {
    double wall = 0, cpu = 0;
    int count = 0;
  };
  std::map<std::string, OpTime> by_op;
  size_t ran = 0;
  for (size_t i = 0; i < steps.size(); ++i) {
    if (run_step && !(*run_step)[i]) continue;
    const Step& st = steps[i];
    ++ran;
    Ctx ctx{*st.node, model.opset, {}, {}};
    ctx.in.reserve(st.in.size());
    for (int s : st.in) {
      if (s >= 0 && !env[s].defined())
        fail(*st.node, "input '" + st.node->inputs[ctx.in.size()] + "' has no value", ctx.in);
      ctx.in.push_back(s < 0 ? at::Tensor() : env[s]);
    }
    double t0 = profile ? now_ms() : 0, c0 = profile ? cpu_ms() : 0;
    execute(*st.node, *st.fn, ctx);
    if (profile) {
      double dt = now_ms() - t0, dc = cpu_ms() - c0;
      OpTime& t = by_op[st.node->op_type];
      t.wall += dt;
      t.cpu += dc;
      ++t.count;
      if (profile >= 2) {
        std::ostringstream o;
        for (const auto& in : ctx.in) o << " " << (in.defined() ? shape_str(in.sizes()) + (in.is_contiguous() ? "" : "s") : "-");
        std::fprintf(stderr, "    %8.2f ms %8.2f cpu %-20s %s:%s\n", dt, dc, st.node->op_type.c_str(), st.node->name.c_str(),
                     o.str().c_str());
      }
    }
    for (size_t k = 0; k < st.out.size(); ++k)
      if (st.out[k] >= 0) env[st.out[k]] = std::move(ctx.out[k]);
    if (after && !after(i)) return false;
    for (int s : st.release)
      if (!keep || !(*keep)[s]) env[s] = at::Tensor();
  }
  if (profile) {
    std::vector<std::pair<double, std::string>> rows;
    double total = 0, total_cpu = 0;
    for (const auto& [op, v] : by_op) rows.emplace_back(v.cpu, op), total += v.wall, total_cpu += v.cpu;
    std::sort(rows.rbegin(), rows.rend());
    std::fprintf(stderr, "%s: %.1f ms (%.1f ms CPU) in %zu nodes; tensor pool: %zu mappings so far, %.0f MiB cached\n",
                 model.path.c_str(), total, total_cpu, ran, tensor_memory_pool_mappings(),
                 double(tensor_memory_pool_cached_bytes()) / (1 << 20));
    for (const auto& [cpu, op] : rows)
      std::fprintf(stderr, "  %-20s %8.2f ms %8.2f ms CPU %5d nodes\n", op.c_str(), by_op[op].wall, cpu, by_op[op].count);
  }
  return true;
}

std::vector<at::Tensor> OnnxGraph::Impl::bind(const std::map<std::string, HostTensor>& feeds) const {
  std::vector<at::Tensor> env = constants;
  for (const auto& [name, s] : input_slots) {
    auto it = feeds.find(name);
    if (it == feeds.end()) throw Error(model.path, "input '" + name + "' was not given");
    env[s] = to_aten(it->second);
  }
  for (const auto& [name, t] : feeds)
    if (!slot_of.count(name)) throw Error(model.path, "the graph has no input named '" + name + "'");
  return env;
}

std::map<std::string, HostTensor> OnnxGraph::Impl::outputs_of(const std::vector<at::Tensor>& env) const {
  std::map<std::string, HostTensor> result;
  for (const auto& [name, s] : output_slots) {
    if (!env[s].defined()) throw Error(model.path, "output '" + name + "' was not produced");
    result[name] = to_host(env[s]);
  }
  return result;
}

std::map<std::string, HostTensor> OnnxGraph::run(const std::map<std::string, HostTensor>& feeds) const {
  c10::InferenceMode guard;
  const Impl& m = *impl_;
  std::vector<at::Tensor> env = m.bind(feeds);
  m.run_steps(env, nullptr, nullptr);
  return m.outputs_of(env);
}

std::map<std::string, HostTensor> OnnxGraph::run(const std::map<std::string, HostTensor>& feeds,
                                                 const std::vector<std::string>& stable_inputs,
                                                 std::shared_ptr<const Stable>& stable) const {
  c10::InferenceMode guard;
  const Impl& m = *impl_;
  auto st = std::make_shared<Stable>();
  st->graph = m.id;
  std::vector<at::Tensor> env = m.bind(feeds);
  // Each runtime value, as the run makes it, is derived (from the stable inputs and shape
  // arithmetic alone: kept), shape arithmetic of the other inputs (small; recomputed by later
  // runs and checked where a kept step read it), or neither.
  enum Kind : char { kOther, kDerived, kShape };
  std::vector<char> kind(size_t(m.slots), kOther), keep(size_t(m.slots), 0);
  for (const std::string& name : stable_inputs) {
    int slot = -1;
    for (const auto& [n, s] : m.input_slots)
      if (n == name) slot = s;
    if (slot < 0) throw Error(m.model.path, "the graph has no input named '" + name + "'");
    kind[size_t(slot)] = kDerived;
    keep[size_t(slot)] = 1;
    st->inputs.emplace(name, feeds.at(name));
  }
  constexpr int64_t kSmall = 64;  // elements: shape arithmetic stays this small
  std::vector<char> guarded(size_t(m.slots), 0);
  st->done.assign(m.steps.size(), 0);
  auto classify = [&](size_t i) {
    const Impl::Step& step = m.steps[i];
    bool all_derived = true, all_known = true;
    for (int s : step.in) {
      if (s < 0 || m.constants[s].defined()) continue;
      all_derived = all_derived && kind[size_t(s)] == kDerived;
      all_known = all_known && kind[size_t(s)] != kOther;
    }
    bool small = true;
    for (int s : step.out) small = small && (s < 0 || !env[size_t(s)].defined() || env[size_t(s)].numel() <= kSmall);
    const bool arithmetic = step.node->op_type == "Shape" || (shape_arithmetic(step.node->op_type) && small);
    Kind out = kOther;
    // A step that is not small arithmetic (a projection, a tile of a constant) over derived
    // values and shape arithmetic is kept, its shape arithmetic checked by later runs.
    if (all_derived || (all_known && !arithmetic)) {
      out = kDerived;
      st->done[i] = 1;
      for (int s : step.in)
        if (s >= 0 && kind[size_t(s)] == kShape && !guarded[size_t(s)]) {
          guarded[size_t(s)] = 1;
          st->guards.emplace_back(s, env[size_t(s)].clone());
        }
    } else if ((all_known && arithmetic) || step.node->op_type == "Shape") {
      out = kShape;
    }
    for (int s : step.out)
      if (s >= 0) kind[size_t(s)] = out;
    // A derived value is held past its last use only when a step that is not kept reads it
    // (this one, or an earlier one): later runs read it from the kept values.
    if (!st->done[i])
      for (int s : step.in)
        if (s >= 0 && kind[size_t(s)] == kDerived) keep[size_t(s)] = 1;
    return true;
  };
  m.run_steps(env, nullptr, &keep, classify);
  // Keep what the other steps, or the outputs, read of the derived values.
  std::vector<char> read(size_t(m.slots), 0);
  for (size_t i = 0; i < m.steps.size(); ++i)
    if (!st->done[i])
      for (int s : m.steps[i].in)
        if (s >= 0) read[size_t(s)] = 1;
  for (const auto& [name, s] : m.output_slots) read[size_t(s)] = 1;
  for (int s = 0; s < m.slots; ++s)
    if (kind[size_t(s)] == kDerived && read[size_t(s)] && env[size_t(s)].defined())
      st->values.emplace_back(s, env[size_t(s)]);
  std::map<std::string, HostTensor> out = m.outputs_of(env);
  stable = st;
  return out;
}

std::map<std::string, HostTensor> OnnxGraph::run(const std::map<std::string, HostTensor>& feeds, const Stable& stable) const {
  c10::InferenceMode guard;
  const Impl& m = *impl_;
  if (stable.graph != m.id) throw Error(m.model.path, "stable values made by another graph");
  std::map<std::string, HostTensor> all = stable.inputs;
  for (const auto& [name, t] : feeds)
    if (!all.emplace(name, t).second)
      throw Error(m.model.path, "input '" + name + "' was given twice (it is one of the stable inputs)");
  std::vector<at::Tensor> env = m.bind(all);
  for (const auto& [s, t] : stable.values) env[size_t(s)] = t;
  // The shape arithmetic the kept values were made with is recomputed by the other steps
  // and checked as it is made; any difference and the whole graph runs.
  std::vector<char> rest(stable.done.size());
  for (size_t i = 0; i < rest.size(); ++i) rest[i] = !stable.done[i];
  // (Guards are values steps make from shapes: never an input itself.)
  auto check = [&](size_t i) {
    for (int s : m.steps[i].out)
      for (const auto& [g, value] : stable.guards)
        if (s == g && !same_value(env[size_t(s)], value)) return false;
    return true;
  };
  if (m.run_steps(env, &rest, nullptr, check)) return m.outputs_of(env);
  ++stable.whole_runs;
  env = m.bind(all);
  m.run_steps(env, nullptr, nullptr);
  return m.outputs_of(env);
}

size_t OnnxGraph::stable_bytes(const Stable& stable) {
  std::set<const void*> seen;  // the caller counts its own inputs
  for (const auto& [n, t] : stable.inputs)
    if (t.numel() > 0) seen.insert(t.bytes->data());
  size_t bytes = 0;
  for (const auto& [s, t] : stable.values)
    if (t.defined() && t.numel() > 0 && seen.insert(t.storage().data()).second) bytes += t.storage().nbytes();
  return bytes;
}

size_t OnnxGraph::whole_runs(const Stable& stable) { return stable.whole_runs.load(); }

uint64_t OnnxGraph::id() const { return impl_->id; }

}  // namespace isegman::models
