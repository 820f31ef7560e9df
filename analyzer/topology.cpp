// Vertex–face incidence and vertex classification over flat arrays.
//
// A vertex is interior when its incident faces form exactly one closed fan: every edge from it
// to a neighbour is shared by exactly two of those faces and the ring of neighbours is one
// cycle. Everything is computed per vertex from its own face list, so the cost is linear in the
// mesh size (valences are small) and needs no halfedge structure.
#include "analyzer/topology.hpp"

#include "analyzer/disjoint_sets.hpp"
#include "common/parallel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <numeric>
#include <queue>
#include <tuple>
#include <utility>

namespace toonwater {

VertexFaces build_vertex_faces(std::size_t vertex_count, std::span<const Triangle> triangles) {
  // A counting sort of the face corners by vertex, on every core: each chunk of faces counts its
  // own corners per vertex, and a vertex's row then holds chunk 0's faces, then chunk 1's, and so
  // on, so every row lists its faces in ascending order whatever the number of chunks.
  const std::size_t chunks = chunk_count(triangles.size());
  std::vector<std::unique_ptr<std::int32_t[]>> cursor(chunks);  // per chunk and vertex
  parallel_chunks(
      triangles.size(), chunks, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        cursor[chunk] = std::make_unique<std::int32_t[]>(vertex_count);  // zeroed by its own thread
        std::int32_t* count = cursor[chunk].get();
        for (std::size_t f = begin; f < end; ++f)
          if (!has_repeated_corner(triangles[f]))
            for (std::int32_t v : triangles[f]) ++count[v];
      });
  VertexFaces vf;
  vf.offsets.resize(vertex_count + 1);
  vf.offsets[0] = 0;
  const std::size_t vertex_chunks = chunk_count(vertex_count);
  parallel_chunks(vertex_count, vertex_chunks,
                  [&](std::size_t, std::size_t begin, std::size_t end) {
                    for (std::size_t v = begin; v < end; ++v) {
                      std::int32_t faces = 0;
                      for (const auto& count : cursor) faces += count[v];
                      vf.offsets[v + 1] = faces;
                    }
                  });
  std::partial_sum(vf.offsets.begin(), vf.offsets.end(), vf.offsets.begin());
  parallel_chunks(vertex_count, vertex_chunks,
                  [&](std::size_t, std::size_t begin, std::size_t end) {
                    for (std::size_t v = begin; v < end; ++v) {
                      std::int32_t row = vf.offsets[v];  // where each chunk's faces of v start
                      for (const auto& count : cursor) row += std::exchange(count[v], row);
                    }
                  });
  vf.face_indices.resize(static_cast<std::size_t>(vf.offsets.back()));
  parallel_chunks(triangles.size(), chunks,
                  [&](std::size_t chunk, std::size_t begin, std::size_t end) {
                    std::int32_t* next = cursor[chunk].get();
                    for (std::size_t f = begin; f < end; ++f)
                      if (!has_repeated_corner(triangles[f]))
                        for (std::int32_t v : triangles[f])
                          vf.face_indices[next[v]++] = static_cast<std::int32_t>(f);
                  });
  return vf;
}

