// isegman nvos-import: turns an NVOS-style benchmark item (a trained LLFF scene, the
// reference view's positive/negative scribbles and the target view's mask) into the
// generic task layout that `isegman eval` scores.
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "app/args.h"
#include "app/command.h"
#include "core/error.h"
#include "core/output_plan.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "segment/scribbles.h"

namespace fs = std::filesystem;

namespace isegman::app {
namespace {

int run_nvos_import(const std::vector<std::string>& argv) {
  Args args(argv, {"scene", "view", "pos", "neg", "mask", "mask-view", "clicks", "out"}, {});
  for (const char* f : {"scene", "view", "pos", "mask", "out"})
    if (!args.has(f)) throw Error(std::string("missing --") + f + " (see isegman help nvos-import)");
  const std::string scene = fs::absolute(args.get("scene")).string();
  SceneBundle b = load_scene(scene);
  const std::string view = args.get("view"), mask_view = args.get("mask-view", view);
  if (!find_camera(b.cameras, view)) throw Error(scene, "no camera named '" + view + "' (the scribbled view)");
  if (!find_camera(b.cameras, mask_view)) throw Error(scene, "no camera named '" + mask_view + "' (the masked view)");
  const int n = args.get_int("clicks", 3);
  if (n < 1 || n > 50) throw Error("--clicks must be between 1 and 50");
  const Camera& cam = *find_camera(b.cameras, view);
  // Scribbles may be drawn at another resolution: a click moves by scaling (core/click.h)
  // and lands on the centre of the camera pixel it falls in (prompts.json names pixels).
  auto scale_to_camera = [&](std::vector<Click> clicks, const Image& img) {
    for (auto& c : clicks) {
      c = rescaled(c, img.width, img.height, cam.width, cam.height);
      c = pixel_centre_click(std::floor(c.x), std::floor(c.y), c.label);
    }
    return clicks;
  };
  Image pos = read_image(args.get("pos"), 1);
  auto clicks = scale_to_camera(segment::clicks_from_scribble(pos, n, 1), pos);
  if (clicks.empty()) throw Error(args.get("pos"), "the positive scribble is empty");
  std::vector<Click> neg;
  if (args.has("neg")) {
    Image ni = read_image(args.get("neg"), 1);
    neg = scale_to_camera(segment::clicks_from_scribble(ni, n, 0), ni);
  }
  const fs::path out = args.get("out");
  const std::string mask_file = (out / "masks" / (camera_file_stem(mask_view) + ".png")).string();
  OutputPlan plan;
  plan.input(b.ply_path, "scene");
  plan.input(b.cameras_path, "camera file");
  for (const char* f : {"pos", "neg", "mask"}) plan.input(args.get(f), std::string("--") + f + " image");
  plan.output((out / "prompts.json").string(), "prompts");
  plan.output(mask_file, "ground-truth mask");
  plan.prepare();
  nlohmann::json p = {{"view", view}, {"positive", nlohmann::json::array()}, {"negative", nlohmann::json::array()}};
  // prompts.json names pixels: the pixel each click lies in.
  for (auto& c : clicks) p["positive"].push_back({std::floor(c.x), std::floor(c.y)});
  for (auto& c : neg) p["negative"].push_back({std::floor(c.x), std::floor(c.y)});
  write_file_atomic((out / "prompts.json").string(), p.dump(1) + "\n");
  Image mask = read_image(args.get("mask"), 1);
  write_png(mask_file, mask);
  std::error_code ec;
  fs::remove(out / "scene", ec);
  fs::create_directory_symlink(scene, out / "scene", ec);
  if (ec) throw Error((out / "scene").string(), "cannot link the scene: " + ec.message());
  std::printf("wrote task %s: %zu positive, %zu negative clicks in %s; ground truth for %s; scene -> %s\n",
              out.string().c_str(), clicks.size(), neg.size(), view.c_str(), mask_view.c_str(), scene.c_str());
  return 0;
}

RegisterCommand reg("nvos-import", "make an eval task from NVOS-style scribbles and a target mask",
                    "usage: isegman nvos-import --scene TRAINED_SCENE --view IMG_NAME --pos POS_SCRIBBLE.png\n"
                    "                           [--neg NEG_SCRIBBLE.png] --mask MASK.png [--mask-view IMG_NAME]\n"
                    "                           [--clicks N] --out TASK_DIR\n"
                    "  Samples N well-spread clicks (farthest-point) from each scribble of the reference view,\n"
                    "  stores the target view's mask as ground truth and links the scene: `isegman eval TASK_DIR`.\n"
                    "  NVOS keeps masks as labels/llff/masks/<scene>/<id>_mask.png; train the LLFF scene first\n"
                    "  (any INRIA-layout trainer) and name the cameras' img_name as in --view/--mask-view.",
                    run_nvos_import);

}  // namespace
}  // namespace isegman::app
