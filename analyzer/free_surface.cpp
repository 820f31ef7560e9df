// Free-surface selection; the rules are stated in free_surface.hpp.
//
// Three passes over the faces on all cores, each marking the corners of some faces rather than
// gathering over every vertex's faces:
//   1. every face's slope: the corners of up faces and of the others (rule 1), and the lengths
//      of the edges sampled for the median edge length, whose corners are read here anyway;
//   2. the corners of faces with a corner that is not upward: rule 1's neighbours;
//   3. the union-find joins of rule 2's patches, along the edges between selected vertices, and
//      the corners of faces with a corner not selected. All three corners of a face that are
//      selected lie in one patch, so a vertex of a kept patch has a face with a corner off the
//      free surface exactly when it has one with a corner off this selection: these marks give
//      the free surface's border ring (FreeSurface::inside) without a pass after the patches
//      are kept or dropped.
// Then the patches are numbered, counted and their heights sampled in passes over the
// vertices, on all cores too.
#include "analyzer/free_surface.hpp"

#include "analyzer/disjoint_sets.hpp"
#include "analyzer/edge_length.hpp"
#include "analyzer/topology.hpp"
#include "common/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <span>

namespace toonwater {
namespace {

// Sets flags[v] from a pass over faces on several threads: two faces of one vertex may set its
// flag at once, which std::atomic_ref makes well defined for the cost of a plain store. The
// passes that mark hold the arrays they read by plain pointers or spans: a byte store may alias
// anything, so through the vectors the compiler would load their addresses again after every
// mark.
void mark(std::uint8_t* flags, std::int32_t v) {
  std::atomic_ref<std::uint8_t>(flags[v]).store(1, std::memory_order_relaxed);
}

// A pass over a byte a vertex costs less than waking a thread for it up to this many vertices.
constexpr std::size_t bytes_per_worker = std::size_t{1} << 20;

// Pass 1. A face without a normal (zero area; a repeated corner among them) is neither up nor
// not up.
struct Slopes {
  std::vector<std::uint8_t> has_up_face, has_other_face;  // per vertex
  double edge_length = 0.0;
};

// Whether a face's normal n (the cross product of two edges) has n·up > c |n|, given n·up and
// |n|², with the square root taken only where the squares cannot tell: the comparison of the
// squares is exact where they differ by more than their round-off, and a face within a
// billionth of the limit is decided as |n| = sqrt(|n|²) would decide it.
bool faces_up(double up_component, double squared_length, double c) {
  if (c >= 0.0 && up_component <= 0.0) return false;
  if (c > 0.0) {
    const double up2 = up_component * up_component, limit2 = c * c * squared_length;
    if (up2 > limit2 * (1.0 + 1e-9)) return true;
    if (up2 < limit2 * (1.0 - 1e-9)) return false;
  }
  return up_component > c * std::sqrt(squared_length);
}

Slopes mark_slopes(const TriangleMesh& mesh, int up, double min_up_component) {
  const std::size_t n = mesh.positions.size(), face_count = mesh.triangles.size();
  Slopes slopes{std::vector<std::uint8_t>(n, 0), std::vector<std::uint8_t>(n, 0)};
  const EdgeSample sample(face_count);
  const std::size_t workers = chunk_count(face_count);
  // Each chunk's sampled lengths at its own place in one array; the gaps of lengths not
  // counted are closed after.
  std::vector<std::size_t> sample_begin(workers + 1);
  for (std::size_t chunk = 0; chunk <= workers; ++chunk)
    sample_begin[chunk] = sample.first_from(face_count * chunk / workers) / sample.stride();
  std::vector<double> lengths(sample_begin[workers]);
  std::vector<std::size_t> sample_end(workers);
  parallel_chunks(face_count, workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    const std::span<const Vec3> positions = mesh.positions;
    const std::span<const Triangle> triangles = mesh.triangles;
    std::uint8_t* const has_up_face = slopes.has_up_face.data();
    std::uint8_t* const has_other_face = slopes.has_other_face.data();
    double* const squared_lengths = lengths.data();
    std::size_t next_sample = sample.first_from(begin), counted = sample_begin[chunk];
    for (std::size_t f = begin; f < end; ++f) {
      const Triangle& t = triangles[f];
      for (; next_sample < 3 * f + 3; next_sample += sample.stride()) {
        squared_lengths[counted] = EdgeSample::squared_length(positions, triangles, next_sample);
        counted += EdgeSample::counts(squared_lengths[counted]);
      }
      const Vec3& a = positions[t[0]];
      const Vec3 cross = (positions[t[1]] - a).cross(positions[t[2]] - a);
      const double squared_length = cross.squaredNorm();  // of the normal
      if (!(squared_length > 0.0 && std::isfinite(squared_length))) continue;
      std::uint8_t* const flags =
          faces_up(cross[up], squared_length, min_up_component) ? has_up_face : has_other_face;
      for (std::int32_t v : t) mark(flags, v);
    }
    sample_end[chunk] = counted;
  });
  std::size_t kept = sample_end[0];
  for (std::size_t chunk = 1; chunk < workers; ++chunk)
    for (std::size_t i = sample_begin[chunk]; i < sample_end[chunk]; ++i)
      lengths[kept++] = lengths[i];
  lengths.resize(kept);
  slopes.edge_length = median_length(lengths);
  return slopes;
}

// Pass 2: `selected` one ring in, the selected vertices all of whose faces' corners are
// selected. A vertex in no face (faces with a repeated corner are none, topology.hpp) stays
// selected.
std::vector<std::uint8_t> one_ring_inside(const TriangleMesh& mesh,
                                          const std::vector<std::uint8_t>& selected) {
  const std::size_t n = mesh.positions.size(), face_count = mesh.triangles.size();
  std::vector<std::uint8_t> near_unselected(n, 0);  // a corner of one of its faces is not selected
  parallel_chunks(face_count, chunk_count(face_count),
                  [&](std::size_t, std::size_t begin, std::size_t end) {
                    const std::span<const Triangle> triangles = mesh.triangles;
                    const std::uint8_t* const in = selected.data();
                    std::uint8_t* const near = near_unselected.data();
                    for (std::size_t f = begin; f < end; ++f) {
                      const Triangle& t = triangles[f];
                      if (has_repeated_corner(t) || (in[t[0]] && in[t[1]] && in[t[2]])) continue;
                      for (std::int32_t v : t) mark(near, v);
                    }
                  });
  parallel_chunks(n, chunk_count(n, bytes_per_worker),
                  [&](std::size_t, std::size_t begin, std::size_t end) {
                    for (std::size_t v = begin; v < end; ++v)
                      near_unselected[v] = selected[v] && !near_unselected[v];
                  });
  return near_unselected;
}

// Rule 1: the vertex's faces and its neighbours' faces all face up. (In Mantaflow output the
// fillets' faces tilt 6°–65° off the vertical.)
std::vector<std::uint8_t> upward_vertices(const TriangleMesh& mesh, Slopes& slopes) {
  std::vector<std::uint8_t>& upward = slopes.has_up_face;
  parallel_chunks(upward.size(), chunk_count(upward.size(), bytes_per_worker),
                  [&](std::size_t, std::size_t begin, std::size_t end) {
                    for (std::size_t v = begin; v < end; ++v)
                      upward[v] = upward[v] && !slopes.has_other_face[v];
                  });
  return one_ring_inside(mesh, upward);
}

// Pass 3 and the numbering: patches, connected components of the upward vertices joined along
// face edges, numbered in the order of their union-find roots; and the marks of the border ring.
struct Patches {
  std::vector<std::int32_t> of_vertex;     // patch index, −1 outside
  std::vector<std::int32_t> size;          // vertices per patch
  std::vector<std::int32_t> first_vertex;  // per patch
  // Per chunk of vertices (chunk_count(n)) and patch, how many of the patch's vertices come
  // before the chunk's first.
  std::vector<std::vector<std::int32_t>> rank_before_chunk;
  std::vector<std::uint8_t> near_unselected;  // per vertex: a corner of a face of it is not upward
};

Patches find_patches(const TriangleMesh& mesh, const std::vector<std::uint8_t>& upward) {
  const std::size_t n = mesh.positions.size(), face_count = mesh.triangles.size();
  Patches patches;
  patches.near_unselected.assign(n, 0);
  DisjointSets sets(n);
  const std::size_t chunks = chunk_count(face_count);
  join_in_parallel(
      sets, face_count, vertex_ranges(mesh.triangles, n, chunks), [&](std::size_t f, auto& join) {
        const Triangle& t = mesh.triangles[f];
        const bool up0 = upward[t[0]], up1 = upward[t[1]], up2 = upward[t[2]];
        if (up0 && up1 && up2) {  // most faces: two edges join them, a third adds nothing
          join(t[0], t[1]);
          join(t[1], t[2]);
          return;
        }
        if (up0 && up1) join(t[0], t[1]);
        if (up1 && up2) join(t[1], t[2]);
        if (up2 && up0) join(t[2], t[0]);
        if (!has_repeated_corner(t))
          for (std::int32_t v : t) mark(patches.near_unselected.data(), v);
      });
  // Each vertex's root, and the roots, chunk by chunk; the roots are numbered in order.
  const std::size_t workers = chunk_count(n);
  patches.of_vertex.resize(n);
  std::vector<std::vector<std::int32_t>> chunk_roots(workers);
  parallel_chunks(n, workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const std::int32_t root = upward[v] ? sets.root_of(static_cast<std::int32_t>(v)) : -1;
      patches.of_vertex[v] = root;
      if (root == static_cast<std::int32_t>(v)) chunk_roots[chunk].push_back(root);
    }
  });
  // Patch index by root, set at the roots only (the other slots are never read or touched).
  std::unique_ptr<std::int32_t[]> patch_of_root(new std::int32_t[n]);
  std::int32_t count = 0;
  for (const auto& roots : chunk_roots)
    for (std::int32_t root : roots) patch_of_root[root] = count++;
  // Each vertex's patch, and each chunk's count and first vertex of every patch.
  const auto patch_count = static_cast<std::size_t>(count);
  std::vector<std::vector<std::int32_t>> chunk_size(workers), chunk_first(workers);
  parallel_chunks(n, workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    std::vector<std::int32_t>& size = chunk_size[chunk];
    std::vector<std::int32_t>& first = chunk_first[chunk];
    size.assign(patch_count, 0);
    first.assign(patch_count, -1);
    // Counted by runs of one patch in a local: counted in the vector, each vertex's count would
    // wait for the last one's store (most of a frame's vertices are in one patch).
    std::int32_t run_patch = -1, run_length = 0;
    for (std::size_t v = begin; v < end; ++v) {
      std::int32_t& patch = patches.of_vertex[v];
      if (patch < 0) continue;
      patch = patch_of_root[patch];
      if (patch != run_patch) {
        if (run_patch >= 0) size[run_patch] += run_length;
        if (first[patch] < 0) first[patch] = static_cast<std::int32_t>(v);
        run_patch = patch;
        run_length = 0;
      }
      ++run_length;
    }
    if (run_patch >= 0) size[run_patch] += run_length;
  });
  patches.size.assign(patch_count, 0);
  patches.first_vertex.assign(patch_count, -1);
  patches.rank_before_chunk.assign(workers, std::vector<std::int32_t>(patch_count));
  for (std::size_t chunk = 0; chunk < workers; ++chunk)
    for (std::size_t p = 0; p < patch_count; ++p) {
      patches.rank_before_chunk[chunk][p] = patches.size[p];
      patches.size[p] += chunk_size[chunk][p];
      if (patches.first_vertex[p] < 0) patches.first_vertex[p] = chunk_first[chunk][p];
    }
  return patches;
}

