// Loops on oneTBB's threads: how many chunks a loop takes, and a loop over contiguous chunks for
// the passes whose chunks keep lists or counts of their own (each in index order, merged in
// chunk order afterwards).
//
// The number of threads is oneTBB's: all cores, unless a tbb::global_control limits
// max_allowed_parallelism (the program's TOONWATER_THREADS, cli/main.cpp). The analyzer's results
// do not depend on it: a chunk's boundaries are a function of the item and chunk counts and only
// decide which thread computes what, never in which order a floating-point sum is taken
// (tests/common/test_thread_count.cpp runs the whole analysis with 1, 2 and 4 threads).
//
// Why oneTBB: its idle workers go to sleep after a short, bounded search for work, so the
// dozens of short loops of an analysis leave no thread spinning on a core another process needs;
// and an exception thrown in any chunk is carried out of the loop to its caller.
#pragma once

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>

namespace toonwater {

// Items below which a loop runs on the calling thread alone: handing work to other threads
// would cost more than the work.
inline constexpr std::size_t serial_below = 16384;

// The threads a loop may use: oneTBB's max_allowed_parallelism, which is the cores the process
// may run on unless a tbb::global_control limits it. A limit above the cores gives more chunks
// than threads, which changes no result (the chunks queue for the threads there are); it lets
// the tests split every pass into 4 chunks on a 2-core machine.
inline std::size_t thread_count() {
  return std::max<std::size_t>(
      1, tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

// One chunk per thread, none smaller than min_per_chunk items (1 below 2 × min_per_chunk).
inline std::size_t chunk_count(std::size_t n, std::size_t min_per_chunk = serial_below) {
  return std::clamp<std::size_t>(n / min_per_chunk, 1, thread_count());
}

// fn(chunk, begin, end) for the chunks [n·c / chunks, n·(c + 1) / chunks) of [0, n), each a task.
// An exception thrown by any chunk is rethrown here once the chunks that started have ended
// (chunks not yet started are then skipped).
template <class Fn>
void parallel_chunks(std::size_t n, std::size_t chunks, Fn&& fn) {
  if (chunks <= 1) {
    fn(std::size_t{0}, std::size_t{0}, n);
    return;
  }
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t chunk) {
    fn(chunk, n * chunk / chunks, n * (chunk + 1) / chunks);
  });
}

}  // namespace toonwater
