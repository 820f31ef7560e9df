#include "render/supervised_process.hpp"

#include <signal.h>
#include <sys/wait.h>

#include <cerrno>
#include <chrono>
#include <thread>

namespace toonwater {

int run_supervised(const std::vector<std::string>& argv, const ChildSetup& setup,
                   const std::atomic<bool>* stop, const std::function<bool()>& tick) {
  using namespace std::chrono_literals;
  const pid_t pid = start_child_process(argv, setup);
  if (pid < 0) return -1;
  const auto stopping = [stop] { return stop && stop->load(); };
  int status = 0;
  bool finished = false;
  auto deadline = std::chrono::steady_clock::time_point::max();
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, finished ? 0 : WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) return -1;
    if (r == 0) {
      const auto now = std::chrono::steady_clock::now();
      if (stopping() && deadline == std::chrono::steady_clock::time_point::max()) {
        ::kill(pid, SIGTERM);
        deadline = now + 10s;
      } else if (now > deadline) {
        ::kill(pid, SIGKILL);
      }
      if (!stopping() && tick && tick()) {
        ::kill(pid, SIGKILL);
        finished = true;
        continue;
      }
      std::this_thread::sleep_for(20ms);
    }
  }
  if (finished) return 0;
  return exit_status(status);
}

}  // namespace toonwater
