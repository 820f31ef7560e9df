// Atomic writes: the target gets exactly the new content; on failure the target is untouched,
// the error names it, and no temporary file is left behind.
#include "common/atomic_file.hpp"
#include "common/temporary_name.hpp"

#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <string>
#include <vector>

namespace toonwater {
namespace {

namespace fs = std::filesystem;
using test::entries;
using test::read_text;
using test::ScratchDir;
using test::temporary_name_of_a_gone_process;
using test::write_text;

// The OutputError message of writing `contents` to `path`, or "" when it succeeds.
std::string write_error(const fs::path& path, std::string_view contents) {
  try {
    write_file_atomically(path, contents);
  } catch (const OutputError& e) {
    return e.what();
  }
  return {};
}

TEST(NewDirectories, RemovesTheDirectoriesItFoundMissingWhileTheyAreEmpty) {
  const ScratchDir dir;
  fs::create_directory(dir / "kept");
  const NewDirectories made(dir / "kept" / "a" / "b" / "c");
  fs::create_directories(dir / "kept" / "a" / "b" / "c");
  made.remove_empty();
  EXPECT_FALSE(fs::exists(dir / "kept" / "a"));
  EXPECT_TRUE(fs::is_directory(dir / "kept")) << "it existed before";

  // A file put there meanwhile keeps its directory and those above it.
  const NewDirectories again(dir / "kept" / "a" / "b" / "c" / "");
  fs::create_directories(dir / "kept" / "a" / "b" / "c");
  write_text(dir / "kept" / "a" / "b" / "other.txt", "someone else's");
  again.remove_empty();
  EXPECT_FALSE(fs::exists(dir / "kept" / "a" / "b" / "c"));
  EXPECT_EQ(read_text(dir / "kept" / "a" / "b" / "other.txt"), "someone else's");

  // Nothing was missing: nothing goes.
  const NewDirectories none(dir / "kept");
  none.remove_empty();
  EXPECT_TRUE(fs::is_directory(dir / "kept"));
  NewDirectories(fs::path()).remove_empty();  // no directory given
}

TEST(AtomicFile, CreatesAndReplacesContent) {
  ScratchDir dir;
  const fs::path target = dir / "out.csv";
  write_file_atomically(target, std::string(100000, 'a'));
  EXPECT_EQ(read_text(target), std::string(100000, 'a'));
  const std::string binary("new\0content\n", 12);
  write_file_atomically(target, binary);
  EXPECT_EQ(read_text(target), binary);
  write_file_atomically(target, "");
  EXPECT_EQ(read_text(target), "");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>({"out.csv"}));
}

TEST(AtomicFile, LongestFileNameWorks) {
  ScratchDir dir;
  const std::string name(255, 'n');
  write_file_atomically(dir / name, "long");
  EXPECT_EQ(read_text(dir / name), "long");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>({name}));
}

TEST(AtomicFile, RelativePathWritesIntoTheCurrentDirectory) {
  ScratchDir dir;
  const fs::path previous = fs::current_path();
  fs::current_path(dir.path());
  write_file_atomically("relative.txt", "here");
  fs::current_path(previous);
  EXPECT_EQ(read_text(dir / "relative.txt"), "here");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>({"relative.txt"}));
}

TEST(AtomicFile, MissingDirectoryFailsNamingTheFile) {
  ScratchDir dir;
  const fs::path target = dir / "missing" / "out.csv";
  const std::string message = write_error(target, "data");
  EXPECT_EQ(message.rfind(target.string() + ": ", 0), 0u) << message;
  EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
  EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(AtomicFile, DirectoryTargetIsRefusedBeforeWriting) {
  ScratchDir dir;
  const fs::path target = dir / "out.csv";
  fs::create_directory(target);
  write_text(target / "kept.txt", "good");
  const std::string message = write_error(target, "new content");
  EXPECT_EQ(message, target.string() + ": is a directory");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>({"out.csv"}));
  EXPECT_EQ(read_text(target / "kept.txt"), "good");
}

