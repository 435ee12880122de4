// Single-precision matrix products on raw row-major buffers, for the executor's MatMul,
// Gemm, linear layers and 1x1 convolutions. With oneDNN (the library libtorch itself uses
// for convolutions, found by CMake) they run on its sgemm, which uses AVX-512 where the CPU
// has it and was 2-3x faster than libtorch's OpenBLAS on the encoder's shapes; otherwise on
// ATen's matrix product.
#pragma once

#include <cstdint>

namespace isegman::models {

// C[m,n] = alpha · op(A)[m,k] · op(B)[k,n] + beta · C, all row-major; op transposes when asked
// (then A is stored [k,m] / B is stored [n,k]). lda/ldb/ldc are row strides in elements.
// Runs on the calling thread's OpenMP threads (one thread inside a parallel region).
void sgemm(bool trans_a, bool trans_b, int64_t m, int64_t n, int64_t k, float alpha, const float* a, int64_t lda,
           const float* b, int64_t ldb, float beta, float* c, int64_t ldc);

// Whether sgemm runs on oneDNN (false: ATen fallback). ISEGMAN_ONNX_NO_DNNL=1 forces false.
bool sgemm_uses_dnnl();

}  // namespace isegman::models
