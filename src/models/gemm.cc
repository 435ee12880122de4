// sgemm (see gemm.h): oneDNN's C API when the build found the library, else ATen.
#include "models/gemm.h"

#include <ATen/ATen.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#ifdef ISEGMAN_HAVE_DNNL
// oneDNN's row-major sgemm, as declared in its public C API header dnnl.h (the -dev
// package with the header is not installed on these machines; the runtime library is a
// dependency of libtorch). Returns dnnl_success (0) on success.
extern "C" int dnnl_sgemm(char transa, char transb, int64_t M, int64_t N, int64_t K, float alpha, const float* A,
                          int64_t lda, const float* B, int64_t ldb, float beta, float* C, int64_t ldc);
#endif

namespace isegman::models {

bool sgemm_uses_dnnl() {
#ifdef ISEGMAN_HAVE_DNNL
  static const bool use = std::getenv("ISEGMAN_ONNX_NO_DNNL") == nullptr;
  return use;
#else
  return false;
#endif
}

void sgemm(bool trans_a, bool trans_b, int64_t m, int64_t n, int64_t k, float alpha, const float* a, int64_t lda,
           const float* b, int64_t ldb, float beta, float* c, int64_t ldc) {
  if (m == 0 || n == 0) return;
  if (k == 0) {  // an empty product: C = beta * C (beta 0 overwrites, even NaN)
    for (int64_t i = 0; i < m; ++i)
      for (int64_t j = 0; j < n; ++j) c[i * ldc + j] = beta == 0.0f ? 0.0f : beta * c[i * ldc + j];
    return;
  }
#ifdef ISEGMAN_HAVE_DNNL
  if (sgemm_uses_dnnl()) {
    int status = dnnl_sgemm(trans_a ? 'T' : 'N', trans_b ? 'T' : 'N', m, n, k, alpha, a, lda, b, ldb, beta, c, ldc);
    if (status != 0) throw std::runtime_error("oneDNN sgemm failed with status " + std::to_string(status));
    return;
  }
#endif
  // Strided views of the caller's buffers (nothing is copied unless ATen needs to).
  auto opts = at::TensorOptions().dtype(at::kFloat);
  at::Tensor A = trans_a ? at::from_blob(const_cast<float*>(a), {k, m}, {lda, 1}, opts).t()
                         : at::from_blob(const_cast<float*>(a), {m, k}, {lda, 1}, opts);
  at::Tensor B = trans_b ? at::from_blob(const_cast<float*>(b), {n, k}, {ldb, 1}, opts).t()
                         : at::from_blob(const_cast<float*>(b), {k, n}, {ldb, 1}, opts);
  at::Tensor C = at::from_blob(c, {m, n}, {ldc, 1}, opts);
  C.addmm_(A, B, beta, alpha);  // beta 0: C's old values (even NaN) are ignored
}

}  // namespace isegman::models
