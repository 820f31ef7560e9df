#include "povgen/scene_directory.hpp"

#include "common/atomic_file.hpp"

#include <fcntl.h>
#include <stdio.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <iterator>
#include <string_view>
#include <system_error>
#include <vector>

namespace toonwater::povgen {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& path, const std::string& what, int error = 0) {
  throw OutputError(path.string() + ": " + what +
                    (error ? ": " + std::generic_category().message(error) : ""));
}

// The target as an absolute path without "." or ".." or a trailing separator.
fs::path normalised(const fs::path& path) {
  fs::path p = fs::absolute(path).lexically_normal();
  if (!p.has_filename() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  return p;
}

// The marker's first line; the names of the files povgen wrote follow, one a line, so that a
// later run knows them from a user's file of the same pattern (a hand-written obj_mine.inc).
constexpr std::string_view marker_header = "toonwater povgen scene directory\n";

// The marker of a scene whose files are those in `directory` (the marker among them).
std::string marker_listing(const fs::path& directory) {
  std::error_code ec;
  std::vector<std::string> names{scene_marker};
  for (const auto& entry : fs::directory_iterator(directory, ec))
    if (entry.path().filename() != scene_marker) names.push_back(entry.path().filename().string());
  if (ec) fail(directory, "cannot list the directory", ec.value());
  std::sort(names.begin(), names.end());
  std::string text(marker_header);
  for (const std::string& name : names) text += name + "\n";
  return text;
}

// Whether povgen wrote the file `name` of the scene whose marker is `marker`. A marker of an
// earlier version lists no files: the names povgen writes are taken for its own then.
bool written_by_povgen(const std::string& name, const std::string& marker) {
  if (marker.size() > marker_header.size() && marker.starts_with(marker_header))
    return marker.find("\n" + name + "\n") != std::string::npos;
  const bool include =
      name.ends_with(".inc") && (name.starts_with("water_") || name.starts_with("obj_"));
  return include || name == "scene.pov" || name == "scene.ini" || name == "toon.inc" ||
         name == scene_marker;
}

// The marker's text ("" where there is none or it cannot be read).
std::string read_marker(const fs::path& directory) {
  std::ifstream in(directory / scene_marker, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Takes an exclusive flock on `path` (created if missing); -1 when another process holds it.
// A lock file removed by its holder in between is not trusted: the lock must be on the file
// the path names now.
int take_lock(const fs::path& path) {
  for (;;) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) fail(path, "cannot create the lock file", errno);
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      ::close(fd);
      if (error == EWOULDBLOCK) return -1;
      fail(path, "cannot lock", error);
    }
    struct stat held {}, named {};
    if (::fstat(fd, &held) == 0 && ::stat(path.c_str(), &named) == 0 &&
        held.st_ino == named.st_ino && held.st_dev == named.st_dev)
      return fd;
    ::close(fd);
  }
}

// Moves the entries of `from` whose names `keep` accepts into `to`, unless `to` has one of that
// name already. Best effort: one that cannot be moved stays in `from`.
template <class Keep>
void move_entries(const fs::path& from, const fs::path& to, Keep keep) {
  std::error_code ec;
  std::vector<fs::path> entries;
  for (const auto& entry : fs::directory_iterator(from, ec)) entries.push_back(entry.path());
  for (const fs::path& entry : entries) {
    const fs::path destination = to / entry.filename();
    const bool taken = fs::symlink_status(destination, ec).type() != fs::file_type::not_found;
    if (taken || !keep(entry.filename().string())) continue;
    fs::rename(entry, destination, ec);
  }
}

}  // namespace

