#include "io/mapped_file.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/error.h"
#include "core/test_dirs.h"

namespace isegman {
namespace {

std::string write_bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  return path;
}

TEST(MappedFile, ReadsTheFileAndReleasedRangesReadBackTheSame) {
  const std::string dir = testing::fresh_temp_dir("isegman-mapped-", "read");
  std::vector<uint8_t> bytes(3 * 4096 * 7 + 123);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = uint8_t((i * 131) ^ (i >> 9));
  const MappedFile f(write_bytes(dir + "/data.bin", bytes));
  ASSERT_EQ(f.size(), bytes.size());
  EXPECT_EQ(std::vector<uint8_t>(f.data(), f.data() + f.size()), bytes);
  // Released pages leave memory, not the file: touched again, they hold the same bytes.
  f.release(100, 5 * 4096);
  f.release(4096 * 10, bytes.size());  // past the end is clipped
  f.release(bytes.size() + 1, 10);
  EXPECT_EQ(std::vector<uint8_t>(f.data(), f.data() + f.size()), bytes);
}

TEST(MappedFile, EmptyFilesAndBadPaths) {
  const std::string dir = testing::fresh_temp_dir("isegman-mapped-", "bad");
  const MappedFile empty(write_bytes(dir + "/empty.bin", {}));
  EXPECT_EQ(empty.size(), 0u);
  empty.release(0, 10);
  EXPECT_THROW(MappedFile{dir + "/missing.bin"}, Error);
  EXPECT_THROW(MappedFile{dir}, Error);  // a directory
  EXPECT_THROW(MappedFile{testing::path_with_nul(dir)}, Error);
}

}  // namespace
}  // namespace isegman
