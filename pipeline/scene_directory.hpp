// A scene directory replaced whole or not at all. povgen writes a new scene into a hidden
// sibling (temporary_name.hpp) and, once every file is complete, swaps it with DIR in one
// rename(2) (renameat2 RENAME_EXCHANGE): a reader sees the earlier scene or the new one, never a
// mix, and a failed, interrupted or killed run leaves the earlier scene exactly as it was. The
// new directory takes the earlier one's permissions, group and setgid bit.
//
// DIR/.toonwater-scene marks a directory povgen wrote. povgen refuses to write into a non-empty
// directory without it (a user's own directory, "/", a home directory) unless forced; forced,
// it moves its files into DIR one by one (each rename atomic, scene.pov last), replacing their
// namesakes, and leaves every other file there alone; if one cannot be moved, the others are
// taken out again and the namesakes put back. A sibling lock file
// ".NAME.lock" (flock) keeps two runs from writing one directory at once: the second fails at
// once with a clear error.
//
// Files in an earlier scene directory that povgen did not write (rendered images, logs, a
// user's notes) are moved into the new one. The marker lists the files povgen wrote, so a
// user's file is known whatever its name; a new scene with a file of the same name as one of
// them (an object named "mine" beside a hand-written obj_mine.inc) is an error, before
// anything is replaced. A run killed after the swap leaves those files in the hidden sibling;
// the next run moves them back before it removes the sibling.
#pragma once

#include <filesystem>
#include <string>

namespace toonwater {

class SceneDirectory {
 public:
  // Checks `target`, takes the lock, removes stale siblings and creates the staging directory.
  // Throws OutputError naming `target`.
  SceneDirectory(std::filesystem::path target, bool force);
  ~SceneDirectory();  // not committed: removes the staging directory; releases the lock
  SceneDirectory(const SceneDirectory&) = delete;
  SceneDirectory& operator=(const SceneDirectory&) = delete;

  // Where the new scene's files go until commit().
  const std::filesystem::path& staging() const { return staging_; }
  // Puts the new scene in place of the target. Throws OutputError (the target as it was).
  void commit();

 private:
  void release();  // removes the staging directory (if any) and the lock
  std::filesystem::path target_, staging_, lock_path_;
  bool merge_into_target_ = false;  // forced over a directory povgen did not write
  int lock_fd_ = -1;
};

// The name of the marker file.
inline constexpr const char* scene_marker = ".toonwater-scene";

}  // namespace toonwater
