// Progress of a frame loop on standard error. On a terminal one line is rewritten in place
// ("\r"); anywhere else (a log file, a pipe) each update is a line of its own, so that nothing
// is overwritten and a message that follows starts on a fresh line.
#pragma once

#include <cstddef>
#include <string>

namespace toonwater::cli {

// A word the user typed (a path, an option), safe to print on one line: control and non-ASCII
// bytes as '?', at most 400 bytes. Every message names paths through it.
std::string printable(const std::string& word);

// The same, quoted for a POSIX shell where it needs it, for a command line the user may paste.
std::string printable_shell_word(const std::string& word);

class FrameProgress {
 public:
  explicit FrameProgress(const char* command);
  // `done` of `total` frames after `elapsed` seconds, of a named pass of the command's when
  // it makes more than one ("survey": "povgen: survey, frame 3/24, ..."), and then `elapsed`
  // and the time left are the pass's own.
  void update(std::size_t done, std::size_t total, double elapsed, const char* pass = nullptr);
  // Ends a rewritten line that is still open (before an error or a warning).
  void finish_line();

 private:
  const char* command_;
  bool terminal_;
  bool line_open_ = false;
};

}  // namespace toonwater::cli
