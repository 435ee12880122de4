// isegman render <scene>: PNG renders of the scene's cameras (colour, optionally depth
// and alpha), and PSNR against the source photos when they are found.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/args.h"
#include "app/command.h"
#include "app/scene_args.h"
#include "core/error.h"
#include "core/output_plan.h"
#include "io/image_io.h"
#include "io/atomic_file.h"
#include "render/rasterizer.h"
#include "segment/trained_background.h"

namespace fs = std::filesystem;

namespace isegman::app {
namespace {

int run_render(const std::vector<std::string>& argv) {
  std::set<std::string> values = scene_value_flags(), switches = scene_switch_flags();
  values.insert({"camera", "width", "out", "background", "threads", "sh-degree"});
  switches.insert({"depth", "alpha", "compare"});
  Args args(argv, values, switches);
  if (!args.has("out")) throw Error("missing --out DIR");
  RenderSettings s;
  s.threads = threads_arg(args);
  s.sh_degree = args.get_int("sh-degree", -1);
  if (s.sh_degree < -1 || s.sh_degree > 3)
    throw Error("--sh-degree must be between 0 and 3 (or -1: the scene's own), got " + args.get("sh-degree"));
  {
    const std::vector<float> bg = background_arg(args, {s.background[0], s.background[1], s.background[2]});
    for (int c = 0; c < 3; ++c) s.background[c] = bg[c];
  }
  const int width = args.get_int("width", 0);
  if (args.has("width") && (width < 8 || width > 16384)) throw Error("--width must be between 8 and 16384");
  SceneBundle b = load_scene_from_args(args);
  if (!args.has("background")) {  // the colour it was trained over, as its photos show
    const segment::TrainedBackground bg = segment::estimate_trained_background(b);
    if (bg.photos > 0) std::printf("%s%s\n", bg.summary().c_str(), bg.found ? "" : ": rendering over black");
    if (bg.found)
      for (int c = 0; c < 3; ++c) s.background[c] = bg.rgb[c];
  }
  const std::string out_dir = args.get("out");

  std::vector<const Camera*> cams;
  const std::string which = args.get("camera", "all");
  if (which == "all") {
    for (const auto& c : b.cameras) cams.push_back(&c);
  } else {
    for (const std::string& key : args.all("camera")) {
      const Camera* c = find_camera(b.cameras, key);
      if (!c) throw Error(b.cameras_path, "no camera with id or name '" + key + "'");
      if (std::find(cams.begin(), cams.end(), c) == cams.end()) cams.push_back(c);
    }
  }
  // Every file this run reads or writes, checked before the first render: a camera name
  // is untrusted (it becomes a file name), and no render may replace a photo, the scene,
  // the cameras or another render.
  OutputPlan plan;
  plan.input(b.ply_path, "scene");
  plan.input(b.cameras_path, "camera file");
  for (const Camera& c : b.cameras) plan.input(c.image_path, "photo of camera '" + c.name + "'");
  std::vector<std::string> stems;
  for (const Camera* c : cams) {
    const std::string stem = (fs::path(out_dir) / camera_file_stem(c->name)).string();
    plan.output(stem + ".png", "render of camera '" + c->name + "'");
    if (args.has("alpha")) plan.output(stem + "_alpha.png", "alpha of camera '" + c->name + "'");
    if (args.has("depth")) plan.output(stem + "_depth.png", "depth of camera '" + c->name + "'");
    stems.push_back(stem);
  }
  plan.prepare();
  const bool compare = args.has("compare");
  double psnr_sum = 0;
  int psnr_n = 0;
  for (size_t k = 0; k < cams.size(); ++k) {
    const Camera* c0 = cams[k];
    Camera cam = *c0;
    if (width > 0) cam = cam.resized(width, std::max(1, int(std::lround(double(c0->height) * width / c0->width))));
    RenderOutput r = render(b.gaussians, cam, s);
    const std::string& stem = stems[k];
    write_png(stem + ".png", r.color);
    std::printf("%-24s %4dx%-4d %8zu visible  %6.1f ms", cam.name.c_str(), cam.width, cam.height, r.stats.visible,
                r.stats.ms_preprocess + r.stats.ms_sort + r.stats.ms_raster);
    if (args.has("alpha")) write_png(stem + "_alpha.png", r.alpha);
    if (args.has("depth")) {
      float max_depth = 0;
      for (float v : r.depth.data) max_depth = std::max(max_depth, v);
      write_file_atomic(stem + "_depth.png", encode_png16(r.depth, max_depth));
      std::printf("  depth 16-bit: 65535 = %.4g", max_depth);
    }
    if (compare && !c0->image_path.empty()) {
      Image photo = read_image(c0->image_path, 3);
      if (photo.width != cam.width || photo.height != cam.height) photo = resize_image(photo, cam.width, cam.height);
      double p = psnr(r.color, photo);
      psnr_sum += p;
      ++psnr_n;
      std::printf("  PSNR %.2f dB", p);
    }
    std::printf("\n");
  }
  if (psnr_n > 0) std::printf("mean PSNR over %d views: %.2f dB\n", psnr_n, psnr_sum / psnr_n);
  else if (compare) std::printf("no source photos found to compare with (use --images DIR)\n");
  return 0;
}

RegisterCommand reg("render", "render the scene's cameras to PNG (colour, depth, alpha; PSNR vs photos)",
                    "usage: isegman render <scene> --out DIR [--camera ID|NAME|all ...] [--width W]\n"
                    "                      [--depth] [--alpha] [--background r,g,b] [--compare]\n"
                    "                      [--threads N] [--sh-degree D] [--cameras FILE] [--images DIR]\n"
                    "  --depth    also write <name>_depth.png (16-bit, scale printed)\n"
                    "  --alpha    also write <name>_alpha.png (accumulated opacity)\n"
                    "  --compare  print PSNR against the source photos (found by camera name)\n"
                    "  --background r,g,b  the colour behind the Gaussians (default: the one the scene was\n"
                    "             trained over where its photos show it, else black)",
                    run_render);

}  // namespace
}  // namespace isegman::app
