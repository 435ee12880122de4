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

inline AppOptions no_segmentation(const std::string& out) {
  AppOptions o;
  o.segmentation = false;
  o.out_dir = out;
  o.threads = 2;
  return o;
}

}  // namespace isegman::server
