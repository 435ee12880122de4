#include "edit/colorize.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "core/error.h"
#include "core/sh.h"
#include "edit/checks.h"

namespace isegman::edit {
namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  c = char(std::tolower(static_cast<unsigned char>(c)));
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

}  // namespace

Rgb parse_color(const std::string& text) {
  const std::string bad = "'" + text + "' is not a colour: use #RRGGBB (sRGB hex) or r,g,b floats in [0, 1]";
  if (text.find(',') != std::string::npos) {
    double v[3];
    std::stringstream ss(text);
    std::string item;
    int n = 0;
    while (std::getline(ss, item, ',')) {
      char* end = nullptr;
      double x = std::strtod(item.c_str(), &end);
      if (n >= 3 || item.empty() || *end != '\0') throw Error("colour", bad);
      if (!std::isfinite(x) || x < 0 || x > 1)
        throw Error("colour", "'" + text + "': each component must be a finite number in [0, 1]");
      v[n++] = x;
    }
    if (n != 3) throw Error("colour", bad);
    return {v[0], v[1], v[2]};
  }
  std::string h = text;
  if (!h.empty() && h[0] == '#') h = h.substr(1);
  if (h.size() == 3) h = std::string{h[0], h[0], h[1], h[1], h[2], h[2]};
  if (h.size() != 6) throw Error("colour", bad);
  double v[3];
  for (int c = 0; c < 3; ++c) {
    int hi = hex_digit(h[2 * c]), lo = hex_digit(h[2 * c + 1]);
    if (hi < 0 || lo < 0) throw Error("colour", bad);
    v[c] = (hi * 16 + lo) / 255.0;
  }
  return {v[0], v[1], v[2]};
}

ColorizeMode parse_colorize_mode(const std::string& text) {
  if (text == "replace") return ColorizeMode::kReplace;
  if (text == "balanced") return ColorizeMode::kBalanced;
  throw Error("colorize", "--mode must be 'replace' or 'balanced', got '" + text + "'");
}

Rgb mean_base_color(const GaussianScene& scene, const std::vector<bool>& mask) {
  double sum[3] = {0, 0, 0};
  size_t n = 0;
  for (size_t i = 0; i < scene.size(); ++i) {
    if (!mask[i]) continue;
    const float* c = scene.sh_of(i);
    for (int ch = 0; ch < 3; ++ch) sum[ch] += 0.5 + double(kShC0) * double(c[ch]);
    ++n;
  }
  if (n == 0) return {};
  return {sum[0] / double(n), sum[1] / double(n), sum[2] / double(n)};
}

Delta plan_colorize(const GaussianScene& scene, const Selection& sel, const Rgb& target, ColorizeMode mode) {
  const std::string op = "colorize";
  check_selection(scene, sel, op);
  const double t[3] = {target.r, target.g, target.b};
  for (double v : t) {
    check_finite(v, "target colour", op);
    if (v < 0 || v > 1) throw Error(op, "target colour components must lie in [0, 1]");
  }
  Delta d;
  d.modified = mask_indices(sel.mask);
  d.before = gather(scene, d.modified);
  d.after = d.before;
  const int k = scene.coeffs();
  char buf[160];
  if (mode == ColorizeMode::kReplace) {
    float dc[3];
    for (int ch = 0; ch < 3; ++ch) dc[ch] = float((t[ch] - 0.5) / double(kShC0));
    for (size_t i = 0; i < d.after.size(); ++i) {
      float* c = d.after.sh_of(i);
      for (int ch = 0; ch < 3; ++ch) c[ch] = dc[ch];
      for (int j = 3; j < 3 * k; ++j) c[j] = 0.f;
    }
    std::snprintf(buf, sizeof buf, "colorize %zu Gaussians: replace with (%.3f, %.3f, %.3f)", d.modified.size(), t[0],
                  t[1], t[2]);
  } else {
    const Rgb m = mean_base_color(scene, sel.mask);
    const double mean[3] = {m.r, m.g, m.b};
    float shift[3];
    for (int ch = 0; ch < 3; ++ch) shift[ch] = float((t[ch] - mean[ch]) / double(kShC0));
    for (size_t i = 0; i < d.after.size(); ++i) {
      float* c = d.after.sh_of(i);
      for (int ch = 0; ch < 3; ++ch) c[ch] += shift[ch];
    }
    std::snprintf(buf, sizeof buf,
                  "colorize %zu Gaussians: balanced, mean colour (%.3f, %.3f, %.3f) -> (%.3f, %.3f, %.3f)",
                  d.modified.size(), mean[0], mean[1], mean[2], t[0], t[1], t[2]);
  }
  d.label = buf;
  check_result(d.after, op);
  return d;
}

}  // namespace isegman::edit
