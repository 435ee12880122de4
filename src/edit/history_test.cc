#include "edit/history.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "edit/colorize.h"
#include "edit/remove.h"
#include "edit/selection_tools.h"
#include "edit/test_scenes.h"
#include "edit/transform.h"

namespace isegman::edit {
namespace {

using testing::random_scene;
using testing::same_scene;

Selection random_selection(const GaussianScene& s, testing::TestRng& rng, double p) {
  std::vector<bool> m(s.size());
  bool any = false;
  for (size_t i = 0; i < m.size(); ++i) any |= (m[i] = rng.uniform() < p);
  if (!any) m[rng.next() % m.size()] = true;
  return Selection::from_mask(s, m);
}

// Runs one random operation on the session's current state.
void random_step(EditSession& e, testing::TestRng& rng) {
  const int kind = int(rng.next() % 8);
  if (kind == 0 || e.selection().empty()) {
    e.select(random_selection(e.scene(), rng, rng.range(0.05, 0.4)), "select");
    return;
  }
  const Selection sel = e.selection();
  Similarity t;
  t.translation = {rng.range(-1, 1), rng.range(-1, 1), rng.range(-1, 1)};
  t.rotation = rotation_from_euler_deg(rng.range(-180, 180), rng.range(-90, 90), rng.range(-180, 180));
  t.scale = rng.range(0.5, 2);
  switch (kind) {
    case 1:
      if (sel.count() < e.scene().size()) e.apply(plan_remove(e.scene(), sel));
      break;
    case 2: e.apply(plan_colorize(e.scene(), sel, {rng.uniform(), rng.uniform(), rng.uniform()}, ColorizeMode::kReplace)); break;
    case 3: e.apply(plan_colorize(e.scene(), sel, {rng.uniform(), rng.uniform(), rng.uniform()}, ColorizeMode::kBalanced)); break;
    case 4: e.apply(plan_scale(e.scene(), sel, rng.range(0.3, 3))); break;
    case 5: e.apply(plan_copy(e.scene(), sel, t)); break;
    case 6: e.apply(plan_transform(e.scene(), sel, t)); break;
    case 7: e.select(invert(sel), "invert"); break;
  }
}

TEST(History, UndoOfAnySequenceRestoresTheSceneBitExactly) {
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    const GaussianScene original = random_scene(300, int(seed % 4), seed);
    EditSession e(original);
    testing::TestRng rng(seed * 77);
    std::vector<GaussianScene> states{original};
    std::vector<std::vector<bool>> masks{e.mask()};
    const int steps = 25;
    for (int i = 0; i < steps; ++i) {
      random_step(e, rng);
      ASSERT_EQ(e.fingerprint(), e.scene().fingerprint()) << "seed " << seed << " step " << i;
      if (e.history().undo_steps() != states.size()) continue;  // a step that did nothing
      states.push_back(e.scene());
      masks.push_back(e.mask());
    }
    ASSERT_GT(states.size(), 10u);
    // Undo everything, checking every intermediate state.
    for (size_t i = states.size() - 1; i > 0; --i) {
      e.undo();
      ASSERT_TRUE(same_scene(e.scene(), states[i - 1])) << "seed " << seed << " step " << i;
      ASSERT_EQ(e.mask(), masks[i - 1]);
      ASSERT_EQ(e.fingerprint(), e.scene().fingerprint()) << "undo seed " << seed << " step " << i;
    }
    EXPECT_EQ(e.scene().fingerprint(), original.fingerprint());
    EXPECT_THROW(e.undo(), Error);
    // Redo everything.
    for (size_t i = 1; i < states.size(); ++i) {
      e.redo();
      ASSERT_TRUE(same_scene(e.scene(), states[i])) << "redo seed " << seed << " step " << i;
      ASSERT_EQ(e.mask(), masks[i]);
      ASSERT_EQ(e.fingerprint(), e.scene().fingerprint()) << "redo seed " << seed << " step " << i;
    }
    EXPECT_THROW(e.redo(), Error);
  }
}

TEST(History, NewStepClearsRedo) {
  EditSession e(random_scene(50, 1, 3));
  e.select(select_box(e.scene(), {-1, -1, -1}, {0, 0, 0}));
  e.apply(plan_scale(e.scene(), e.selection(), 2));
  e.undo();
  EXPECT_EQ(e.history().redo_steps(), 1u);
  e.apply(plan_colorize(e.scene(), e.selection(), {1, 0, 0}, ColorizeMode::kReplace));
  EXPECT_EQ(e.history().redo_steps(), 0u);
  EXPECT_THROW(e.redo(), Error);
}

TEST(History, MemoryIsProportionalToWhatChanged) {
  const GaussianScene s = random_scene(20000, 3, 5);
  const size_t scene_bytes = 4 * (s.positions.size() + s.normals.size() + s.sh.size() + s.opacity.size() +
                                  s.scales.size() + s.rotations.size());
  EditSession e(s);
  std::vector<bool> m(s.size(), false);
  for (int i = 0; i < 10; ++i) m[size_t(i) * 997] = true;
  e.select(Selection::from_mask(s, m));
  const size_t after_select = e.history().bytes();
  EXPECT_LT(after_select, 2000u);  // 10 flipped indices, not a mask of 20000
  e.apply(plan_colorize(e.scene(), e.selection(), {0, 0, 1}, ColorizeMode::kReplace));
  const size_t colorize = e.history().bytes() - after_select;
  // 10 Gaussians of 65 floats before and after, plus overhead: far below a scene copy.
  EXPECT_LT(colorize, 10000u);
  EXPECT_LT(colorize * 100, scene_bytes);
  e.apply(plan_remove(e.scene(), e.selection()));
  EXPECT_LT(e.history().bytes() - after_select - colorize, 10000u);
}

TEST(History, CapDropsOldestStepsWithANotice) {
  const GaussianScene s = random_scene(2000, 3, 9);
  HistoryLimits lim;
  lim.max_steps = 3;
  EditSession e(s, lim);
  e.select(select_sphere(s, {0, 0, 0}, 0.5));
  EXPECT_EQ(e.notice(), "");
  for (int i = 0; i < 2; ++i) e.apply(plan_scale(e.scene(), e.selection(), 1.1));
  EXPECT_EQ(e.notice(), "");
  e.apply(plan_scale(e.scene(), e.selection(), 1.1));
  EXPECT_NE(e.notice().find("dropped the 1 oldest step"), std::string::npos) << e.notice();
  EXPECT_EQ(e.history().undo_steps(), 3u);

  // A byte cap smaller than one step: applied, not undoable, with a clear notice.
  HistoryLimits tiny;
  tiny.max_bytes = 4096;
  EditSession t(s, tiny);
  t.select(select_sphere(s, {0, 0, 0}, 0.5));
  EXPECT_EQ(t.history().undo_steps(), 1u);
  const GaussianScene before = t.scene();
  t.apply(plan_colorize(t.scene(), t.selection(), {1, 1, 0}, ColorizeMode::kReplace));
  EXPECT_NE(t.notice().find("cannot be undone"), std::string::npos) << t.notice();
  EXPECT_FALSE(t.history().can_undo());
  EXPECT_FALSE(same_scene(t.scene(), before));
  try {
    t.undo();
    FAIL();
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("nothing to undo"), std::string::npos);
  }
}

