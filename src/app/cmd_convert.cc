// isegman convert <scene> --out FILE: rewrites a scene's Gaussians in another splat format
// (chosen by the output extension), printing what the format could not keep.
#include <cstdio>

#include "app/args.h"
#include "app/command.h"
#include "core/error.h"
#include "io/gaussian_file.h"

namespace isegman::app {
namespace {

int run_convert(const std::vector<std::string>& argv) {
  Args args(argv, {"out", "spz-version"}, {});
  const std::string in = args.positional(0, "<scene>: a scene directory or a splat file");
  if (args.positionals().size() > 1) throw Error("convert: unexpected argument '" + args.positionals()[1] + "'");
  if (!args.has("out")) throw Error("convert: --out FILE is required");
  const std::string out = args.get("out");
  const SplatFormat f = output_format_for_path(out);  // fail early on an unknown extension
  GaussianWriteOptions wo;
  if (args.has("spz-version")) {
    wo.spz_version = args.get_int("spz-version", 0);
    if (wo.spz_version < 2 || wo.spz_version > 4) throw Error("--spz-version must be 2, 3 or 4");
  }
  const LoadedGaussians l = load_gaussians(in);
  for (const auto& n : l.notes) std::printf("note: %s\n", n.c_str());
  std::vector<std::string> notes;
  write_gaussians(out, l.scene, {l.file}, &notes, nullptr, wo);
  for (const auto& n : notes) std::printf("note: %s\n", n.c_str());
  std::printf("read %s (%s, %zu Gaussians, SH degree %d)\nwrote %s (%s)\n", l.file.c_str(),
              splat_format_name(l.format), l.scene.size(), l.scene.sh_degree, out.c_str(), splat_format_name(f));
  return 0;
}

RegisterCommand reg("convert", "rewrite a scene in another splat format (PLY, compressed PLY, .splat, .spz, .sog)",
                    "isegman convert <scene> --out FILE [--spz-version 2|3|4]\n"
                    "<scene>: a scene directory or a splat file (PLY, compressed PLY, .splat, .spz, .sog);\n"
                    "the format is detected by content. The output format comes from the extension:\n"
                    "*.ply, *.compressed.ply, *.splat, *.spz, *.sog. Never replaces its input.\n",
                    run_convert);

}  // namespace
}  // namespace isegman::app
