#include "io/ply.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <random>

#include "core/error.h"
#include "io/atomic_file.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

GaussianScene random_scene(size_t n, int degree, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> N(0.f, 1.f);
  GaussianScene s;
  s.resize(n, degree);
  for (auto* v : {&s.positions, &s.sh, &s.opacity, &s.scales, &s.rotations})
    for (float& x : *v) x = N(rng);
  return s;
}

void expect_same(const GaussianScene& a, const GaussianScene& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.sh_degree, b.sh_degree);
  auto bits = [](const std::vector<float>& x, const std::vector<float>& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), 4 * x.size()) == 0;
  };
  EXPECT_TRUE(bits(a.positions, b.positions));
  EXPECT_TRUE(bits(a.sh, b.sh));
  EXPECT_TRUE(bits(a.opacity, b.opacity));
  EXPECT_TRUE(bits(a.scales, b.scales));
  EXPECT_TRUE(bits(a.rotations, b.rotations));
}

std::string error_of(const std::string& text) {
  try {
    parse_ply(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "bad.ply");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string header(size_t n, const std::string& props, const std::string& fmt = "binary_little_endian") {
  return "ply\nformat " + fmt + " 1.0\nelement vertex " + std::to_string(n) + "\n" + props + "end_header\n";
}

std::string minimal_props(const std::string& type = "float") {
  std::string p;
  for (const char* n : {"x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2", "opacity", "scale_0", "scale_1", "scale_2",
                        "rot_0", "rot_1", "rot_2", "rot_3"})
    p += "property " + (std::string(n) == "x" ? type : std::string("float")) + " " + n + "\n";
  return p;
}

TEST(Ply, BinaryRoundTripIsBitExactForEveryDegree) {
  for (int d = 0; d <= 3; ++d) {
    GaussianScene s = random_scene(257, d, 11 + d);
    std::vector<uint8_t> bytes = serialize_ply(s);
    GaussianScene r = parse_ply(bytes.data(), bytes.size(), "mem");
    expect_same(s, r);
    EXPECT_EQ(serialize_ply(r), bytes) << "degree " << d;  // re-serialising is byte-identical
  }
}

TEST(Ply, LargeFilesParseInParallelBlocksAndReportEveryByteOnce) {
  // More rows than one parallel block (65536), read from a file as every command does.
  GaussianScene s = random_scene(150001, 1, 3);
  const fs::path path = fs::temp_directory_path() / ("isegman-ply-large-" + std::to_string(::getpid()) + ".ply");
  write_ply(path.string(), s);
  expect_same(s, read_ply(path.string()));
  const std::vector<uint8_t> bytes = read_file_bytes(path.string());
  fs::remove(path);
  std::vector<int> seen(bytes.size(), 0);
  std::mutex m;
  GaussianScene r = parse_ply(bytes.data(), bytes.size(), "mem", nullptr, [&](size_t offset, size_t length) {
    std::lock_guard<std::mutex> lock(m);
    for (size_t i = offset; i < offset + length; ++i) ++seen[i];
  });
  expect_same(s, r);
  const size_t header = bytes.size() - s.size() * (bytes.size() / s.size());  // records are fixed size
  for (size_t i = 0; i < bytes.size(); ++i) ASSERT_EQ(seen[i], i < header ? 0 : 1) << "byte " << i;
}

TEST(Ply, FRestIsChannelMajor) {
  GaussianScene s;
  s.resize(1, 1);
  // f_rest_0..2 are red coefficients 1..3, f_rest_3..5 green, f_rest_6..8 blue.
  std::string text = header(1, [] {
    std::string p = minimal_props();
    for (int i = 0; i < 9; ++i) p += "property float f_rest_" + std::to_string(i) + "\n";
    return p;
  }(), "ascii");
  text += "0 0 0  0.1 0.2 0.3  0  0 0 0  1 0 0 0  1 2 3 4 5 6 7 8 9\n";
  GaussianScene r = parse_ply(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "a.ply");
  ASSERT_EQ(r.sh_degree, 1);
  const float* sh = r.sh_of(0);
  EXPECT_FLOAT_EQ(sh[0], 0.1f);                 // DC red
  EXPECT_FLOAT_EQ(sh[3 * 1 + 0], 1.f);          // coefficient 1, red
  EXPECT_FLOAT_EQ(sh[3 * 3 + 0], 3.f);          // coefficient 3, red
  EXPECT_FLOAT_EQ(sh[3 * 1 + 1], 4.f);          // coefficient 1, green
  EXPECT_FLOAT_EQ(sh[3 * 3 + 2], 9.f);          // coefficient 3, blue
}

TEST(Ply, AsciiBigEndianCommentsAndDoubles) {
  GaussianScene s = random_scene(3, 0, 5);
  std::string props;
  for (const char* n : {"x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2", "opacity", "scale_0", "scale_1", "scale_2",
                        "rot_0", "rot_1", "rot_2", "rot_3"})
    props += std::string("property double ") + n + "\n";
  std::string text = "ply\r\nformat binary_big_endian 1.0\r\ncomment made by hand\r\nelement vertex 3\r\n" + props +
                     "end_header\n";
  for (size_t i = 0; i < 3; ++i) {
    const float vals[14] = {s.positions[3 * i], s.positions[3 * i + 1], s.positions[3 * i + 2], s.sh[3 * i],
                            s.sh[3 * i + 1], s.sh[3 * i + 2], s.opacity[i], s.scales[3 * i], s.scales[3 * i + 1],
                            s.scales[3 * i + 2], s.rotations[4 * i], s.rotations[4 * i + 1], s.rotations[4 * i + 2],
                            s.rotations[4 * i + 3]};
    for (float v : vals) {
      double d = v;
      uint8_t b[8];
      std::memcpy(b, &d, 8);
      for (int k = 7; k >= 0; --k) text.push_back(char(b[k]));
    }
  }
  GaussianScene r = parse_ply(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "be.ply");
  expect_same(s, r);
}

TEST(Ply, KeepsExtraPropertiesAndNormals) {
  std::string props = minimal_props() + "property float nx\nproperty float ny\nproperty float nz\n" +
                      "property uchar label\nproperty float confidence\n";
  std::string text = header(2, props, "ascii") + "1 2 3 0 0 0 0 0 0 0 1 0 0 0 0 0 1 7 0.25\n" +
                     "4 5 6 0 0 0 0 0 0 0 1 0 0 0 0 1 0 9 0.5\n";
  PlyReadReport report;
  GaussianScene r = parse_ply(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "x.ply", &report);
  ASSERT_EQ(r.extras.size(), 2u);
  EXPECT_EQ(r.extras[0].name, "label");
  EXPECT_EQ(r.extras[0].data, (std::vector<uint8_t>{7, 9}));
  ASSERT_EQ(r.normals.size(), 6u);
  EXPECT_EQ(r.normals[2], 1.f);
  // Written and read back: extras survive with their types.
  std::vector<uint8_t> bytes = serialize_ply(r);
  GaussianScene back = parse_ply(bytes.data(), bytes.size(), "mem");
  ASSERT_EQ(back.extras.size(), 2u);
  EXPECT_EQ(back.extras[0].type, "uchar");
  EXPECT_EQ(back.extras[0].data, r.extras[0].data);
  EXPECT_EQ(back.extras[1].data, r.extras[1].data);
  EXPECT_EQ(back.normals, r.normals);
}

TEST(Ply, SkipsOtherElementsBeforeVertices) {
  std::string text = "ply\nformat ascii 1.0\nelement camera 1\nproperty float view\n"
                     "element face 1\nproperty list uchar int vertex_indices\nelement vertex 1\n" +
                     minimal_props() + "end_header\n9\n3 0 1 2\n1 2 3 0 0 0 0 0 0 0 1 0 0 0\n";
  GaussianScene r = parse_ply(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "x.ply");
  EXPECT_EQ(r.positions[2], 3.f);
}

TEST(Ply, ErrorsNameTheFileAndTheProblem) {
  GaussianScene s = random_scene(10, 3, 1);
  std::vector<uint8_t> bytes = serialize_ply(s);
  std::string good(bytes.begin(), bytes.end());
  EXPECT_NE(error_of(good.substr(0, good.size() - 7)).find("truncated"), std::string::npos);
  EXPECT_NE(error_of(good.substr(0, 40)).find("end_header"), std::string::npos);
  EXPECT_NE(error_of("hello").find("not a PLY"), std::string::npos);
  EXPECT_NE(error_of(header(1, minimal_props("uchar"))).find("property 'x' has type uchar"), std::string::npos);
  std::string no_rot = header(1, "property float x\nproperty float y\nproperty float z\n");
  EXPECT_NE(error_of(no_rot).find("missing required"), std::string::npos);
  std::string rest5 = minimal_props();
  for (int i = 0; i < 5; ++i) rest5 += "property float f_rest_" + std::to_string(i) + "\n";
  EXPECT_NE(error_of(header(1, rest5)).find("5 f_rest"), std::string::npos);
  EXPECT_NE(error_of(header(4000000000ull, minimal_props()) + "abc").find("truncated"), std::string::npos);
  EXPECT_NE(error_of(header(0, minimal_props())).find("no Gaussians"), std::string::npos);
  std::string nan_text = header(1, minimal_props(), "ascii") + "nan 0 0 0 0 0 0 0 0 0 1 0 0 0\n";
  EXPECT_EQ(error_of(nan_text), "bad.ply: Gaussian 0 has a non-finite position");
  EXPECT_EQ(error_of(header(1, minimal_props(), "ascii") + "1 2 three").find("bad.ply: 'three' is not a number"), 0u);
  std::string dup = header(1, minimal_props() + "property float x\n");
  EXPECT_NE(error_of(dup).find("duplicate property 'x'"), std::string::npos);
}

TEST(Ply, HugeElementBeforeVerticesIsRefusedNotWalked) {
  // Fuzzer finding: 10^11 rows of an element before the vertices were walked one by one.
  for (const char* fmt : {"ascii", "binary_little_endian"}) {
    std::string text = std::string("ply\nformat ") + fmt + " 1.0\nelement junk 99999999999\nproperty float a\n" +
                       "element vertex 1\n" + minimal_props() + "end_header\n" + std::string(56, '0');
    EXPECT_NE(error_of(text).find("element 'junk' declares"), std::string::npos) << fmt;
    std::string empty = std::string("ply\nformat ") + fmt + " 1.0\nelement junk 99999999999\nelement vertex 1\n" +
                        minimal_props() + "end_header\n" +
                        (std::string(fmt) == "ascii" ? std::string("0 0 0 0 0 0 0 0 0 0 1 0 0 0\n") : [] {
                          float rec[14] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0};  // rot_0 = 1
                          return std::string(reinterpret_cast<const char*>(rec), sizeof rec);
                        }());
    EXPECT_EQ(error_of(empty), "") << fmt;  // property-less rows take no bytes: fine
  }
}

TEST(Ply, WriteRefusesEmptyAndNonFiniteScenesAndLeavesNoTemp) {
  fs::path dir = fs::temp_directory_path() / ("isegman_ply_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  GaussianScene empty;
  EXPECT_THROW(write_ply((dir / "e.ply").string(), empty), Error);
  GaussianScene bad = random_scene(2, 0, 3);
  bad.opacity[1] = INFINITY;
  EXPECT_THROW(write_ply((dir / "b.ply").string(), bad), Error);
  GaussianScene good = random_scene(5, 2, 4);
  write_ply((dir / "g.ply").string(), good);
  expect_same(read_ply((dir / "g.ply").string()), good);
  size_t files = 0;
  for (auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);  // no temporaries or partial outputs left behind
  EXPECT_THROW(refuse_overwriting_inputs((dir / "g.ply").string(), {(dir / "g.ply").string()}), Error);
  fs::remove_all(dir);
}

TEST(Ply, ReadsFixtureScenesAndRewritesThemBitExactly) {
  const fs::path root = ISEGMAN_FIXTURES_DIR;
  if (!fs::exists(root)) GTEST_SKIP() << "fixtures not found at " << root << "; skipping real-data test";
  for (const char* scene : {"fern/scene/point_cloud/iteration_3000/point_cloud.ply"}) {
    const std::string path = (root / scene).string();
    if (!fs::exists(path)) GTEST_SKIP() << path << " missing";
    std::vector<uint8_t> original = read_file_bytes(path);
    GaussianScene s = parse_ply(original.data(), original.size(), path);
    EXPECT_EQ(s.size(), 81815u);
    EXPECT_EQ(s.sh_degree, 3);
    std::vector<uint8_t> again = serialize_ply(s);
    // Same record layout as the trainer's file: the vertex data must match byte for byte.
    const size_t data_bytes = s.size() * 62 * 4;
    ASSERT_GE(original.size(), data_bytes);
    ASSERT_GE(again.size(), data_bytes);
    EXPECT_EQ(0, std::memcmp(original.data() + original.size() - data_bytes, again.data() + again.size() - data_bytes,
                             data_bytes));
  }
}

}  // namespace
}  // namespace isegman