TEST(History, SelectRejectsAnotherScenesSelection) {
  EditSession e(random_scene(40, 0, 1));
  const GaussianScene other = random_scene(40, 0, 2);
  EXPECT_THROW(e.select(Selection::all_of(other)), Error);
}

// The session keeps its scene's fingerprint instead of hashing the scene per selection: a
// selection made before an edit must still be refused after it, and again after an undo
// and a redo of that edit.
TEST(History, SelectRejectsASelectionOfTheSceneBeforeAnEdit) {
  EditSession e(random_scene(60, 1, 5));
  e.select(select_box(e.scene(), {-1, -1, -1}, {0, 0, 0}));
  const Selection before = e.selection();
  e.apply(plan_scale(e.scene(), e.selection(), 2));
  EXPECT_NE(e.selection().scene_fingerprint, before.scene_fingerprint);
  EXPECT_THROW(e.select(before), Error);
  e.undo();
  EXPECT_EQ(e.selection().scene_fingerprint, before.scene_fingerprint);
  e.redo();
  EXPECT_THROW(e.select(before), Error);
  e.undo();
  EXPECT_NO_THROW(e.select(before));
}

TEST(Delta, RevertRejectsAMismatchedScene) {
  GaussianScene s = random_scene(10, 1, 1);
  std::vector<bool> mask(10, false);
  Delta d;
  d.modified = {3, 12};
  d.before = gather(s, {3, 3});
  d.after = d.before;
  EXPECT_THROW(apply_delta(d, s, mask), Error);
}

}  // namespace
}  // namespace isegman::edit
