// Σ term(i) over [0, n) on all threads, with bits that do not depend on the number of threads.
//
// Floating-point addition is not associative, so a sum split by thread (a parallel reduction)
// changes in its last bits with the thread count, and a threshold taken from it could label a
// vertex differently on a laptop and on a farm. Here [0, n) is cut into blocks of a size fixed
// in this file, whatever the thread count; each block is summed in index order on whichever
// thread takes it, and the blocks' sums are then added serially in block order: the same
// additions, in the same order, on any number of threads.
#pragma once

#include "common/parallel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace toonwater {

// Indices a block: few blocks' sums to add serially (123 at 1M), each long enough to stream.
inline constexpr std::size_t deterministic_sum_block = 8192;

template <class Term>
double deterministic_sum(std::size_t n, Term&& term) {
  const std::size_t blocks = (n + deterministic_sum_block - 1) / deterministic_sum_block;
  std::vector<double> block_sums(blocks);
  // Blocks are handed out no fewer than serial_below indices at a time: a sum of at most
  // serial_below terms stays on the calling thread.
  const std::size_t grain = std::max<std::size_t>(1, serial_below / deterministic_sum_block);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, grain),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t block = range.begin(); block < range.end(); ++block) {
                        double sum = 0.0;
                        const std::size_t end = std::min(n, (block + 1) * deterministic_sum_block);
                        for (std::size_t i = block * deterministic_sum_block; i < end; ++i)
                          sum += term(i);
                        block_sums[block] = sum;
                      }
                    });
  double total = 0.0;
  for (const double sum : block_sums) total += sum;
  return total;
}

}  // namespace toonwater