// At most this many heights sampled evenly from a patch give its median.
constexpr std::size_t median_samples = 100000;

// The median height of every patch, from every stride-th of its vertices in vertex order.
std::vector<double> median_heights(const TriangleMesh& mesh, int up, const Patches& patches) {
  const std::size_t n = mesh.positions.size(), count = patches.size.size();
  std::vector<std::int32_t> stride(count);
  std::vector<std::size_t> sample_begin(count + 1, 0);
  for (std::size_t p = 0; p < count; ++p) {
    const std::size_t size = static_cast<std::size_t>(patches.size[p]);
    stride[p] = static_cast<std::int32_t>(std::max<std::size_t>(1, size / median_samples));
    sample_begin[p + 1] = sample_begin[p] + (size + stride[p] - 1) / stride[p];
  }
  // Each chunk starts every patch at the first sample at or after its rank there.
  std::vector<double> heights(sample_begin.back());
  const std::size_t workers = patches.rank_before_chunk.size();
  parallel_chunks(n, workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    std::vector<std::size_t> next_sample(count);
    std::vector<std::int32_t> until_sample(count);
    for (std::size_t p = 0; p < count; ++p) {
      const std::int32_t rank = patches.rank_before_chunk[chunk][p];
      const std::int32_t sampled_before = (rank + stride[p] - 1) / stride[p];
      next_sample[p] = sample_begin[p] + static_cast<std::size_t>(sampled_before);
      until_sample[p] = sampled_before * stride[p] - rank;
    }
    // The current patch's place in locals, for runs of vertices of one patch (see find_patches).
    std::int32_t run_patch = -1, until = 0, run_stride = 1;
    std::size_t next = 0;
    for (std::size_t v = begin; v < end; ++v) {
      const std::int32_t p = patches.of_vertex[v];
      if (p < 0) continue;
      if (p != run_patch) {
        if (run_patch >= 0) {
          until_sample[run_patch] = until;
          next_sample[run_patch] = next;
        }
        run_patch = p;
        until = until_sample[p];
        next = next_sample[p];
        run_stride = stride[p];
      }
      if (until-- > 0) continue;
      heights[next++] = mesh.positions[v][up];
      until = run_stride - 1;
    }
  });
  std::vector<double> median(count);
  for (std::size_t p = 0; p < count; ++p) {
    double* const first = heights.data() + sample_begin[p];
    double* const middle = first + (sample_begin[p + 1] - sample_begin[p]) / 2;
    std::nth_element(first, middle, heights.data() + sample_begin[p + 1]);
    median[p] = *middle;
  }
  return median;
}

}  // namespace

