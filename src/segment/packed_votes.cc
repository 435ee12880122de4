#include "segment/packed_votes.h"

#include <algorithm>
#include <string>

#include "core/error.h"
#include "core/parallel.h"

namespace isegman::segment {

PackedVotes::PackedVotes(const ViewVotes& v) {
  const size_t n = v.index.size();
  if (v.weight.size() != n)
    throw Error("packed votes: " + std::to_string(n) + " indices but " + std::to_string(v.weight.size()) + " weights");
  gap_.resize(n);
  weight_.resize(n);
  blocks_.reserve((n + kBlock - 1) / kBlock);
  uint64_t next = 0;
  for (size_t k = 0; k < n; ++k) {
    if (k % kBlock == 0) blocks_.push_back({uint32_t(next), uint32_t(wide_gap_.size()), uint32_t(wide_weight_.size())});
    const uint32_t index = v.index[k];
    if (index < next)
      throw Error("packed votes: Gaussian indices are not strictly ascending at entry " + std::to_string(k));
    const uint32_t gap = uint32_t(index - next);
    if (gap < kWideGap) {
      gap_[k] = uint8_t(gap);
    } else {
      gap_[k] = kWideGap;
      wide_gap_.push_back(gap);
    }
    const int64_t w = v.weight[k];
    if (w >= 0 && w < int64_t(kWideWeight)) {
      weight_[k] = uint32_t(w);
    } else {
      weight_[k] = kWideWeight;
      wide_weight_.push_back(w);
    }
    next = uint64_t(index) + 1;
  }
}

size_t PackedVotes::bytes() const {
  return gap_.capacity() + weight_.capacity() * sizeof(uint32_t) + wide_gap_.capacity() * sizeof(uint32_t) +
         wide_weight_.capacity() * sizeof(int64_t) + blocks_.capacity() * sizeof(Block);
}

void PackedVotes::unpack(ViewVotes& out, int threads) const {
  const size_t n = size();
  out.index.resize(n);
  out.weight.resize(n);
  parallel_for(blocks_.size(), threads, [&](int, size_t b) {
    const Block& block = blocks_[b];
    uint32_t next = block.next;
    const uint32_t* wide_gap = wide_gap_.data() + block.wide_gaps;
    const int64_t* wide_weight = wide_weight_.data() + block.wide_weights;
    const size_t end = std::min(n, (b + 1) * kBlock);
    for (size_t k = b * kBlock; k < end; ++k) {
      const uint32_t index = next + (gap_[k] == kWideGap ? *wide_gap++ : gap_[k]);
      out.index[k] = index;
      out.weight[k] = weight_[k] == kWideWeight ? *wide_weight++ : int64_t(weight_[k]);
      next = index + 1;
    }
  });
}

ViewVotes PackedVotes::unpack(int threads) const {
  ViewVotes out;
  unpack(out, threads);
  return out;
}

}  // namespace isegman::segment
