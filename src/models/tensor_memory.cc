// The large-block CPU allocator behind use_tensor_memory_pool() (see tensor_memory.h).
#include "models/tensor_memory.h"

#include <c10/core/CPUAllocator.h>

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <map>
#include <mutex>
#include <new>
#include <unordered_map>

namespace isegman::models {
namespace {

constexpr size_t kLargeBlock = size_t(1) << 20;  // smaller requests go to the default allocator
constexpr size_t kHugePage = size_t(2) << 20;
constexpr size_t kMaxCached = size_t(3) << 30;  // freed bytes kept for reuse at most

size_t round_up(size_t n, size_t to) { return (n + to - 1) / to * to; }

class PooledCpuAllocator final : public c10::Allocator {
 public:
  explicit PooledCpuAllocator(c10::Allocator* fallback) : fallback_(fallback), fallback_delete_(fallback->raw_deleter()) {}

  c10::DataPtr allocate(size_t n) const override {
    if (n < kLargeBlock) {
      // Re-wrapped with our deleter: oneDNN frees through raw_deleter() with the bare pointer.
      c10::DataPtr d = fallback_->allocate(n);
      void* p = d.release_context();
      return {p, p, &PooledCpuAllocator::release, c10::Device(c10::DeviceType::CPU)};
    }
    size_t size = round_up(n, kHugePage);
    std::lock_guard<std::mutex> lock(mutex_);
    void* p = take(size);
    if (!p) {
      p = map(size);
      ++maps_;
    }
    live_[p] = size;
    return {p, p, &PooledCpuAllocator::release, c10::Device(c10::DeviceType::CPU)};
  }

  c10::DeleterFnPtr raw_deleter() const override { return &PooledCpuAllocator::release; }

  size_t trim() const {
    std::multimap<size_t, void*> blocks;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      blocks.swap(free_);
      cached_ = 0;
    }
    size_t bytes = 0;
    for (const auto& [size, p] : blocks) {
      munmap(p, size);
      bytes += size;
    }
    return bytes;
  }

  size_t cached_bytes() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return cached_;
  }
  size_t maps() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return maps_;
  }

 private:
  // A cached block of at least `size` bytes and at most a quarter more (best fit), or null.
  void* take(size_t size) const {
    auto it = free_.lower_bound(size);
    if (it == free_.end() || it->first > size + size / 4) return nullptr;
    void* p = it->second;
    cached_ -= it->first;
    free_.erase(it);
    return p;
  }

  static void* map(size_t size) {
    // Over-map by one huge page so the block can start on a 2 MiB boundary.
    void* raw = mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    uintptr_t start = round_up(uintptr_t(raw), kHugePage);
    size_t head = start - uintptr_t(raw);
    if (head) munmap(raw, head);
    if (size_t tail = kHugePage - head) munmap(reinterpret_cast<char*>(start) + size, tail);
    madvise(reinterpret_cast<void*>(start), size, MADV_HUGEPAGE);  // advice only: fine if refused
    return reinterpret_cast<void*>(start);
  }

  static void release(void* p);

  void give_back(void* p) const {
    size_t size = 0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = live_.find(p);
      if (it != live_.end()) {
        size = it->second;
        live_.erase(it);
        if (cached_ + size <= kMaxCached) {
          free_.emplace(size, p);
          cached_ += size;
          return;
        }
      }
    }
    if (size) munmap(p, size);
    else fallback_delete_(p);
  }

  c10::Allocator* fallback_;
  c10::DeleterFnPtr fallback_delete_;
  mutable std::mutex mutex_;
  mutable std::unordered_map<void*, size_t> live_;  // large blocks in use, by address
  mutable std::multimap<size_t, void*> free_;        // large blocks kept for reuse, by size
  mutable size_t cached_ = 0;
  mutable size_t maps_ = 0;  // fresh mappings made so far
};

PooledCpuAllocator* pool = nullptr;

void PooledCpuAllocator::release(void* p) {
  if (p) pool->give_back(p);
}

}  // namespace

void use_tensor_memory_pool() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (std::getenv("ISEGMAN_ONNX_NO_POOL")) return;
    // Never destroyed: tensors may be freed during static destruction.
    c10::Allocator* fallback = c10::GetCPUAllocator();
    if (!fallback->raw_deleter()) return;  // cannot wrap it
    pool = new PooledCpuAllocator(fallback);
    c10::SetCPUAllocator(pool, /*priority=*/1);
  });
}

size_t trim_tensor_memory_pool() { return pool ? pool->trim() : 0; }

size_t tensor_memory_pool_cached_bytes() { return pool ? pool->cached_bytes() : 0; }

size_t tensor_memory_pool_mappings() { return pool ? pool->maps() : 0; }

}  // namespace isegman::models