FreeSurface select_free_surface(const TriangleMesh& mesh, const FreeSurfaceOptions& options) {
  const int up = static_cast<int>(options.up);
  const std::size_t n = mesh.positions.size();
  FreeSurface surface;
  Slopes slopes = mark_slopes(mesh, up, options.min_up_component);
  surface.edge_length = slopes.edge_length;
  surface.selected = upward_vertices(mesh, slopes);
  Patches patches = find_patches(mesh, surface.selected);
  const std::size_t count = patches.size.size();
  const std::vector<double> median = median_heights(mesh, up, patches);

  // The largest patch; of equal ones, the one whose first vertex comes first.
  std::size_t largest = 0;
  for (std::size_t p = 1; p < count; ++p)
    if (patches.size[p] > patches.size[largest] ||
        (patches.size[p] == patches.size[largest] &&
         patches.first_vertex[p] < patches.first_vertex[largest]))
      largest = p;
  surface.rest_height = options.rest_height.value_or(count > 0 ? median[largest] : 0.0);

  std::vector<std::uint8_t> keep(count, 0);
  for (std::size_t p = 0; p < count; ++p) {
    keep[p] = p == largest ||
              (static_cast<std::size_t>(patches.size[p]) >= options.min_patch_vertices &&
               median[p] >= surface.rest_height - options.max_depth * surface.edge_length);
    surface.patches_kept += keep[p];
    if (keep[p]) surface.vertices += static_cast<std::size_t>(patches.size[p]);
  }
  surface.patches_dropped = count - surface.patches_kept;
  surface.inside = std::move(patches.near_unselected);
  parallel_chunks(n, chunk_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    std::uint8_t *const selected = surface.selected.data(), *const inside = surface.inside.data();
    const std::int32_t* const patch = patches.of_vertex.data();
    const std::uint8_t* const kept = keep.data();
    for (std::size_t v = begin; v < end; ++v) {
      selected[v] = patch[v] >= 0 && kept[patch[v]];
      inside[v] = selected[v] && !inside[v];
    }
  });
  return surface;
}

}  // namespace toonwater
