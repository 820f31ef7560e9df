// Writes a file so that readers only ever see the old or the complete new content: the data goes
// to a temporary file in the same directory, which is renamed over the target once complete.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string_view>

namespace toonwater {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
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
  std::filesystem::path path_;
  std::filesystem::path temporary_;
  int fd_ = -1;
  int slot_ = -1;  // in the table remove_temporaries_on_signals() reads
};

// Replaces `path` with `contents` atomically (AtomicFileWriter in one piece).
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// Installs handlers for SIGINT, SIGTERM and SIGHUP that delete the temporary files of the
// AtomicFileWriters in progress, then let the signal end the process as it would have: an
// interrupted run leaves no temporary file. main() installs them first; povgen and render replace
// them while they stop gracefully between frames.
void remove_temporaries_on_signals();

}  // namespace toonwater
