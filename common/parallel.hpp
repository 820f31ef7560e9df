// Splits [0, n) into one contiguous chunk per hardware thread and runs fn(chunk, begin, end) on
// each, the first on the calling thread. Small inputs run on the calling thread alone, where
// starting threads would cost more than the work.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace toonwater {

inline std::size_t worker_count(std::size_t n, std::size_t min_per_worker = 16384) {
  const std::size_t hardware = std::max(1u, std::thread::hardware_concurrency());
  return std::clamp<std::size_t>(n / min_per_worker, 1, hardware);
}

template <class Fn>
void parallel_chunks(std::size_t n, std::size_t workers, Fn&& fn) {
  if (workers <= 1) {
    fn(std::size_t{0}, std::size_t{0}, n);
    return;
  }
  std::vector<std::jthread> threads;
  threads.reserve(workers - 1);
  for (std::size_t w = 1; w < workers; ++w)
    threads.emplace_back([&fn, w, n, workers] { fn(w, n * w / workers, n * (w + 1) / workers); });
  fn(std::size_t{0}, std::size_t{0}, n / workers);
}

}  // namespace toonwater