SceneDirectory::SceneDirectory(fs::path target, bool force) : target_(normalised(target)) {
  std::error_code ec;
  // A link to a directory: the scene replaces the directory it leads to, the link stays.
  if (fs::is_symlink(fs::symlink_status(target_, ec)) && fs::is_directory(target_, ec))
    target_ = fs::canonical(target_, ec);
  if (target_ == target_.root_path())
    fail(target_, "refusing to write a scene into the root directory");
  const fs::path parent = target_.parent_path();
  fs::create_directories(parent, ec);
  if (ec) fail(parent, "cannot create the directory", ec.value());

  const std::string name = target_.filename().string();
  lock_path_ = parent / ("." + name + ".lock");
  lock_fd_ = take_lock(lock_path_);
  if (lock_fd_ < 0)
    fail(target_, "another toonwater povgen is writing this scene directory (lock " +
                      lock_path_.filename().string() + ")");
  try {  // a constructor that throws gets no destructor call: release() by hand
    const fs::file_status status = fs::status(target_, ec);
    if (fs::exists(status)) {
      if (!fs::is_directory(status)) fail(target_, "exists and is not a directory");
      const bool marked = fs::exists(target_ / scene_marker, ec);
      const bool empty = fs::is_empty(target_, ec);
      if (ec) fail(target_, "cannot read the directory", ec.value());
      if (!marked && !empty) {
        if (!force)
          fail(target_, "is not empty and is not a toonwater scene directory (no " +
                            std::string(scene_marker) + "); give an empty or new directory, " +
                            "or --force to write the scene's files into it");
        merge_into_target_ = true;
      }
    }
    remove_stale_temporaries(parent);
    staging_ = parent / ("." + name + ".tmp-" + std::to_string(::getpid()));
    fs::remove_all(staging_, ec);
    if (!fs::create_directory(staging_, ec) || ec) {
      const int error = ec.value();
      staging_.clear();
      fail(parent, "cannot create a temporary directory", error);
    }
    write_file_atomically(staging_ / scene_marker, std::string(marker_header));
  } catch (...) {
    release();
    throw;
  }
}

SceneDirectory::~SceneDirectory() { release(); }

void SceneDirectory::release() {
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
  staging_.clear();
  if (lock_fd_ >= 0) {
    ::unlink(lock_path_.c_str());  // while still held: a waiting run re-checks the inode
    ::close(lock_fd_);
  }
  lock_fd_ = -1;
}

void SceneDirectory::commit() {
  std::error_code ec;
  write_file_atomically(staging_ / scene_marker, marker_listing(staging_));
  if (merge_into_target_) {
    // Forced into a directory of other files: each scene file replaces its namesake only.
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(staging_, ec)) files.push_back(entry.path());
    if (ec) fail(staging_, "cannot list the directory", ec.value());
    std::stable_partition(files.begin(), files.end(),
                          [](const fs::path& p) { return p.filename() != "scene.pov"; });
    for (const fs::path& file : files) {
      fs::rename(file, target_ / file.filename(), ec);
      if (ec) fail(target_ / file.filename(), "cannot move into place", ec.value());
    }
  } else if (!fs::exists(target_, ec)) {
    if (::rename(staging_.c_str(), target_.c_str()) != 0) fail(target_, "cannot create", errno);
  } else {
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) != 0) {
      // A file system without the exchange: two renames, between which DIR is briefly absent.
      const int error = errno;
      if (error != EINVAL && error != ENOSYS) fail(target_, "cannot replace the directory", error);
      const fs::path old = staging_.string() + "-old";
      if (::rename(target_.c_str(), old.c_str()) != 0)
        fail(target_, "cannot replace the directory", errno);
      if (::rename(staging_.c_str(), target_.c_str()) != 0) {
        const int e = errno;
        ::rename(old.c_str(), target_.c_str());
        fail(target_, "cannot replace the directory", e);
      }
      staging_ = old;
    }
    // staging_ now holds the earlier scene: keep what povgen did not write there.
    const std::string earlier_marker = read_marker(staging_);
    move_entries(staging_, target_,
                 [&](const std::string& n) { return !written_by_povgen(n, earlier_marker); });
  }
  fs::remove_all(staging_, ec);
  staging_.clear();
}

}  // namespace toonwater::povgen
