// isegman eval: segment from prompts and score against ground-truth masks (mIoU, mAcc).
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "app/args.h"
#include "app/command.h"
#include "app/segment_args.h"
#include "core/error.h"
#include "core/output_plan.h"
#include "io/atomic_file.h"
#include "segment/evaluation.h"

namespace isegman::app {
namespace {

int run_eval(const std::vector<std::string>& argv) {
  std::set<std::string> values = segment_value_flags();
  values.insert({"json", "fixtures"});
  Args args(argv, values, segment_switch_flags());
  const std::string path = args.positional(0, "<task dir or folder of task dirs>");
  std::vector<segment::EvalTask> tasks = segment::find_tasks(path, args.get("fixtures", "../shared/fixtures"));
  SegmentSetup setup = parse_segment_setup(args);
  if (args.has("json")) {  // checked before the tasks run: never one of their files
    OutputPlan plan;
    for (const auto& t : tasks) {
      plan.input((std::filesystem::path(t.dir) / "prompts.json").string(), "prompts of task " + t.name);
      for (const auto& m : t.masks) plan.input(m.second, "mask of task " + t.name);
    }
    plan.output(args.get("json"), "report (--json)");
    plan.prepare();
  }
  auto sam = load_sam(setup);
  nlohmann::json report = nlohmann::json::array();
  double miou = 0, macc = 0, interaction = 0;
  std::printf("%-24s %8s %8s %9s %12s %10s\n", "task", "IoU", "Acc", "selected", "interaction", "views");
  for (const auto& task : tasks) {
    segment::TaskResult r = segment::evaluate_task(task, sam, setup.session, setup.views, setup.views_spec);
    std::printf("%-24s %7.2f%% %7.2f%% %9zu %9.0f ms %7.0f ms\n", r.name.c_str(), 100 * r.iou, 100 * r.accuracy,
                r.selected, r.timings.ms_interaction(), r.timings.ms_views);
    miou += r.iou;
    macc += r.accuracy;
    interaction += r.timings.ms_interaction();
    nlohmann::json masks = nlohmann::json::array();
    for (const auto& m : r.masks) masks.push_back({{"view", m.view}, {"iou", m.iou}, {"accuracy", m.accuracy}});
    report.push_back({{"task", r.name}, {"iou", r.iou}, {"accuracy", r.accuracy}, {"selected", r.selected},
                      {"ms_interaction", r.timings.ms_interaction()}, {"ms_views", r.timings.ms_views},
                      {"masks", masks}});
  }
  const double n = double(tasks.size());
  std::printf("mean over %zu task(s): mIoU %.2f%%  mAcc %.2f%%  interaction %.0f ms\n", tasks.size(), 100 * miou / n,
              100 * macc / n, interaction / n);
  if (args.has("json")) {
    nlohmann::json doc = {{"mode", segment::mode_name(setup.session.propagation.mode)},
                          {"views", setup.views_spec},
                          {"tau", setup.session.tau},
                          {"inspection", setup.session.inspection},
                          {"miou", miou / n},
                          {"macc", macc / n},
                          {"tasks", report}};
    write_file_atomic(args.get("json"), doc.dump(2) + "\n");
    std::printf("wrote %s\n", args.get("json").c_str());
  }
  return 0;
}

RegisterCommand reg("eval", "score segmentation on tasks with ground-truth masks (mIoU, mAcc, timings)",
                    std::string("usage: isegman eval <task dir | folder of task dirs> [--json FILE] [options]\n"
                                "  <task>/scene/ (scene dir), <task>/prompts.json {\"view\", \"positive\", \"negative\"},\n"
                                "  <task>/masks/<img_name>.png (ground truth, non-zero = object; any resolution)\n"
                                "  --fixtures DIR: root of the scenes tasks name by \"fixture_scene\" (default ../shared/fixtures)\n") +
                        kSegmentOptionsHelp,
                    run_eval);

}  // namespace
}  // namespace isegman::app
