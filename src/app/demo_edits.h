// The manipulation part of `isegman demo`: box-selects an object of the synthetic demo
// scene, then removes, recolours, scales and copies it (each undone before the next),
// writing before/after renders, so every operation can be seen without any data.
#pragma once

#include <string>

#include "app/demo_scene.h"

namespace isegman {

// Writes into `out_dir` (created when missing): edit_before_<cam>.png,
// edit_removed_<cam>.png, edit_recoloured_<cam>.png, edit_scaled_<cam>.png,
// edit_copied_<cam>.png for two cameras, edit_overview.png (all five side by side),
// edit_selection.isel (the box selection) and edit_copied.ply (the scene with the
// rotated copy). Prints what each step changed. Throws Error on failure.
void run_edit_demo(const DemoScene& demo, const std::string& out_dir);

}  // namespace isegman
