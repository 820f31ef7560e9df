// A scene directory replaced whole or not at all. povgen writes a new scene into a hidden
// sibling ".NAME.tmp-PID" and, once every file is complete, swaps it with DIR in one
// rename(2) (renameat2 RENAME_EXCHANGE): a reader sees the earlier scene or the new one, never a
// mix, and a failed, interrupted or killed run leaves the earlier scene exactly as it was (a
// killed run's sibling is removed by the next run, remove_stale_temporaries).
//
// DIR/.toonwater-scene marks a directory povgen wrote. povgen refuses to write into a non-empty
// directory without it (a user's own directory, "/", a home directory) unless forced; forced,
// it moves its files into DIR one by one (each rename atomic, scene.pov last) and leaves every
// other file there alone. A sibling lock file ".NAME.lock" (flock) keeps two runs from writing
// one directory at once: the second fails at once with a clear error.
//
// Files in an earlier scene directory that povgen did not write (rendered images, logs, a
// user's notes) are moved into the new one, unless the new scene has a file of that name. The
// marker lists the files povgen wrote, so a user's file is kept whatever its name.
#pragma once

#include <filesystem>
#include <string>

namespace toonwater::povgen {

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

}  // namespace toonwater::povgen
