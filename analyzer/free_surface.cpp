// Free-surface selection; the rules are stated in free_surface.hpp.
#include "analyzer/free_surface.hpp"

#include "analyzer/disjoint_sets.hpp"
#include "analyzer/topology.hpp"
#include "common/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace toonwater {
namespace {

// Sets flags[v] from a pass over faces on several threads: two faces of one vertex may set its
// flag at once, which std::atomic_ref makes well defined for the cost of a plain store.
void mark(std::vector<std::uint8_t>& flags, std::int32_t v) {
  std::atomic_ref<std::uint8_t>(flags[v]).store(1, std::memory_order_relaxed);
}

// Rule 1 of the header: the vertex's faces and its neighbours' faces all face up. (In Mantaflow
// output the fillets' faces tilt 6°–65° off the vertical.) A pass over the faces marks the
// corners of up faces and of the others, so no pass gathers over each vertex's faces.
// Faces with a repeated corner, no faces of a vertex (topology.hpp), have no normal either.
std::vector<std::uint8_t> upward_vertices(const TriangleMesh& mesh, int up, double min_up_component) {
  const std::size_t n = mesh.positions.size(), face_count = mesh.triangles.size();
  // A face without a normal (zero area) is neither up nor not up.
  std::vector<std::uint8_t> has_up_face(n, 0), has_other_face(n, 0);
  parallel_chunks(face_count, worker_count(face_count),
                  [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f) {
      const Triangle& t = mesh.triangles[f];
      const Vec3& a = mesh.positions[t[0]];
      const Vec3 cross = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
      const double length = cross.norm();
      if (!(length > 0.0 && std::isfinite(length))) continue;
      auto& flags = cross[up] > min_up_component * length ? has_up_face : has_other_face;
      for (std::int32_t v : t) mark(flags, v);
    }
  });
  parallel_chunks(n, worker_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) has_up_face[v] = has_up_face[v] && !has_other_face[v];
  });
  return one_ring_inside(mesh, has_up_face);
}

// At most this many heights sampled evenly from a patch give its median.
constexpr std::size_t median_samples = 100000;

// Patches: connected components of the upward vertices, joined along face edges, numbered in
// the order of their first vertex.
struct Patches {
  std::vector<std::int32_t> of_vertex;  // patch index, −1 outside
  std::vector<std::int32_t> size;       // vertices per patch
};

Patches find_patches(const TriangleMesh& mesh, const std::vector<std::uint8_t>& upward) {
  const std::size_t n = mesh.positions.size(), face_count = mesh.triangles.size();
  DisjointSets sets(n);
  const std::size_t chunks = worker_count(face_count);
  join_in_parallel(sets, face_count, vertex_ranges(mesh.triangles, n, chunks),
                   [&](std::size_t f, auto& join) {
                     const Triangle& t = mesh.triangles[f];
                     const bool up0 = upward[t[0]], up1 = upward[t[1]], up2 = upward[t[2]];
                     // With all three upward, two edges join the face; its third would add nothing.
                     if (up0 && up1) join(t[0], t[1]);
                     if (up1 && up2) join(t[1], t[2]);
                     if (up2 && up0 && !up1) join(t[2], t[0]);
                   });
  // Each vertex's root in parallel, then the roots numbered in vertex order on one thread (in
  // place: a root is numbered at its patch's first vertex, which no later vertex precedes).
  Patches patches;
  patches.of_vertex.resize(n);
  std::vector<std::int32_t> index_of_root(n);
  parallel_chunks(n, worker_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      patches.of_vertex[v] = upward[v] ? sets.root_of(static_cast<std::int32_t>(v)) : -1;
      index_of_root[v] = -1;
    }
  });
  for (std::size_t v = 0; v < n; ++v) {
    std::int32_t& patch = patches.of_vertex[v];
    if (patch < 0) continue;
    std::int32_t& index = index_of_root[patch];
    if (index < 0) {
      index = static_cast<std::int32_t>(patches.size.size());
      patches.size.push_back(0);
    }
    patch = index;
    ++patches.size[index];
  }
  return patches;
}

}  // namespace

