// Welding by exact position: one pass over the vertices with an open-addressing hash table
// (linear probing over a flat array of welded-vertex indices, at most half full), so the cost is
// linear in the vertex count. Positions are compared with ==, so +0 and -0 weld, and hashed after
// adding +0.0, which turns -0 into +0 so that both hash alike.
#include "analyzer/weld.hpp"

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
  std::size_t count = 0;
  for (std::size_t v = 0; v < n; ++v) {
    const Vec3 p = positions[v];
    std::size_t slot = position_hash(p) & mask;
    while (slots[slot] >= 0 && positions[slots[slot]] != p) slot = (slot + 1) & mask;
    if (slots[slot] < 0) {
      slots[slot] = static_cast<std::int32_t>(count);
      positions[count++] = p;
    }
    welded.input_to_mesh[v] = slots[slot];
  }
  positions.resize(count);
  welded.merged_vertex_count = n - count;

  for (Triangle& t : mesh.triangles)
    for (std::int32_t& corner : t) corner = welded.input_to_mesh[corner];
  welded.mesh = std::move(mesh);
  return welded;
}

}  // namespace toonwater
