#include "core/output_plan.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/error.h"

namespace fs = std::filesystem;

namespace isegman {

OutputPlan::Entry OutputPlan::resolve(const std::string& path, const std::string& what, bool is_output) {
  if (path.empty()) throw Error(what + ": empty path");
  if (path.find('\0') != std::string::npos) throw Error(what + ": the path contains a NUL character");
  Entry e;
  e.path = path;
  e.what = what;
  std::error_code ec;
  // Not normalised lexically: "link/../x" must mean what the kernel makes of it.
  const fs::path abs = fs::absolute(path, ec);
  if (ec) throw Error(path, "cannot resolve: " + ec.message());
  // For an output the last component is replaced by rename (a symlink there is replaced,
  // not followed), so only its folder is resolved; an input is resolved completely.
  fs::path head = is_output ? abs.parent_path() : abs, tail = is_output ? abs.filename() : fs::path();
  if (is_output && (tail.empty() || tail == "." || tail == ".."))
    throw Error(path, what + ": names a folder, not a file");
  // Deepest existing ancestor: realpath it, keep the rest (which does not exist yet, so
  // cannot be a symlink) as written.
  fs::path rest;
  while (!head.empty()) {
    struct stat st;
    if (::lstat(head.c_str(), &st) == 0) break;
    rest = head.filename() / rest;
    if (head == head.parent_path()) break;
    head = head.parent_path();
  }
  fs::path real = fs::canonical(head, ec);
  if (ec) real = head;
  e.resolved = (real / rest / tail).lexically_normal().string();
  while (!e.resolved.empty() && e.resolved.size() > 1 && e.resolved.back() == '/') e.resolved.pop_back();
  e.target = e.resolved;
  struct stat st;
  if (::stat(e.resolved.c_str(), &st) == 0) {  // follows a final symlink: what it leads to
    e.exists = true;
    e.dev = st.st_dev;
    e.ino = st.st_ino;
    if (is_output && S_ISDIR(st.st_mode)) throw Error(path, what + ": names a folder, not a file");
    const fs::path t = fs::canonical(e.resolved, ec);
    if (!ec) e.target = t.string();
  }
  return e;
}

// Indexed by path and by (st_dev, st_ino), so a render of thousands of cameras checks
// each output against thousands of photos in logarithmic time.
const OutputPlan::Entry* OutputPlan::find(const Index& index, const Entry& e) {
  auto hit = index.by_path.find(e.resolved);
  if (hit == index.by_path.end()) hit = index.by_path.find(e.target);
  if (hit != index.by_path.end()) return &hit->second;
  if (e.exists) {
    auto id = index.by_inode.find({e.dev, e.ino});
    if (id != index.by_inode.end()) return &id->second;
  }
  return nullptr;
}

void OutputPlan::add(Index& index, const Entry& e) {
  index.by_path.emplace(e.resolved, e);
  index.by_path.emplace(e.target, e);
  if (e.exists) index.by_inode.emplace(std::make_pair(e.dev, e.ino), e);
}

void OutputPlan::input(const std::string& path, const std::string& what) {
  if (path.empty()) return;
  const Entry e = resolve(path, what, false);
  if (const Entry* o = find(outputs_, e))
    throw Error(o->path, "refusing to overwrite an input: the " + o->what + " is the same file as the " + what +
                             " (" + path + "); choose another output path");
  add(inputs_, e);
}

void OutputPlan::output(const std::string& path, const std::string& what) {
  const Entry e = resolve(path, what, true);
  if (const Entry* in = find(inputs_, e))
    throw Error(path, "refusing to overwrite an input: the " + what + " is the same file as the " + in->what +
                          " (" + in->path + "); choose another output path");
  if (const Entry* o = find(outputs_, e))
    throw Error(path, "two outputs name the same file: the " + what + " and the " + o->what + " (" + o->path +
                          "); give them different paths");
  add(outputs_, e);
  dirs_.insert(fs::path(e.resolved).parent_path().string());
}

void OutputPlan::prepare() const {
  for (const std::string& d : dirs_) {
    const fs::path dir = d;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error(dir.string(), "cannot create the folder for the outputs: " + ec.message());
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
      throw Error(dir.string(), std::string("cannot write the outputs here: ") + std::strerror(errno));
  }
}

std::string camera_file_stem(const std::string& name) {
  const std::string who = "camera name '" + name.substr(0, 80) + "'";
  if (name.empty()) throw Error(who + ": empty, cannot be used as a file name");
  if (name.size() > 200) throw Error(who + "...: longer than 200 bytes, cannot be used as a file name");
  std::string stem;
  for (char c : name) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      throw Error(who + ": contains a control character, cannot be used as a file name");
    stem += (c == '/' || c == '\\') ? '_' : c;
  }
  if (stem == "." || stem == "..") throw Error(who + ": cannot be used as a file name");
  return stem;
}

}  // namespace isegman
