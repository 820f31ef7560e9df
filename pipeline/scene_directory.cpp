#include "pipeline/scene_directory.hpp"

#include "common/atomic_file.hpp"
#include "common/temporary_name.hpp"

#include <fcntl.h>
#include <stdio.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cerrno>
#include <fstream>
#include <iterator>
#include <string_view>
#include <system_error>
#include <vector>

namespace toonwater {
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
    struct stat held {
    }, named{};
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

// Where a forced run keeps the files its scene replaces until every file is in place.
constexpr const char* replaced_aside = ".replaced";

// A killed run's staging directory of the scene `target`, as a later run finds it. Killed just
// after the swap, it holds the earlier scene with the files povgen did not write (a user's, or
// rendered images) still to be moved back: they go into the target now (the marker inside tells
// them from povgen's). Whether it may then be removed: not while it holds one that could not
// be moved (the target has a file of that name); it stays for the user to look at.
bool recover_user_files(const fs::path& stale, const fs::path& target) {
  std::error_code ec;
  if (!fs::is_directory(target, ec)) return true;
  const std::string marker = read_marker(stale);
  if (marker.empty()) return true;  // not a scene: a staging directory before its marker
  move_entries(stale, target, [&](const std::string& n) { return !written_by_povgen(n, marker); });
  for (const auto& entry : fs::directory_iterator(stale, ec))
    if (!written_by_povgen(entry.path().filename().string(), marker)) return false;
  return !ec;
}

// The first file of the new scene in `staging` whose name the target scene holds as a file
// povgen did not write (per `target_marker`): a clash the new scene must not resolve by
// replacing a user's file. Empty when there is none.
fs::path clashing_file(const fs::path& staging, const fs::path& target,
                       const std::string& target_marker) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(staging, ec)) {
    const std::string name = entry.path().filename().string();
    std::error_code missing;
    if (fs::symlink_status(target / name, missing).type() == fs::file_type::not_found) continue;
    if (!written_by_povgen(name, target_marker)) return target / name;
  }
  if (ec) fail(staging, "cannot list the directory", ec.value());
  return {};
}

// Gives `directory` the permission bits (setgid included) and group of `like`, as a careful
// editor keeps a file's: the new scene directory replaces the earlier one with its access.
// Best effort: a group the user is not in stays the user's.
void copy_access(const fs::path& like, const fs::path& directory) {
  struct stat status {};
  if (::stat(like.c_str(), &status) != 0) return;
  if (::chown(directory.c_str(), static_cast<uid_t>(-1), status.st_gid) != 0) {
    // Not a member of that group: the mode alone, without a setgid bit for a foreign group.
    status.st_mode &= ~static_cast<mode_t>(S_ISGID);
  }
  ::chmod(directory.c_str(), status.st_mode & 07777);
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
    // A killed run's staging directory of this scene gives back what it holds of the user's.
    remove_stale_temporaries(parent, [&](const fs::path& stale) {
      std::string made_for;
      return !is_own_temporary(stale.filename().string(), &made_for) || made_for != name ||
             recover_user_files(stale, target_);
    });
    staging_ = parent / temporary_name(name);
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
  const bool target_exists = fs::exists(target_, ec);
  const std::string target_marker = target_exists ? read_marker(target_) : std::string();
  if (target_exists && !merge_into_target_) {
    const fs::path clash = clashing_file(staging_, target_, target_marker);
    if (!clash.empty())
      fail(clash,
           "is not a file toonwater povgen wrote, and the new scene has a file of that "
           "name; rename or move it (nothing was replaced)");
  }
  if (merge_into_target_) {
    // Forced into a directory of other files: the files are moved in one by one (scene.pov
    // last), each namesake they replace kept aside in the staging directory until all are in;
    // if one cannot be moved, the others are taken out again and the namesakes put back.
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(staging_, ec)) files.push_back(entry.path());
    if (ec) fail(staging_, "cannot list the directory", ec.value());
    std::stable_partition(files.begin(), files.end(),
                          [](const fs::path& p) { return p.filename() != "scene.pov"; });
    const fs::path aside = staging_ / replaced_aside;
    std::vector<std::uint8_t> replaced(files.size(), 0);
    auto undo = [&](std::size_t moved) {
      std::error_code ignored;
      for (std::size_t j = 0; j < moved; ++j) {
        fs::rename(target_ / files[j].filename(), files[j], ignored);
        if (replaced[j])
          fs::rename(aside / files[j].filename(), target_ / files[j].filename(), ignored);
      }
    };
    for (std::size_t i = 0; i < files.size(); ++i) {
      const fs::path destination = target_ / files[i].filename();
      std::error_code missing;
      if (fs::symlink_status(destination, missing).type() != fs::file_type::not_found) {
        if (!fs::exists(aside)) fs::create_directory(aside, ec);
        if (!ec) fs::rename(destination, aside / files[i].filename(), ec);
        replaced[i] = !ec;
      }
      if (!ec) fs::rename(files[i], destination, ec);
      if (!ec) continue;
      const int error = ec.value();
      if (replaced[i]) fs::rename(aside / files[i].filename(), destination, missing);
      replaced[i] = 0;
      undo(i);
      fail(destination, "cannot move into place (nothing was replaced)", error);
    }
  } else if (!target_exists) {
    if (::rename(staging_.c_str(), target_.c_str()) != 0) fail(target_, "cannot create", errno);
  } else {
    copy_access(target_, staging_);
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) != 0) {
      // A file system without the exchange: two renames, between which DIR is briefly absent.
      const int error = errno;
      if (error != EINVAL && error != ENOSYS) fail(target_, "cannot replace the directory", error);
      const fs::path old = target_.parent_path() / temporary_name(target_.filename().string());
      if (::rename(target_.c_str(), old.c_str()) != 0)
        fail(target_, "cannot replace the directory", errno);
      if (::rename(staging_.c_str(), target_.c_str()) != 0) {
        const int e = errno;
        ::rename(old.c_str(), target_.c_str());
        fail(target_, "cannot replace the directory", e);
      }
      staging_ = old;
    }
    // staging_ now holds the earlier scene: keep what povgen did not write there (a run killed
    // here leaves them to the next, recover_user_files).
    move_entries(staging_, target_,
                 [&](const std::string& n) { return !written_by_povgen(n, target_marker); });
    for (const auto& entry : fs::directory_iterator(staging_, ec))
      if (!written_by_povgen(entry.path().filename().string(), target_marker)) {
        // One could not be moved back: the earlier scene stays whole for a later run to
        // recover, rather than lose it.
        staging_.clear();
        return;
      }
  }
  fs::remove_all(staging_, ec);
  staging_.clear();
}

}  // namespace toonwater
