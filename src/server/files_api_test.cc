// API tests of the files of the web app: export in every format io writes (download
// and on the server), the data folder's scenes listed for combine, and uploads.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/gaussian_file.h"
#include "io/ply.h"
#include "io/scene_loader.h"
#include "server/test_server.h"

namespace fs = std::filesystem;

namespace isegman::server {
namespace {

std::string ply_bytes(const GaussianScene& g) {
  const std::vector<uint8_t> b = serialize_gaussians(g, SplatFormat::kPly);
  return std::string(b.begin(), b.end());
}

TEST(FilesApi, ExportsEveryFormatIoWrites) {
  DemoScene d = small_demo();
  const size_t n = d.bundle.gaussians.size();
  const std::string dir = temp_dir("files-export");
  Running s(d.bundle, no_segmentation(dir + "/out"));
  for (const std::string f : {"ply", "compressed.ply", "splat", "spz", "sog"}) {
    auto r = s.client->Get(("/api/export?format=" + f).c_str());
    ASSERT_TRUE(r) << f;
    ASSERT_EQ(r->status, 200) << f << ": " << r->body.substr(0, 200);
    EXPECT_NE(r->get_header_value("Content-Disposition").find("edited." + f), std::string::npos);
    const auto* data = reinterpret_cast<const uint8_t*>(r->body.data());
    const SplatFormat got = detect_splat_format(data, r->body.size(), f);
    EXPECT_EQ(got, output_format_for_path("x." + f)) << f;
    EXPECT_EQ(parse_gaussians(data, r->body.size(), got, f).size(), n) << f;
  }
  s.get_json("/api/export?format=obj", 400);
  for (const std::string name : {"a.sog", "b.compressed.ply", "c.spz"}) {
    const json w = s.post_json("/api/export", json{{"path", name}}.dump());
    EXPECT_EQ(load_gaussians(w["path"].get<std::string>()).scene.size(), n) << name;
  }
}

TEST(FilesApi, ListsTheDataFolderAndCombinesUploads) {
  DemoScene d = small_demo();
  const size_t n = d.bundle.gaussians.size();
  const std::string dir = temp_dir("files-list");
  const std::string data = dir + "/data";
  std::vector<bool> few(n, false);
  for (size_t i = 0; i < n; i += 10) few[i] = true;
  const GaussianScene part = d.bundle.gaussians.subset(few);
  fs::create_directories(data + "/sub/deeper");
  fs::create_directories(dir + "/outside");
  write_ply(data + "/a.ply", part);
  write_gaussians(data + "/sub/b.spz", part, {});
  write_ply(data + "/.hidden.ply", part);
  write_ply(dir + "/outside/secret.ply", part);
  fs::create_symlink(dir + "/outside/secret.ply", data + "/link.ply");
  fs::create_directory_symlink(dir + "/outside", data + "/linkdir");
  write_scene_dir(data + "/scene_folder", part, d.bundle.cameras, 7);
  { std::ofstream(data + "/notes.txt") << "not a scene"; }

  AppOptions o = no_segmentation(dir + "/out");
  o.data_dir = data;
  o.max_upload_bytes = 4 << 20;
  Running s(d.bundle, o);
  const json f = s.get_json("/api/files");
  std::vector<std::string> names;
  for (const json& e : f["files"]) names.push_back(e["name"].get<std::string>());
  EXPECT_EQ(names, (std::vector<std::string>{"a.ply", "scene_folder", "sub/b.spz"}));
  EXPECT_EQ(f["files"][1]["kind"], "folder");
  EXPECT_EQ(f["uploads"].size(), 0u);
  EXPECT_EQ(f["max_upload_bytes"].get<uint64_t>(), uint64_t(4) << 20);

  // Combine a listed file, then an uploaded one.
  EXPECT_EQ(s.post_json("/api/edit/combine", R"({"path": "sub/b.spz"})")["gaussians"].get<size_t>(), n + part.size());
  auto up = s.client->Post("/api/upload?name=../my%20part.ply", ply_bytes(part), "application/octet-stream");
  ASSERT_TRUE(up);
  ASSERT_EQ(up->status, 200) << up->body;
  const json u = json::parse(up->body);
  EXPECT_EQ(u["name"], "mypart.ply");  // base name, odd characters dropped
  EXPECT_EQ(u["gaussians"].get<size_t>(), part.size());
  auto up2 = s.client->Post("/api/upload?name=mypart.ply", ply_bytes(part), "application/octet-stream");
  ASSERT_TRUE(up2);
  EXPECT_EQ(json::parse(up2->body)["name"], "mypart-2.ply");
  EXPECT_EQ(s.get_json("/api/files")["uploads"].size(), 2u);
  const json c = s.post_json("/api/edit/combine", R"({"upload": "mypart-2.ply", "translate": [0, 0, 1]})");
  EXPECT_EQ(c["gaussians"].get<size_t>(), n + 2 * part.size());
  EXPECT_EQ(c["selected"].get<size_t>(), part.size());
  // One history step each: undo takes the upload's Gaussians out again.
  EXPECT_EQ(s.post_json("/api/undo", "")["gaussians"].get<size_t>(), n + part.size());

  // Refused: unknown upload, both sources, garbage, an empty body, no name, too large.
  s.post_json("/api/edit/combine", R"({"upload": "nope.ply"})", 404);
  s.post_json("/api/edit/combine", R"({"upload": "mypart.ply", "path": "a.ply"})", 400);
  s.post_json("/api/edit/combine", R"({"path": "link.ply"})", 400);
  auto bad = s.client->Post("/api/upload?name=x.ply", std::string("ply\nformat garbage\n"), "application/octet-stream");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400) << bad->body;
  auto empty = s.client->Post("/api/upload?name=x.ply", std::string(), "application/octet-stream");
  ASSERT_TRUE(empty);
  EXPECT_EQ(empty->status, 400);
  auto noname = s.client->Post("/api/upload", ply_bytes(part), "application/octet-stream");
  ASSERT_TRUE(noname);
  EXPECT_EQ(noname->status, 400);
  auto big = s.client->Post("/api/upload?name=big.ply", std::string(5 << 20, 'x'), "application/octet-stream");
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 400) << big->body;  // over the app's limit
  // The HTTP layer's limit answers 413 from the head, and other routes keep their 1 MiB.
  auto json_big = s.client->Post("/api/select/box", std::string(2 << 20, ' '), "application/json");
  ASSERT_TRUE(json_big);
  EXPECT_EQ(json_big->status, 413);
}

TEST(FilesApi, UploadLimitOfTheHttpLayer) {
  DemoScene d = small_demo();
  HttpLimits limits;
  limits.max_upload_bytes = 1 << 16;
  Running s(d.bundle, no_segmentation(temp_dir("files-limit")), limits);
  auto big = s.client->Post("/api/upload?name=big.ply", std::string(1 << 17, 'x'), "application/octet-stream");
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);
}

}  // namespace
}  // namespace isegman::server
