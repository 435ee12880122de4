// End to end: semantic editing of one object of a small synthetic scene with the built-in
// (deterministic) editor.
#include "edit/semantic_edit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.h"
#include "core/sh.h"
#include "render/rasterizer.h"
#include "io/image_io.h"
#include <cstdlib>

namespace isegman::edit {
namespace {

void add(GaussianScene& s, Vec3 p, Vec3 log_scale, float opacity_logit, Vec3 rgb) {
  const size_t i = s.size();
  s.positions.insert(s.positions.end(), {float(p.x), float(p.y), float(p.z)});
  s.scales.insert(s.scales.end(), {float(log_scale.x), float(log_scale.y), float(log_scale.z)});
  s.rotations.insert(s.rotations.end(), {1.f, 0.f, 0.f, 0.f});
  s.opacity.push_back(opacity_logit);
  s.sh.resize((i + 1) * s.coeffs() * 3, 0.f);
  for (int c = 0; c < 3; ++c) s.sh[i * s.coeffs() * 3 + c] = rgb_to_sh_dc(float(rgb[c]));
}

// A checkered ground (z = 0), a textured ball (the object to edit) and a box behind it.
struct ToyScene {
  GaussianScene scene;
  std::vector<bool> ball;
  std::vector<Camera> cameras;
};

ToyScene make_toy_scene() {
  ToyScene t;
  t.scene.sh_degree = 1;
  std::mt19937 rng(3);
  auto U = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  for (int i = -14; i <= 14; ++i)
    for (int j = -14; j <= 14; ++j) {
      const bool dark = ((i + 100) / 3 + (j + 100) / 3) % 2;
      add(t.scene, {i * 0.1, j * 0.1, 0}, {std::log(0.07), std::log(0.07), std::log(0.01)}, 4.f,
          dark ? Vec3{0.25, 0.3, 0.25} : Vec3{0.75, 0.7, 0.65});
      t.ball.push_back(false);
    }
  for (int k = 0; k < 260; ++k) {  // box behind the ball
    add(t.scene, {U(-0.5, 0.5), 0.9 + U(-0.1, 0.1), U(0.0, 0.6)}, {std::log(0.06), std::log(0.06), std::log(0.06)}, 3.f,
        {0.6, 0.2, 0.2});
    t.ball.push_back(false);
  }
  for (int k = 0; k < 500; ++k) {  // ball: points on a sphere, striped texture
    const double z = U(-1, 1), phi = U(0, 2 * M_PI), r = std::sqrt(1 - z * z);
    const Vec3 n{r * std::cos(phi), r * std::sin(phi), z};
    const double stripe = 0.5 + 0.4 * std::sin(6 * phi);
    add(t.scene, Vec3{0, 0, 0.35} + 0.3 * n, {std::log(0.05), std::log(0.05), std::log(0.05)}, 3.f,
        {0.2 * stripe, 0.35 * stripe + 0.1, 0.9 * stripe});
    t.ball.push_back(true);
  }
  for (int v = 0; v < 6; ++v) {
    const double a = 2 * M_PI * v / 6 + 0.3;
    Camera c = Camera::look_at({2.2 * std::cos(a), 2.2 * std::sin(a), 1.1}, {0, 0, 0.3}, {0, 0, 1}, 64, 48, 45);
    c.name = "cam" + std::to_string(v);
    c.id = v;
    t.cameras.push_back(c);
  }
  return t;
}

TEST(SemanticEdit, BuiltinEditorEndToEndMatchesTargetsAndFreezesTheRest) {
  ToyScene toy = make_toy_scene();
  const Selection sel = Selection::from_mask(toy.scene, toy.ball);
  auto editor = make_builtin_editor("builtin:recolor");
  SemanticEditOptions o;
  o.instruction = "turn the ball into gold";
  o.steps = std::getenv("SEM_STEPS") ? std::atoi(std::getenv("SEM_STEPS")) : 800;
  o.refresh_every = std::getenv("SEM_REFRESH") ? std::atoi(std::getenv("SEM_REFRESH")) : 10;
  o.threads = 2;
  for (int c = 0; c < 3; ++c) o.background[c] = 0.1f;
  const SemanticEditResult r = semantic_edit(toy.scene, toy.cameras, sel, *editor, o);
  EXPECT_EQ(r.steps_done, o.steps);
  EXPECT_EQ(r.views.size(), toy.cameras.size());
  // Initial edits, then one view re-edited every refresh_every steps (not after the last).
  EXPECT_EQ(r.editor_calls, int(toy.cameras.size()) + (o.steps - 1) / o.refresh_every);

  // Every unselected Gaussian is bit-identical; selected ones changed.
  size_t changed = 0;
  for (size_t i = 0; i < toy.scene.size(); ++i) {
    const bool same = std::equal(toy.scene.sh_of(i), toy.scene.sh_of(i) + toy.scene.coeffs() * 3, r.scene.sh_of(i)) &&
                      toy.scene.opacity[i] == r.scene.opacity[i] &&
                      std::equal(&toy.scene.positions[3 * i], &toy.scene.positions[3 * i + 3], &r.scene.positions[3 * i]) &&
                      std::equal(&toy.scene.scales[3 * i], &toy.scene.scales[3 * i + 3], &r.scene.scales[3 * i]) &&
                      std::equal(&toy.scene.rotations[4 * i], &toy.scene.rotations[4 * i + 4], &r.scene.rotations[4 * i]);
    if (!toy.ball[i]) ASSERT_TRUE(same) << "unselected Gaussian " << i << " changed";
    else changed += !same;
  }
  EXPECT_GT(changed, 400u);

  RenderSettings rs;
  for (int c = 0; c < 3; ++c) rs.background[c] = 0.1f;
  double worst = 1e9;
  for (const SemanticView& v : r.views) {
    const Image now = render(r.scene, v.camera, rs).color;
    // Inside the object's mask the render matches the edited target.
    const double p = masked_psnr(now, v.target, v.mask);
    if (std::getenv("SEM_DUMP")) {
      write_png("/tmp/sem_" + v.camera.name + "_orig.png", v.original);
      write_png("/tmp/sem_" + v.camera.name + "_target.png", v.target);
      write_png("/tmp/sem_" + v.camera.name + "_now.png", now);
    }
    worst = std::min(worst, p);
    if (std::getenv("SEM_DUMP")) std::printf("%s %.2f dB\n", v.camera.name.c_str(), p);
    // And it is gold now, not the original blue: before the edit it was far from the target.
    EXPECT_LT(masked_psnr(v.original, v.target, v.mask), 15.0) << v.camera.name;
    // Outside the object (coverage below 1e-3 before and after) the render is unchanged.
    const Image cov = render_selection(r.scene, v.camera, toy.ball, rs);
    size_t outside = 0;
    double max_diff = 0;
    for (int y = 0; y < now.height; ++y)
      for (int x = 0; x < now.width; ++x) {
        if (v.mask.at(x, y) >= 1e-3f || cov.at(x, y) >= 1e-3f) continue;
        ++outside;
        for (int c = 0; c < 3; ++c) max_diff = std::max(max_diff, double(std::abs(now.at(x, y, c) - v.original.at(x, y, c))));
      }
    EXPECT_GT(outside, size_t(now.width * now.height / 4));
    EXPECT_LT(max_diff, 3e-3) << v.camera.name;
  }
  EXPECT_GE(worst, 30.0);
  EXPECT_GE(r.mean_mask_psnr, 30.0);
}

TEST(SemanticEdit, InterruptionKeepsTheStateAndEditorErrorsPropagate) {
  ToyScene toy = make_toy_scene();
  const Selection sel = Selection::from_mask(toy.scene, toy.ball);
  auto editor = make_builtin_editor("builtin:recolor");
  std::atomic<bool> stop{false};
  SemanticEditOptions o;
  o.instruction = "make it red";
  o.steps = 1000;
  o.stop = &stop;
  o.progress_every = 20;
  o.progress = [&](const SemanticProgress&) { stop = true; };
  const SemanticEditResult r = semantic_edit(toy.scene, toy.cameras, sel, *editor, o);
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.steps_done, 20);

  auto failing = make_command_editor("exit 9; {in} {out}", 5);
  o.stop = nullptr;
  EXPECT_THROW(semantic_edit(toy.scene, toy.cameras, sel, *failing, o), Error);
  EXPECT_THROW(semantic_edit(toy.scene, toy.cameras, Selection::none_of(toy.scene), *editor, o), Error);
  GaussianScene other = toy.scene;
  other.opacity[0] += 1.f;
  EXPECT_THROW(semantic_edit(other, toy.cameras, sel, *editor, o), Error);  // selection of another scene
}

}  // namespace
}  // namespace isegman::edit
