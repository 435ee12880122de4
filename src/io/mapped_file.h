// A file mapped read-only into memory, for parsing large scene files without holding a
// second copy: parsed ranges can be dropped from the process's memory again (release), so
// a parse's peak is the parsed result plus the part of the file not yet parsed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace isegman {

class MappedFile {
 public:
  // Maps `path`; files that cannot be mapped (empty, special) are read into memory instead.
  explicit MappedFile(const std::string& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  const uint8_t* data() const { return data_; }
  size_t size() const { return size_; }
  // Bytes [offset, offset + length) will not be read again: their whole pages leave the
  // process's resident memory (they are read from the file again if touched). Thread safe.
  void release(size_t offset, size_t length) const;

 private:
  const uint8_t* data_ = nullptr;
  size_t size_ = 0;
  void* map_ = nullptr;
  std::vector<uint8_t> copy_;  // when the file could not be mapped
};

}  // namespace isegman
