// AtomicFileWriter: writes ".NAME.tmp-PID-N" beside the target, closes it (checking every
// step), then rename(2)s it over the target, which POSIX makes atomic within one file system —
// hence the temporary file lives in the target's own directory. There is no fsync: the guarantee
// is against failed and interrupted runs, not against power loss, and syncing large outputs would
// cost more than the rest of the run. Writers in progress list their temporary file in a fixed
// table that a signal handler can read (remove_temporaries_on_signals).
#include "analyzer/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

namespace toonwater {
namespace {

namespace fs = std::filesystem;

// ---- temporary files in progress, for the signal handler ----
// Lock-free atomics and fixed buffers only, so that the handler may read them. A writer that finds
// the table full still works; only a signal would then leave its temporary file.
struct InProgress {
  std::atomic<bool> claimed{false};
  std::atomic<bool> ready{false};  // path holds a temporary file's name
  char path[4096];
};
InProgress in_progress[64];
static_assert(std::atomic<bool>::is_always_lock_free);

int track(const fs::path& temporary) {
  const std::string& name = temporary.native();
  if (name.size() >= sizeof(InProgress::path)) return -1;
  for (int i = 0; i < static_cast<int>(std::size(in_progress)); ++i) {
    bool expected = false;
    if (!in_progress[i].claimed.compare_exchange_strong(expected, true)) continue;
    std::memcpy(in_progress[i].path, name.c_str(), name.size() + 1);
    in_progress[i].ready = true;
    return i;
  }
  return -1;
}

void untrack(int& slot) {
  if (slot < 0) return;
  in_progress[slot].ready = false;
  in_progress[slot].claimed = false;
  slot = -1;
}

extern "C" void remove_temporaries_and_end(int signal_number) {
  for (InProgress& entry : in_progress)
    if (entry.ready) ::unlink(entry.path);
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

// Blocks SIGINT, SIGTERM and SIGHUP in this thread while alive: no signal falls between creating
// a temporary file and tracking it.
class HandledSignalsBlocked {
 public:
  HandledSignalsBlocked() {
    sigset_t set;
    ::sigemptyset(&set);
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) ::sigaddset(&set, s);
    ::pthread_sigmask(SIG_BLOCK, &set, &previous_);
  }
  ~HandledSignalsBlocked() { ::pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
  HandledSignalsBlocked(const HandledSignalsBlocked&) = delete;
  HandledSignalsBlocked& operator=(const HandledSignalsBlocked&) = delete;

 private:
  sigset_t previous_;
};

[[noreturn]] void throw_output_error(const fs::path& path, const std::string& what, int error) {
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
    if (errno != EEXIST)
      throw_output_error(path, "cannot create a temporary file in " + directory.string(), errno);
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

AtomicFileWriter::AtomicFileWriter(fs::path path) : path_(std::move(path)) {
  if (!path_.has_filename()) throw OutputError(path_.string() + ": not a file name");
  const HandledSignalsBlocked blocked;
  fd_ = create_temporary(path_, temporary_);
  slot_ = track(temporary_);
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ >= 0) ::close(fd_);
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
  untrack(slot_);
}

void AtomicFileWriter::fail(const std::string& what, int error) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(temporary_.c_str());
  temporary_.clear();
  untrack(slot_);
  throw_output_error(path_, what, error);
}

void AtomicFileWriter::write(std::string_view bytes) {
  if (fd_ < 0) throw OutputError(path_.string() + ": written after it was committed");
  if (!write_all(fd_, bytes)) fail("cannot write", errno);
}

void AtomicFileWriter::commit() {
  if (fd_ < 0) throw OutputError(path_.string() + ": committed twice");
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("cannot write", errno);
  if (::rename(temporary_.c_str(), path_.c_str()) != 0) fail("cannot replace the file", errno);
  temporary_.clear();
  untrack(slot_);
}

void remove_temporaries_on_signals() {
  for (const int s : {SIGINT, SIGTERM, SIGHUP}) ::signal(s, remove_temporaries_and_end);
}

void write_file_atomically(const fs::path& path, std::string_view contents) {
  AtomicFileWriter file(path);
  file.write(contents);
  file.commit();
}

}  // namespace toonwater