TEST(AtomicFile, FailedReplaceKeepsTheTargetAndLeavesNoTemporary) {
  // The target becomes a non-empty directory while the file is written, which rename() cannot
  // replace: the failure comes at the last step, after the temporary file exists.
  ScratchDir dir;
  const fs::path target = dir / "out.csv";
  AtomicFileWriter file(target);
  file.write("new content");
  fs::create_directory(target);
  write_text(target / "kept.txt", "good");
  try {
    file.commit();
    ADD_FAILURE() << "no error";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(target.string() + ": cannot replace the file: ", 0), 0u)
        << e.what();
  }
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>({"out.csv"}));
  EXPECT_EQ(read_text(target / "kept.txt"), "good");
}

TEST(AtomicFile, BatchReplacesAllOrNone) {
  ScratchDir dir;
  write_text(dir / "a.csv", "old a");
  {
    OutputBatch batch;
    write_file_atomically(dir / "a.csv", "new a");
    EXPECT_EQ(read_text(dir / "a.csv"), "old a") << "renamed only by the batch";
    EXPECT_THROW(write_file_atomically(dir / "missing" / "b.csv", "b"), OutputError);
  }  // not committed: a.csv stays
  EXPECT_EQ(read_text(dir / "a.csv"), "old a");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>({"a.csv"}));
  {
    OutputBatch batch;
    write_file_atomically(dir / "a.csv", "new a");
    write_file_atomically(dir / "b.csv", "new b");
    batch.commit();
  }
  EXPECT_EQ(read_text(dir / "a.csv"), "new a");
  EXPECT_EQ(read_text(dir / "b.csv"), "new b");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>({"a.csv", "b.csv"}));
}

TEST(AtomicFile, LinksAreWrittenThroughAndStaleTemporariesRemoved) {
  ScratchDir dir;
  write_text(dir / "target.csv", "old");
  fs::create_symlink("target.csv", dir / "link.csv");
  write_file_atomically(dir / "link.csv", "new");
  EXPECT_TRUE(fs::is_symlink(dir / "link.csv"));
  EXPECT_EQ(read_text(dir / "target.csv"), "new");

  // Removed: a killed run's temporary. Kept: this process's, a user's file that looks like a
  // temporary (no valid check), and names whose name or fields were changed after the check.
  const std::string stale = temporary_name_of_a_gone_process("out.csv");
  const std::string live = temporary_name("out.csv");
  const pid_t gone = ::fork();
  if (gone == 0) ::_exit(0);
  ::waitpid(gone, nullptr, 0);
  const std::string look_alike = ".out.csv.tmp-" + std::to_string(gone) + "-3";
  std::string renamed = stale;
  renamed.replace(1, 3, "abc");  // ".abc.csv.tmp-…": the check was made for another name
  std::string foreign = temporary_name_of_a_gone_process("out.csv");
  foreign.replace(foreign.find(".tmp-") + 5, 8, "00000000");  // the host's hash changed
  for (const std::string& name : {stale, live, look_alike, renamed, foreign})
    write_text(dir / name, "something");
  remove_stale_temporaries(dir.path());
  EXPECT_FALSE(fs::exists(dir / stale));
  EXPECT_TRUE(fs::exists(dir / live));
  EXPECT_TRUE(fs::exists(dir / look_alike)) << "a user's file is not a temporary";
  EXPECT_TRUE(fs::exists(dir / renamed));
  EXPECT_TRUE(fs::exists(dir / foreign));
}

TEST(AtomicFile, PathWithoutFileNameIsRejected) {
  ScratchDir dir;
  const std::string message = write_error(dir.path() / "", "data");
  EXPECT_NE(message.find("not a file name"), std::string::npos) << message;
  EXPECT_TRUE(entries(dir.path()).empty());
}

}  // namespace
}  // namespace toonwater
