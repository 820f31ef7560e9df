// Splits [0, n) into one contiguous chunk per hardware thread and runs fn(chunk, begin, end) on
// each, the first on the calling thread. Small inputs run on the calling thread alone, where
// waking threads would cost more than the work.
//
// The other chunks run on a pool of hardware − 1 threads started once and asleep between calls:
// starting threads anew cost about as much as a pass over a 55k-vertex mesh. Waking a sleeping
// thread costs tens of microseconds more (on this project's VM about 60 µs for a call's two
// wake-ups), and a stage makes dozens of calls a few passes apart. So a thread that has run a
// chunk watches for the next call, and a caller for the pool's last chunk, for `spin_time_ns`
// before it sleeps. The watch is a busy wait with the processor's pause hint and never yields:
// a yielding watch was tried and reverted, because on a loaded machine each yield gave the core
// away for whole time slices (calls of 0.1–5.8 ms instead of 0.03–0.07). A busy wait keeps its
// core for at most spin_time_ns, and then sleeps as before. Each side watches only while watching
// pays: when the last event it waited for (the next call, the last chunk's end) came later than
// spin_time_ns after it began to wait, it sleeps at once next time. On a loaded machine the other
// thread is often off its core, and watching for it only took CPU time from everyone (a 55k
// analyze took 1.11× the CPU time beside two busy processes). A call made while
// the pool is busy (from inside a chunk, or from a second thread) or with more chunks than the
// pool has threads starts threads of its own, as does one in a child process forked after the
// pool started (whose threads did not follow it).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <type_traits>
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
      stopping_.store(true, std::memory_order_release);
    }
    wake_.notify_all();
    for (std::thread& thread : threads_) thread.join();
  }

  // Runs task(context, c) for c in [1, chunks) on the pool and task(context, 0) on the calling
  // thread; false (and nothing run) when the pool cannot take the call. Not inlined either, so
  // that its wait, too, writes only frames below the caller's (ChunkedCall::run_chunk).
  [[gnu::noinline]] bool run(std::size_t chunks, Task task, void* context) {
    if (chunks - 1 > threads_.size() || ::getpid() != owner_) return false;
    std::unique_lock busy(busy_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    {
      std::lock_guard lock(mutex_);
      task_ = task;
      context_ = context;
      chunks_ = chunks;
      remaining_.store(chunks - 1, std::memory_order_relaxed);
      called_at_ = now();
      generation_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
    // The other chunks use the caller's context: wait for them even when this chunk throws.
    std::exception_ptr failure;
    try {
      task(context, 0);
    } catch (...) {
      failure = std::current_exception();
    }
    auto finished = [&] { return remaining_.load(std::memory_order_acquire) == 0; };
    const std::int64_t waiting_since = now();
    if (!(caller_watches_ && spin_until(finished))) {
      std::unique_lock lock(mutex_);
      done_.wait(lock, finished);
    }
    caller_watches_ =
        last_chunk_done_at_.load(std::memory_order_relaxed) - waiting_since < spin_time_ns;
    if (failure) std::rethrow_exception(failure);
    return true;
  }

 private:
  explicit ThreadPool(std::size_t threads) : owner_(::getpid()) {
    threads_.reserve(threads);
    for (std::size_t i = 0; i < threads; ++i) threads_.emplace_back([this, i] { serve(i + 1); });
  }

  // How long a thread watches for the next call, or a caller for the last chunk, before it
  // sleeps: the gap between most passes of a stage on a 55k-vertex mesh, and short enough that
  // a busy machine loses little to it.
  static constexpr std::int64_t spin_time_ns = 50'000;

  // The steady clock in nanoseconds.
  static std::int64_t now() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }

  // Polls `ready` for up to spin_time_ns without giving up the core; true once it holds.
  template <class Ready>
  static bool spin_until(Ready&& ready) {
    const std::int64_t deadline = now() + spin_time_ns;
    for (;;) {
      for (int i = 0; i < 32; ++i) {
        if (ready()) return true;
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();  // lets the other hyper-thread run and eases the exit from the loop
#endif
      }
      if (now() > deadline) return ready();
    }
  }

  void serve(std::size_t chunk) {
    std::uint64_t seen = 0;
    auto called = [&] {
      return stopping_.load(std::memory_order_acquire) ||
             generation_.load(std::memory_order_acquire) != seen;
    };
    bool watch = true;
    for (;;) {
      const std::int64_t waiting_since = now();
      if (watch) spin_until(called);
      // The call's fields are read under the lock: a thread that sat out the last call (fewer
      // chunks than threads) may see the next one while it is being set up.
      std::unique_lock lock(mutex_);
      wake_.wait(lock, called);
      if (stopping_.load(std::memory_order_relaxed)) return;
      seen = generation_.load(std::memory_order_relaxed);
      watch = called_at_ - waiting_since < spin_time_ns;
      if (chunk >= chunks_) continue;  // fewer chunks than threads this time
      const Task task = task_;
      void* const context = context_;
      lock.unlock();
      task(context, chunk);
      last_chunk_done_at_.store(now(), std::memory_order_relaxed);
      if (remaining_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        // Under the lock, so that a caller about to sleep on done_ cannot miss the notice.
        std::lock_guard done_lock(mutex_);
        done_.notify_one();
      }
    }
  }

  const pid_t owner_;
  std::vector<std::thread> threads_;
  std::mutex busy_;   // held by the call the pool is running
  std::mutex mutex_;  // guards the call's fields below; generation_ and stopping_ change under it
  std::condition_variable wake_, done_;
  Task task_ = nullptr;
  void* context_ = nullptr;
  std::size_t chunks_ = 0;
  std::atomic<std::size_t> remaining_{0};  // chunks of the call not yet done, but the caller's
  std::atomic<std::uint64_t> generation_{0};
  std::atomic<bool> stopping_{false};
  std::int64_t called_at_ = 0;  // when the current call was made (now())
  // When a pool thread last finished a chunk; read by the caller once the call is done.
  std::atomic<std::int64_t> last_chunk_done_at_{0};
  bool caller_watches_ = true;  // only the thread holding busy_ uses it
};

