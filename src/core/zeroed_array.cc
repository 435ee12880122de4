#include "core/zeroed_array.h"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <new>

namespace isegman {
namespace {

constexpr size_t kMapFrom = size_t(1) << 20;   // smaller blocks: calloc
constexpr size_t kHugePage = size_t(2) << 20;

size_t round_up(size_t n, size_t to) { return (n + to - 1) / to * to; }

}  // namespace

void* zeroed_alloc(size_t bytes) {
  if (bytes < kMapFrom) {
    void* p = std::calloc(bytes ? bytes : 1, 1);
    if (!p) throw std::bad_alloc();
    return p;
  }
  const size_t size = round_up(bytes, kHugePage);
  // Over-map by one huge page so the block can start on a 2 MiB boundary.
  void* raw = mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const uintptr_t start = round_up(uintptr_t(raw), kHugePage);
  const size_t head = start - uintptr_t(raw);
  if (head) munmap(raw, head);
  if (const size_t tail = kHugePage - head) munmap(reinterpret_cast<char*>(start) + size, tail);
  madvise(reinterpret_cast<void*>(start), size, MADV_HUGEPAGE);  // advice only: fine if refused
  return reinterpret_cast<void*>(start);
}

void zeroed_free(void* p, size_t bytes) {
  if (!p) return;
  if (bytes < kMapFrom) std::free(p);
  else munmap(p, round_up(bytes, kHugePage));
}

}  // namespace isegman
