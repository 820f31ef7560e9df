// The benchmarks' main: the large arrays live where the toonwater program keeps them
// (common/large_arrays.hpp), so that a stage repeated in a benchmark reuses its pages as the
// stages of one analysis and the frames of one povgen run do, instead of timing the kernel's
// page faults and zeroing on every repetition.
#include "common/large_arrays.hpp"

#include <benchmark/benchmark.h>

int main(int argc, char** argv) {
  toonwater::set_up_heap_for_large_arrays();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
