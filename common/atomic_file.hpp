// Writes a file so that readers only ever see the old or the complete new content: the data goes
// to a temporary file in the same directory, which is renamed over the target once complete.
// The new file keeps the owner, group and permissions of the one it replaces.
//
// Where the output goes: "-" is standard output, and so are /dev/stdout, /dev/stderr,
// /dev/fd/N and /proc/self/fd/N (the open descriptor itself); a symbolic link is followed to
// the file it leads to, which is replaced atomically while the link stays a link; a FIFO, a
// character device or a socket is written as a stream, in place (no rename is possible there).
#pragma once

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace toonwater {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run stopped by a signal between steps: what it had finished is complete, nothing is partial.
class InterruptedError : public OutputError {
 public:
  using OutputError::OutputError;
};

// A file written in pieces and put in place at once: write() appends to a temporary file beside
// the target, commit() renames it over the target. Destroyed without commit() (an exception, an
// early return), it removes the temporary file and leaves the target as it was. Every failure
// throws OutputError naming the target.
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(std::filesystem::path path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  void write(std::string_view bytes);
  void commit();

 private:
  [[noreturn]] void fail(const std::string& what, int error);
  std::filesystem::path name_;  // as given, for messages
  std::filesystem::path path_;  // the file replaced: name_ with its links followed
  std::filesystem::path temporary_;
  int fd_ = -1;
  int slot_ = -1;        // in the table remove_temporaries_on_signals() reads
  bool stream_ = false;  // written in place: standard output, a FIFO or a device
};

// All-or-nothing for a run with several outputs. While an OutputBatch exists, the commit() of
// every AtomicFileWriter (in any thread) completes its temporary file but leaves the rename to
// OutputBatch::commit(), which renames them all once every output is complete. Destroyed
// without commit(), it removes the temporary files: no output is replaced. (Streams are written
// as they go: what reached a pipe cannot be taken back.) One batch at a time.
class OutputBatch {
 public:
  OutputBatch();
  ~OutputBatch();
  OutputBatch(const OutputBatch&) = delete;
  OutputBatch& operator=(const OutputBatch&) = delete;
  void commit();
};

// An output directory and those of its ancestors that do not exist yet: a run that fails
// after making them (the maps directory of a run that then finds the disk full) removes them
// again, so that it leaves nothing behind. Only the directories that are then empty go: a
// file that another process put there meanwhile keeps its directory.
class NewDirectories {
 public:
  explicit NewDirectories(const std::filesystem::path& directory);
  // Removes, deepest first, each of the directories that did not exist when this was made.
  void remove_empty() const;

 private:
  std::vector<std::filesystem::path> missing_;  // deepest first
};

// The file an AtomicFileWriter of `path` replaces, as one absolute name: symbolic links
// followed (dangling ones too: the file they name is created), the directory made canonical.
// Two outputs with the same target are one file, whatever their names.
std::filesystem::path output_target(const std::filesystem::path& path);

// Replaces `path` with `contents` atomically (AtomicFileWriter in one piece).
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// Removes the temporary files and directories in `directory` that toonwater's processes which
// no longer exist left behind (killed by SIGKILL, say): only entries whose names prove them
// toonwater's, made on this machine (is_stale_temporary, temporary_name.hpp). Those of running
// processes and of other machines stay. `recover`, when given, is called first for each stale
// directory: one it returns false for stays. Best effort: what cannot be listed or removed is
// left as it is.
void remove_stale_temporaries(
    const std::filesystem::path& directory,
    const std::function<bool(const std::filesystem::path&)>& recover = {});

// Installs handlers for SIGINT, SIGTERM and SIGHUP that delete the temporary files of the
// AtomicFileWriters in progress, then let the signal end the process as it would have: an
// interrupted run leaves no temporary file. main() installs them first; povgen and render replace
// them while they stop gracefully between frames.
void remove_temporaries_on_signals();

}  // namespace toonwater
