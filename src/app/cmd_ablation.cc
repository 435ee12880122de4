// isegman ablation: the design choices of the segmentation measured on the built-in
// synthetic scene, whose per-Gaussian labels are known: propagation mode, inspection
// on/off and view sampling. Every object is selected from one click; the score is the
// IoU of the rendered selection against the true object in every camera that sees it.
#include <algorithm>
#include <cstdio>

#include "app/args.h"
#include "app/command.h"
#include "app/demo_scene.h"
#include "app/segment_args.h"
#include "core/error.h"
#include "segment/evaluation.h"
#include "segment/pipeline.h"

namespace isegman::app {
namespace {

struct Config {
  std::string label;
  segment::PropagationMode mode;
  bool inspection;
  std::string views;
};

int run_ablation(const std::vector<std::string>& argv) {
  Args args(argv, {"density", "threads", "sam", "cache", "width", "height"}, {});
  DemoSceneOptions opt;
  opt.density = float(args.get_double("density", 1.0));
  opt.width = args.get_int("width", 480);
  opt.height = args.get_int("height", 360);
  if (!(opt.density > 0.01f && opt.density <= 50.f)) throw Error("--density must be in (0.01, 50]");
  DemoScene demo = make_demo_scene(opt);
  SegmentSetup setup = parse_segment_setup(args);
  auto sam = load_sam(setup);
  const std::vector<Config> configs = {
      {"hybrid, IIM, 100% views", segment::PropagationMode::Hybrid, true, "all"},
      {"epipolar, IIM, 100% views", segment::PropagationMode::Epipolar, true, "all"},
      {"depth, IIM, 100% views", segment::PropagationMode::Depth, true, "all"},
      {"hybrid, no IIM, 100% views", segment::PropagationMode::Hybrid, false, "all"},
      {"epipolar, no IIM, 100% views", segment::PropagationMode::Epipolar, false, "all"},
      {"hybrid, IIM, 50% views", segment::PropagationMode::Hybrid, true, "50%"},
      {"hybrid, IIM, 25% views", segment::PropagationMode::Hybrid, true, "25%"},
      {"hybrid, IIM, 10% views", segment::PropagationMode::Hybrid, true, "10%"},
  };
  // The clicks: one per object, in the first camera that sees its centre.
  std::vector<std::pair<int, Click>> clicks;
  for (size_t o = 0; o < demo.objects.size(); ++o) {
    int cam = 0;
    double x = 0, y = 0;  // a pixel
    if (!demo_click(demo, int(o), cam, x, y)) throw Error("ablation: no camera sees " + demo.objects[o].name);
    clicks.push_back({cam, pixel_centre_click(x, y, 1)});
  }
  std::printf("synthetic scene: %zu Gaussians, %zu objects, %zu cameras at %dx%d; one click per object\n\n",
              demo.bundle.gaussians.size(), demo.objects.size(), demo.bundle.cameras.size(), opt.width, opt.height);
  std::printf("| configuration | mIoU | mAcc |");
  for (const auto& o : demo.objects) std::printf(" %s |", o.name.c_str());
  std::printf(" interaction |\n|---|---|---|");
  for (size_t o = 0; o < demo.objects.size(); ++o) std::printf("---|");
  std::printf("---|\n");
  for (const Config& cfg : configs) {
    segment::SessionOptions so = setup.session;
    so.propagation.mode = cfg.mode;
    so.inspection = cfg.inspection;
    double miou = 0, macc = 0, ms = 0;
    std::vector<double> per;
    for (size_t o = 0; o < demo.objects.size(); ++o) {
      segment::PipelineTimings t;
      auto s = segment::segment_from_prompts(demo.bundle, clicks[o].first, {clicks[o].second}, sam, so, setup.views,
                                             cfg.views, &t);
      const std::vector<bool> truth = demo_object_mask(demo, int(o));
      double iou = 0, acc = 0;
      int n = 0;
      for (const Camera& cam : demo.bundle.cameras) {
        const Image gt = segment::selection_mask(demo.bundle.gaussians, cam, truth, cam.width, cam.height);
        if (std::count(gt.data.begin(), gt.data.end(), 1.f) < 50) continue;
        const segment::MaskScore sc = segment::score_mask(
            segment::selection_mask(demo.bundle.gaussians, cam, s->selection(), cam.width, cam.height), gt);
        iou += sc.iou;
        acc += sc.accuracy;
        ++n;
      }
      per.push_back(n ? iou / n : 0);
      miou += per.back();
      macc += n ? acc / n : 0;
      ms += t.ms_interaction();
    }
    const double k = double(demo.objects.size());
    std::printf("| %s | %.2f | %.2f |", cfg.label.c_str(), 100 * miou / k, 100 * macc / k);
    for (double p : per) std::printf(" %.1f |", 100 * p);
    std::printf(" %.2f s |\n", ms / k / 1000);
    std::fflush(stdout);
  }
  return 0;
}

RegisterCommand reg("ablation", "measure propagation modes, inspection and view sampling on the synthetic scene",
                    "usage: isegman ablation [--density D] [--width W --height H] [--sam DIR] [--cache DIR]\n"
                    "                        [--threads N]\n"
                    "  Prints a Markdown table: mIoU / mAcc over the objects (IoU of the rendered selection vs\n"
                    "  the true object in every camera that sees it) and the time per interaction.",
                    run_ablation);

}  // namespace
}  // namespace isegman::app
