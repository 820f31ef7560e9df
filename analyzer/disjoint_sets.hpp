// Disjoint sets over 0..n−1 (union-find) with union by rank and path halving: near-constant
// time per operation (Tarjan 1975), so labelling connected parts of a mesh is linear in its size.
//
// join_in_parallel joins the pairs of a pass over faces on all cores: the elements are split
// into one contiguous range per chunk of faces, and a chunk joins the pairs that lie in its own
// range itself (a set's root and every step of a path to it stay in the range, so the chunks
// write disjoint parts of the arrays); the pairs that cross ranges are joined afterwards on one
// thread. On a mesh whose vertices and faces are both in a spatial order (as simulation
// output and grids are) few pairs cross; in any order the result is the same sets.
#pragma once

#include "analyzer/mesh.hpp"
#include "common/parallel.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace toonwater {

class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(new std::int32_t[n]) {
    // Left uninitialised by new and filled by the threads that will use each part first.
    parallel_chunks(n, chunk_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
      std::fill(parent_.get() + begin, parent_.get() + end, root_of_rank(0));
    });
  }

  // Path halving: each element on the way is pointed at its grandparent.
  std::int32_t root(std::int32_t i) {
    std::int32_t* const parent = parent_.get();
    while (parent[i] >= 0) {
      const std::int32_t up = parent[i];
      if (parent[up] < 0) return up;
      i = parent[i] = parent[up];
    }
    return i;
  }

  // The root without shortening the path: safe from several threads at once once no set changes.
  std::int32_t root_of(std::int32_t i) const {
    while (parent_[i] >= 0) i = parent_[i];
    return i;
  }

  void join(std::int32_t a, std::int32_t b) {
    std::int32_t* const parent = parent_.get();
    // Siblings are in one set already. On a mesh swept in order most joins are of two vertices
    // just hung under the root of the set that grows, so this saves them two walks.
    if (parent[a] == parent[b] && parent[a] >= 0) return;
    a = root(a);
    b = root(b);
    if (a == b) return;
    if (parent[a] > parent[b]) std::swap(a, b);  // a's rank is the higher
    if (parent[a] == parent[b]) --parent[a];     // one rank more
    parent[b] = a;
  }

 private:
  // A root holds −1 − its rank (which bounds its tree's height: at most log2(n)), any other
  // element its parent: one array, 4 bytes an element instead of 5 in two.
  static constexpr std::int32_t root_of_rank(std::int32_t rank) { return -1 - rank; }
  std::unique_ptr<std::int32_t[]> parent_;
};

// range_begin for join_in_parallel over the vertices of `triangles`, split as parallel_chunks
// splits them into `chunks`: chunk w's range starts at the smallest corner of its first face.
inline std::vector<std::int32_t> vertex_ranges(std::span<const Triangle> triangles,
                                               std::size_t vertex_count, std::size_t chunks) {
  std::vector<std::int32_t> range_begin(chunks + 1, 0);
  for (std::size_t w = 1; w < chunks; ++w) {
    const Triangle& first = triangles[triangles.size() * w / chunks];
    range_begin[w] = std::max(range_begin[w - 1], std::min({first[0], first[1], first[2]}));
  }
  range_begin[chunks] = static_cast<std::int32_t>(vertex_count);
  for (std::size_t w = 1; w < chunks; ++w)
    range_begin[w] = std::min(range_begin[w], range_begin[chunks]);
  return range_begin;
}

// The pairs that cross ranges, set aside by a call out of the joins' loop.
using JoinPairs = std::vector<std::pair<std::int32_t, std::int32_t>>;
[[gnu::noinline]] inline void set_aside(JoinPairs& pairs, std::int32_t a, std::int32_t b) {
  pairs.emplace_back(a, b);
}

template <class FacePairs>
void join_in_parallel(DisjointSets& sets, std::size_t face_count,
                      std::span<const std::int32_t> range_begin, FacePairs&& face_pairs) {
  const std::size_t chunks = range_begin.size() - 1;
  std::vector<JoinPairs> crossing(chunks);
  parallel_chunks(face_count, chunks, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    const std::int32_t low = range_begin[chunk];
    const auto size = static_cast<std::uint32_t>(range_begin[chunk + 1] - low);
    JoinPairs& later = crossing[chunk];
    // Each end tested against the range by one unsigned comparison: four signed ones, branch by
    // branch, made the pass 1.5 times as long (single-threaded, bench_analyzer's wave fields).
    auto join = [&](std::int32_t a, std::int32_t b) {
      if (static_cast<std::uint32_t>(a - low) < size && static_cast<std::uint32_t>(b - low) < size)
          [[likely]]
        sets.join(a, b);
      else
        set_aside(later, a, b);
    };
    for (std::size_t f = begin; f < end; ++f) face_pairs(f, join);
  });
  for (const JoinPairs& pairs : crossing)
    for (const auto& [a, b] : pairs) sets.join(a, b);
}

}  // namespace toonwater
