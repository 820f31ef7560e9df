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

WeldedMesh weld_coincident_vertices(const TriangleMesh& input) {
  const std::size_t n = input.positions.size();
  if (n > static_cast<std::size_t>(INT32_MAX)) throw std::length_error("too many vertices to weld");
  const std::size_t capacity = std::bit_ceil(std::max<std::size_t>(2 * n, 16));
  const std::size_t mask = capacity - 1;
  std::vector<std::int32_t> slots(capacity, -1);  // welded vertex index, or -1 for empty

  WeldedMesh welded;
  welded.input_to_mesh.resize(n);
  welded.mesh.positions.reserve(n);
  for (std::size_t v = 0; v < n; ++v) {
    const Vec3& p = input.positions[v];
    std::size_t slot = position_hash(p) & mask;
    while (slots[slot] >= 0 && welded.mesh.positions[slots[slot]] != p) slot = (slot + 1) & mask;
    if (slots[slot] < 0) {
      slots[slot] = static_cast<std::int32_t>(welded.mesh.positions.size());
      welded.mesh.positions.push_back(p);
    }
    welded.input_to_mesh[v] = slots[slot];
  }
  welded.merged_vertex_count = n - welded.mesh.positions.size();

  welded.mesh.triangles.resize(input.triangles.size());
  for (std::size_t f = 0; f < input.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c)
      welded.mesh.triangles[f][c] = welded.input_to_mesh[input.triangles[f][c]];
  return welded;
}

}  // namespace toonwater
