// write_file_atomically: writes ".NAME.tmp-PID-N" beside the target, closes it (checking every
// step), then rename(2)s it over the target, which POSIX makes atomic within one file system —
// hence the temporary file lives in the target's own directory. There is no fsync: the guarantee
// is against failed and interrupted runs, not against power loss, and syncing large outputs would
// cost more than the rest of the run.
#include "analyzer/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <string>
#include <system_error>

namespace toonwater {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& path, const std::string& what, int error) {
  throw OutputError(path.string() + ": " + what + ": " + std::generic_category().message(error));
}

// Creates a new temporary file beside `path`; returns its descriptor and sets `temporary`.
int create_temporary(const fs::path& path, fs::path& temporary) {
  static std::atomic<unsigned> counter{0};
  const fs::path directory = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  // At most 100 characters of the target's name, so that the temporary name stays within the
  // file system's limit (255) whatever the target's name. Built by appending: GCC 12 misreports
  // "." + string (-Wrestrict).
  std::string prefix = ".";
  prefix += path.filename().string().substr(0, 100);
  prefix += ".tmp-" + std::to_string(::getpid()) + "-";
  for (;;) {
    temporary = directory / (prefix + std::to_string(counter++));
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    // A name left by an earlier process with the same pid: try the next one.
    if (errno != EEXIST) fail(path, "cannot create a temporary file in " + directory.string(), errno);
  }
}

bool write_all(int fd, std::string_view contents) {
  while (!contents.empty()) {
    const ssize_t n = ::write(fd, contents.data(), contents.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return false;
    contents.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

}  // namespace

void write_file_atomically(const fs::path& path, std::string_view contents) {
  if (!path.has_filename()) throw OutputError(path.string() + ": not a file name");
  fs::path temporary;
  const int fd = create_temporary(path, temporary);
  const auto discard = [&](const std::string& what) {
    const int error = errno;
    ::unlink(temporary.c_str());
    fail(path, what, error);
  };
  if (!write_all(fd, contents)) {
    const int error = errno;
    ::close(fd);
    errno = error;
    discard("cannot write");
  }
  if (::close(fd) != 0) discard("cannot write");
  if (::rename(temporary.c_str(), path.c_str()) != 0) discard("cannot replace the file");
}

}  // namespace toonwater
