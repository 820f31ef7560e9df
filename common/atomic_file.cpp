// AtomicFileWriter: writes ".NAME.tmp-…" (temporary_name.hpp) beside the target, with the
// target's owner, group and mode when it replaces one, closes it (checking every
// step), then rename(2)s it over the target, which POSIX makes atomic within one file system —
// hence the temporary file lives in the target's own directory. There is no fsync: the guarantee
// is against failed and interrupted runs, not against power loss, and syncing large outputs would
// cost more than the rest of the run. Writers in progress list their temporary file in a fixed
// table that a signal handler can read (remove_temporaries_on_signals).
#include "common/atomic_file.hpp"

#include "common/temporary_name.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <charconv>
#include <functional>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

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

// An OutputBatch's renames are one step: a signal that arrives while they run waits for the
// last of them, or the run would end with some outputs new and the others old. The handler may
// run on any thread, so the two sides agree through one atomic state: the handler ends the
// process only from `idle` (then nothing can start committing), and a commit starts only from
// `idle` (then no handler is ending the process).
enum CommitState : int { idle, committing, ending };
std::atomic<int> commit_state{idle};
std::atomic<int> deferred_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void remove_temporaries_and_end(int signal_number) {
  int state = idle;
  if (!commit_state.compare_exchange_strong(state, ending)) {
    if (state == committing) deferred_signal.store(signal_number);
    return;  // committing: ended after the renames; ending: another thread is ending it
  }
  for (InProgress& entry : in_progress)
    if (entry.ready) ::unlink(entry.path);
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

// Holds signals off an OutputBatch's renames while alive; a signal that came meanwhile ends the
// process once they are done (end_deferred).
class RenamesUninterrupted {
 public:
  RenamesUninterrupted() {
    int state = idle;
    // `ending`: a handler on another thread is removing the temporaries and ending the process.
    while (!commit_state.compare_exchange_weak(state, committing)) {
      if (state == ending) ::pause();
      state = idle;
    }
  }
  ~RenamesUninterrupted() { commit_state.store(idle); }
  RenamesUninterrupted(const RenamesUninterrupted&) = delete;
  RenamesUninterrupted& operator=(const RenamesUninterrupted&) = delete;

  // After the renames (and after this object): the signal that waited, as it would have acted.
  static void end_deferred() {
    if (const int signal_number = deferred_signal.exchange(0))
      remove_temporaries_and_end(signal_number);
  }
};

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

// The files of the open OutputBatch, complete and waiting for their rename.
struct BatchFile {
  fs::path temporary, target, name;
  int slot = -1;
};
std::mutex batch_mutex;
bool batch_open = false;
std::vector<BatchFile> batch_files;

[[noreturn]] void throw_output_error(const fs::path& path, const std::string& what, int error) {
  throw OutputError(path.string() + ": " + what + ": " + std::generic_category().message(error));
}

// Creates a new temporary file beside `path` (temporary_name.hpp); returns its descriptor and
// sets `temporary`.
int create_temporary(const fs::path& path, fs::path& temporary) {
  const fs::path directory = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  for (;;) {
    temporary = directory / temporary_name(path.filename().string());
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    if (errno != EEXIST)  // a random name taken already: try another
      throw_output_error(path, "cannot create a temporary file in " + directory.string(), errno);
  }
}

// The descriptor a name of an open descriptor stands for ("-", /dev/stdout, /dev/fd/3,
// /proc/self/fd/3), or -1.
int descriptor_named(const fs::path& path) {
  const std::string& p = path.native();
  if (p == "-" || p == "/dev/stdout") return STDOUT_FILENO;
  if (p == "/dev/stderr") return STDERR_FILENO;
  for (const std::string_view prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    if (!p.starts_with(prefix)) continue;
    int fd = -1;
    const char* begin = p.data() + prefix.size();
    const auto [end, error] = std::from_chars(begin, p.data() + p.size(), fd);
    if (error == std::errc{} && end == p.data() + p.size() && fd >= 0) return fd;
  }
  return -1;
}

// `path` with its symbolic links followed (the last component's, repeatedly): the file an
// atomic replacement must rename over, so that a link stays a link. A dangling link leads to the
// file it names, which is then created.
fs::path follow_links(fs::path path) {
  constexpr int max_links = 40;  // as the kernel's ELOOP limit
  for (int i = 0; i < max_links; ++i) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(path, ec))) return path;
    const fs::path target = fs::read_symlink(path, ec);
    if (ec) return path;
    path = target.is_absolute() ? target : path.parent_path() / target;
  }
  throw OutputError(path.string() + ": too many levels of symbolic links");
}

