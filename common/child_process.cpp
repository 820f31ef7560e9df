// Child processes that do not outlive toonwater; stated in child_process.hpp.
#include "common/child_process.hpp"

#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

namespace toonwater {

void prepare_child_process(pid_t parent) {
  ::signal(SIGPIPE, SIG_DFL);
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  // The parent may have ended between fork() and prctl(): then no signal would come.
  if (::getppid() != parent) ::_exit(128 + SIGTERM);
}

}  // namespace toonwater
