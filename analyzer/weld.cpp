// Welding by exact position: one pass over the vertices with an open-addressing hash table
// (linear probing over a flat array of welded-vertex indices, at most half full), so the cost is
// linear in the vertex count. Positions are compared with ==, so +0 and -0 weld, and hashed after
// adding +0.0, which turns -0 into +0 so that both hash alike. The hashing and the renumbering
// of the triangles (skipped when nothing merged) run on every core; the insertion stays serial,
// so welded vertices keep the order of their first occurrence.
#include "analyzer/weld.hpp"

#include "common/parallel.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
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
  const std::size_t capacity = std::bit_ceil(std::max<std::size_t>(2 * n, 16));
  const std::size_t mask = capacity - 1;
  std::vector<std::int32_t> slots(capacity, -1);  // welded vertex index, or -1 for empty

  // Welded vertices are compacted to the front of the same array: a vertex's welded index is
  // never above its input index, so no position is overwritten before it is read.
  std::vector<Vec3>& positions = mesh.positions;
  WeldedMesh welded;
  welded.input_to_mesh.resize(n);
  // The hashes first (on every core), so that the serial insertion below can prefetch the slot
  // it will probe a few vertices ahead: the probes are random over a table far larger than the
  // cache, and waiting for each in turn was most of the cost.
  std::vector<std::uint32_t> home(n);
  parallel_chunks(n, chunk_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
      home[v] = static_cast<std::uint32_t>(position_hash(positions[v]) & mask);
  });
  constexpr std::size_t prefetch_distance = 16;
  std::size_t count = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (v + prefetch_distance < n) __builtin_prefetch(&slots[home[v + prefetch_distance]]);
    const Vec3 p = positions[v];
    std::size_t slot = home[v];
    while (slots[slot] >= 0 && positions[slots[slot]] != p) slot = (slot + 1) & mask;
    if (slots[slot] < 0) {
      slots[slot] = static_cast<std::int32_t>(count);
      positions[count++] = p;
    }
    welded.input_to_mesh[v] = slots[slot];
  }
  positions.resize(count);
  welded.merged_vertex_count = n - count;

  std::vector<Triangle>& triangles = mesh.triangles;
  if (count == n) {  // nothing merged: every vertex kept its index, the triangles are unchanged
    welded.mesh = std::move(mesh);
    return welded;
  }
  parallel_chunks(triangles.size(), chunk_count(triangles.size()),
                  [&](std::size_t, std::size_t begin, std::size_t end) {
                    for (std::size_t f = begin; f < end; ++f)
                      for (std::int32_t& corner : triangles[f])
                        corner = welded.input_to_mesh[corner];
                  });
  welded.mesh = std::move(mesh);
  return welded;
}

}  // namespace toonwater
