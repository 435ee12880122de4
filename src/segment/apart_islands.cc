#include "segment/apart_islands.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "core/zeroed_array.h"
#include "segment/link_grid.h"

namespace isegman::segment {

namespace {

// Views past this many (8 bits a Gaussian) are not read: a user gives a few positive clicks.
constexpr size_t kMaxClickedViews = 8;
// A broad Gaussian is not followed when its search would read more grid cells than this.
constexpr int64_t kMaxBroadCells = 512;

// kFlooding: reached by the seed's flood under way; kSettled: a whole set that stays, apart.
enum Flood : uint8_t { kUnvisited = 0, kJoined = 1, kSettled = 2, kLeaving = 3, kFlooding = 4 };

// Marks bit `bit` in `behind` for every Gaussian of `seen` (selected, seen in the view; its
// centre at (u, v), depth z) that selected Gaussians nearer by the gap flank on both sides;
// appends to `marked` each Gaussian no view had marked before.
struct SeenAt {
  uint32_t g;
  float u, v, z;
};
void mark_behind(const std::vector<SeenAt>& seen, const Camera& camera, const ApartOptions& o, uint8_t bit,
                 ZeroedArray<uint8_t>& behind, std::vector<uint32_t>& marked) {
  const double side = std::max(camera.width, camera.height);
  const double cell = std::max(1.0, o.cell_share * side);
  const int w = int(std::ceil(camera.width / cell)), h = int(std::ceil(camera.height / cell));
  const int reach = std::max(1, int(std::lround(o.flank_share * side / cell)));
  std::vector<float> nearest(size_t(w) * size_t(h), INFINITY);
  auto at = [&](int x, int y) -> float& { return nearest[size_t(y) * size_t(w) + size_t(x)]; };
  auto cell_of = [&](const SeenAt& s, int& x, int& y) {
    // A broad Gaussian seen in the view may be centred far outside it (or near the camera's
    // plane): compare before converting.
    if (!(s.u >= 0 && s.v >= 0 && s.u < camera.width && s.v < camera.height)) return false;
    x = std::min(w - 1, int(s.u / cell));
    y = std::min(h - 1, int(s.v / cell));
    return true;
  };
  for (const SeenAt& s : seen) {
    int x, y;
    if (cell_of(s, x, y)) at(x, y) = std::min(at(x, y), s.z);
  }
  for (const SeenAt& s : seen) {
    int x, y;
    if (!cell_of(s, x, y)) continue;
    const float front = float(double(s.z) / (1 + o.behind_gap));
    // Whether a cell 1..reach steps along (dx, dy) holds something nearer than `front`.
    auto nearer = [&](int dx, int dy) {
      for (int k = 1; k <= reach; ++k) {
        const int cx = x + k * dx, cy = y + k * dy;
        if (cx < 0 || cy < 0 || cx >= w || cy >= h) return false;
        if (at(cx, cy) < front) return true;
      }
      return false;
    };
    if ((nearer(-1, 0) && nearer(1, 0)) || (nearer(0, -1) && nearer(0, 1))) {
      if (!behind[s.g]) marked.push_back(s.g);
      behind[s.g] = uint8_t(behind[s.g] | bit);
    }
  }
}

// Sets mostly seen behind, each too small to leave on its own (`fragments` into `pieces`), that
// lie nearer to what leaves (state kLeaving) than to the set joined to the clicks (kJoined):
// the pieces of a bookcase the plant before it parts, apart from the piece that left and from
// each other. A leaf of the plant behind the clicked one, apart from it, lies nearer the plant.
// Distances are counted in cells of a grid over the selection's linkable Gaussians, its
// longest side `cells` cells (26-neighbour steps from every cell each side holds). Appends
// what leaves to `leave`; returns the number of sets.
int follow_nearest(const GaussianScene& scene, const ZeroedArray<uint8_t>& state,
                   const std::vector<uint32_t>& members, const std::vector<uint32_t>& pieces,
                   const std::vector<std::pair<size_t, size_t>>& fragments, int cells, std::vector<uint32_t>& leave) {
  if (members.empty() || cells < 2) return 0;
  Vec3 lo = scene.position(members[0]), hi = lo;
  for (uint32_t g : members) {
    const Vec3 p = scene.position(g);
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double side = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-9}) / double(cells - 1);
  const int nx = int((hi.x - lo.x) / side) + 1, ny = int((hi.y - lo.y) / side) + 1, nz = int((hi.z - lo.z) / side) + 1;
  auto cell_of = [&](uint32_t g) {
    const Vec3 p = scene.position(g);
    const int x = std::clamp(int((p.x - lo.x) / side), 0, nx - 1), y = std::clamp(int((p.y - lo.y) / side), 0, ny - 1),
              z = std::clamp(int((p.z - lo.z) / side), 0, nz - 1);
    return (size_t(z) * size_t(ny) + size_t(y)) * size_t(nx) + size_t(x);
  };
  // Steps from the nearest cell holding what leaves, and what stays (breadth first; empty
  // where no member is either).
  auto steps_from = [&](auto holds) {
    std::vector<int32_t> d(size_t(nx) * size_t(ny) * size_t(nz), -1);
    std::vector<size_t> queue;
    for (uint32_t g : members)
      if (holds(g)) {
        const size_t c = cell_of(g);
        if (d[c] < 0) {
          d[c] = 0;
          queue.push_back(c);
        }
      }
    for (size_t head = 0; head < queue.size(); ++head) {
      const size_t c = queue[head];
      const int x = int(c % size_t(nx)), y = int(c / size_t(nx) % size_t(ny)), z = int(c / (size_t(nx) * size_t(ny)));
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int X = x + dx, Y = y + dy, Z = z + dz;
            if (X < 0 || Y < 0 || Z < 0 || X >= nx || Y >= ny || Z >= nz) continue;
            const size_t e = (size_t(Z) * size_t(ny) + size_t(Y)) * size_t(nx) + size_t(X);
            if (d[e] >= 0) continue;
            d[e] = d[c] + 1;
            queue.push_back(e);
          }
    }
    if (queue.empty()) d.clear();
    return d;
  };
  const std::vector<int32_t> to_leaving = steps_from([&](uint32_t g) { return state[g] == kLeaving; });
  const std::vector<int32_t> to_staying = steps_from([&](uint32_t g) { return state[g] == kJoined; });
  // Nothing linkable joined to the clicks (their Gaussians too broad to link): no nearness to
  // compare with, and nothing follows.
  if (to_leaving.empty() || to_staying.empty()) return 0;
  int sets = 0;
  for (const auto& [offset, count] : fragments) {
    int32_t near_leaving = INT32_MAX, near_staying = INT32_MAX;
    for (size_t i = offset; i < offset + count; ++i) {
      const size_t c = cell_of(pieces[i]);
      if (to_leaving[c] >= 0) near_leaving = std::min(near_leaving, to_leaving[c]);
      if (to_staying[c] >= 0) near_staying = std::min(near_staying, to_staying[c]);
    }
    if (near_leaving >= near_staying) continue;
    leave.insert(leave.end(), pieces.begin() + std::ptrdiff_t(offset), pieces.begin() + std::ptrdiff_t(offset + count));
    ++sets;
  }
  return sets;
}

}  // namespace

