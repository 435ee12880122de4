#include "io/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"
#include "io/atomic_file.h"

namespace isegman {

MappedFile::MappedFile(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) throw Error(path, std::string("cannot open: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw Error(path, "is a directory, expected a file");
  if (S_ISREG(st.st_mode) && st.st_size > 0) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw Error(path, std::string("cannot open for reading: ") + std::strerror(errno));
    void* m = ::mmap(nullptr, size_t(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
    ::close(fd);  // the mapping keeps the file
    if (m != MAP_FAILED) {
      ::madvise(m, size_t(st.st_size), MADV_SEQUENTIAL);
      map_ = m;
      data_ = static_cast<const uint8_t*>(m);
      size_ = size_t(st.st_size);
      return;
    }
  }
  copy_ = read_file_bytes(path);
  data_ = copy_.data();
  size_ = copy_.size();
}

MappedFile::~MappedFile() {
  if (map_) ::munmap(map_, size_);
}

void MappedFile::release(size_t offset, size_t length) const {
  if (!map_ || offset >= size_) return;
  length = std::min(length, size_ - offset);
  const size_t page = size_t(::sysconf(_SC_PAGESIZE));
  const size_t begin = (offset + page - 1) / page * page;  // whole pages inside the range only
  const size_t end = offset + length == size_ ? (size_ + page - 1) / page * page : (offset + length) / page * page;
  if (end > begin) ::madvise(static_cast<uint8_t*>(map_) + begin, end - begin, MADV_DONTNEED);
}

}  // namespace isegman
