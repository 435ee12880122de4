#include "server/pick.h"

#include <gtest/gtest.h>

#include <cmath>

namespace isegman::server {
namespace {

// One opaque Gaussian 5 units in front of a camera at the origin looking along +z.
GaussianScene one_blob() {
  GaussianScene g;
  g.resize(1, 0);
  g.positions = {0.5f, 0.f, 5.f};
  g.scales = {std::log(0.3f), std::log(0.3f), std::log(0.3f)};
  g.opacity = {6.f};
  return g;
}

Camera camera() { return Camera::look_at({0, 0, 0}, {0, 0, 1}, {0, -1, 0}, 128, 96, 60); }

TEST(Pick, FindsTheSurfaceUnderThePixel) {
  const Camera cam = camera();
  double u = 0, v = 0;
  ASSERT_TRUE(cam.project({0.5, 0, 5}, u, v));
  RenderSettings rs;
  rs.threads = 1;
  const PickResult p = pick_surface(one_blob(), cam, u, v, rs);
  ASSERT_TRUE(p.hit);
  EXPECT_NEAR(p.depth, 5.0, 1e-3);
  EXPECT_NEAR(p.point.x, 0.5, 0.05);
  EXPECT_NEAR(p.point.y, 0.0, 0.05);
  EXPECT_NEAR(p.point.z, 5.0, 1e-3);
}

TEST(Pick, MissesEmptySkyAndOutsideTheImage) {
  const Camera cam = camera();
  RenderSettings rs;
  rs.threads = 1;
  EXPECT_FALSE(pick_surface(one_blob(), cam, 2, 2, rs).hit);
  EXPECT_FALSE(pick_surface(one_blob(), cam, -1, 10, rs).hit);
  EXPECT_FALSE(pick_surface(one_blob(), cam, 10, 96, rs).hit);
}

TEST(Pick, RendersSmallAndMapsPixelsBack) {
  // A 1280-wide camera rendered at 160 px must still return the blob's point.
  const Camera big = Camera::look_at({0, 0, 0}, {0, 0, 1}, {0, -1, 0}, 1280, 960, 60);
  double u = 0, v = 0;
  ASSERT_TRUE(big.project({0.5, 0, 5}, u, v));
  RenderSettings rs;
  rs.threads = 1;
  const PickResult p = pick_surface(one_blob(), big, u, v, rs, 160);
  ASSERT_TRUE(p.hit);
  EXPECT_NEAR(p.point.x, 0.5, 0.05);
  EXPECT_NEAR(p.point.z, 5.0, 1e-3);
}

}  // namespace
}  // namespace isegman::server
