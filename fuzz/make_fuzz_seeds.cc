// Writes seed corpora for the fuzzers with the library's own writers:
//   make_fuzz_seeds <out dir> [fixtures dir]
// creates <out>/ply_fuzzer, <out>/colmap_fuzzer and <out>/npy_fuzzer. With a fixtures
// folder, a few Gaussians of each fixture scene (SH degree 3) are added as PLY seeds.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/colmap.h"
#include "io/llff.h"
#include "io/npy.h"
#include "io/compressed_ply.h"
#include "io/gaussian_file.h"
#include "io/ply.h"
#include "io/spz.h"

using namespace isegman;
namespace fs = std::filesystem;

namespace {

std::vector<Camera> rig(int n) {
  std::vector<Camera> cams;
  for (int i = 0; i < n; ++i) {
    Camera c = Camera::look_at({2.0 * i - 1, -0.5, -3}, {0, 0, 0}, {0, -1, 0}, 64 + 16 * i, 48, 50 + 5 * i);
    c.id = i;
    c.name = "view" + std::to_string(i);
    cams.push_back(c);
  }
  return cams;
}

GaussianScene tiny_scene(size_t n, int degree) {
  GaussianScene s;
  s.resize(n, degree);
  for (size_t i = 0; i < n; ++i) {
    s.positions[3 * i] = float(i);
    s.opacity[i] = 0.5f;
    s.scales[3 * i] = -2.f;
  }
  for (size_t k = 0; k < s.sh.size(); ++k) s.sh[k] = 0.01f * float(k % 7);
  return s;
}

// [mode][cameras length, 2 bytes][cameras][images], as colmap_fuzzer reads it.
std::vector<uint8_t> colmap_seed(bool text, const std::vector<uint8_t>& cams, const std::vector<uint8_t>& imgs) {
  std::vector<uint8_t> out = {uint8_t(text ? 1 : 0), uint8_t(cams.size() & 0xff), uint8_t(cams.size() >> 8)};
  out.insert(out.end(), cams.begin(), cams.end());
  out.insert(out.end(), imgs.begin(), imgs.end());
  return out;
}

std::vector<uint8_t> bytes_of(const std::string& s) { return {s.begin(), s.end()}; }

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s <out dir> [fixtures dir]\n", argv[0]);
    return 2;
  }
  try {
    fs::path out(argv[1]);
    for (const char* d : {"ply_fuzzer", "colmap_fuzzer", "npy_fuzzer", "spz_fuzzer", "compressed_ply_fuzzer",
                          "sog_fuzzer", "splat_file_fuzzer"})
      fs::create_directories(out / d);

    // Splat formats: .spz v2-4 and compressed PLY at SH 0 and 3, .splat.
    for (int degree : {0, 3}) {
      const GaussianScene s = tiny_scene(3, degree);
      for (int v : {2, 3, 4}) {
        SpzWriteOptions o;
        o.version = v;
        const std::string name = "v" + std::to_string(v) + "_sh" + std::to_string(degree) + ".spz";
        write_file_atomic((out / "spz_fuzzer" / name).string(), serialize_spz(s, o));
        write_file_atomic((out / "splat_file_fuzzer" / name).string(), serialize_spz(s, o));
      }
      const std::string cp = "sh" + std::to_string(degree) + ".compressed.ply";
      write_file_atomic((out / "compressed_ply_fuzzer" / cp).string(), serialize_compressed_ply(s));
      write_file_atomic((out / "splat_file_fuzzer" / cp).string(), serialize_compressed_ply(s));
    }
    write_file_atomic((out / "splat_file_fuzzer" / "tiny.splat").string(),
                      serialize_gaussians(tiny_scene(2, 0), SplatFormat::kSplat));

    // PLY: binary little-endian at SH 0, 1 and 3, ASCII and big-endian by hand.
    for (int degree : {0, 1, 3})
      write_file_atomic((out / "ply_fuzzer" / ("tiny_sh" + std::to_string(degree) + ".ply")).string(),
                        serialize_ply(tiny_scene(2, degree)));
    write_file_atomic((out / "ply_fuzzer" / "ascii.ply").string(),
                      std::string("ply\nformat ascii 1.0\ncomment seed\nelement vertex 2\n"
                                  "property float x\nproperty float y\nproperty float z\n"
                                  "property float f_dc_0\nproperty float f_dc_1\nproperty float f_dc_2\n"
                                  "property float opacity\nproperty float scale_0\nproperty float scale_1\n"
                                  "property float scale_2\nproperty float rot_0\nproperty float rot_1\n"
                                  "property float rot_2\nproperty float rot_3\nelement face 1\n"
                                  "property list uchar int vertex_indices\nend_header\n"
                                  "0 0 0 0.1 0.2 0.3 0 -3 -3 -3 1 0 0 0\n1 2 3 0 0 0 1 -2 -2 -2 0.5 0.5 0 0\n"
                                  "3 0 1 1\n"));
    {
      std::string be = "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty double x\n"
                       "property double y\nproperty double z\nproperty uchar opacity\nend_header\n";
      std::vector<uint8_t> b = bytes_of(be);
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 8; ++j) b.push_back(j == 0 ? 0x3f : (j == 1 ? 0xf0 : 0));  // 1.0
      b.push_back(200);
      write_file_atomic((out / "ply_fuzzer" / "big_endian.ply").string(), b);
    }
    if (argc > 2) {
      for (const char* scene : {"fern", "dtu24"}) {
        fs::path dir = fs::path(argv[2]) / scene / "scene" / "point_cloud";
        std::error_code ec;
        for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
          if (it->path().filename() != "point_cloud.ply") continue;
          GaussianScene s = read_ply(it->path().string());
          std::vector<bool> keep(s.size(), false);
          for (size_t i = 0; i < keep.size() && i < 3; ++i) keep[i] = true;
          write_file_atomic((out / "ply_fuzzer" / (std::string(scene) + "_3.ply")).string(),
                            serialize_ply(s.subset(keep)));
          break;
        }
      }
    }

    // COLMAP: binary and text models of 1 and 3 views, a distorted text model.
    for (int n : {1, 3}) {
      std::vector<ColmapCamera> cc;
      std::vector<ColmapImage> ci;
      cameras_to_colmap(rig(n), cc, ci);
      write_file_atomic((out / "colmap_fuzzer" / ("bin" + std::to_string(n))).string(),
                        colmap_seed(false, serialize_colmap_cameras_bin(cc), serialize_colmap_images_bin(ci)));
      fs::path tmp = out / ("tmp_text" + std::to_string(n));
      fs::create_directories(tmp);
      write_colmap_text(tmp.string(), rig(n));
      write_file_atomic((out / "colmap_fuzzer" / ("txt" + std::to_string(n))).string(),
                        colmap_seed(true, read_file_bytes((tmp / "cameras.txt").string()),
                                    read_file_bytes((tmp / "images.txt").string())));
      fs::remove_all(tmp);
    }
    write_file_atomic((out / "colmap_fuzzer" / "txt_opencv").string(),
                      colmap_seed(true, bytes_of("1 OPENCV 64 48 50 50 32 24 0.01 0 0 0\n2 SIMPLE_RADIAL 9 9 5 4 4 0.1\n"),
                                  bytes_of("1 1 0 0 0 0 0 0 1 a/im0.jpg\n1 2 3 4 5 6\n2 0.5 0.5 0.5 0.5 1 1 1 2 b.png\n\n")));

    // .npy: LLFF arrays of 1 and 3 views, float32 and a v2 header by hand.
    for (int n : {1, 3})
      write_file_atomic((out / "npy_fuzzer" / ("llff" + std::to_string(n) + ".npy")).string(),
                        serialize_npy({size_t(n), 17}, cameras_to_llff(rig(n), 0.5, 10)));
    {
      std::vector<uint8_t> f = {0x93, 'N', 'U', 'M', 'P', 'Y', 2, 0};
      std::string h = "{'descr': '<f4', 'fortran_order': False, 'shape': (1, 17), }\n";
      for (int k = 0; k < 4; ++k) f.push_back(uint8_t(k == 0 ? h.size() : 0));
      f.insert(f.end(), h.begin(), h.end());
      std::vector<double> row = cameras_to_llff(rig(1), 0.5, 10);
      for (double v : row) {
        float x = float(v);
        const uint8_t* p = reinterpret_cast<const uint8_t*>(&x);
        f.insert(f.end(), p, p + 4);
      }
      write_file_atomic((out / "npy_fuzzer" / "llff1_f4_v2.npy").string(), f);
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "make_fuzz_seeds: %s\n", e.what());
    return 1;
  }
  return 0;
}
