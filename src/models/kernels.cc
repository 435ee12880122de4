// Kernels of the ONNX executor (see kernels.h), on top of gemm.h's sgemm.
#include "models/kernels.h"

#include <ATen/ATen.h>
#include <ATen/Parallel.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "models/gemm.h"

namespace isegman::models {
namespace {

// How sgemm reads one matrix of a [..., rows, cols] tensor: row-major with row stride
// `ld`, or (transposed) column-major with column stride `ld`.
struct MatrixLayout {
  bool transposed = false;
  int64_t ld = 0;
};

bool layout_of(const at::Tensor& t, MatrixLayout& l) {
  int64_t rows = t.size(-2), cols = t.size(-1), rs = t.stride(-2), cs = t.stride(-1);
  if ((cs == 1 || cols == 1) && rs >= std::max<int64_t>(cols, 1)) {
    l = {false, rs};
    return true;
  }
  if ((rs == 1 || rows == 1) && cs >= std::max<int64_t>(rows, 1)) {
    l = {true, cs};
    return true;
  }
  return false;
}

std::vector<int64_t> broadcast(std::vector<int64_t> a, std::vector<int64_t> b) {
  if (a.size() < b.size()) std::swap(a, b);
  b.insert(b.begin(), a.size() - b.size(), 1);
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i] == b[i] || b[i] == 1) continue;
    if (a[i] == 1) { a[i] = b[i]; continue; }
    throw std::invalid_argument("batch shapes cannot be broadcast");
  }
  return a;
}

// Element offset of batch item i (row-major over `batch`) in a tensor expanded to it.
int64_t batch_offset(const std::vector<int64_t>& batch, const at::Tensor& t, int64_t i) {
  int64_t off = 0;
  for (int64_t d = int64_t(batch.size()) - 1; d >= 0; --d) {
    off += (i % batch[d]) * t.stride(d);
    i /= batch[d];
  }
  return off;
}

std::vector<int64_t> with_matrix(std::vector<int64_t> batch, int64_t rows, int64_t cols) {
  batch.push_back(rows);
  batch.push_back(cols);
  return batch;
}

std::vector<int64_t> batch_of(const at::Tensor& t) {
  if (t.dim() < 2) return {};
  return {t.sizes().begin(), t.sizes().end() - 2};
}

// exp(x) for the softmax: x = n ln2 + r with |r| <= ln2/2 (n rounded with the 1.5 * 2^23
// trick, ln2 split in two for an exact n ln2), e^r by its Taylor series to r^7 (truncation
// error < 1e-8 relative), 2^n built in the exponent bits; inputs are clamped to [-87, 88]
// (results stay normal floats). One template for a float and for a vector of 8 (GCC's
// vector extensions: AVX where the CPU has it, pairs of SSE registers elsewhere), so the
// two compute the same operations in the same order, lane for lane.
typedef float Float8 __attribute__((vector_size(32)));
typedef int32_t Int8 __attribute__((vector_size(32)));

template <class F>
inline F splat(float v) {
  return F{} + v;  // v in every lane
}

template <class F, class I>
inline F exp_for_softmax(F x) {
  x = x < -87.0f ? splat<F>(-87.0f) : x;
  x = x > 88.0f ? splat<F>(88.0f) : x;
  F t = x * 1.44269504088896341f;
  F n = (t + 12582912.0f) - 12582912.0f;
  F r = x - n * 0.693359375f + n * 2.12194440e-4f;
  F p = splat<F>(1.0f / 5040.0f);
  p = p * r + 1.0f / 720.0f;
  p = p * r + 1.0f / 120.0f;
  p = p * r + 1.0f / 24.0f;
  p = p * r + 1.0f / 6.0f;
  p = p * r + 0.5f;
  p = p * r + 1.0f;
  p = p * r + 1.0f;
  I bits;
  if constexpr (sizeof(F) == sizeof(float)) {
    bits = (int32_t(n) + 127) << 23;
  } else {
    bits = (__builtin_convertvector(n, I) + 127) << 23;
  }
  F two_n;
  std::memcpy(&two_n, &bits, sizeof two_n);
  return p * two_n;
}

