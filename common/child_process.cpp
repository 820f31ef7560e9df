// Child processes that do not outlive toonwater; stated in child_process.hpp.
#include "common/child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace toonwater {

namespace {

// The signals that stop toonwater: its handlers only note them (cli/stop_signals.cpp).
constexpr int stop_signals[] = {SIGINT, SIGTERM, SIGHUP};

// In the child, right after fork(), with the stop signals blocked; `parent` is getpid() of the
// parent before the fork and `mask` its signal mask. Async-signal-safe. A stop signal that came
// since the fork is pending: it ends the child once the handlers are back to their defaults and
// the mask restored, instead of being taken by the parent's handler, which the child inherits
// until exec, and lost. When the parent has already gone, the child ends at once (128 + 15).
void prepare_child_process(pid_t parent, const sigset_t& mask) {
  ::signal(SIGPIPE, SIG_DFL);
  for (const int s : stop_signals) {
    struct sigaction current {};
    ::sigaction(s, nullptr, &current);
    if (current.sa_handler != SIG_IGN) ::signal(s, SIG_DFL);  // an ignored one stays ignored
  }
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  ::sigprocmask(SIG_SETMASK, &mask, nullptr);
  // The parent may have ended between fork() and prctl(): then no signal would come.
  if (::getppid() != parent) ::_exit(128 + SIGTERM);
}

}  // namespace

pid_t start_child_process(const std::vector<std::string>& argv, const ChildSetup& setup) {
  // Everything the child uses is made before fork(): after it, only async-signal-safe calls.
  std::vector<std::string> copies = argv;
  std::vector<char*> args;
  for (auto& a : copies) args.push_back(a.data());
  args.push_back(nullptr);
  const pid_t parent = ::getpid();
  sigset_t stops, mask;
  ::sigemptyset(&stops);
  for (const int s : stop_signals) ::sigaddset(&stops, s);
  ::pthread_sigmask(SIG_BLOCK, &stops, &mask);
  const pid_t pid = ::fork();
  if (pid != 0) {
    ::pthread_sigmask(SIG_SETMASK, &mask, nullptr);  // a stop meanwhile reaches the parent now
    return pid;
  }
  prepare_child_process(parent, mask);
  // Opened close-on-exec: only the descriptors dup2 puts in place reach the program.
  const int null = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  if (null >= 0) ::dup2(null, STDIN_FILENO);
  int out = setup.out_fd, err = setup.err_fd;
  if (!setup.output_file.empty()) {
    out = err = ::open(setup.output_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (out < 0) ::_exit(child_cannot_write_output);
  }
  if (!setup.working_directory.empty() && ::chdir(setup.working_directory.c_str()) != 0)
    ::_exit(child_cannot_enter_directory);
  if (out >= 0) ::dup2(out, STDOUT_FILENO);
  if (err >= 0) ::dup2(err, STDERR_FILENO);
  ::execvp(args[0], args.data());
  ::_exit(child_cannot_execute);
}

int exit_status(int wait_status) {
  return WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : 128 + WTERMSIG(wait_status);
}

}  // namespace toonwater
