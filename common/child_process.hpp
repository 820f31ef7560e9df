// What every child process toonwater starts (POV-Ray, GNU parallel, sbatch) does between fork
// and exec, so that no child outlives a toonwater that ends abruptly.
//
// - PR_SET_PDEATHSIG: the kernel sends the child SIGTERM when toonwater ends, whatever ended it
//   (SIGKILL included); POV-Ray and GNU parallel stop on SIGTERM. A toonwater that stops
//   gracefully (SIGINT, SIGTERM, SIGHUP between steps) stops its children itself first.
// - SIGPIPE back to its default: toonwater ignores it (main.cpp), so that a closed standard
//   error or output is an error it reports rather than a death that strands its children, and
//   an ignored signal would stay ignored across exec.
#pragma once

#include <sys/types.h>

namespace toonwater {

// Called in the child, right after fork(); `parent` is getpid() of the parent before the fork.
// Async-signal-safe. When the parent has already gone, the child ends at once (exit 128 + 15).
void prepare_child_process(pid_t parent);

}  // namespace toonwater
