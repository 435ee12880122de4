#include "core/camera.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace isegman {
namespace {

TEST(Camera, ProjectsKnownPoints) {
  Camera c;
  c.width = 640;
  c.height = 480;
  c.fx = 500;
  c.fy = 400;
  c.cx = 320;
  c.cy = 240;
  double u, v, d;
  ASSERT_TRUE(c.project({0, 0, 2}, u, v, &d));
  EXPECT_DOUBLE_EQ(u, 320);
  EXPECT_DOUBLE_EQ(v, 240);
  EXPECT_DOUBLE_EQ(d, 2);
  ASSERT_TRUE(c.project({1, -0.5, 2}, u, v));
  EXPECT_DOUBLE_EQ(u, 320 + 500 * 0.5);
  EXPECT_DOUBLE_EQ(v, 240 - 400 * 0.25);
  EXPECT_FALSE(c.project({0, 0, -1}, u, v));
}

TEST(Camera, CentreRotationRoundTrip) {
  Mat3 c2w = Quat::from_axis_angle({0.3, -1, 0.5}, 0.7).to_matrix();
  Vec3 centre{1.5, -2, 0.25};
  Camera c = Camera::from_center_rotation(centre, c2w);
  Vec3 back = c.center();
  EXPECT_NEAR(back.x, centre.x, 1e-12);
  EXPECT_NEAR(back.y, centre.y, 1e-12);
  EXPECT_NEAR(back.z, centre.z, 1e-12);
  // The camera's own z axis (third column of c2w) maps to +z in camera space.
  Vec3 ahead = centre + c2w.col(2) * 3.0;
  Vec3 pc = c.world_to_camera(ahead);
  EXPECT_NEAR(pc.x, 0, 1e-12);
  EXPECT_NEAR(pc.y, 0, 1e-12);
  EXPECT_NEAR(pc.z, 3, 1e-12);
}

TEST(Camera, LookAtKeepsUpUpAndRightRight) {
  Camera c = Camera::look_at({0, -5, 0}, {0, 0, 0}, {0, 0, 1}, 200, 100, 60);
  double u, v;
  ASSERT_TRUE(c.project({0, 0, 1}, u, v));  // above the target: upper half of the image
  EXPECT_NEAR(u, 100, 1e-9);
  EXPECT_LT(v, 50);
  ASSERT_TRUE(c.project({1, 0, 0}, u, v));  // +x is to the right when looking along +y
  EXPECT_GT(u, 100);
  EXPECT_NO_THROW(c.validate("test"));
}

TEST(Camera, RayThroughPixelHitsProjectedPoint) {
  Camera c = Camera::look_at({3, 1, 2}, {0, 0, 0}, {0, 0, 1}, 300, 200, 50);
  Vec3 p{0.2, -0.3, 0.1};
  double u, v, depth;
  ASSERT_TRUE(c.project(p, u, v, &depth));
  Vec3 dir = c.ray_direction(u, v);
  Vec3 to_p = normalized(p - c.center());
  EXPECT_NEAR(dot(dir, to_p), 1.0, 1e-12);
}

TEST(Camera, ResizedScalesIntrinsics) {
  Camera c;
  c.width = 400;
  c.height = 300;
  c.fx = c.fy = 350;
  c.cx = 200;
  c.cy = 150;
  Camera r = c.resized(200, 150);
  EXPECT_DOUBLE_EQ(r.fx, 175);
  EXPECT_DOUBLE_EQ(r.cx, 100);
  EXPECT_DOUBLE_EQ(r.cy, 75);
}

TEST(Camera, ValidateNamesTheProblem) {
  Camera c = Camera::look_at({0, -5, 0}, {0, 0, 0}, {0, 0, 1}, 200, 100, 60);
  c.name = "cam7";
  Camera z = c;
  z.width = 0;
  try {
    z.validate("cams.json");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cams.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("cam7"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("zero"), std::string::npos);
  }
  Camera n = c;
  n.fx = std::nan("");
  EXPECT_THROW(n.validate("x"), Error);
  Camera s = c;
  s.R.m[0][0] = 2;
  EXPECT_THROW(s.validate("x"), Error);
}

TEST(Camera, FindByNameOrId) {
  std::vector<Camera> cams(3);
  for (int i = 0; i < 3; ++i) {
    cams[i].id = 10 + i;
    cams[i].name = "img" + std::to_string(i);
  }
  EXPECT_EQ(find_camera(cams, "img2"), &cams[2]);
  EXPECT_EQ(find_camera(cams, "11"), &cams[1]);
  EXPECT_EQ(find_camera(cams, "5"), nullptr);
  EXPECT_EQ(find_camera(cams, "nope"), nullptr);
}

TEST(Quat, MatrixRoundTrip) {
  for (double a : {0.1, 1.0, 2.5, 3.1}) {
    Quat q = Quat::from_axis_angle({1, 2, -0.5}, a);
    Quat r = Quat::from_matrix(q.to_matrix());
    double d = std::fabs(q.w * r.w + q.x * r.x + q.y * r.y + q.z * r.z);
    EXPECT_NEAR(d, 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace isegman
