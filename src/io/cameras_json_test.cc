#include "io/cameras_json.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

TEST(CamerasJson, ReadsTheInriaLayout) {
  const std::string text = R"([{"id": 3, "img_name": "frame_03", "width": 400, "height": 300,
     "position": [1, 2, 3], "rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "fx": 350.5, "fy": 351}])";
  auto cams = parse_cameras_json(text, "c.json");
  ASSERT_EQ(cams.size(), 1u);
  const Camera& c = cams[0];
  EXPECT_EQ(c.id, 3);
  EXPECT_EQ(c.name, "frame_03");
  EXPECT_DOUBLE_EQ(c.cx, 200);
  EXPECT_DOUBLE_EQ(c.cy, 150);
  Vec3 centre = c.center();
  EXPECT_NEAR(centre.x, 1, 1e-12);
  EXPECT_NEAR(centre.z, 3, 1e-12);
  // rotation is camera-to-world: world point centre - z_world lies straight ahead.
  double u, v, d;
  ASSERT_TRUE(c.project({1, 2, 1}, u, v, &d));
  EXPECT_NEAR(u, 200, 1e-9);
  EXPECT_NEAR(v, 150, 1e-9);
  EXPECT_NEAR(d, 2, 1e-12);
}

TEST(CamerasJson, RoundTrip) {
  std::vector<Camera> cams;
  for (int i = 0; i < 4; ++i) {
    Camera c = Camera::look_at({4.0 * std::cos(i), 4.0 * std::sin(i), 1.5}, {0, 0, 0}, {0, 0, 1}, 320, 240, 50);
    c.id = i;
    c.name = "v" + std::to_string(i);
    if (i == 2) c.cx = 150;  // off-centre principal points are kept
    cams.push_back(c);
  }
  auto back = parse_cameras_json(cameras_to_json(cams), "mem");
  ASSERT_EQ(back.size(), cams.size());
  for (size_t i = 0; i < cams.size(); ++i) {
    EXPECT_EQ(back[i].name, cams[i].name);
    EXPECT_DOUBLE_EQ(back[i].cx, cams[i].cx);
    for (int r = 0; r < 3; ++r) {
      EXPECT_NEAR(back[i].t[r], cams[i].t[r], 1e-12);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[i].R.m[r][k], cams[i].R.m[r][k], 1e-12);
    }
  }
}

TEST(CamerasJson, ErrorsNameFileAndCamera) {
  auto err = [](const std::string& t) {
    try {
      parse_cameras_json(t, "cams.json");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(err("{").find("cams.json: invalid JSON"), std::string::npos);
  EXPECT_NE(err("[]").find("no cameras"), std::string::npos);
  EXPECT_NE(err(R"([{"img_name": "a", "width": 0, "height": 3, "fx": 1, "fy": 1, "position": [0,0,0],
                   "rotation": [[1,0,0],[0,1,0],[0,0,1]]}])")
                .find("camera 'a' has a zero"),
            std::string::npos);
  EXPECT_NE(err(R"([{"img_name": "a", "width": 4, "height": 3, "fx": 1, "position": [0,0,0],
                   "rotation": [[1,0,0],[0,1,0],[0,0,1]]}])")
                .find("no 'fy'"),
            std::string::npos);
}

TEST(CamerasJson, ReadsFixtureCameras) {
  const fs::path p = fs::path(ISEGMAN_FIXTURES_DIR) / "dtu24/scene/cameras.json";
  if (!fs::exists(p)) GTEST_SKIP() << "fixtures not found (" << p << "); skipping";
  auto cams = read_cameras_json(p.string());
  EXPECT_EQ(cams.size(), 49u);
  EXPECT_EQ(cams[0].width, 400);
}

}  // namespace
}  // namespace isegman
