// Welding by exact position with open-addressing hash tables (linear probing over flat arrays of
// input-vertex indices, each at most half full), so the cost is linear in the vertex count.
// Positions are compared with ==, so +0 and -0 weld, and hashed after adding +0.0, which turns
// -0 into +0 so that both hash alike.
//
// Every core takes part: the hashes split the vertices into one part per core, each with a
// table of its own, and each core inserts its part's vertices in input order, so it finds for
// every vertex the first input vertex at its position. Equal positions hash alike and so share a
// part; the result does not depend on the number of parts. The first occurrences are then
// numbered in input order (welded vertices keep the order of their first occurrence).
#include "analyzer/weld.hpp"

#include "common/parallel.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace toonwater {
namespace {

std::uint64_t mix(std::uint64_t h) {  // the splitmix64 finaliser
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

std::uint64_t position_hash(const Vec3& p) {
  std::uint64_t h = 0;
  for (int axis = 0; axis < 3; ++axis) h = mix(h ^ std::bit_cast<std::uint64_t>(p[axis] + 0.0));
  return h;
}

}  // namespace

WeldedMesh weld_coincident_vertices(TriangleMesh mesh) {
  const std::size_t n = mesh.positions.size();
  if (n > static_cast<std::size_t>(INT32_MAX)) throw std::length_error("too many vertices to weld");
  const std::vector<Vec3>& positions = mesh.positions;
  const std::size_t chunks = worker_count(n);
  const std::size_t parts = std::min<std::size_t>(chunks, 64);  // a part is a byte below

  // The hashes first (on every core), so that each part's insertion below can prefetch the slot
  // it will probe a few vertices ahead: the probes are random over a table far larger than the
  // cache, and waiting for each in turn was most of the cost.
  std::vector<std::uint32_t> hash(n);
  std::vector<std::uint8_t> part_of(n);
  std::vector<std::vector<std::size_t>> part_sizes(chunks, std::vector<std::size_t>(parts, 0));
  parallel_chunks(n, chunks, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const std::uint64_t h = position_hash(positions[v]);
      hash[v] = static_cast<std::uint32_t>(h);
      part_of[v] = static_cast<std::uint8_t>(((h >> 32) * parts) >> 32);
      ++part_sizes[chunk][part_of[v]];
    }
  });

  // first[v]: the first input vertex at v's position (v itself for a first occurrence).
  std::vector<std::int32_t> first(n);
  parallel_chunks(parts, parts, [&](std::size_t part, std::size_t, std::size_t) {
    std::size_t size = 0;
    for (const auto& sizes : part_sizes) size += sizes[part];
    const std::size_t capacity = std::bit_ceil(std::max<std::size_t>(2 * size, 16));
    const std::size_t mask = capacity - 1;
    std::vector<std::int32_t> slots(capacity, -1);  // input vertex index, or -1 for empty
    constexpr std::size_t prefetch_distance = 16;
    for (std::size_t v = 0; v < n; ++v) {
      const std::size_t ahead = v + prefetch_distance;
      if (ahead < n && part_of[ahead] == part) __builtin_prefetch(&slots[hash[ahead] & mask]);
      if (part_of[v] != part) continue;
      const Vec3& p = positions[v];
      std::size_t slot = hash[v] & mask;
      while (slots[slot] >= 0 && positions[slots[slot]] != p) slot = (slot + 1) & mask;
      if (slots[slot] < 0) slots[slot] = static_cast<std::int32_t>(v);
      first[v] = slots[slot];
    }
  });

  // Welded indices: first occurrences numbered in input order, counted per chunk first.
  std::vector<std::size_t> firsts_before(chunks + 1, 0);
  parallel_chunks(n, chunks, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    std::size_t count = 0;
    for (std::size_t v = begin; v < end; ++v) count += first[v] == static_cast<std::int32_t>(v);
    firsts_before[chunk + 1] = count;
  });
  std::partial_sum(firsts_before.begin(), firsts_before.end(), firsts_before.begin());
  const std::size_t count = firsts_before.back();

  WeldedMesh welded;
  welded.merged_vertex_count = n - count;
  std::vector<std::int32_t>& input_to_mesh = welded.input_to_mesh;
  input_to_mesh = std::move(first);
  if (count == n) {  // no vertex merged: every vertex is its own first, its index unchanged
    welded.mesh = std::move(mesh);
    return welded;
  }
  // The first occurrences' indices, then every other vertex takes its first's; a vertex's first
  // is never after it, so only first occurrences are written in the first pass.
  std::vector<std::int32_t> welded_index(n);
  parallel_chunks(n, chunks, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    auto next = static_cast<std::int32_t>(firsts_before[chunk]);
    for (std::size_t v = begin; v < end; ++v)
      if (input_to_mesh[v] == static_cast<std::int32_t>(v)) welded_index[v] = next++;
  });
  parallel_chunks(n, chunks, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) input_to_mesh[v] = welded_index[input_to_mesh[v]];
  });
  // Welded vertices are compacted to the front of the same array: a vertex's welded index is
  // never above its input index, so no position is overwritten before it is read.
  std::vector<Vec3>& compacted = mesh.positions;
  std::size_t next = 0;
  for (std::size_t v = 0; v < n; ++v)
    if (static_cast<std::size_t>(input_to_mesh[v]) == next) compacted[next++] = compacted[v];
  compacted.resize(count);

  std::vector<Triangle>& triangles = mesh.triangles;
  parallel_chunks(triangles.size(), worker_count(triangles.size()),
                  [&](std::size_t, std::size_t begin, std::size_t end) {
                    for (std::size_t f = begin; f < end; ++f)
                      for (std::int32_t& corner : triangles[f]) corner = input_to_mesh[corner];
                  });
  welded.mesh = std::move(mesh);
  return welded;
}

}  // namespace toonwater