// Gives the new file `fd` the owner, group and permission bits of the file it replaces, as a
// careful editor does. Best effort: a user who may not give the file its owner (only root may)
// or group (one they are not in) keeps what they can, and a setgid or setuid bit goes with a
// group or owner that could not be kept.
void keep_access(const struct stat& replaced, int fd) {
  mode_t mode = replaced.st_mode & 07777;
  if (::fchown(fd, replaced.st_uid, replaced.st_gid) != 0) {
    mode &= ~static_cast<mode_t>(S_ISUID);
    if (::fchown(fd, static_cast<uid_t>(-1), replaced.st_gid) != 0)
      mode &= ~static_cast<mode_t>(S_ISGID);
  }
  ::fchmod(fd, mode);
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

AtomicFileWriter::AtomicFileWriter(fs::path path) : name_(path), path_(std::move(path)) {
  const std::string shown = name_ == "-" ? "standard output" : name_.string();
  if (const int fd = descriptor_named(name_); fd >= 0) {
    fd_ = ::fcntl(fd, F_DUPFD_CLOEXEC, 3);
    if (fd_ < 0) throw_output_error(shown, "cannot write", errno);
    stream_ = true;
    return;
  }
  if (!path_.has_filename()) throw OutputError(path_.string() + ": not a file name");
  path_ = follow_links(path_);
  struct stat status {};
  if (::stat(path_.c_str(), &status) == 0 && !S_ISREG(status.st_mode)) {
    if (S_ISDIR(status.st_mode)) throw OutputError(name_.string() + ": is a directory");
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);  // a FIFO, device or socket
    if (fd_ < 0) throw_output_error(name_, "cannot open", errno);
    stream_ = true;
    return;
  }
  const HandledSignalsBlocked blocked;
  fd_ = create_temporary(path_, temporary_);
  slot_ = track(temporary_);
  if (S_ISREG(status.st_mode)) keep_access(status, fd_);
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ >= 0) ::close(fd_);
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
  untrack(slot_);
}

void AtomicFileWriter::fail(const std::string& what, int error) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
  temporary_.clear();
  untrack(slot_);
  throw_output_error(name_ == "-" ? fs::path("standard output") : name_, what, error);
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
  if (stream_) return;
  {
    std::lock_guard lock(batch_mutex);
    if (batch_open) {  // renamed by OutputBatch::commit(), with the others
      batch_files.push_back({temporary_, path_, name_, slot_});
      temporary_.clear();
      slot_ = -1;
      return;
    }
  }
  if (::rename(temporary_.c_str(), path_.c_str()) != 0) fail("cannot replace the file", errno);
  temporary_.clear();
  untrack(slot_);
}

OutputBatch::OutputBatch() {
  std::lock_guard lock(batch_mutex);
  if (batch_open) throw std::logic_error("OutputBatch: one at a time");
  batch_open = true;
}

OutputBatch::~OutputBatch() {
  std::lock_guard lock(batch_mutex);
  for (BatchFile& f : batch_files) {
    ::unlink(f.temporary.c_str());
    untrack(f.slot);
  }
  batch_files.clear();
  batch_open = false;
}

namespace {

// The open batch's files, each renamed over its target; after a failed rename, the others
// removed.
void rename_batch_files() {
  std::lock_guard lock(batch_mutex);
  batch_open = false;
  for (std::size_t i = 0; i < batch_files.size(); ++i) {
    BatchFile& f = batch_files[i];
    if (::rename(f.temporary.c_str(), f.target.c_str()) != 0) {
      const int error = errno;
      const fs::path name = f.name;
      for (std::size_t j = i; j < batch_files.size(); ++j) {
        ::unlink(batch_files[j].temporary.c_str());
        untrack(batch_files[j].slot);
      }
      batch_files.clear();
      throw_output_error(name, "cannot replace the file", error);
    }
    untrack(f.slot);
  }
  batch_files.clear();
}

}  // namespace

void OutputBatch::commit() {
  try {
    const RenamesUninterrupted uninterrupted;
    rename_batch_files();
  } catch (...) {
    RenamesUninterrupted::end_deferred();  // a signal that waited still ends the run
    throw;
  }
  RenamesUninterrupted::end_deferred();
}

void remove_stale_temporaries(const fs::path& directory,
                              const std::function<bool(const fs::path&)>& recover) {
  std::error_code ec;
  const fs::path listed = directory.empty() ? fs::path(".") : directory;
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(listed, ec))
    if (is_stale_temporary(entry.path().filename().string())) stale.push_back(entry.path());
  for (const fs::path& entry : stale) {
    std::error_code ignored;
    if (recover && fs::is_directory(fs::symlink_status(entry, ignored)) && !recover(entry))
      continue;
    fs::remove_all(entry, ignored);
  }
}

void remove_temporaries_on_signals() {
  for (const int s : {SIGINT, SIGTERM, SIGHUP}) ::signal(s, remove_temporaries_and_end);
}

NewDirectories::NewDirectories(const fs::path& directory) {
  if (directory.empty()) return;
  std::error_code ec;
  fs::path p = fs::absolute(directory, ec).lexically_normal();
  if (ec) return;
  if (!p.has_filename()) p = p.parent_path();  // a trailing separator names the same directory
  for (; p.has_relative_path(); p = p.parent_path()) {
    // A path that cannot be examined (not found sets the error too) is taken as missing only
    // when it is not found.
    if (fs::symlink_status(p, ec).type() != fs::file_type::not_found) break;
    missing_.push_back(p);
  }
}

void NewDirectories::remove_empty() const {
  std::error_code ignored;
  for (const fs::path& directory : missing_) fs::remove(directory, ignored);  // only if empty
}

fs::path output_target(const fs::path& path) {
  std::error_code ec;
  const fs::path followed = fs::absolute(follow_links(path), ec);
  if (ec) return path;
  const fs::path directory = fs::weakly_canonical(followed.parent_path(), ec);
  return ec ? followed.lexically_normal() : directory / followed.filename();
}

void write_file_atomically(const fs::path& path, std::string_view contents) {
  AtomicFileWriter file(path);
  file.write(contents);
  file.commit();
}

}  // namespace toonwater