inline Float8 load8(const float* p) {
  Float8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store8(float* p, Float8 v) { std::memcpy(p, &v, sizeof v); }

// Rows shorter than one 16-lane step: every value goes through the scalar tail, one row
// at a time. Eight rows at once, one per lane, do the same operations in the same order
// for each row (the attention of many queries over a few keys: SAM's image-to-token).
void softmax_short_rows_by_eight(float* x, int64_t n, int64_t ld) {
  auto column = [&](int64_t j) {
    Float8 v;
    for (int l = 0; l < 8; ++l) v[l] = x[l * ld + j];
    return v;
  };
  auto set_column = [&](int64_t j, Float8 v) {
    for (int l = 0; l < 8; ++l) x[l * ld + j] = v[l];
  };
  Float8 m = splat<Float8>(-INFINITY);
  for (int64_t j = 0; j < n; ++j) {
    const Float8 v = column(j);
    m = m < v ? v : m;
  }
  Float8 sum = splat<Float8>(0.0f);
  for (int64_t j = 0; j < n; ++j) {
    const Float8 e = exp_for_softmax<Float8, Int8>(column(j) - m);
    set_column(j, e);
    sum += e;
  }
  const Float8 inv = 1.0f / sum;
  for (int64_t j = 0; j < n; ++j) set_column(j, column(j) * inv);
}

}  // namespace

void softmax_rows(float* x, int64_t rows, int64_t n, int64_t ld) {
  // 16 independent lanes (two vectors of 8) for the maximum and the sum; the lanes are
  // then reduced in order and the tail added one by one.
  constexpr int64_t L = 16;
  int64_t r = 0;
  if (n < L)
    for (; r + 8 <= rows; r += 8) softmax_short_rows_by_eight(x + r * ld, n, ld);
  for (; r < rows; ++r) {
    float* row = x + r * ld;
    Float8 m0 = splat<Float8>(-INFINITY), m1 = m0;
    int64_t j = 0;
    for (; j + L <= n; j += L) {  // std::max(lane, v): v where lane < v
      const Float8 a = load8(row + j), b = load8(row + j + 8);
      m0 = m0 < a ? a : m0;
      m1 = m1 < b ? b : m1;
    }
    float m = -INFINITY;
    for (int l = 0; l < 8; ++l) m = std::max(m, m0[l]);
    for (int l = 0; l < 8; ++l) m = std::max(m, m1[l]);
    for (; j < n; ++j) m = std::max(m, row[j]);
    Float8 s0 = splat<Float8>(0.0f), s1 = s0;
    j = 0;
    for (; j + L <= n; j += L) {
      const Float8 e0 = exp_for_softmax<Float8, Int8>(load8(row + j) - m);
      const Float8 e1 = exp_for_softmax<Float8, Int8>(load8(row + j + 8) - m);
      store8(row + j, e0);
      store8(row + j + 8, e1);
      s0 += e0;
      s1 += e1;
    }
    float sum = 0.0f;
    for (int l = 0; l < 8; ++l) sum += s0[l];
    for (int l = 0; l < 8; ++l) sum += s1[l];
    for (; j < n; ++j) {
      float e = exp_for_softmax<float, int32_t>(row[j] - m);
      row[j] = e;
      sum += e;
    }
    float inv = 1.0f / sum;
    for (j = 0; j < n; ++j) row[j] *= inv;
  }
}

at::Tensor batched_matmul(const at::Tensor& a0, const at::Tensor& b0) {
  if (a0.dim() < 2 || b0.dim() < 2 || a0.scalar_type() != at::kFloat || b0.scalar_type() != at::kFloat)
    return at::matmul(a0, b0);
  int64_t m = a0.size(-2), k = a0.size(-1), n = b0.size(-1);
  if (b0.size(-2) != k) throw std::invalid_argument("matmul: inner dimensions differ");
  std::vector<int64_t> batch = broadcast(batch_of(a0), batch_of(b0));
  std::vector<int64_t> shape_c = with_matrix(batch, m, n);
  at::Tensor a = a0.expand(with_matrix(batch, m, k)), b = b0.expand(with_matrix(batch, k, n));  // batch strides 0 where broadcast
  MatrixLayout la, lb;
  if (!layout_of(a, la)) a = a.contiguous(), layout_of(a, la);
  if (!layout_of(b, lb)) b = b.contiguous(), layout_of(b, lb);
  at::Tensor c = at::empty(shape_c, a0.options());
  if (c.numel() == 0) return c;
  if (k == 0) return c.zero_();
  int64_t count = 1;
  for (int64_t d : batch) count *= d;
  const float* pa = a.data_ptr<float>();
  const float* pb = b.data_ptr<float>();
  float* pc = c.data_ptr<float>();
  auto run = [&](int64_t i) {
    sgemm(la.transposed, lb.transposed, m, n, k, 1.0f, pa + batch_offset(batch, a, i), la.ld, pb + batch_offset(batch, b, i),
          lb.ld, 0.0f, pc + i * m * n, n);
  };
  if (count == 1) {
    run(0);  // one product: sgemm uses all threads itself
  } else {
    // Many small products: one per thread at a time (sgemm runs single-threaded inside).
    at::parallel_for(0, count, 1, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) run(i);
    });
  }
  return c;
}

