// Fixed-size arrays of zeros that cost nothing until written. std::vector<int64_t>(n, 0)
// writes every element and so faults in every 4 KiB page at once; on the dev VMs a fault
// costs ~20-35 us, and the vote sums of a 6M-Gaussian scene (144 MB, made afresh every
// click) spent over a second in page faults. A large ZeroedArray is a fresh anonymous
// mapping (zero by definition, nothing written), advised as transparent huge pages so
// the pages it does touch come in 2 MiB at a time; small ones come from calloc.
#pragma once

#include <cstddef>
#include <cstring>
#include <type_traits>
#include <utility>

namespace isegman {

// Zero-filled memory of `bytes` (at least 1): a fresh mapping from 1 MiB on, else calloc.
void* zeroed_alloc(size_t bytes);
void zeroed_free(void* p, size_t bytes);

template <class T>
class ZeroedArray {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_default_constructible_v<T>,
                "zero bytes must be a valid value");

 public:
  ZeroedArray() = default;
  explicit ZeroedArray(size_t n) : n_(n), p_(n ? static_cast<T*>(zeroed_alloc(n * sizeof(T))) : nullptr) {}
  ZeroedArray(const ZeroedArray& o) : ZeroedArray(o.n_) {
    if (n_) std::memcpy(p_, o.p_, n_ * sizeof(T));
  }
  ZeroedArray(ZeroedArray&& o) noexcept : n_(std::exchange(o.n_, 0)), p_(std::exchange(o.p_, nullptr)) {}
  ZeroedArray& operator=(ZeroedArray o) noexcept {
    std::swap(n_, o.n_);
    std::swap(p_, o.p_);
    return *this;
  }
  ~ZeroedArray() {
    if (p_) zeroed_free(p_, n_ * sizeof(T));
  }

  size_t size() const { return n_; }
  bool empty() const { return n_ == 0; }
  T* data() { return p_; }
  const T* data() const { return p_; }
  T& operator[](size_t i) { return p_[i]; }
  const T& operator[](size_t i) const { return p_[i]; }
  T* begin() { return p_; }
  T* end() { return p_ + n_; }
  const T* begin() const { return p_; }
  const T* end() const { return p_ + n_; }
  bool operator==(const ZeroedArray& o) const { return n_ == o.n_ && (!n_ || std::memcmp(p_, o.p_, n_ * sizeof(T)) == 0); }
  bool operator!=(const ZeroedArray& o) const { return !(*this == o); }

 private:
  size_t n_ = 0;
  T* p_ = nullptr;
};

}  // namespace isegman