std::vector<std::uint8_t> one_ring_inside(const TriangleMesh& mesh,
                                          const std::vector<std::uint8_t>& selected) {
  const std::size_t n = mesh.positions.size(), face_count = mesh.triangles.size();
  std::vector<std::uint8_t> near_unselected(n, 0);  // a corner of one of its faces is not selected
  parallel_chunks(face_count, worker_count(face_count),
                  [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f) {
      const Triangle& t = mesh.triangles[f];
      if (has_repeated_corner(t) || (selected[t[0]] && selected[t[1]] && selected[t[2]])) continue;
      for (std::int32_t v : t) mark(near_unselected, v);
    }
  });
  parallel_chunks(n, worker_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) near_unselected[v] = selected[v] && !near_unselected[v];
  });
  return near_unselected;
}

FreeSurface select_free_surface(const TriangleMesh& mesh, double edge_length,
                                const FreeSurfaceOptions& options) {
  const int up = static_cast<int>(options.up);
  const std::size_t n = mesh.positions.size();
  FreeSurface surface;
  surface.selected = upward_vertices(mesh, up, options.min_up_component);
  const Patches patches = find_patches(mesh, surface.selected);
  const std::size_t count = patches.size.size();

  // Each patch's sampled heights in one array: every stride-th of its vertices in vertex order.
  std::vector<std::int32_t> stride(count), until_sample(count, 0);
  std::vector<std::size_t> sample_begin(count + 1, 0);
  for (std::size_t p = 0; p < count; ++p) {
    const std::size_t size = static_cast<std::size_t>(patches.size[p]);
    stride[p] = static_cast<std::int32_t>(std::max<std::size_t>(1, size / median_samples));
    sample_begin[p + 1] = sample_begin[p] + (size + stride[p] - 1) / stride[p];
  }
  std::vector<double> heights(sample_begin.back());
  std::vector<std::size_t> fill(sample_begin.begin(), sample_begin.end() - 1);
  for (std::size_t v = 0; v < n; ++v) {
    const std::int32_t p = patches.of_vertex[v];
    if (p < 0 || until_sample[p]-- > 0) continue;
    heights[fill[p]++] = mesh.positions[v][up];
    until_sample[p] = stride[p] - 1;
  }
  std::size_t largest = 0;
  for (std::size_t p = 1; p < count; ++p)
    if (patches.size[p] > patches.size[largest]) largest = p;

  std::vector<double> median(count);
  for (std::size_t p = 0; p < count; ++p) {
    const auto first = heights.begin() + static_cast<std::ptrdiff_t>(sample_begin[p]);
    const auto last = heights.begin() + static_cast<std::ptrdiff_t>(sample_begin[p + 1]);
    const auto middle = first + (last - first) / 2;
    std::nth_element(first, middle, last);
    median[p] = *middle;
  }
  surface.rest_height = options.rest_height.value_or(count > 0 ? median[largest] : 0.0);

  std::vector<std::uint8_t> keep(count, 0);
  for (std::size_t p = 0; p < count; ++p) {
    keep[p] = p == largest ||
              (static_cast<std::size_t>(patches.size[p]) >= options.min_patch_vertices &&
               median[p] >= surface.rest_height - options.max_depth * edge_length);
    surface.patches_kept += keep[p];
  }
  surface.patches_dropped = count - surface.patches_kept;
  for (std::size_t p = 0; p < count; ++p)
    if (keep[p]) surface.vertices += static_cast<std::size_t>(patches.size[p]);
  parallel_chunks(n, worker_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
      surface.selected[v] = patches.of_vertex[v] >= 0 && keep[patches.of_vertex[v]];
  });
  return surface;
}

}  // namespace toonwater
