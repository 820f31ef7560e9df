// The signals that stop a long run between its steps: SIGINT (Ctrl-C), SIGTERM (kill, Slurm's
// scancel) and SIGHUP (a closed terminal or ssh session). The run then stops its children
// (POV-Ray, GNU parallel, a Slurm job), removes what it had not finished and exits 4
// (interrupted), or, when the signal came once everything was in place, reports success.
// SIGPIPE is ignored (main.cpp): a closed standard error or output is a failed write, not an
// end that would strand the run's children.
#pragma once

#include <atomic>

namespace toonwater::cli {

// Installs the handlers (replacing main's, which end the run at once); returns the flag they set.
const std::atomic<bool>* stop_on_signals();

}  // namespace toonwater::cli
