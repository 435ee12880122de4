#include "server/view_reuse.h"

#include <gtest/gtest.h>

#include "app/demo_scene.h"

namespace isegman::server {
namespace {

DemoScene demo() {
  DemoSceneOptions o;
  o.cameras = 8;
  o.width = 160;
  o.height = 120;
  o.density = 0.3f;
  o.sh_degree = 1;
  return make_demo_scene(o);
}

bool same_image(const Image& a, const Image& b) { return a.width == b.width && a.height == b.height && a.data == b.data; }

TEST(ViewReuse, DiffFindsRemovedChangedAndAddedGaussians) {
  const DemoScene d = demo();
  const GaussianScene& g = d.bundle.gaussians;
  EXPECT_TRUE(diff_scenes(g, g).empty());
  // A reordering is no change.
  std::vector<bool> keep(g.size(), true);
  keep[3] = keep[10] = false;
  GaussianScene removed = g.subset(keep);
  SceneDiff r = diff_scenes(g, removed);
  EXPECT_EQ(r.removed, (std::vector<uint32_t>{3, 10}));
  EXPECT_TRUE(r.added.empty());
  GaussianScene recoloured = g;
  recoloured.sh_of(7)[0] += 0.5f;
  recoloured.append_from(g, 0);  // a duplicate of Gaussian 0: one more of the same
  SceneDiff c = diff_scenes(g, recoloured);
  EXPECT_EQ(c.removed, (std::vector<uint32_t>{7}));
  ASSERT_EQ(c.added.size(), 2u);
  EXPECT_EQ(c.added[0], 7u);
  GaussianScene other_degree = g;
  other_degree.resize(g.size(), 0);
  EXPECT_TRUE(diff_scenes(g, other_degree).everything);
}

// The promise the reuse rests on: a view the diff does not reach renders bit-identically
// after the edit; one it reaches differs.
TEST(ViewReuse, UnreachedViewsRenderTheSame) {
  const DemoScene d = demo();
  const GaussianScene& g = d.bundle.gaussians;
  // Remove the first object.
  std::vector<bool> keep(g.size());
  for (size_t i = 0; i < g.size(); ++i) keep[i] = d.labels[i] != 0;
  const GaussianScene after = g.subset(keep);
  const SceneDiff diff = diff_scenes(g, after);
  ASSERT_FALSE(diff.empty());
  // The training cameras plus close-ups of each object (the other objects' close-ups
  // do not see the removed one).
  std::vector<Camera> cams = d.bundle.cameras;
  for (const DemoObject& o : d.objects) {
    const Vec3 eye = o.center + Vec3{0, 0, 0.2 + 2.5 * o.radius};
    cams.push_back(Camera::look_at(eye, o.center, {0, 1, 0}, 160, 120, 30));
  }
  RenderSettings rs;
  rs.threads = 2;
  int reached = 0, unreached = 0;
  for (const Camera& cam : cams) {
    const bool changed = diff_reaches_view(g, after, diff, cam, rs);
    const RenderOutput a = render(g, cam, rs), b = render(after, cam, rs);
    const bool identical = same_image(a.color, b.color) && same_image(a.depth, b.depth) && same_image(a.alpha, b.alpha);
    if (!changed) {
      EXPECT_TRUE(identical) << cam.name;
    }
    (changed ? reached : unreached)++;
  }
  EXPECT_GT(reached, 0);
  EXPECT_GT(unreached, 0) << "every view was reached: the test shows nothing";
}

}  // namespace
}  // namespace isegman::server
