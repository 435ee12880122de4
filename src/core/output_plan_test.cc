// Issue 11 items 1-3, 6, 13: outputs never replace inputs or each other, whatever the
// spelling, camera names are safe file names, and nothing is created before the check.
#include "core/output_plan.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/test_dirs.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

std::string temp_dir(const std::string& name) { return testing::fresh_temp_dir("isegman-plan-", name); }

std::string nul_path(const std::string& d) { return testing::path_with_nul(d); }

void touch(const std::string& p) { std::ofstream(p) << "x"; }

TEST(OutputPlan, RefusesReplacingAnInputWhateverTheSpelling) {
  const std::string d = temp_dir("inputs");
  fs::create_directories(d + "/images");
  fs::create_directories(d + "/other");
  touch(d + "/images/cam0.png");
  fs::create_directory_symlink(d + "/images", d + "/imglink");
  fs::create_hard_link(d + "/images/cam0.png", d + "/other/hard.png");
  for (const std::string& out : {d + "/images/cam0.png", d + "/other/../images/cam0.png", d + "/imglink/cam0.png",
                                 d + "/other/hard.png"}) {
    OutputPlan plan;
    plan.input(d + "/images/cam0.png", "photo");
    EXPECT_THROW(plan.output(out, "render"), Error) << out;
  }
  // Relative spelling, and input registered after the output.
  const fs::path cwd = fs::current_path();
  fs::current_path(d + "/other");
  {
    OutputPlan plan;
    plan.output("../images/cam0.png", "render");
    EXPECT_THROW(plan.input(d + "/imglink/cam0.png", "photo"), Error);
  }
  fs::current_path(cwd);
  OutputPlan ok;
  ok.input(d + "/images/cam0.png", "photo");
  EXPECT_NO_THROW(ok.output(d + "/renders/cam0.png", "render"));
}

TEST(OutputPlan, RefusesTwoOutputsNamingOneFile) {
  const std::string d = temp_dir("outputs");
  OutputPlan plan;
  plan.output(d + "/sel.isel", "selection");
  EXPECT_THROW(plan.output(d + "/./sel.isel", "scene"), Error);
  EXPECT_THROW(plan.output(d + "/new/../sel.isel", "scene"), Error);
  EXPECT_THROW(plan.output(d, "scene"), Error);  // a folder
  EXPECT_THROW(plan.output(nul_path(d), "scene"), Error);
}

TEST(OutputPlan, CreatesFoldersOnlyWhenPrepared) {
  const std::string d = temp_dir("prepare");
  OutputPlan plan;
  plan.input(d + "/scene.ply", "scene");
  plan.output(d + "/a/b/out.ply", "result");
  EXPECT_FALSE(fs::exists(d + "/a"));
  plan.prepare();
  EXPECT_TRUE(fs::is_directory(d + "/a/b"));
  // An unwritable place fails at prepare, before any work (root may write anywhere).
  if (::geteuid() != 0) {
    fs::create_directories(d + "/ro");
    fs::permissions(d + "/ro", fs::perms::owner_read | fs::perms::owner_exec);
    OutputPlan ro;
    ro.output(d + "/ro/x.png", "render");
    EXPECT_THROW(ro.prepare(), Error);
  }
}

TEST(CameraFileStem, SanitisesOrRefusesUnsafeNames) {
  EXPECT_EQ(camera_file_stem("frame_0001"), "frame_0001");
  EXPECT_EQ(camera_file_stem("../../x"), ".._.._x");
  EXPECT_EQ(camera_file_stem("/etc/passwd"), "_etc_passwd");
  EXPECT_EQ(camera_file_stem("sub\\dir/img"), "sub_dir_img");
  EXPECT_THROW(camera_file_stem(""), Error);
  EXPECT_THROW(camera_file_stem(".."), Error);
  EXPECT_THROW(camera_file_stem(std::string("a\0b", 3)), Error);
  EXPECT_THROW(camera_file_stem("a\nb"), Error);
  EXPECT_THROW(camera_file_stem(std::string(300, 'a')), Error);
}

}  // namespace
}  // namespace isegman