// A call's function and chunks, as every thread of the call reads them: a cache line of its
// own, written once before the call and then only read.
template <class Fn>
struct alignas(64) ChunkedCall {
  Fn& fn;
  std::size_t n, workers;

  // One chunk, in a frame of its own, on any thread. Never inlined into the caller: the other
  // threads read the caller's frame (the function object and the locals it captures by
  // reference) all through the call, and the calling thread's chunk, inlined there, spilled
  // its registers into that frame at every step, so that each read on another core had to
  // fetch the line back: the free surface's slope pass took twice as long, in about half of
  // the runs (as the stack happened to lie).
  [[gnu::noinline]] static void run_chunk(void* context, std::size_t chunk) {
    const ChunkedCall& c = *static_cast<const ChunkedCall*>(context);
    c.fn(chunk, c.n * chunk / c.workers, c.n * (chunk + 1) / c.workers);
  }
};

template <class Fn>
void parallel_chunks(std::size_t n, std::size_t workers, Fn&& fn) {
  if (workers <= 1) {
    fn(std::size_t{0}, std::size_t{0}, n);
    return;
  }
  using Call = ChunkedCall<std::remove_reference_t<Fn>>;
  Call call{fn, n, workers};
  const ThreadPool::Task task = &Call::run_chunk;
  if (ThreadPool::shared().run(workers, task, &call)) return;
  std::vector<std::jthread> threads;
  threads.reserve(workers - 1);
  for (std::size_t w = 1; w < workers; ++w) threads.emplace_back([&task, &call, w] { task(&call, w); });
  task(&call, 0);
}

}  // namespace toonwater