namespace {

// The two corners of `t` other than `v`.
std::pair<std::int32_t, std::int32_t> other_corners(const Triangle& t, std::int32_t v) {
  if (t[0] == v) return {t[1], t[2]};
  if (t[1] == v) return {t[2], t[0]};
  return {t[0], t[1]};
}

struct RingNeighbour {
  std::int32_t vertex;
  std::int32_t face_count;  // faces around the centre that contain the edge centre–vertex
  std::int32_t outgoing;    // of those, the faces whose winding runs centre → vertex
  std::int32_t root;        // union-find over the ring, to test that it is one cycle
};

std::int32_t find_root(std::vector<RingNeighbour>& ring, std::int32_t i) {
  while (ring[i].root != i) i = ring[i].root = ring[ring[i].root].root;
  return i;
}

// The slot of `vertex` in the ring, added if new. Scanning is fastest for the handful of
// neighbours most vertices have; the ring of a vertex with more faces than this (a fan of
// thousands, as degenerate or hostile input has) is listed sorted beforehand and searched, so
// that classifying it costs O(k log k) instead of O(k²).
constexpr std::size_t ring_scan_limit = 32;

std::int32_t ring_slot(std::vector<RingNeighbour>& ring, std::int32_t vertex, bool sorted) {
  if (sorted) {
    const auto it =
        std::lower_bound(ring.begin(), ring.end(), vertex,
                         [](const RingNeighbour& r, std::int32_t w) { return r.vertex < w; });
    return static_cast<std::int32_t>(it - ring.begin());
  }
  for (std::size_t i = 0; i < ring.size(); ++i)
    if (ring[i].vertex == vertex) return static_cast<std::int32_t>(i);
  ring.push_back({vertex, 0, 0, static_cast<std::int32_t>(ring.size())});
  return static_cast<std::int32_t>(ring.size() - 1);
}

// Every neighbour of v in its slot, sorted by vertex.
void list_ring_sorted(const TriangleMesh& mesh, std::span<const std::int32_t> faces, std::int32_t v,
                      std::vector<RingNeighbour>& ring) {
  for (std::int32_t f : faces) {
    const auto [a, b] = other_corners(mesh.triangles[f], v);
    ring.push_back({a, 0, 0, 0});
    ring.push_back({b, 0, 0, 0});
  }
  std::sort(ring.begin(), ring.end(),
            [](const RingNeighbour& x, const RingNeighbour& y) { return x.vertex < y.vertex; });
  ring.erase(std::unique(ring.begin(), ring.end(),
                         [](const RingNeighbour& x, const RingNeighbour& y) {
                           return x.vertex == y.vertex;
                         }),
             ring.end());
  for (std::size_t i = 0; i < ring.size(); ++i) ring[i].root = static_cast<std::int32_t>(i);
}

struct VertexEdges {
  VertexKind kind;
  std::size_t boundary_edges;     // edges from this vertex with one face
  std::size_t nonmanifold_edges;  // edges from this vertex with three or more faces
  std::size_t misoriented_edges;  // edges from it with two faces that wind them the same way
};

// Whether v's faces, each winding v → a → b → v, form one consistently wound fan: following each
// face to the face whose a is its b visits every face once and comes back. Then every neighbour
// is the a of one face and the b of one (two faces on each edge, wound opposite ways) and the
// ring is one cycle: v is interior with no boundary, non-manifold or misoriented edge, as
// classify_vertex's general count would find. Nearly every vertex of a surface is such a fan,
// and this test of a few comparisons (k² for k faces, up to 16) costs a fraction of the count.
constexpr std::size_t fan_test_limit = 16;

bool is_closed_consistent_fan(const TriangleMesh& mesh, std::span<const std::int32_t> faces,
                              std::int32_t v) {
  const std::size_t k = faces.size();
  if (k > fan_test_limit) return false;
  std::int32_t a[fan_test_limit], b[fan_test_limit];
  for (std::size_t i = 0; i < k; ++i)
    std::tie(a[i], b[i]) = other_corners(mesh.triangles[faces[i]], v);
  std::size_t face = 0;
  for (std::size_t step = 1; step <= k; ++step) {
    std::size_t next = 0;
    while (next < k && a[next] != b[face]) ++next;
    if (next == k) return false;  // an edge with one face, or wound the same way twice
    face = next;
    if (face == 0) return step == k;  // back at the start: one cycle through all k faces?
  }
  return false;
}

VertexEdges classify_vertex(const TriangleMesh& mesh, const VertexFaces& vf, std::int32_t v,
                            std::vector<RingNeighbour>& ring) {
  const auto faces = vf.of(v);
  if (faces.empty()) return {VertexKind::isolated, 0, 0, 0};
  if (is_closed_consistent_fan(mesh, faces, v)) return {VertexKind::interior, 0, 0, 0};
  ring.clear();
  const bool sorted = faces.size() > ring_scan_limit;
  if (sorted) list_ring_sorted(mesh, faces, v, ring);
  for (std::int32_t f : faces) {
    // The face winds v → a → b → v: the edge to a leaves v, the edge to b enters it.
    const auto [a, b] = other_corners(mesh.triangles[f], v);
    const std::int32_t sa = ring_slot(ring, a, sorted);
    const std::int32_t sb = ring_slot(ring, b, sorted);
    ++ring[sa].face_count;
    ++ring[sa].outgoing;
    ++ring[sb].face_count;
    ring[find_root(ring, sa)].root = find_root(ring, sb);
  }
  VertexEdges result{VertexKind::interior, 0, 0, 0};
  std::int32_t roots = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    if (ring[i].face_count == 1) ++result.boundary_edges;
    if (ring[i].face_count >= 3) ++result.nonmanifold_edges;
    if (ring[i].face_count == 2 && ring[i].outgoing != 1) ++result.misoriented_edges;
    if (find_root(ring, static_cast<std::int32_t>(i)) == static_cast<std::int32_t>(i)) ++roots;
  }
  if (result.nonmanifold_edges > 0 || roots > 1 || result.boundary_edges > 2)
    result.kind = VertexKind::nonmanifold;  // fans meeting at a point, or a fin
  else if (result.boundary_edges > 0)
    result.kind = VertexKind::boundary;
  return result;
}

}  // namespace