at::Tensor linear(const at::Tensor& x, const at::Tensor& w0, const at::Tensor& bias) {
  int64_t k = w0.size(0), n = w0.size(1);
  if (x.size(-1) != k) throw std::invalid_argument("linear: inner dimensions differ");
  at::Tensor x2 = x.reshape({-1, k});
  if (x2.stride(1) != 1 || x2.stride(0) < k) x2 = x2.contiguous();
  at::Tensor w = w0.contiguous();
  int64_t m = x2.size(0);
  std::vector<int64_t> shape = x.sizes().vec();
  shape.back() = n;
  at::Tensor y = at::empty({m, n}, x.options());
  float beta = 0.0f;
  if (bias.defined()) {
    y.copy_(bias.reshape({1, n}).expand({m, n}));  // sgemm adds the product onto the bias rows
    beta = 1.0f;
  }
  if (m > 0) sgemm(false, false, m, n, k, 1.0f, x2.data_ptr<float>(), x2.stride(0), w.data_ptr<float>(), n, beta,
                   y.data_ptr<float>(), n);
  return y.reshape(shape);
}

namespace {
// dst[c * dst_ld + r] = src[r * src_ld + c] (+ add[c]) for r < rows, c < cols, in 8 x 8
// tiles: a tile's 8 source rows and 8 destination rows stay in L1 (row by row, one of the
// two strides runs over a new cache line at every element: 1.5x slower for conv1x1's blocks).
void transpose_into(const float* src, int64_t src_ld, float* dst, int64_t dst_ld, int64_t rows, int64_t cols,
                    const float* add = nullptr) {
  constexpr int64_t kTile = 8;
  for (int64_t c0 = 0; c0 < cols; c0 += kTile)
    for (int64_t r0 = 0; r0 < rows; r0 += kTile) {
      const int64_t c1 = std::min(cols, c0 + kTile), r1 = std::min(rows, r0 + kTile);
      for (int64_t c = c0; c < c1; ++c) {
        const float a = add ? add[c] : 0.0f;
        float* d = dst + c * dst_ld;
        for (int64_t r = r0; r < r1; ++r) d[r] = src[r * src_ld + c] + a;
      }
    }
}
}  // namespace

at::Tensor conv1x1(const at::Tensor& x0, const at::Tensor& w0, const at::Tensor& bias0) {
  const int64_t batch = x0.size(0), ci = x0.size(1), hw = x0.size(2) * x0.size(3), co = w0.size(0);
  const bool nhwc = x0.stride(1) == 1 && x0.stride(3) == ci && x0.stride(2) == x0.size(3) * ci;
  const at::Tensor x = nhwc ? x0 : x0.contiguous();
  const at::Tensor w = w0.reshape({co, ci}).contiguous();
  const at::Tensor bias = bias0.defined() ? bias0.contiguous() : at::Tensor();
  at::Tensor y = at::empty({batch, co, x0.size(2), x0.size(3)}, x0.options());
  if (hw == 0 || co == 0) return y;
  // 256 pixels: the block's x^T and product (64 + 256 KB at 64 -> 256 channels) stay in L2;
  // 256, 512 and 1024 ran 82, 84 and 96 ms for the encoder's first 1x1 on one Zen 1 core.
  constexpr int64_t kBlock = 256;
  const int64_t per_image = (hw + kBlock - 1) / kBlock;
  const float* px = x.data_ptr<float>();
  const float* pw = w.data_ptr<float>();
  const float* pb = bias.defined() ? bias.data_ptr<float>() : nullptr;
  float* py = y.data_ptr<float>();
  at::parallel_for(0, batch * per_image, 1, [&](int64_t begin, int64_t end) {
    std::vector<float> xt(nhwc ? 0 : size_t(kBlock * ci)), product(size_t(kBlock * co));
    for (int64_t t = begin; t < end; ++t) {
      const int64_t n = t / per_image, j0 = (t % per_image) * kBlock, nb = std::min(kBlock, hw - j0);
      const float* a = px + n * x.stride(0) + j0 * ci;  // NHWC: the block's rows in place
      if (!nhwc) {
        transpose_into(px + n * ci * hw + j0, hw, xt.data(), ci, ci, nb);
        a = xt.data();
      }
      sgemm(false, true, nb, co, ci, 1.0f, a, ci, pw, ci, 0.0f, product.data(), co);
      transpose_into(product.data(), co, py + n * co * hw + j0, hw, nb, co, pb);
    }
  });
  return y;
}

