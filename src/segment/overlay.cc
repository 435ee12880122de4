#include "segment/overlay.h"

#include <algorithm>
#include <cmath>

namespace isegman::segment {

namespace {
void put(Image& img, int x, int y, const float c[3]) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
  for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[k];
}
void disc(Image& img, double cx, double cy, double r, const float c[3]) {
  static const float white[3] = {1, 1, 1};
  for (int y = int(cy - r - 1); y <= int(cy + r + 1); ++y)
    for (int x = int(cx - r - 1); x <= int(cx + r + 1); ++x) {
      const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
      if (d <= r) put(img, x, y, d > r - 1.5 ? white : c);
    }
}

// The pixels of `m` (> 0.5) with a 4-neighbour outside it, drawn in `c`.
void outline(Image& out, const Image& m, const float c[3]) {
  if (m.empty()) return;
  for (int y = 1; y + 1 < m.height; ++y)
    for (int x = 1; x + 1 < m.width; ++x)
      if (m.at(x, y) > 0.5f && (m.at(x - 1, y) <= 0.5f || m.at(x + 1, y) <= 0.5f || m.at(x, y - 1) <= 0.5f || m.at(x, y + 1) <= 0.5f))
        put(out, x, y, c);
}
}  // namespace

Image make_overlay(const Image& rgb, const ViewState& st, const Image& coverage, const Image& truth) {
  Image out = rgb;
  const size_t n = size_t(rgb.width) * rgb.height;
  for (size_t i = 0; i < n; ++i) {
    float* p = &out.data[3 * i];
    const bool in_mask = !st.mask.empty() && st.mask[i];
    const bool in_sel = !coverage.empty() && coverage.data[i] > 0.5f;
    for (int k = 0; k < 3; ++k) p[k] *= 0.75f;  // dim so the tints read well
    if (in_mask) { p[0] = 0.6f * p[0]; p[1] = 0.6f * p[1] + 0.15f; p[2] = 0.6f * p[2] + 0.4f; }
    if (in_sel) { p[0] = 0.5f * p[0] + 0.5f; p[1] = 0.5f * p[1] + 0.25f; p[2] *= 0.5f; }
  }
  // Selection outline in bright orange so it stays visible over the SAM tint; the truth's
  // in cyan over it.
  const float orange[3] = {1.f, 0.55f, 0.f}, cyan[3] = {0.f, 0.95f, 1.f};
  outline(out, coverage, orange);
  outline(out, truth, cyan);
  const double r = std::max(4.0, 0.012 * std::max(rgb.width, rgb.height));
  for (const Click& c : st.clicks) {
    const float col[3] = {c.label ? 0.1f : 0.95f, c.label ? 0.9f : 0.1f, 0.1f};
    disc(out, c.x, c.y, r, col);
  }
  // Border: green accepted, red dropped, grey not segmented.
  const float green[3] = {0.1f, 0.85f, 0.2f}, red[3] = {0.95f, 0.1f, 0.1f}, grey[3] = {0.5f, 0.5f, 0.5f};
  const float* border = st.status == ViewStatus::Accepted ? green
                        : (st.status == ViewStatus::NoClicks ? grey : red);
  const int bw = std::max(2, rgb.width / 100);
  for (int y = 0; y < rgb.height; ++y)
    for (int x = 0; x < rgb.width; ++x)
      if (x < bw || y < bw || x >= rgb.width - bw || y >= rgb.height - bw) put(out, x, y, border);
  return out;
}

}  // namespace isegman::segment
