#include "io/gaussian_file.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/format_test_util.h"
#include "io/ply.h"
#include "io/scene_loader.h"
#include "io/sog.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

using testing_formats::differences;
using testing_formats::plausible_scene;

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("isegman_gaussian_file_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

TEST(GaussianFile, WritesByExtensionAndReadsByContent) {
  const fs::path d = temp_dir();
  const GaussianScene s = plausible_scene(500, 3, 1);
  const struct {
    const char* name;
    SplatFormat format;
    int degree;
  } cases[] = {{"a.ply", SplatFormat::kPly, 3},
               {"a.compressed.ply", SplatFormat::kCompressedPly, 3},
               {"a.splat", SplatFormat::kSplat, 0},
               {"a.spz", SplatFormat::kSpz, 3},
               {"A.SPZ", SplatFormat::kSpz, 3}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = (d / c.name).string();
    EXPECT_EQ(output_format_for_path(path), c.format);
    std::vector<uint32_t> order;
    write_gaussians(path, s, {}, nullptr, &order);
    // Same bytes under a misleading name: detected by content, with a note.
    const std::string renamed = (d / (std::string(c.name) + ".bin")).string();
    fs::copy_file(path, renamed, fs::copy_options::overwrite_existing);
    for (const std::string& p : {path, renamed}) {
      const LoadedGaussians l = load_gaussians(p);
      EXPECT_EQ(l.format, c.format);
      EXPECT_EQ(l.scene.sh_degree, c.degree);
      ASSERT_EQ(l.scene.size(), s.size());
      EXPECT_LT(differences(s, l.scene, order).position, 5e-3);
    }
  }
  const std::string ply = (d / "x.ply").string();
  const std::string spz_named_ply = (d / "y.ply").string();
  write_file_atomic(spz_named_ply, serialize_gaussians(s, SplatFormat::kSpz));
  const LoadedGaussians l = load_gaussians(spz_named_ply);
  EXPECT_EQ(l.format, SplatFormat::kSpz);
  ASSERT_FALSE(l.notes.empty());
  EXPECT_NE(l.notes[0].find("content is .spz"), std::string::npos);
  EXPECT_THROW(output_format_for_path((d / "x.obj").string()), Error);
  EXPECT_THROW(write_gaussians(spz_named_ply, s, {spz_named_ply}), Error);  // never over an input
  fs::remove_all(d);
}

TEST(GaussianFile, SceneDirectoriesAndBareSplatFilesLoadWithVirtualViews) {
  const fs::path d = temp_dir();
  const GaussianScene s = plausible_scene(300, 1, 2);
  write_scene_dir((d / "scene").string(), s, {});
  const LoadedGaussians l = load_gaussians((d / "scene").string());
  EXPECT_EQ(l.format, SplatFormat::kPly);
  EXPECT_NE(l.file.find("point_cloud.ply"), std::string::npos);
  write_gaussians((d / "bare.spz").string(), s, {});
  SceneLoadOptions opt;
  opt.virtual_views.count = 8;
  std::vector<std::string> notes;
  opt.notes = &notes;
  const SceneBundle b = load_scene((d / "bare.spz").string(), opt);
  ASSERT_EQ(b.cameras.size(), 8u);
  EXPECT_EQ(b.cameras[0].name, "virtual_000");
  EXPECT_EQ(b.cameras[7].name, "virtual_007");
  EXPECT_FALSE(notes.empty());
  opt.virtual_views_when_missing = false;
  EXPECT_THROW(load_scene((d / "bare.spz").string(), opt), Error);
  fs::remove_all(d);
}

TEST(GaussianFile, ACaptureFolderWithNotesIsNotTakenForSogAndNamesItsSceneBelow) {
  // A capture's folder as the fixtures lay it out: meta.json (the trainer's notes), scene/.
  const fs::path d = temp_dir();
  write_scene_dir((d / "scene").string(), plausible_scene(50, 0, 3), {});
  write_file_atomic((d / "meta.json").string(), std::string(R"({"trainer":"opensplat","train_psnr":29.4})"));
  EXPECT_FALSE(is_sog_dir(d.string()));
  try {
    load_scene(d.string());
    ADD_FAILURE() << "loaded a folder without a point cloud";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find("SOG"), std::string::npos) << what;
    EXPECT_NE(what.find("one level down: " + (d / "scene").string()), std::string::npos) << what;
  }
  // SOG's own meta.json (it has "means") still makes the folder a SOG folder.
  write_file_atomic((d / "meta.json").string(), std::string(R"({"version":2,"means":{}})"));
  EXPECT_TRUE(is_sog_dir(d.string()));
  fs::remove_all(d);
}

TEST(GaussianFile, RejectsWhatIsNoSplatFile) {
  const uint8_t text[] = "hello world, not a scene at all!";
  EXPECT_THROW(detect_splat_format(text, 32, "t.txt"), Error);
  EXPECT_THROW(detect_splat_format(text, 0, "t.txt"), Error);
  EXPECT_THROW(load_gaussians("/nonexistent/scene.spz"), Error);
}

}  // namespace
}  // namespace isegman
