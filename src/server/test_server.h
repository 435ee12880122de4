// Helpers of the server's API tests (test use only): a real server on an ephemeral
// loopback port driven over HTTP, and a small demo scene.
#pragma once

#include <httplib.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "app/demo_scene.h"
#include "core/test_dirs.h"
#include "render/rasterizer.h"
#include "server/app_state.h"
#include "server/http_server.h"

namespace isegman::server {

using nlohmann::json;

inline std::string temp_dir(const std::string& name) { return testing::fresh_temp_dir("isegman-server-test-", name); }

inline DemoScene small_demo() {
  DemoSceneOptions o;
  o.cameras = 8;
  o.width = 200;
  o.height = 150;
  o.density = 0.3f;
  o.sh_degree = 1;
  return make_demo_scene(o);
}

struct Running {
  std::unique_ptr<AppState> app;
  std::unique_ptr<HttpServer> http;
  std::unique_ptr<httplib::Client> client;
  int port = 0;

  Running(const SceneBundle& bundle, AppOptions options, const HttpLimits& limits = {}) {
    app = std::make_unique<AppState>(bundle, options);
    http = std::make_unique<HttpServer>(*app, limits);
    port = http->start("127.0.0.1", 0);
    client = std::make_unique<httplib::Client>("127.0.0.1", port);
    client->set_connection_timeout(5);
    client->set_read_timeout(60);
    app->start();
  }
  ~Running() {
    http->stop();
    app->stop();
  }
  json get_json(const std::string& path, int expect = 200) {
    auto r = client->Get(path.c_str());
    EXPECT_TRUE(r) << path;
    if (!r) return {};
    EXPECT_EQ(r->status, expect) << path << ": " << r->body;
    return json::parse(r->body);
  }
  json post_json(const std::string& path, const std::string& body, int expect = 200) {
    auto r = client->Post(path.c_str(), body, "application/json");
    EXPECT_TRUE(r) << path;
    if (!r) return {};
    EXPECT_EQ(r->status, expect) << path << " " << body << ": " << r->body;
    json j = json::parse(r->body, nullptr, false);
    EXPECT_FALSE(j.is_discarded()) << r->body;
    if (expect >= 400) {
      EXPECT_TRUE(j.contains("error") && !j["error"].get<std::string>().empty()) << r->body;
    }
    return j;
  }
};

// The scene of the server's SAM click tests (one scene, so their cached embeddings are shared):
// the demo scene at 320x240, and the object with the largest fully covered area in camera 0
// with the centroid pixel of that area (on the object: callers check `on_object`).
struct SamClickScene {
  DemoScene demo;
  int object = -1;
  int px = 0, py = 0;
  bool on_object = false;
};
inline SamClickScene sam_click_scene() {
  DemoSceneOptions o;
  o.cameras = 8;
  o.width = 320;
  o.height = 240;
  o.density = 0.5f;
  SamClickScene c{make_demo_scene(o)};
  const DemoScene& d = c.demo;
  const Camera& cam = d.bundle.cameras[0];
  size_t best_px = 0;
  Image best_cov;
  for (size_t k = 0; k < d.objects.size(); ++k) {
    std::vector<bool> m(d.labels.size());
    for (size_t i = 0; i < m.size(); ++i) m[i] = d.labels[i] == int(k);
    Image cov = render_selection(d.bundle.gaussians, cam, m);
    size_t px = 0;
    for (float v : cov.data) px += v > 0.95f;
    if (px > best_px) best_px = px, c.object = int(k), best_cov = cov;
  }
  if (c.object < 0) return c;
  double sx = 0, sy = 0, cnt = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      if (best_cov.at(x, y) > 0.95f) sx += x, sy += y, cnt += 1;
  c.px = int(sx / cnt);
  c.py = int(sy / cnt);
  c.on_object = best_cov.at(c.px, c.py) > 0.95f;
  return c;
}

// Server options for those tests: SAM from `sam_dir`, four of the eight views, the shared cache.
inline AppOptions sam_click_options(const std::string& out, const std::string& sam_dir) {
  AppOptions opt;
  opt.out_dir = out;
  opt.sam_dir = sam_dir;
  opt.views.cache_dir = std::string(ISEGMAN_BINARY_DIR) + "/server-test-sam-cache";
  opt.views.max_side = 320;
  opt.settings.views_spec = "0,2,4,6";
  return opt;
}

inline AppOptions no_segmentation(const std::string& out) {
  AppOptions o;
  o.segmentation = false;
  o.out_dir = out;
  o.threads = 2;
  return o;
}

}  // namespace isegman::server