ApartReport drop_apart_islands(std::vector<bool>& selection, const GaussianScene& scene,
                               const std::vector<ClickedViewVotes>& clicked,
                               const std::vector<uint32_t>& click_gaussians, double min_weight,
                               const ApartOptions& options, const IslandOptions& link) {
  ApartReport out;
  if (!options.enabled || clicked.empty() || click_gaussians.empty()) return out;
  const size_t n = selection.size();
  const size_t views = std::min(clicked.size(), kMaxClickedViews);
  // Per Gaussian: inside some clicked view's mask; and a bit per clicked view that sees it
  // outside its mask, that sees it at all (blending the vote's minimum weight), and that sees
  // it behind the gaps of something nearer (mark_behind).
  ZeroedArray<uint8_t> inside(n), outside(n), at_click(n), seen(n), behind(n), beyond(n);
  for (uint32_t g : click_gaussians) at_click[g] = 1;
  std::vector<uint32_t> seeds;
  size_t in_masks = 0;  // the object as the clicked views' masks show it: its selected Gaussians there
  const double min_fixed = min_weight * kVoteScale;
  std::vector<SeenAt> seen_at;
  std::vector<uint32_t> behind_marked;  // every Gaussian some clicked view sees behind
  std::vector<uint32_t> beyond_marked;  // every Gaussian some clicked view sees behind the clicked surface
  for (size_t v = 0; v < views; ++v) {
    const ViewVotes& total = *clicked[v].total;
    const ViewVotes& mask = *clicked[v].inside;
    const Camera* camera = options.behind ? clicked[v].camera : nullptr;
    seen_at.clear();
    // The clicked surface's depth in this view: the median of what the clicks' pixels show.
    double beyond_z = INFINITY;
    if (camera && options.behind_click_gap > 0) {
      std::vector<double> zs;
      for (uint32_t g : click_gaussians) {
        double u, w, z;
        if (camera->project(scene.position(g), u, w, &z)) zs.push_back(z);
      }
      if (!zs.empty()) {
        std::nth_element(zs.begin(), zs.begin() + std::ptrdiff_t(zs.size() / 2), zs.end());
        beyond_z = zs[zs.size() / 2] * (1 + options.behind_click_gap);
      }
    }
    size_t m = 0;
    for (size_t i = 0; i < total.index.size(); ++i) {
      const uint32_t g = total.index[i];
      while (m < mask.index.size() && mask.index[m] < g) ++m;
      if (!selection[g]) continue;
      const double a = double(total.weight[i]);
      const double p = m < mask.index.size() && mask.index[m] == g ? double(mask.weight[m]) : 0.0;
      if (a >= min_fixed) {
        seen[g] = uint8_t(seen[g] | (1u << v));
        double u, w, z;
        if (camera && camera->project(scene.position(g), u, w, &z)) {
          seen_at.push_back({g, float(u), float(w), float(z)});
          if (z > beyond_z) {
            if (!beyond[g]) beyond_marked.push_back(g);
            beyond[g] = uint8_t(beyond[g] | (1u << v));
          }
        }
      }
      if (p > 0 && p >= options.inside_share * a) {
        in_masks += !inside[g];
        inside[g] = 1;
      } else if (a >= min_fixed && p <= options.outside_share * a) {
        if (!outside[g]) seeds.push_back(g);
        outside[g] = uint8_t(outside[g] | (1u << v));
      }
    }
    if (camera) mark_behind(seen_at, *camera, options, uint8_t(1u << v), behind, behind_marked);
  }
  size_t behind_seeds = behind_marked.size();  // seen behind either way
  for (uint32_t g : beyond_marked) behind_seeds += !behind[g];
  const size_t outside_seeds = seeds.size();
  for (uint32_t g : behind_marked)
    if (!outside[g]) seeds.push_back(g);
  for (uint32_t g : beyond_marked)
    if (!outside[g] && !behind[g]) seeds.push_back(g);
  // A set leaves only with at least min_size_share x in_masks Gaussians, min_seen_share of
  // them seen outside one clicked view's mask, all of them seeds; or with at least
  // behind_size_share / (1 + behind_size_share) of the selection, min_seen_share of them
  // seen behind. With fewer seeds than either needs no set can, and the floods (a neighbour
  // search per Gaussian) are skipped.
  const bool apart_possible =
      double(outside_seeds) >= options.min_seen_share * options.min_size_share * double(in_masks);
  const size_t selected_total = size_t(std::count(selection.begin(), selection.end(), true));
  const bool behind_possible =
      behind_seeds > 0 && double(behind_seeds) >= options.min_seen_share * options.behind_size_share /
                                                      (1 + options.behind_size_share) * double(selected_total);
  if (seeds.empty() || (!apart_possible && !behind_possible)) return out;
  // Large Gaussians do not link: a few broad flat ones of the floor the selection took join
  // everything standing on it.
  std::vector<uint32_t> members, broad;  // the linkable Gaussians, and the selected others
  double limit = 0;                       // the largest scale that links
  {
    std::vector<uint32_t> selected;
    std::vector<float> scales;
    for (size_t j = 0; j < n; ++j)
      if (selection[j]) {
        selected.push_back(uint32_t(j));
        scales.push_back(scene.largest_scale(j));
      }
    std::vector<float> sorted = scales;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
    limit = options.max_link_scale * sorted[sorted.size() / 2];
    for (size_t i = 0; i < selected.size(); ++i) (scales[i] > limit ? broad : members).push_back(selected[i]);
  }
  const LinkGrid touching(scene, members, link.link_sigmas);
  ZeroedArray<uint8_t> state(n);
  std::vector<uint32_t> frontier, leave;
  std::vector<uint32_t> pieces;                    // the Gaussians of the sets mostly seen behind too small to leave ...
  std::vector<std::pair<size_t, size_t>> fragments;  // ... each set's (offset, count) there
  // Searches queue[head] (then advances head) and joins to the clicks what it touches that no
  // flood reached, appending it to `queue`; true when it touches the set a seed's flood is
  // flooding (kFlooding). A click's Gaussian far broader than the members is not searched cell
  // by cell.
  auto join_next = [&](std::vector<uint32_t>& queue, size_t& head) {
    bool met = false;
    touching.for_each(
        queue[head++],
        [&](uint32_t j) {
          met = met || state[j] == kFlooding;
          if (state[j] != kUnvisited) return;
          state[j] = kJoined;
          queue.push_back(j);
        },
        kMaxBroadCells);
    return met;
  };
  // Behind the clicked surface counts only where the set joined to the clicks is an object's
  // worth of what the clicked masks hold: a skeleton's bones, each a set of its own, do not
  // stand for it. That set is flooded first, as far as that share (a seed's flood stops where
  // it meets it), and what touches a click's own Gaussian joins even where that Gaussian is too
  // broad to link.
  bool beyond_counts = false;
  std::vector<uint32_t> click_set;  // the set joined to the clicks as far as flooded, in flood order
  size_t click_head = 0;            // ... its members before this have been searched
  {
    const double needed = options.behind_click_gap > 0 ? options.min_click_set_share * double(in_masks) : 0.0;
    for (uint32_t g : click_gaussians)
      if (selection[g] && state[g] == kUnvisited) {
        state[g] = kJoined;
        click_set.push_back(g);
      }
    const size_t own = click_set.size();
    while (click_head < click_set.size() && (click_head < own || double(click_set.size()) < needed))
      join_next(click_set, click_head);
    beyond_counts = options.behind_click_gap > 0 && in_masks > 0 && double(click_set.size()) >= needed;
  }
  for (uint32_t seed : seeds) {
    // A seed only behind the clicked surface needs that to count (its flood would decide nothing).
    const bool beyond_seed = beyond_counts && beyond[seed];
    if (state[seed] != kUnvisited || (inside[seed] && !behind[seed] && !beyond_seed) ||
        (!outside[seed] && !behind[seed] && !beyond_seed) || scene.largest_scale(seed) > limit)
      continue;
    // Flood the set breadth first over the linkable Gaussians; it ends early when it joins what
    // a positive click's pixel shows (or a set that did), which for the rest of an object is
    // near. Not the mask: a clicked view's mask may spill onto the neighbour's near edge.
    // The set joined to the clicks floods on a search for each of its searches, and the two
    // join where they meet: halfway, not at the clicks' set (the far side of an object: at
    // 6M Gaussians 540k searches a click before, 445k now). Touching is mutual but for the
    // search's reach (whole_islands.h): a Gaussian broader than the reach finds neighbours
    // that do not find it, and a flood joined by such a link alone now joins from either side.
    frontier.assign(1, seed);
    state[seed] = kFlooding;
    bool joined = at_click[seed] != 0;
    for (size_t head = 0; head < frontier.size() && !joined; ++head) {
      touching.for_each(frontier[head], [&](uint32_t j) {
        if (joined) return;
        if (at_click[j] || state[j] == kJoined) {
          joined = true;
          return;
        }
        if (state[j] != kUnvisited) return;
        state[j] = kFlooding;
        frontier.push_back(j);
      });
      if (!joined && click_head < click_set.size()) joined = join_next(click_set, click_head);
    }
    for (uint32_t g : frontier) state[g] = joined ? kJoined : kSettled;
    if (joined) continue;
    size_t seen_outside[kMaxClickedViews] = {}, seen_in[kMaxClickedViews] = {}, seen_behind[kMaxClickedViews] = {};
    for (uint32_t g : frontier)
      for (size_t v = 0; v < views; ++v) {
        seen_outside[v] += (outside[g] >> v) & 1u;
        seen_in[v] += (seen[g] >> v) & 1u;
        seen_behind[v] += ((behind[g] | (beyond_counts ? beyond[g] : 0)) >> v) & 1u;
      }
    const size_t most = *std::max_element(seen_outside, seen_outside + views);
    const bool apart = double(most) >= options.min_seen_share * double(frontier.size()) &&
                       double(frontier.size()) >= options.min_size_share * double(in_masks);
    // Seen through the object's gaps: most of what a clicked view sees of it, and a real share
    // of it, lies behind; an object's worth of Gaussians.
    bool mostly_behind = false;
    for (size_t v = 0; v < views && options.behind; ++v)
      mostly_behind =
          mostly_behind || (seen_in[v] > 0 && double(seen_behind[v]) >= options.min_behind_share * double(seen_in[v]) &&
                            double(seen_behind[v]) >= options.min_seen_share * double(frontier.size()));
    const bool through =
        mostly_behind && double(frontier.size()) >= options.behind_size_share * double(selected_total - frontier.size());
    if (!apart && !through) {
      if (mostly_behind && options.nearest_follow) {  // too small to leave alone: decided by what it lies nearest
        fragments.push_back({pieces.size(), frontier.size()});
        pieces.insert(pieces.end(), frontier.begin(), frontier.end());
      }
      continue;
    }
    for (uint32_t g : frontier) state[g] = kLeaving;
    leave.insert(leave.end(), frontier.begin(), frontier.end());
    ++out.islands;
  }
  if (!leave.empty() && !fragments.empty()) {
    // The whole set joined to the clicks (flooded on from all the floods reached of it): what
    // stays for certain.
    std::vector<uint32_t> reached;
    for (uint32_t g : members)
      if (state[g] == kJoined) reached.push_back(g);
    for (uint32_t g : click_gaussians)  // a click's own Gaussian may be too broad to be a member
      if (state[g] == kJoined && scene.largest_scale(g) > limit) reached.push_back(g);
    for (size_t head = 0; head < reached.size();) join_next(reached, head);
    const size_t before = leave.size();
    out.islands += follow_nearest(scene, state, members, pieces, fragments, options.nearest_cells, leave);
    for (size_t i = before; i < leave.size(); ++i) state[leave[i]] = kLeaving;
  }
  // A broad Gaussian that touches what leaves and nothing that stays leaves with it: the
  // floor's broad Gaussians under a neighbour.
  if (!leave.empty() && options.broad_follow)
    for (uint32_t g : broad) {
      bool leaving = false, staying = false;
      const bool read = touching.for_each(
          g, [&](uint32_t j) { (state[j] == kLeaving ? leaving : staying) = true; }, kMaxBroadCells);
      if (read && leaving && !staying) leave.push_back(g);
    }
  // Only after every flood: the touch rule sees one selection throughout.
  for (uint32_t g : leave) selection[g] = false;
  out.removed = leave.size();
  return out;
}

}  // namespace isegman::segment
