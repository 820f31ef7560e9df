// Wall-clock seconds for the timings the commands report (read, analysis, write, ...).
#pragma once

#include <chrono>

namespace toonwater {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace toonwater
