// Tensor-level kernels of the ONNX executor that ATen lacks or runs slowly on CPU.
// Internal to the models layer: include only from its .cc files (it pulls in ATen).
#pragma once

#include <ATen/core/Tensor.h>

namespace isegman::models {

// a @ b with NumPy broadcasting of the batch axes (both operands rank >= 2, float), each
// matrix read where it lies: a transposed or row-strided view (Transpose, Split outputs)
// is passed to sgemm with its strides instead of being copied. Returns a contiguous tensor.
at::Tensor batched_matmul(const at::Tensor& a, const at::Tensor& b);

// x[..., K] @ w[K, N] (+ bias[N]) as one sgemm over the flattened rows.
at::Tensor linear(const at::Tensor& x, const at::Tensor& w, const at::Tensor& bias);

// 1x1 convolution, stride 1, no padding: per image W[Co, Ci] @ x[Ci, H*W] (+ bias[Co]).
at::Tensor conv1x1(const at::Tensor& x, const at::Tensor& w, const at::Tensor& bias);

}  // namespace isegman::models
