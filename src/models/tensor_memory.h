// Memory for large ATen tensors. On the dev VMs every first touch of a fresh 4 KiB page
// costs ~20 us (a 64 MiB tensor: ~350 ms of page faults for ~6 ms of arithmetic), and
// glibc hands blocks above its mmap threshold (32 MiB at most) back to the kernel on free,
// so every large intermediate of the encoder was faulted in again on every run.
#pragma once

#include <cstddef>

namespace isegman::models {

// Installs, once per process, a CPU allocator for libtorch that serves blocks of 1 MiB
// and more from 2 MiB-aligned mappings advised as transparent huge pages (one fault per
// 2 MiB) and keeps freed blocks for reuse (up to a cap, see tensor_memory.cc). Smaller
// blocks go to libtorch's default allocator. ISEGMAN_ONNX_NO_POOL=1 leaves the default
// allocator in place (for comparisons).
void use_tensor_memory_pool();

// Gives every block the pool keeps for reuse back to the system and returns their bytes.
// For the end of an encoding burst (a session's views are encoded): the blocks sized for
// the encoder's activations would otherwise stay resident for the rest of the process.
// Later runs map afresh what they need (the pool fills again).
size_t trim_tensor_memory_pool();

// Bytes the pool currently keeps for reuse (0 when it is not installed).
size_t tensor_memory_pool_cached_bytes();
// Fresh mappings the pool has made so far (each costs page faults on first touch).
size_t tensor_memory_pool_mappings();

}  // namespace isegman::models