at::Tensor conv_transpose_blocks(const at::Tensor& x0, const at::Tensor& w0, const at::Tensor& bias0) {
  const int64_t batch = x0.size(0), ci = x0.size(1), h = x0.size(2), wd = x0.size(3), hw = h * wd;
  const int64_t co = w0.size(1), kh = w0.size(2), kw = w0.size(3), cols = co * kh * kw;
  if (w0.size(0) != ci) throw std::invalid_argument("conv_transpose_blocks: input channels differ");
  at::Tensor w = w0.contiguous();  // [Ci, Co*kh*kw]
  at::Tensor bias = bias0.defined() ? bias0.contiguous() : at::Tensor();
  // The product P [H*W, Co*kh*kw] = x[n]^T @ W: tall and narrow, the shape sgemm runs
  // fastest (2x a wide [Co*kh*kw, H*W] one here). x[n]^T is read in place from an NHWC view.
  // An NCHW input is transposed first: sgemm reading x^T in place ran 2x slower than the copy.
  at::Tensor x = x0;
  const bool nhwc = x.stride(1) == 1 && x.stride(3) == ci && x.stride(2) == wd * ci;
  if (!nhwc) x = transpose_last_two(x.contiguous().reshape({batch, ci, hw}));  // [N, H*W, Ci]
  at::Tensor y = at::empty({batch, co, h * kh, wd * kw}, x0.options());
  at::Tensor product = at::empty({hw, cols}, x0.options());
  const float* pbias = bias.defined() ? bias.data_ptr<float>() : nullptr;
  const float* pp = product.data_ptr<float>();
  const int64_t plane = hw * kh * kw;
  for (int64_t n = 0; n < batch; ++n) {
    const float* px = x.data_ptr<float>() + n * x.stride(0);
    sgemm(false, false, hw, cols, ci, 1.0f, px, ci, w.data_ptr<float>(), cols, 0.0f, product.data_ptr<float>(), cols);
    float* py = y.data_ptr<float>() + n * co * plane;
    // Row i*W + j of P holds the block of input pixel (i, j) for every output channel. Per
    // input row (P's rows of it stay in cache), each output row i*kh + a of each channel is
    // written in one sweep; writing all channels' rows side by side instead hits the same
    // cache sets (the planes lie a power of two apart) and ran 3x slower.
    at::parallel_for(0, h, 1, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i)
        for (int64_t o = 0; o < co; ++o) {
          const float add = pbias ? pbias[o] : 0.0f;
          for (int64_t a = 0; a < kh; ++a) {
            float* dst = py + o * plane + (i * kh + a) * wd * kw;
            const float* src = pp + i * wd * cols + (o * kh + a) * kw;
            for (int64_t j = 0; j < wd; ++j)
              for (int64_t b = 0; b < kw; ++b) dst[j * kw + b] = src[j * cols + b] + add;
          }
        }
    });
  }
  return y;
}

at::Tensor transpose_last_two(const at::Tensor& x) {
  const int64_t m = x.size(-2), n = x.size(-1), batch = m * n != 0 ? x.numel() / (m * n) : 0;
  std::vector<int64_t> shape = x.sizes().vec();
  std::swap(shape[shape.size() - 2], shape.back());
  at::Tensor y = at::empty(shape, x.options());
  const float* px = x.data_ptr<float>();
  float* py = y.data_ptr<float>();
  // Strips of 8 rows, each transposed in 8 x 8 tiles (transpose_into): the rows of a tile
  // lie a power of two apart and share cache sets, so larger blocks (16, 32, or through a
  // buffer) measured 2-4x slower on [256, 4096].
  constexpr int64_t B = 8;
  const int64_t strips = (m + B - 1) / B;
  at::parallel_for(0, batch * strips, 1, [&](int64_t begin, int64_t end) {
    for (int64_t t = begin; t < end; ++t) {
      const int64_t b = t / strips, i0 = (t % strips) * B;
      transpose_into(px + b * m * n + i0 * n, n, py + b * m * n + i0, m, std::min(B, m - i0), n);
    }
  });
  return y;
}

}  // namespace isegman::models