MeshTopology analyze_topology(const TriangleMesh& mesh) {
  MeshTopology topo;
  topo.vertex_faces = build_vertex_faces(mesh.positions.size(), mesh.triangles);
  const std::size_t n = mesh.positions.size();
  topo.kind.resize(n);

  // Counts are exact in any order, so the threads' counts may be added as they come.
  struct Counts {
    std::size_t boundary_edge_ends = 0, nonmanifold_edge_ends = 0, misoriented_edge_ends = 0;
    std::size_t boundary = 0, nonmanifold = 0, isolated = 0;
  };
  const Counts total = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, serial_below), Counts{},
      [&](const tbb::blocked_range<std::size_t>& range, Counts counts) {
        std::vector<RingNeighbour> ring;  // reused from vertex to vertex of the range
        for (std::size_t v = range.begin(); v < range.end(); ++v) {
          const VertexEdges e =
              classify_vertex(mesh, topo.vertex_faces, static_cast<std::int32_t>(v), ring);
          topo.kind[v] = e.kind;
          counts.boundary_edge_ends += e.boundary_edges;
          counts.nonmanifold_edge_ends += e.nonmanifold_edges;
          counts.misoriented_edge_ends += e.misoriented_edges;
          counts.boundary += e.kind == VertexKind::boundary;
          counts.nonmanifold += e.kind == VertexKind::nonmanifold;
          counts.isolated += e.kind == VertexKind::isolated;
        }
        return counts;
      },
      [](Counts a, const Counts& b) {
        a.boundary_edge_ends += b.boundary_edge_ends;
        a.nonmanifold_edge_ends += b.nonmanifold_edge_ends;
        a.misoriented_edge_ends += b.misoriented_edge_ends;
        a.boundary += b.boundary;
        a.nonmanifold += b.nonmanifold;
        a.isolated += b.isolated;
        return a;
      });
  topo.boundary_vertices = total.boundary;
  topo.nonmanifold_vertices = total.nonmanifold;
  topo.isolated_vertices = total.isolated;
  topo.boundary_edges = total.boundary_edge_ends / 2;  // each edge was seen from both of its ends
  topo.nonmanifold_edges = total.nonmanifold_edge_ends / 2;
  topo.misoriented_edges = total.misoriented_edge_ends / 2;
  return topo;
}

