// sam_bench: the C++ side of the SAM benchmark and the dev helper of the reference tool
// (tools/sam_reference). Not a test.
//   sam_bench time [--encoder F] [--decoder F] [--runs N] [--threads N] <image>...
//       encoder ms per 1024 image and decoder ms per prompt (median), as JSON on stdout
//   sam_bench dump-input <image> <out.f32> [--transpose]
//       SAM's preprocessed 1x3x1024x1024 input tensor (raw float32) and its geometry as JSON
//   sam_bench embed <image> <out.f32> [--transpose]
//       the encoder's embedding (raw float32) for comparisons during development
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/image_io.h"
#include "models/onnx_graph.h"
#include "models/sam.h"

using namespace isegman;
using namespace isegman::models;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

Image transpose(const Image& a) {
  Image b(a.height, a.width, a.channels);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < a.channels; ++c) b.at(y, x, c) = a.at(x, y, c);
  return b;
}

void write_raw(const std::string& path, const float* p, size_t n) {
  std::ofstream o(path, std::ios::binary);
  o.write(reinterpret_cast<const char*>(p), std::streamsize(n * 4));
  if (!o) throw Error(path, "cannot write");
}

struct Options {
  std::string encoder, decoder;
  int runs = 3, threads = 0;
  bool transpose = false;
  std::vector<std::string> positional;
};

Options parse(int argc, char** argv, int first) {
  Options o;
  std::string dir = default_sam_dir();
  o.encoder = dir + "/encoder.onnx";
  o.decoder = dir + "/sam.onnx";
  for (int i = first; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw Error(a, "needs a value");
      return argv[++i];
    };
    if (a == "--encoder") o.encoder = value();
    else if (a == "--decoder") o.decoder = value();
    else if (a == "--runs") o.runs = std::stoi(value());
    else if (a == "--threads") o.threads = std::stoi(value());
    else if (a == "--transpose") o.transpose = true;
    else if (a.rfind("--", 0) == 0) throw Error(a, "unknown option");
    else o.positional.push_back(a);
  }
  return o;
}

Image load(const std::string& path, bool t) {
  Image img = read_image(path, 3);
  return t ? transpose(img) : img;
}

int cmd_time(const Options& o) {
  if (o.positional.empty()) throw Error("sam_bench time", "give at least one image");
  SamModel model(o.encoder, o.decoder, o.threads);
  std::vector<double> enc, dec;
  bool warm = false;
  for (const auto& path : o.positional) {
    Image img = load(path, false);
    if (!warm) {  // one untimed run: first-touch allocations, thread pools
      SamEmbedding e = model.encode(img);
      model.decode(e, {{img.width * 0.5, img.height * 0.5, 1}});
      warm = true;
    }
    SamEmbedding e;
    for (int r = 0; r < o.runs; ++r) {
      SamTimings t;
      e = model.encode(img, &t);
      enc.push_back(t.encoder_ms);
    }
    std::vector<std::vector<Click>> prompts = {
        {{img.width * 0.5, img.height * 0.5, 1}},
        {{img.width * 0.3, img.height * 0.4, 1}, {img.width * 0.7, img.height * 0.6, 0}},
        {{img.width * 0.2, img.height * 0.2, 1}, {img.width * 0.6, img.height * 0.3, 1}, {img.width * 0.5, img.height * 0.8, 0}}};
    for (int r = 0; r < o.runs; ++r)
      for (const auto& p : prompts) {
        SamTimings t;
        SegmentResult first = model.decode(e, p, nullptr, &t);
        dec.push_back(t.decoder_ms);
        model.decode(e, p, &first.low_res_logits(), &t);
        dec.push_back(t.decoder_ms);
      }
  }
  std::printf("{\"engine\": \"isegman-libtorch\", \"encoder_ms\": %.2f, \"decoder_ms\": %.2f, \"encoder_runs\": %zu, "
              "\"decoder_runs\": %zu}\n",
              median(enc), median(dec), enc.size(), dec.size());
  return 0;
}

int cmd_dump_input(const Options& o) {
  if (o.positional.size() != 2) throw Error("sam_bench dump-input", "usage: dump-input <image> <out.f32> [--transpose]");
  Image img = load(o.positional[0], o.transpose);
  SamInput in = sam_preprocess(img);
  write_raw(o.positional[1], in.chw.data(), in.chw.size());
  std::printf("{\"width\": %d, \"height\": %d, \"resized_width\": %d, \"resized_height\": %d, \"size\": %d, "
              "\"image_key\": \"%s\"}\n",
              in.image_width, in.image_height, in.resized_width, in.resized_height, in.size, sam_image_key(img).c_str());
  return 0;
}

int cmd_embed(const Options& o) {
  if (o.positional.size() != 2) throw Error("sam_bench embed", "usage: embed <image> <out.f32> [--transpose]");
  SamModel model(o.encoder, o.decoder, o.threads);
  Image img = load(o.positional[0], o.transpose);
  SamTimings t;
  SamEmbedding e = model.encode(img, &t);
  write_raw(o.positional[1], e.features.data<float>(), size_t(e.features.numel()));
  std::fprintf(stderr, "encoder %.1f ms\n", t.encoder_ms);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc < 2) {
      std::fprintf(stderr, "usage: sam_bench time|dump-input|embed ... (see the source header)\n");
      return 2;
    }
    std::string cmd = argv[1];
    Options o = parse(argc, argv, 2);
    if (cmd == "time") return cmd_time(o);
    if (cmd == "dump-input") return cmd_dump_input(o);
    if (cmd == "embed") return cmd_embed(o);
    throw Error(cmd, "unknown sam_bench command");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sam_bench: error: %s\n", e.what());
    return 1;
  }
}