namespace isegman::models {

at::Tensor attention(const at::Tensor& q0, const at::Tensor& kt0, const at::Tensor& v0, double scale, const at::Tensor& bias0) {
  int64_t m = q0.size(-2), k = q0.size(-1), n = kt0.size(-1), d = v0.size(-1);
  if (kt0.size(-2) != k || v0.size(-2) != n) throw std::invalid_argument("attention: inner dimensions differ");
  std::vector<int64_t> batch = broadcast(broadcast(batch_of(q0), batch_of(kt0)), batch_of(v0));
  at::Tensor bias;
  if (bias0.defined()) {
    // The bias broadcasts against [batch..., m, n]; its matrix part must have unit column stride.
    std::vector<int64_t> full = broadcast(with_matrix(batch, m, n), bias0.sizes().vec());
    batch.assign(full.begin(), full.end() - 2);
    if (full[full.size() - 2] != m || full.back() != n) throw std::invalid_argument("attention: bias does not broadcast");
    bias = bias0.expand(full);
    if (bias.stride(-1) != 1 && n > 1) bias = bias0.contiguous().expand(full);
  }
  at::Tensor q = q0.expand(with_matrix(batch, m, k)), kt = kt0.expand(with_matrix(batch, k, n)),
             v = v0.expand(with_matrix(batch, n, d));
  MatrixLayout lq, lk, lv;
  if (!layout_of(q, lq)) q = q.contiguous(), layout_of(q, lq);
  if (!layout_of(kt, lk)) kt = kt.contiguous(), layout_of(kt, lk);
  if (!layout_of(v, lv)) v = v.contiguous(), layout_of(v, lv);
  at::Tensor out = at::empty(with_matrix(batch, m, d), q0.options());
  int64_t count = 1;
  for (int64_t b : batch) count *= b;
  if (out.numel() == 0) return out;
  if (n == 0) return out.fill_(NAN);  // softmax over nothing
  // Work unit: `rows` score rows of one batch item (about 64 KiB of scores, cache-resident).
  int64_t rows = std::clamp<int64_t>(16384 / n, 1, m);
  int64_t tiles = (m + rows - 1) / rows;
  const float* pq = q.data_ptr<float>();
  const float* pk = kt.data_ptr<float>();
  const float* pv = v.data_ptr<float>();
  const float* pb = bias.defined() ? bias.data_ptr<float>() : nullptr;
  float* po = out.data_ptr<float>();
  // Row r of q's matrix starts at r * row step (row-major: ld; transposed: 1).
  int64_t q_row = lq.transposed ? 1 : lq.ld;
  at::parallel_for(0, count * tiles, 1, [&](int64_t begin, int64_t end) {
    std::vector<float> scores(size_t(rows * n));
    for (int64_t unit = begin; unit < end; ++unit) {
      int64_t item = unit / tiles, r0 = (unit % tiles) * rows, nr = std::min(rows, m - r0);
      float* s = scores.data();
      sgemm(lq.transposed, lk.transposed, nr, n, k, float(scale), pq + batch_offset(batch, q, item) + r0 * q_row, lq.ld,
            pk + batch_offset(batch, kt, item), lk.ld, 0.0f, s, n);
      if (pb) {
        const float* b = pb + batch_offset(batch, bias, item);
        int64_t brs = bias.stride(-2), bcs = bias.stride(-1);
        for (int64_t r = 0; r < nr; ++r) {
          const float* brow = b + (r0 + r) * brs;
          float* srow = s + r * n;
          if (bcs == 1) {
            for (int64_t j = 0; j < n; ++j) srow[j] += brow[j];
          } else {
            for (int64_t j = 0; j < n; ++j) srow[j] += brow[j * bcs];
          }
        }
      }
      softmax_rows(s, nr, n, n);
      sgemm(false, lv.transposed, nr, d, n, 1.0f, s, n, pv + batch_offset(batch, v, item), lv.ld, 0.0f,
            po + (item * m + r0) * d, d);
    }
  });
  return out;
}

}  // namespace isegman::models
