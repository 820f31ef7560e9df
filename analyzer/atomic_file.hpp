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
};

// Replaces `path` with `contents` atomically (AtomicFileWriter in one piece).
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace toonwater
