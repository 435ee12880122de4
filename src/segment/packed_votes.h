// A view's all-pixel votes as a session keeps them: the same ascending Gaussian indices
// and exact fixed-point sums as a ViewVotes, packed. Every view holds one for the whole
// session, about one entry per Gaussian it shows (2.6M per view of a 6M-Gaussian scene:
// 31 MB as 12-byte entries, 13 MB packed; with 20 views, segment_bench's LargeScene/6000000
// peaked at 5,410 MiB instead of 6,074).
//
// An entry is a 1-byte index gap and a 4-byte weight. A gap that does not fit (the next
// index more than 254 past the previous one) or a weight outside [0, 2^32 - 1) goes to a
// side list instead, in order. Blocks of kBlock entries record where their side lists
// start, so they unpack in parallel.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "segment/votes.h"

namespace isegman::segment {

class PackedVotes {
 public:
  PackedVotes() = default;
  // Throws Error when the indices are not strictly ascending or the lists differ in length.
  explicit PackedVotes(const ViewVotes& votes);

  size_t size() const { return weight_.size(); }
  bool empty() const { return weight_.empty(); }
  size_t bytes() const;  // heap bytes held

  // The votes, unpacked into `out` (its buffers are reused: a round unpacks one view after
  // another into the same lists), by `threads` workers (0: every core).
  void unpack(ViewVotes& out, int threads = 1) const;
  ViewVotes unpack(int threads = 1) const;

  static constexpr size_t kBlock = size_t(1) << 16;

 private:
  static constexpr uint8_t kWideGap = 255;
  static constexpr uint32_t kWideWeight = 0xFFFFFFFFu;
  struct Block {
    uint32_t next = 0;          // the index the block's first gap counts from (previous + 1)
    uint32_t wide_gaps = 0;     // where its entries start in wide_gap_ ...
    uint32_t wide_weights = 0;  // ... and in wide_weight_
  };
  std::vector<uint8_t> gap_;          // index - (previous index + 1); kWideGap: in wide_gap_
  std::vector<uint32_t> weight_;      // kWideWeight: in wide_weight_
  std::vector<uint32_t> wide_gap_;
  std::vector<int64_t> wide_weight_;
  std::vector<Block> blocks_;
};

}  // namespace isegman::segment
