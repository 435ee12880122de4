#include "segment/coherence.h"

namespace isegman::segment {

std::vector<bool> coherent_selection(const VoteAccumulator& votes, const GaussianScene& scene, const CentreIndex& index,
                                     double tau, double min_total, const CoherenceOptions& o, const CentreRule& centre,
                                     const std::vector<bool>* known_strong, const std::vector<uint32_t>* candidates,
                                     const WholeRule& whole) {
  const std::vector<bool> computed = known_strong ? std::vector<bool>() : votes.select(tau, min_total, centre, whole);
  const std::vector<bool>& strong = known_strong ? *known_strong : computed;
  std::vector<bool> out = strong;
  // select(-1) and ratios(), per Gaussian where asked.
  const int64_t min_fixed = VoteAccumulator::min_fixed(min_total);
  auto observed = [&](uint32_t j) { return votes.selects(j, -1.0, min_fixed); };
  auto share = [&](uint32_t j) {
    return votes.total()[j] > 0 ? float(double(votes.positive()[j]) / double(votes.total()[j])) : 0.f;
  };
  auto decide = [&](uint32_t i) {
    if (strong[i] || !observed(i) || !(share(i) > o.tau_low)) return;
    int seen = 0, selected = 0, others = 0;
    // k + 1: the Gaussian is its own nearest centre.
    for (uint32_t j : index.nearest(scene.position(i), o.neighbours + 1, 0)) {
      if (j == i || ++others > o.neighbours || !observed(j)) continue;
      ++seen;
      selected += strong[j];
    }
    if (seen > 0 && selected >= o.min_selected * seen) out[i] = true;
  };
  // A share above tau_low >= 0 needs P > 0: only the candidates can have it.
  if (candidates && o.tau_low >= 0)
    for (uint32_t i : *candidates) decide(i);
  else
    for (uint32_t i = 0; i < uint32_t(votes.size()); ++i) decide(i);
  return out;
}

}  // namespace isegman::segment
