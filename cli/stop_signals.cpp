#include "cli/stop_signals.hpp"

#include <csignal>

namespace toonwater::cli {
namespace {

std::atomic<bool> stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void request_stop(int) { stop_requested = true; }

}  // namespace

const std::atomic<bool>* stop_on_signals() {
  for (const int s : {SIGINT, SIGTERM, SIGHUP}) std::signal(s, request_stop);
  return &stop_requested;
}

}  // namespace toonwater::cli
