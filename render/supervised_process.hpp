// A child process (POV-Ray, ffmpeg) run to its end under a stop flag: what render.cpp and
// video.cpp share. The child is started by start_child_process (common/child_process.hpp).
#pragma once

#include "common/child_process.hpp"

#include <atomic>
#include <functional>
#include <string>
#include <vector>

namespace toonwater {

// Runs `argv` as `setup` says and waits for it, calling `tick` every 20 ms meanwhile. Once
// `stop` is set, terminates it (SIGTERM, then SIGKILL if it lingers 10 s). When `tick` returns
// true, the process has done all that was asked of it: it is killed at once instead of waited
// for, and the status is 0. Returns its exit status (128 + a signal that ended it), or -1 when
// it could not be started or waited for.
int run_supervised(const std::vector<std::string>& argv, const ChildSetup& setup,
                   const std::atomic<bool>* stop, const std::function<bool()>& tick = {});

}  // namespace toonwater
