// API tests of the selection tools: screen-space shapes (rect, lasso, brush; visible
// surface only), the eyedropper, attribute ranges, grow/shrink, combine modes, and each
// as one step of the one history.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "edit/screen_selection.h"
#include "edit/selection_tools.h"
#include "io/scene_loader.h"
#include "server/test_server.h"

namespace isegman::server {
namespace {

size_t library_count(const GaussianScene& g, const Camera& cam, const edit::ScreenShape& shape, bool visible = false) {
  edit::ScreenSelectOptions o;
  o.visible_only = visible;
  return edit::select_in_shape(g, cam, shape, o).count();
}

TEST(SelectionApi, RectLassoBrushInATrainingView) {
  DemoScene d = small_demo();
  Running s(d.bundle, no_segmentation(temp_dir("sel-shapes")));
  const Camera& cam = d.bundle.cameras[0];
  const double w = cam.width, h = cam.height;
  const edit::ScreenShape rect{edit::ShapeKind::kRect, {{0.25 * w, 0.25 * h}, {0.75 * w, 0.75 * h}}, 0};
  const size_t want = library_count(d.bundle.gaussians, cam, rect);
  ASSERT_GT(want, 10u);
  const json rect_body = {{"view", 0}, {"points", {{0.25 * w, 0.25 * h}, {0.75 * w, 0.75 * h}}}};
  json r = s.post_json("/api/select/rect", rect_body.dump());
  EXPECT_EQ(r["selected"].get<size_t>(), want);
  EXPECT_EQ(r["kind"], "select");
  EXPECT_NE(r["label"].get<std::string>().find("rect selection (replace)"), std::string::npos);

  // Visible surface only: a subset (the ground and objects hide what lies behind them).
  json vis_body = rect_body;
  vis_body["visible"] = true;
  const size_t vis = s.post_json("/api/select/rect", vis_body.dump())["selected"].get<size_t>();
  EXPECT_EQ(vis, library_count(d.bundle.gaussians, cam, rect, true));
  EXPECT_LT(vis, want);
  EXPECT_GT(vis, 0u);

  // A lasso (triangle) added to the rectangle, then a brush stroke subtracted.
  s.post_json("/api/select/rect", rect_body.dump());
  const json lasso = {{"view", 0}, {"mode", "add"}, {"points", {{0.0, 0.0}, {0.3 * w, 0.0}, {0.0, 0.3 * h}}}};
  const size_t with_lasso = s.post_json("/api/select/lasso", lasso.dump())["selected"].get<size_t>();
  const edit::ScreenShape tri{edit::ShapeKind::kLasso, {{0, 0}, {0.3 * w, 0}, {0, 0.3 * h}}, 0};
  EXPECT_EQ(with_lasso, edit::unite(edit::select_in_shape(d.bundle.gaussians, cam, rect),
                                    edit::select_in_shape(d.bundle.gaussians, cam, tri)).count());
  const json brush = {{"view", 0}, {"mode", "subtract"}, {"radius", 0.08 * w},
                      {"points", {{0.3 * w, 0.5 * h}, {0.5 * w, 0.5 * h}, {0.7 * w, 0.5 * h}}}};
  const size_t after_brush = s.post_json("/api/select/brush", brush.dump())["selected"].get<size_t>();
  EXPECT_LT(after_brush, with_lasso);
  EXPECT_GT(after_brush, 0u);

  // Each tool is one step of the one history: undo the brush, redo it.
  EXPECT_EQ(s.post_json("/api/undo", "")["selected"].get<size_t>(), with_lasso);
  EXPECT_EQ(s.post_json("/api/redo", "")["selected"].get<size_t>(), after_brush);
  const json st = s.get_json("/api/status");
  EXPECT_EQ(st["history"]["entries"].size(), 5u);
  EXPECT_EQ(st["history"]["entries"][4]["kind"], "select");
}

TEST(SelectionApi, FreeCameraRectAndIntersect) {
  DemoScene d = small_demo();
  Running s(d.bundle, no_segmentation(temp_dir("sel-free")));
  const json cam = {{"eye", {0, -6, 3}}, {"target", {0, 0, 0}}, {"up", {0, 0, 1}}, {"fov", 60}, {"width", 320},
                    {"height", 240}};
  const json left = {{"camera", cam}, {"points", {{0, 0}, {160, 240}}}};
  const size_t l = s.post_json("/api/select/rect", left.dump())["selected"].get<size_t>();
  const json top = {{"camera", cam}, {"points", {{0, 0}, {320, 120}}}, {"mode", "intersect"}};
  const size_t both = s.post_json("/api/select/rect", top.dump())["selected"].get<size_t>();
  FreeCameraSpec spec;
  spec.eye = {0, -6, 3};
  spec.target = {0, 0, 0};
  spec.up = {0, 0, 1};
  spec.width = 320;
  spec.height = 240;
  const Camera c = make_free_camera(spec);
  const Selection a = edit::select_in_shape(d.bundle.gaussians, c, edit::ScreenShape{edit::ShapeKind::kRect, {{0, 0}, {160, 240}}, 0});
  const Selection b = edit::select_in_shape(d.bundle.gaussians, c, edit::ScreenShape{edit::ShapeKind::kRect, {{0, 0}, {320, 120}}, 0});
  EXPECT_EQ(l, a.count());
  EXPECT_EQ(both, edit::intersect(a, b).count());
  EXPECT_GT(both, 0u);
  EXPECT_LT(both, l);
}

TEST(SelectionApi, EyedropperRangesGrowShrink) {
  DemoScene d = small_demo();
  const size_t n = d.bundle.gaussians.size();
  Running s(d.bundle, no_segmentation(temp_dir("sel-misc")));
  // The eyedropper at the centre of an object in view 0 picks a similar-colour set.
  const DemoObject& obj = d.objects[0];
  const Camera& cam = d.bundle.cameras[0];
  double u = 0, v = 0;
  ASSERT_TRUE(cam.project(obj.center, u, v));
  const json pick = {{"view", 0}, {"x", u}, {"y", v}, {"tolerance", 0.15}};
  json r = s.post_json("/api/select/color", pick.dump());
  const size_t similar = r["selected"].get<size_t>();
  EXPECT_GT(similar, 0u);
  EXPECT_LT(similar, n);
  EXPECT_NE(r["label"].get<std::string>().find("colour selection (#"), std::string::npos);
  const int64_t g = edit::gaussian_at(d.bundle.gaussians, cam, u, v);
  ASSERT_GE(g, 0);
  EXPECT_EQ(similar,
            edit::select_similar_color(d.bundle.gaussians, edit::base_color(d.bundle.gaussians, size_t(g)), 0.15).count());
  EXPECT_EQ(s.post_json("/api/select/color", R"({"color": "#808080", "tolerance": 0})")["selected"].get<size_t>(),
            edit::select_similar_color(d.bundle.gaussians, {128 / 255.0, 128 / 255.0, 128 / 255.0}, 0).count());

  // Attribute ranges.
  const size_t opaque = s.post_json("/api/select/opacity", R"({"min": 0.5, "max": 1})")["selected"].get<size_t>();
  EXPECT_EQ(opaque, edit::select_opacity(d.bundle.gaussians, 0.5, 1).count());
  const size_t big = s.post_json("/api/select/size", R"({"min": 0.05})")["selected"].get<size_t>();
  EXPECT_EQ(big, edit::select_size(d.bundle.gaussians, 0.05, 1e7).count());

  // Grow then shrink by neighbours and by a radius.
  const Vec3 rr{obj.radius, obj.radius, obj.radius * 0.3};  // a slab of the (hollow) object
  const Vec3 lo = obj.center - rr, hi = obj.center + rr;
  const json box = {{"lo", {lo.x, lo.y, lo.z}}, {"hi", {hi.x, hi.y, hi.z}}};
  const size_t seed = s.post_json("/api/select/box", box.dump())["selected"].get<size_t>();
  ASSERT_GT(seed, 0u);
  const Selection seed_sel = edit::select_box(d.bundle.gaussians, lo, hi);
  const size_t grown = s.post_json("/api/select/grow", R"({"k": 6, "steps": 2})")["selected"].get<size_t>();
  EXPECT_EQ(grown, edit::grow(d.bundle.gaussians, seed_sel, 6, 0, 2).count());
  EXPECT_GT(grown, seed);
  const size_t shrunk = s.post_json("/api/select/shrink", R"({"k": 6, "steps": 2})")["selected"].get<size_t>();
  EXPECT_EQ(shrunk, edit::shrink(d.bundle.gaussians, edit::grow(d.bundle.gaussians, seed_sel, 6, 0, 2), 6, 0, 2).count());
  EXPECT_LT(shrunk, grown);
  const double radius = obj.radius * 0.2;
  const json by_radius = {{"radius", radius}};
  const size_t rg = s.post_json("/api/select/grow", by_radius.dump())["selected"].get<size_t>();
  EXPECT_GE(rg, shrunk);

  // Bad requests name the field.
  s.post_json("/api/select/rect", R"({"view": 0, "points": [[0, 0]]})", 400);
  s.post_json("/api/select/rect", R"({"view": 99, "points": [[0, 0], [5, 5]]})", 400);
  s.post_json("/api/select/rect", R"({"points": [[0, 0], [5, 5]]})", 400);
  s.post_json("/api/select/rect", R"({"view": 0, "points": [[0, 0], [5, "x"]]})", 400);
  s.post_json("/api/select/rect", R"({"view": 0, "points": [[0, 0], [5, 5]], "colour": 1})", 400);
  s.post_json("/api/select/brush", R"({"view": 0, "points": [[0, 0]]})", 400);  // no radius
  s.post_json("/api/select/lasso", R"({"view": 0, "points": [[0, 0], [1, 1]]})", 400);
  s.post_json("/api/select/color", R"({"view": 0, "x": 1e4, "y": 5})", 400);
  s.post_json("/api/select/opacity", R"({"min": 0.8, "max": 0.2})", 400);
  s.post_json("/api/select/grow", R"({"k": 0})", 400);
  s.post_json("/api/select/shrink", R"({"steps": 0})", 400);
  s.post_json("/api/select/rect", R"({"view": 0, "points": [[0, 0], [5, 5]], "mode": "xor"})", 400);
}

// The screen-space tools through `isegman edit` and through the API, on a scene folder
// with cameras: rect (visible surface), lasso added, brush subtracted, then a colorize;
// the written files must be the same bytes.
TEST(SelectionApi, CliAndApiScreenToolsWriteTheSameBytes) {
  namespace fs = std::filesystem;
  const std::string bin = std::string(ISEGMAN_BINARY_DIR) + "/isegman";
  if (!fs::exists(bin)) GTEST_SKIP() << "no isegman binary at " << bin;
  DemoScene d = small_demo();
  const std::string dir = temp_dir("cli-api-screen");
  const std::string scene_dir = dir + "/scene";
  write_scene_dir(scene_dir, d.bundle.gaussians, d.bundle.cameras, 1);
  SceneBundle bundle = load_scene(scene_dir);
  const Camera& cam = bundle.cameras[0];
  const double w = cam.width, h = cam.height;
  auto num = [](double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return std::string(b);
  };
  const std::string name = cam.name;
  const std::string rect = name + ":" + num(0.2 * w) + "," + num(0.2 * h) + "," + num(0.8 * w) + "," + num(0.8 * h);
  const std::string lasso = name + ":0,0," + num(0.4 * w) + ",0,0," + num(0.4 * h);
  const std::string brush = name + ":" + num(0.06 * w) + ":" + num(0.3 * w) + "," + num(0.5 * h) + "," + num(0.7 * w) +
                            "," + num(0.55 * h);
  const std::string cli_out = dir + "/cli.ply";
  const std::string cmd = bin + " edit " + scene_dir + " --rect '" + rect + "' --visible select --lasso '" + lasso +
                          "' --combine add select --brush '" + brush + "' --combine subtract" +
                          " colorize --color '#20c040' --out " + cli_out + " > " + dir + "/cli.log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;

  Running s(bundle, no_segmentation(dir + "/out"));
  const json r = {{"view", 0}, {"visible", true}, {"points", {{0.2 * w, 0.2 * h}, {0.8 * w, 0.8 * h}}}};
  s.post_json("/api/select/rect", r.dump());
  const json l = {{"view", 0}, {"mode", "add"}, {"points", {{0.0, 0.0}, {0.4 * w, 0.0}, {0.0, 0.4 * h}}}};
  s.post_json("/api/select/lasso", l.dump());
  const json b = {{"view", 0}, {"mode", "subtract"}, {"radius", 0.06 * w},
                  {"points", {{0.3 * w, 0.5 * h}, {0.7 * w, 0.55 * h}}}};
  EXPECT_GT(s.post_json("/api/select/brush", b.dump())["selected"].get<size_t>(), 0u);
  s.post_json("/api/edit/colorize", R"({"color": "#20c040"})");
  const json out = s.post_json("/api/export", R"({"path": "api.ply"})");

  std::ifstream fa(cli_out, std::ios::binary), fb(out["path"].get<std::string>(), std::ios::binary);
  const std::string cli_bytes((std::istreambuf_iterator<char>(fa)), {}), api_bytes((std::istreambuf_iterator<char>(fb)), {});
  ASSERT_GT(cli_bytes.size(), 1000u);
  EXPECT_TRUE(cli_bytes == api_bytes) << "the CLI and the API wrote different files";
  // And the edit did something: the input differs from both.
  std::ifstream fi(scene_dir + "/point_cloud/iteration_1/point_cloud.ply", std::ios::binary);
  const std::string in_bytes((std::istreambuf_iterator<char>(fi)), {});
  EXPECT_FALSE(in_bytes == cli_bytes);
}

}  // namespace
}  // namespace isegman::server
