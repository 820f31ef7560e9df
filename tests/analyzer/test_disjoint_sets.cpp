// Union-find joined over the faces on several cores: the same sets as joined on one, whatever
// the order of the faces (a shuffled order makes most pairs cross the chunks' ranges).
#include "analyzer/disjoint_sets.hpp"
#include "corpus/analytic_surfaces.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace toonwater::test {
namespace {

// Per vertex: the smallest vertex of its set, so two partitions compare element by element.
std::vector<std::int32_t> smallest_of_set(DisjointSets& sets, std::size_t n) {
  std::vector<std::int32_t> smallest(n, -1), result(n);
  for (std::size_t v = 0; v < n; ++v) {
    std::int32_t& s = smallest[sets.root(static_cast<std::int32_t>(v))];
    if (s < 0) s = static_cast<std::int32_t>(v);
    result[v] = s;
  }
  return result;
}

TEST(DisjointSets, JoiningInParallelGivesTheSetsOfJoiningInOrder) {
  TriangleMesh mesh = make_wave_field(300, 0.1, 6.0, 1.0).mesh;  // 178k faces: several chunks
  const std::size_t n = mesh.positions.size();
  // Pairs only between vertices whose (pseudo-random) bit agrees: many small sets.
  std::vector<std::uint8_t> kept(n);
  std::mt19937 rng(7);
  for (auto& k : kept) k = rng() % 3 != 0;
  auto pairs_of = [&](std::size_t f, auto& join) {
    const Triangle& t = mesh.triangles[f];
    for (int c = 0; c < 3; ++c)
      if (kept[t[c]] && kept[t[(c + 1) % 3]]) join(t[c], t[(c + 1) % 3]);
  };
  for (const bool shuffled : {false, true}) {
    if (shuffled) std::shuffle(mesh.triangles.begin(), mesh.triangles.end(), rng);
    DisjointSets in_order(n);
    auto join_now = [&](std::int32_t a, std::int32_t b) { in_order.join(a, b); };
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) pairs_of(f, join_now);
    for (const std::size_t chunks : {1, 2, 3, 8}) {
      DisjointSets parallel(n);
      join_in_parallel(parallel, mesh.triangles.size(), vertex_ranges(mesh.triangles, n, chunks),
                       pairs_of);
      EXPECT_EQ(smallest_of_set(parallel, n), smallest_of_set(in_order, n))
          << chunks << " chunks, faces " << (shuffled ? "shuffled" : "in order");
    }
  }
}

}  // namespace
}  // namespace toonwater::test
