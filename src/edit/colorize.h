// Colorize a selection S (the paper's two modes). A Gaussian's base colour is carried by
// its SH DC term: colour = 0.5 + C0 * f_dc (per channel, before the renderer's clamp).
//   replace:  every Gaussian of S shows the target colour from every direction:
//             f_dc = (target - 0.5) / C0 and every higher coefficient is zeroed.
//   balanced: shift each base colour by target - mean(colour over S), keeping texture
//             and view dependence: f_dc += (target - mean) / C0 (unweighted mean).
#pragma once

#include <string>

#include "core/scene.h"
#include "core/selection.h"
#include "edit/delta.h"

namespace isegman::edit {

enum class ColorizeMode { kReplace, kBalanced };

struct Rgb {
  double r = 0, g = 0, b = 0;
};

// Parses "#RRGGBB", "RRGGBB", "#RGB" (sRGB, 8 bits per channel) or "r,g,b" floats in
// [0, 1]. Throws Error("colour", ...) naming the text.
Rgb parse_color(const std::string& text);
// "replace" / "balanced"; throws otherwise.
ColorizeMode parse_colorize_mode(const std::string& text);

// Mean base colour (0.5 + C0 * f_dc) over S.
Rgb mean_base_color(const GaussianScene& scene, const std::vector<bool>& mask);

Delta plan_colorize(const GaussianScene& scene, const Selection& selection, const Rgb& target, ColorizeMode mode);

}  // namespace isegman::edit
