// Connectivity of a triangle soup held in flat arrays: which faces touch each vertex, which
// vertices lie on a boundary or a non-manifold edge, and a consistent face orientation.
#pragma once

#include "analyzer/mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace toonwater {

// Faces incident to each vertex in compressed rows: faces of vertex v are
// face_indices[offsets[v] .. offsets[v + 1]).
struct VertexFaces {
  std::vector<std::int32_t> offsets;
  std::vector<std::int32_t> face_indices;

  std::span<const std::int32_t> of(std::int32_t v) const {
    return {face_indices.data() + offsets[v], face_indices.data() + offsets[v + 1]};
  }
};

enum class VertexKind : std::uint8_t {
  interior,     // its faces form one closed fan
  boundary,     // on an edge with one face
  nonmanifold,  // on an edge with three or more faces, or where several fans meet
  isolated,     // in no (non-degenerate) face
};

struct MeshTopology {
  VertexFaces vertex_faces;
  std::vector<VertexKind> kind;  // per vertex
  std::size_t boundary_vertices = 0;
  std::size_t nonmanifold_vertices = 0;
  std::size_t isolated_vertices = 0;
  std::size_t boundary_edges = 0;
  std::size_t nonmanifold_edges = 0;
  // Two-face edges whose faces both wind them the same way (as read, before orient_consistently).
  std::size_t misoriented_edges = 0;
};

// Faces with a repeated corner index are not faces of the surface; they are ignored here.
// Inline: the passes over every face call it.
inline bool has_repeated_corner(const Triangle& t) {
  return t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
}

// One key per undirected edge {a, b} of non-negative vertex indices, the same either way round.
inline std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

VertexFaces build_vertex_faces(std::size_t vertex_count, std::span<const Triangle> triangles);

MeshTopology analyze_topology(const TriangleMesh& mesh);

// Connected components: sets of faces joined through shared vertices (isolated vertices are
// none). `topology` is analyze_topology's of `mesh`. Not part of analyze_topology, whose other
// results every analysis needs: no output of the analyzer depends on it.
std::size_t count_components(const TriangleMesh& mesh, const MeshTopology& topology);

// Flips faces so that neighbours across every two-face edge agree, component by component. Each
// component keeps the orientation held by the larger share of its faces (by count), so the
// normals point to the side the file's winding mostly points to. Returns the number of faces
// flipped: the faces whose winding disagreed with their neighbours'. A mesh with no misoriented
// edge (`topology` is analyze_topology's of `mesh`) is consistent already and is left untouched
// without a search.
std::size_t orient_consistently(TriangleMesh& mesh, const MeshTopology& topology);

}  // namespace toonwater
