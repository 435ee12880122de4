#include "io/sog.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/format_test_util.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

using testing_formats::differences;
using testing_formats::plausible_scene;

TEST(Sog, WritesAndReadsBackWithinCodebookQuantisation) {
  for (int degree : {0, 3}) {
    SCOPED_TRACE("degree " + std::to_string(degree));
    const GaussianScene s = plausible_scene(700, degree, 31 + degree);
    const std::vector<uint8_t> bytes = serialize_sog(s);
    EXPECT_TRUE(looks_like_zip(bytes.data(), bytes.size()));
    const GaussianScene r = parse_sog_zip(bytes.data(), bytes.size(), "mem.sog");
    ASSERT_EQ(r.size(), s.size());
    EXPECT_EQ(r.sh_degree, degree);
    const auto d = differences(s, r);
    // 16 bits of ln(|x| + 1) over +-3: ~1e-4; 256-entry codebooks; 8-bit rotations.
    EXPECT_LE(d.position, 5e-4);
    EXPECT_LE(d.log_scale, 0.03);
    EXPECT_LE(d.alpha, 0.5 / 255 + 1e-5);
    EXPECT_LE(d.rotation, 0.04);
    EXPECT_LE(d.dc, 0.02);
    EXPECT_LE(d.sh, 0.01);  // one palette entry per Gaussian: only the codebook quantises
  }
}

TEST(Sog, ReadsAFolderWithMetaJsonAndRefusesNamesOutsideIt) {
  const fs::path d = fs::temp_directory_path() / ("isegman_sog_" + std::to_string(::getpid()));
  fs::create_directories(d);
  const GaussianScene s = plausible_scene(100, 1, 4);
  const std::vector<uint8_t> zipped = serialize_sog(s);
  // Unpack through the zip reader's own output: write each member by re-encoding.
  const GaussianScene from_zip = parse_sog_zip(zipped.data(), zipped.size(), "z.sog");
  write_file_atomic((d / "scene.sog").string(), zipped);
  EXPECT_FALSE(is_sog_dir((d / "scene.sog").string()));
  write_file_atomic((d / "meta.json").string(), std::string(R"({"version":2,"count":1,"means":{"mins":[0,0,0],)"
                                                            R"("maxs":[1,1,1],"files":["../secret.webp","x.webp"]},)"
                                                            R"("scales":{"codebook":[],"files":[]},"quats":{"files":[]},)"
                                                            R"("sh0":{"codebook":[],"files":[]}})"));
  EXPECT_TRUE(is_sog_dir(d.string()));
  try {
    read_sog_dir(d.string());
    ADD_FAILURE() << "accepted a file name outside the folder";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("outside its folder"), std::string::npos) << e.what();
  }
  EXPECT_EQ(from_zip.size(), 100u);
  fs::remove_all(d);
}

TEST(Sog, CorruptArchivesNameTheFileAndNeverCrash) {
  const GaussianScene s = plausible_scene(64, 2, 8);
  const std::vector<uint8_t> bytes = serialize_sog(s);
  for (size_t cut : {size_t(4), size_t(100), bytes.size() / 2, bytes.size() - 1}) {
    try {
      parse_sog_zip(bytes.data(), cut, "cut.sog");
      ADD_FAILURE() << "accepted an archive cut at " << cut;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("cut.sog: ", 0), 0u) << e.what();
    }
  }
  SplitMix64 r(2);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<uint8_t> bad = bytes;
    for (int k = 0; k < 4; ++k) bad[r.next() % bad.size()] ^= uint8_t(1 + r.next() % 255);
    try {
      parse_sog_zip(bad.data(), bad.size(), "flipped.sog");
    } catch (const Error&) {
    }
  }
}

}  // namespace
}  // namespace isegman