// Vertices in a face, joined along the faces' edges on every core; a root that is a used
// (non-isolated) vertex is one component.
std::size_t count_components(const TriangleMesh& mesh, const MeshTopology& topology) {
  const std::vector<VertexKind>& kind = topology.kind;
  const std::size_t n = mesh.positions.size();
  const std::span<const Triangle> triangles = mesh.triangles;
  DisjointSets sets(n);
  join_in_parallel(sets, triangles.size(),
                   vertex_ranges(triangles, n, chunk_count(triangles.size())),
                   [&](std::size_t f, auto& join) {
                     const Triangle& t = triangles[f];
                     if (has_repeated_corner(t)) return;
                     join(t[0], t[1]);
                     join(t[1], t[2]);
                   });
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, serial_below), std::size_t{0},
      [&](const tbb::blocked_range<std::size_t>& range, std::size_t components) {
        for (std::size_t v = range.begin(); v < range.end(); ++v) {
          const auto i = static_cast<std::int32_t>(v);
          components += kind[v] != VertexKind::isolated && sets.root_of(i) == i;
        }
        return components;
      },
      std::plus<>());
}

namespace {

// Does triangle t traverse the edge a→b in its winding?
bool has_directed_edge(const Triangle& t, std::int32_t a, std::int32_t b) {
  return (t[0] == a && t[1] == b) || (t[1] == a && t[2] == b) || (t[2] == a && t[0] == b);
}

// The single other face sharing edge {a, b} with face f, or -1 on a boundary or non-manifold edge.
std::int32_t manifold_neighbour(const TriangleMesh& mesh, const VertexFaces& vf, std::int32_t f,
                                std::int32_t a, std::int32_t b) {
  std::int32_t found = -1;
  for (std::int32_t g : vf.of(a)) {
    if (g == f) continue;
    const Triangle& t = mesh.triangles[g];
    if (t[0] == b || t[1] == b || t[2] == b) {
      if (found >= 0) return -1;
      found = g;
    }
  }
  return found;
}

}  // namespace

std::size_t orient_consistently(TriangleMesh& mesh, const MeshTopology& topology) {
  if (topology.misoriented_edges == 0) return 0;  // every neighbour agrees: nothing would flip
  const VertexFaces& vf = topology.vertex_faces;
  const std::size_t face_count = mesh.triangles.size();
  constexpr std::int8_t unvisited = -1;
  std::vector<std::int8_t> flip(face_count, unvisited);
  std::vector<std::int32_t> component_faces;
  std::queue<std::int32_t> queue;
  std::size_t flipped = 0;

  for (std::size_t seed = 0; seed < face_count; ++seed) {
    if (flip[seed] != unvisited || has_repeated_corner(mesh.triangles[seed])) continue;
    component_faces.clear();
    flip[seed] = 0;
    queue.push(static_cast<std::int32_t>(seed));
    std::size_t flipped_in_component = 0;
    while (!queue.empty()) {
      const std::int32_t f = queue.front();
      queue.pop();
      component_faces.push_back(f);
      const Triangle& t = mesh.triangles[f];
      for (int c = 0; c < 3; ++c) {
        // Edge a→b as face f would traverse it after its own flip.
        std::int32_t a = t[c], b = t[(c + 1) % 3];
        if (flip[f]) std::swap(a, b);
        const std::int32_t g = manifold_neighbour(mesh, vf, f, a, b);
        if (g < 0 || flip[g] != unvisited) continue;
        // A consistent neighbour traverses the shared edge the other way, b→a.
        flip[g] = has_directed_edge(mesh.triangles[g], a, b) ? 1 : 0;
        flipped_in_component += static_cast<std::size_t>(flip[g]);
        queue.push(g);
      }
    }
    // Keep the orientation most of the component's faces already have.
    const bool invert = 2 * flipped_in_component > component_faces.size();
    for (std::int32_t f : component_faces) {
      if (invert) flip[f] = static_cast<std::int8_t>(1 - flip[f]);
      if (flip[f]) {
        std::swap(mesh.triangles[f][1], mesh.triangles[f][2]);
        ++flipped;
      }
    }
  }
  return flipped;
}

}  // namespace toonwater
