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

// 1x1 convolution, stride 1, no padding: y[n, :, p] = W[Co, Ci] x[n, :, p] (+ bias[Co]).
// Works through blocks of 256 pixels: each block's x^T [pixels, Ci] (read in place from
// an NHWC view, else transposed into a buffer) times W^T read transposed, then written
// back channel by channel with the bias while in cache; the blocks spread over the
// threads. One wide product W @ x[Ci, H*W] per image, as before, ran the encoder's 1x1
// convolutions 2-3x slower on a Zen 1 EPYC: oneDNN's sgemm takes a slow path there for a
// wide, 64-byte aligned right-hand matrix (moved 16 bytes off, the same product ran 1.6x
// faster; docs/sam.md, Speed).
at::Tensor conv1x1(const at::Tensor& x, const at::Tensor& w, const at::Tensor& bias);

// ConvTranspose2d whose kernel equals its stride (no padding, dilation 1, one group):
// every input pixel writes its own kh x kw output block, y[n,o,i*kh+a,j*kw+b] =
// sum_c x[n,c,i,j] w[c,o,a,b] + bias[o]. One sgemm per image, x^T [H*W, Ci] @ W [Ci, Co*kh*kw]
// (x^T read in place from an NHWC view, else transposed first), then one pass that spreads
// the product's rows into the blocks and adds the bias. w [Ci, Co, kh, kw], bias [Co] or undefined.
at::Tensor conv_transpose_blocks(const at::Tensor& x, const at::Tensor& w, const at::Tensor& bias);

// x [..., M, N] (contiguous) as a contiguous [..., N, M]: a blocked copy, several times
// faster than ATen's strided one on these CPUs.
at::Tensor transpose_last_two(const at::Tensor& x);

// softmax(scale · q @ kt + bias) @ v, softmax over the last axis: q [..., M, K],
// kt [..., K, N], v [..., N, D], bias (optional) broadcastable to [..., M, N]; batch axes
// broadcast. Works through blocks of score rows that stay in cache: two sgemms, the bias
// and a row softmax per block, never the whole score tensor. Returns [..., M, D].
at::Tensor attention(const at::Tensor& q, const at::Tensor& kt, const at::Tensor& v, double scale, const at::Tensor& bias);

// In place, each of `rows` rows of n floats (row stride ld): exp(x - max) / sum.
void softmax_rows(float* x, int64_t rows, int64_t n, int64_t ld);

}  // namespace isegman::models
