#include "segment/coherence.h"

namespace isegman::segment {

std::vector<bool> coherent_selection(const VoteAccumulator& votes, const GaussianScene& scene, const CentreIndex& index,
                                     double tau, double min_total, const CoherenceOptions& o,
                                     const CentreRule& centre) {
  std::vector<bool> strong = votes.select(tau, min_total, centre);
  std::vector<bool> out = strong;
  const std::vector<bool> observed = votes.select(-1.0, min_total);
  const std::vector<float> share = votes.ratios();
  for (uint32_t i = 0; i < uint32_t(share.size()); ++i) {
    if (strong[i] || !observed[i] || !(share[i] > o.tau_low)) continue;
    int seen = 0, selected = 0, others = 0;
    // k + 1: the Gaussian is its own nearest centre.
    for (uint32_t j : index.nearest(scene.position(i), o.neighbours + 1, 0)) {
      if (j == i || ++others > o.neighbours || !observed[j]) continue;
      ++seen;
      selected += strong[j];
    }
    if (seen > 0 && selected >= o.min_selected * seen) out[i] = true;
  }
  return out;
}

}  // namespace isegman::segment
