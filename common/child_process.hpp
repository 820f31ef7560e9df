// Every child process toonwater starts (POV-Ray, GNU parallel, sbatch, scancel) is started by
// start_child_process, which does between fork and exec what keeps a child from outliving a
// toonwater that ends abruptly:
//
// - PR_SET_PDEATHSIG: the kernel sends the child SIGTERM when toonwater ends, whatever ended it
//   (SIGKILL included); POV-Ray and GNU parallel stop on SIGTERM. A toonwater that stops
//   gracefully (SIGINT, SIGTERM, SIGHUP between steps) stops its children itself first.
// - SIGPIPE back to its default: toonwater ignores it (main.cpp), so that a closed standard
//   error or output is an error it reports rather than a death that strands its children, and
//   an ignored signal would stay ignored across exec.
// - SIGINT, SIGTERM and SIGHUP back to their defaults, blocked from before the fork until then:
//   a stop that reaches the child before it becomes its program ends it, rather than being
//   taken by toonwater's own handler, which the child holds until exec, and lost (the program
//   would then run on, stopped by nobody).
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace toonwater {

// How a child's standard output and error and its working directory are set up
// (start_child_process).
struct ChildSetup {
  std::string working_directory;  // empty: the parent's
  // Standard output and error both into this file, created or truncated; empty: `out_fd` and
  // `err_fd`.
  std::string output_file;
  int out_fd = -1, err_fd = -1;  // standard output and error (e.g. pipe ends); -1: the parent's
};

// Exit statuses of a child that could not become the program asked for (the shell's
// conventions, above those of the programs toonwater runs).
inline constexpr int child_cannot_write_output = 125;
inline constexpr int child_cannot_enter_directory = 126;
inline constexpr int child_cannot_execute = 127;

// Starts argv[0] (looked up in PATH, no shell) as `setup` says, its standard input from
// /dev/null. Returns its pid, or -1 when it could not be forked.
pid_t start_child_process(const std::vector<std::string>& argv, const ChildSetup& setup);

// A waitpid status as an exit status: the child's own, or 128 + the signal that ended it.
int exit_status(int wait_status);

}  // namespace toonwater
