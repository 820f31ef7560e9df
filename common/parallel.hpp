// Splits [0, n) into one contiguous chunk per hardware thread and runs fn(chunk, begin, end) on
// each, the first on the calling thread. Small inputs run on the calling thread alone, where
// waking threads would cost more than the work.
//
// The other chunks run on a pool of hardware − 1 threads started once and asleep between calls:
// starting threads anew cost about as much as a pass over a 55k-vertex mesh. A call made while
// the pool is busy (from inside a chunk, or from a second thread) or with more chunks than the
// pool has threads starts threads of its own, as does one in a child process forked after the
// pool started (whose threads did not follow it).
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include <unistd.h>

namespace toonwater {

inline std::size_t worker_count(std::size_t n, std::size_t min_per_worker = 16384) {
  const std::size_t hardware = std::max(1u, std::thread::hardware_concurrency());
  return std::clamp<std::size_t>(n / min_per_worker, 1, hardware);
}

class ThreadPool {
 public:
  using Task = void (*)(void* context, std::size_t chunk);

  static ThreadPool& shared() {
    static ThreadPool pool(std::max(1u, std::thread::hardware_concurrency()) - 1);
    return pool;
  }

  ~ThreadPool() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    for (std::thread& thread : threads_) thread.join();
  }

  // Runs task(context, c) for c in [1, chunks) on the pool and task(context, 0) on the calling
  // thread; false (and nothing run) when the pool cannot take the call.
  bool run(std::size_t chunks, Task task, void* context) {
    if (chunks - 1 > threads_.size() || ::getpid() != owner_) return false;
    std::unique_lock busy(busy_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    {
      std::lock_guard lock(mutex_);
      task_ = task;
      context_ = context;
      chunks_ = chunks;
      remaining_ = chunks - 1;
      ++generation_;
    }
    wake_.notify_all();
    // The other chunks use the caller's context: wait for them even when this chunk throws.
    std::exception_ptr failure;
    try {
      task(context, 0);
    } catch (...) {
      failure = std::current_exception();
    }
    {
      std::unique_lock lock(mutex_);
      done_.wait(lock, [&] { return remaining_ == 0; });
    }
    if (failure) std::rethrow_exception(failure);
    return true;
  }

 private:
  explicit ThreadPool(std::size_t threads) : owner_(::getpid()) {
    threads_.reserve(threads);
    for (std::size_t i = 0; i < threads; ++i) threads_.emplace_back([this, i] { serve(i + 1); });
  }

  void serve(std::size_t chunk) {
    std::uint64_t seen = 0;
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
      if (stopping_) return;
      seen = generation_;
      if (chunk >= chunks_) continue;  // fewer chunks than threads this time
      const Task task = task_;
      void* const context = context_;
      lock.unlock();
      task(context, chunk);
      lock.lock();
      if (--remaining_ == 0) done_.notify_one();
    }
  }

  const pid_t owner_;
  std::vector<std::thread> threads_;
  std::mutex busy_;   // held by the call the pool is running
  std::mutex mutex_;  // guards the fields below
  std::condition_variable wake_, done_;
  Task task_ = nullptr;
  void* context_ = nullptr;
  std::size_t chunks_ = 0, remaining_ = 0;
  std::uint64_t generation_ = 0;
  bool stopping_ = false;
};

template <class Fn>
void parallel_chunks(std::size_t n, std::size_t workers, Fn&& fn) {
  if (workers <= 1) {
    fn(std::size_t{0}, std::size_t{0}, n);
    return;
  }
  struct Call {
    Fn& fn;
    std::size_t n, workers;
  } call{fn, n, workers};
  const ThreadPool::Task task = [](void* context, std::size_t chunk) {
    const Call& c = *static_cast<Call*>(context);
    c.fn(chunk, c.n * chunk / c.workers, c.n * (chunk + 1) / c.workers);
  };
  if (ThreadPool::shared().run(workers, task, &call)) return;
  std::vector<std::jthread> threads;
  threads.reserve(workers - 1);
  for (std::size_t w = 1; w < workers; ++w) threads.emplace_back([&task, &call, w] { task(&call, w); });
  task(&call, 0);
}

}  // namespace toonwater
