// Kernels of the ONNX executor (see kernels.h), on top of gemm.h's sgemm.
#include "models/kernels.h"

#include <ATen/ATen.h>
#include <ATen/Parallel.h>

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

}  // namespace

at::Tensor batched_matmul(const at::Tensor& a0, const at::Tensor& b0) {
  if (a0.dim() < 2 || b0.dim() < 2 || a0.scalar_type() != at::kFloat || b0.scalar_type() != at::kFloat)
    return at::matmul(a0, b0);
  int64_t m = a0.size(-2), k = a0.size(-1), n = b0.size(-1);
  if (b0.size(-2) != k) throw std::invalid_argument("matmul: inner dimensions differ");
  std::vector<int64_t> batch = broadcast({a0.sizes().begin(), a0.sizes().end() - 2}, {b0.sizes().begin(), b0.sizes().end() - 2});
  std::vector<int64_t> shape_a = batch, shape_b = batch, shape_c = batch;
  shape_a.insert(shape_a.end(), {m, k});
  shape_b.insert(shape_b.end(), {k, n});
  shape_c.insert(shape_c.end(), {m, n});
  at::Tensor a = a0.expand(shape_a), b = b0.expand(shape_b);  // batch strides 0 where broadcast
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
    int64_t oa = 0, ob = 0, rest = i;
    for (int64_t d = int64_t(batch.size()) - 1; d >= 0; --d) {
      int64_t idx = rest % batch[d];
      rest /= batch[d];
      oa += idx * a.stride(d);
      ob += idx * b.stride(d);
    }
    sgemm(la.transposed, lb.transposed, m, n, k, 1.0f, pa + oa, la.ld, pb + ob, lb.ld, 0.0f, pc + i * m * n, n);
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

at::Tensor conv1x1(const at::Tensor& x0, const at::Tensor& w0, const at::Tensor& bias) {
  at::Tensor x = x0.contiguous(), w = w0.contiguous();
  int64_t batch = x.size(0), ci = x.size(1), hw = x.size(2) * x.size(3), co = w.size(0);
  at::Tensor y = at::empty({batch, co, x.size(2), x.size(3)}, x.options());
  float beta = 0.0f;
  if (bias.defined()) {
    y.copy_(bias.reshape({1, co, 1, 1}).expand(y.sizes()));
    beta = 1.0f;
  }
  for (int64_t i = 0; i < batch; ++i)
    sgemm(false, false, co, hw, ci, 1.0f, w.data_ptr<float>(), ci, x.data_ptr<float>() + i * ci * hw, hw, beta,
          y.data_ptr<float>() + i * co * hw, hw);
  return y;
}

}  // namespace isegman::models
