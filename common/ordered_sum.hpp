// Sums over [0, n) on all cores whose bits do not depend on the number of cores.
//
// Floating-point addition is not associative, so a sum split by core (one partial sum a
// chunk) changes in its last bits with the machine, and a threshold taken from it could label
// a vertex differently on a laptop and on a farm. Here the range is cut into blocks of a size
// fixed in this file; each block is summed in index order, on whichever core takes it, and the
// blocks' sums are then added in block order: the same operations, in the same order, on any
// number of cores. A serial loop is one chain of dependent additions: over a 1M-vertex frame's
// areas it took about 4 ms, twice the pass that reads the curvature into the flow field.
#pragma once

#include "common/parallel.hpp"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace toonwater {

// Indices a block. A multiple of the 4 KiB page in doubles, and large enough that the blocks'
// sums are few (123 at 1M) and one core's run of blocks streams through memory.
constexpr std::size_t ordered_sum_block = 8192;

// Σ term(i) over [0, n).
template <class Term>
double ordered_sum(std::size_t n, Term&& term) {
  const std::size_t blocks = (n + ordered_sum_block - 1) / ordered_sum_block;
  std::vector<double> block_sums(blocks);
  parallel_chunks(blocks, worker_count(n), [&](std::size_t, std::size_t first, std::size_t last) {
    for (std::size_t block = first; block < last; ++block) {
      double sum = 0.0;  // in a local: in the vector, each add would wait for a store
      const std::size_t end = std::min(n, (block + 1) * ordered_sum_block);
      for (std::size_t i = block * ordered_sum_block; i < end; ++i) sum += term(i);
      block_sums[block] = sum;
    }
  });
  double total = 0.0;
  for (const double sum : block_sums) total += sum;
  return total;
}

}  // namespace toonwater
