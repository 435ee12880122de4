#include "app/demo_edits.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/image.h"
#include "core/selection.h"
#include "edit/checks.h"
#include "edit/colorize.h"
#include "edit/history.h"
#include "edit/remove.h"
#include "edit/scene_format.h"
#include "edit/selection_tools.h"
#include "edit/transform.h"
#include "io/image_io.h"
#include "render/rasterizer.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

using namespace isegman::edit;

std::string fmt(const Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.3f, %.3f, %.3f)", v.x, v.y, v.z);
  return buf;
}

// Images side by side (same height).
Image side_by_side(const std::vector<Image>& images) {
  int w = 0;
  for (const Image& im : images) w += im.width;
  Image out(w, images[0].height, 3, 1.f);
  int x0 = 0;
  for (const Image& im : images) {
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x)
        for (int c = 0; c < 3; ++c) out.at(x0 + x, y, c) = im.at(x, y, c);
    x0 += im.width;
  }
  return out;
}

}  // namespace

void run_edit_demo(const DemoScene& demo, const std::string& out_dir) {
  const GaussianScene& scene = demo.bundle.gaussians;
  const std::vector<Camera>& cams = demo.bundle.cameras;
  if (demo.objects.empty() || cams.empty()) throw Error("edit demo", "the demo scene has no objects or no cameras");
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw Error(out_dir, "cannot create directory: " + ec.message());
  const fs::path dir(out_dir);

  // 1. Box-select an object (the blue cylinder: its copy shows the rotation plainly):
  //    its bounding box, lifted just off the ground plane (z = 0).
  int target = 0;
  for (size_t o = 0; o < demo.objects.size(); ++o)
    if (demo.objects[o].name == "blue_cylinder") target = int(o);
  const DemoObject& obj = demo.objects[target];
  // The box a user would draw around the object: its extent, padded by 1 cm.
  Vec3 lo{1e30, 1e30, 1e30}, hi{-1e30, -1e30, -1e30};
  size_t truth = 0;
  for (size_t i = 0; i < scene.size(); ++i) {
    if (demo.labels[i] != target) continue;
    ++truth;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], double(scene.positions[3 * i + a]) - 0.01);
      hi[a] = std::max(hi[a], double(scene.positions[3 * i + a]) + 0.01);
    }
  }
  if (truth == 0) throw Error("edit demo", "object '" + obj.name + "' has no Gaussians");
  lo.z = std::max(lo.z, 0.004);  // stay off the ground plane (z = 0)
  const Selection box = select_box(scene, lo, hi);
  size_t hit = 0;
  for (size_t i = 0; i < scene.size(); ++i) hit += box.mask[i] && demo.labels[i] == target;
  std::printf("edit demo: box %s..%s selects %zu Gaussians: %zu of the %zu of '%s', %zu of anything else\n",
              fmt(lo).c_str(), fmt(hi).c_str(), box.count(), hit, truth, obj.name.c_str(), box.count() - hit);
  write_selection((dir / "edit_selection.isel").string(), box);

  // Two views: the camera closest to the object, and one a quarter turn around.
  size_t best = 0;
  for (size_t c = 1; c < cams.size(); ++c)
    if (norm(cams[c].center() - obj.center) < norm(cams[best].center() - obj.center)) best = c;
  const std::vector<size_t> views{best, (best + cams.size() / 4) % cams.size()};
  RenderSettings rs;
  rs.background[0] = rs.background[1] = rs.background[2] = 1.f;

  EditSession session(scene);
  session.select(box, "box selection");
  const uint64_t original = session.scene().fingerprint();
  std::vector<Image> overview;
  auto snapshot = [&](const std::string& name) {
    for (size_t k = 0; k < views.size(); ++k) {
      const Camera& cam = cams[views[k]];
      Image img = render(session.scene(), cam, rs).color;
      write_png((dir / ("edit_" + name + "_" + cam.name + ".png")).string(), img);
      if (k == 0) overview.push_back(resize_image(img, cam.width / 2, cam.height / 2));
    }
    std::printf("  rendered edit_%s_*.png\n", name.c_str());
  };
  auto step = [&](Delta d) {
    const Vec3 c0 = selection_centroid(session.scene(), session.mask());
    const size_t n0 = session.scene().size();
    const std::string label = d.label;
    session.apply(std::move(d));
    std::printf("  %s: %zu -> %zu Gaussians, selection centroid %s -> %s\n", label.c_str(), n0,
                session.scene().size(), fmt(c0).c_str(),
                session.selection().empty() ? "-" : fmt(selection_centroid(session.scene(), session.mask())).c_str());
  };

  snapshot("before");
  step(plan_remove(session.scene(), session.selection()));
  snapshot("removed");
  session.undo();

  step(plan_colorize(session.scene(), session.selection(), parse_color("#f08020"), ColorizeMode::kBalanced));
  snapshot("recoloured");
  session.undo();

  step(plan_scale(session.scene(), session.selection(), 1.4));
  snapshot("scaled");
  session.undo();

  // Copy beside the original, laid on its side (90 degrees about x, then 30 about z)
  // and lowered onto the ground; orientations and SH bands turn with it.
  Similarity t;
  t.translation = {1.1, 0.3, -0.2};
  t.rotation = rotation_from_euler_deg(90, 0, 30);
  step(plan_copy(session.scene(), session.selection(), t));
  snapshot("copied");
  write_scene_file((dir / "edit_copied.ply").string(), session.scene(), {});
  session.undo();

  if (session.scene().fingerprint() != original)
    throw Error("edit demo", "undo did not restore the scene exactly");
  std::printf("  undo restored the original scene bit-exactly (fingerprint %016llx); history %zu steps, %.2f MiB\n",
              static_cast<unsigned long long>(original), session.history().undo_steps(),
              double(session.history().bytes()) / (1 << 20));
  write_png((dir / "edit_overview.png").string(), side_by_side(overview));
  std::printf("  wrote %s (before | removed | recoloured | scaled | copied)\n",
              (dir / "edit_overview.png").string().c_str());
}

}  // namespace isegman
