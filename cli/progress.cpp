#include "cli/progress.hpp"

#include "common/printable_text.hpp"
#include "render/farm.hpp"

#include <unistd.h>

#include <cstdio>

namespace toonwater::cli {

FrameProgress::FrameProgress(const char* command)
    : command_(command), terminal_(::isatty(STDERR_FILENO) == 1) {}

void FrameProgress::update(std::size_t done, std::size_t total, double elapsed, const char* pass) {
  const double left =
      done == 0 ? 0.0 : elapsed / static_cast<double>(done) * static_cast<double>(total - done);
  std::fprintf(stderr, "%s%s: %s%sframe %zu/%zu, %.1f s, about %.1f s left%s",
               terminal_ ? "\r" : "", command_, pass ? pass : "", pass ? ", " : "", done, total,
               elapsed, left, terminal_ ? "   " : "\n");
  line_open_ = terminal_;
  if (done == total) finish_line();
}

void FrameProgress::finish_line() {
  if (line_open_) std::fputc('\n', stderr);
  line_open_ = false;
}

std::string printable(const std::string& word) {
  constexpr std::size_t longest_word_shown = 400;  // a path
  return printable_text(word, longest_word_shown);
}

std::string printable_shell_word(const std::string& word) { return shell_quote(printable(word)); }

}  // namespace toonwater::cli
