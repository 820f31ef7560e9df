// Loops on OpenMP's threads: how many chunks a loop takes, the first exception of a parallel
// region carried out of it, and a loop over contiguous chunks for the passes whose chunks keep
// lists or counts of their own (each in index order, merged in chunk order afterwards).
//
// OMP_NUM_THREADS (or omp_set_num_threads) sets the number of threads. The analyzer's results
// do not depend on it: a chunk's boundaries only decide which thread computes what, never in
// which order a floating-point sum is taken (tests/common/test_thread_count.cpp runs the whole
// analysis with 1, 2 and 4 threads).
#pragma once

#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <exception>

namespace toonwater {

// Items below which a loop runs on the calling thread alone: waking the other threads would
// cost more than the work.
inline constexpr std::size_t serial_below = 16384;

// One chunk per thread, none smaller than min_per_chunk items (1 below 2 × min_per_chunk).
inline std::size_t chunk_count(std::size_t n, std::size_t min_per_chunk = serial_below) {
  const auto threads = static_cast<std::size_t>(std::max(1, omp_get_max_threads()));
  return std::clamp<std::size_t>(n / min_per_chunk, 1, threads);
}

// The first exception thrown inside a parallel region, rethrown after it: an exception that
// leaves an OpenMP region ends the program (std::terminate).
class FirstException {
 public:
  // fn(), its exception kept when it is the region's first.
  template <class Fn>
  void run(Fn&& fn) noexcept {
    try {
      fn();
    } catch (...) {
      keep(std::current_exception());
    }
  }
  // After the region: rethrows the exception kept, if any.
  void rethrow() const {
    if (first_) std::rethrow_exception(first_);
  }

 private:
  void keep(std::exception_ptr thrown) noexcept {
#pragma omp critical(toonwater_first_exception)
    if (!first_) first_ = std::move(thrown);
  }
  std::exception_ptr first_;
};

// fn(chunk, begin, end) for the chunks [n·c / chunks, n·(c + 1) / chunks) of [0, n), one
// thread a chunk; the first exception any chunk throws is rethrown once all have ended.
template <class Fn>
void parallel_chunks(std::size_t n, std::size_t chunks, Fn&& fn) {
  if (chunks <= 1) {
    fn(std::size_t{0}, std::size_t{0}, n);
    return;
  }
  FirstException failure;
  const auto count = static_cast<std::ptrdiff_t>(chunks);
#pragma omp parallel for schedule(static, 1)
  for (std::ptrdiff_t c = 0; c < count; ++c) {
    const auto chunk = static_cast<std::size_t>(c);
    failure.run([&] { fn(chunk, n * chunk / chunks, n * (chunk + 1) / chunks); });
  }
  failure.rethrow();
}

}  // namespace toonwater
