// Free-surface selection; the rules are stated in free_surface.hpp.
#include "analyzer/free_surface.hpp"

#include "analyzer/disjoint_sets.hpp"
#include "common/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>

namespace toonwater {
namespace {

// Rule 1 of the header: the vertex's faces and its neighbours' faces all face up. (In Mantaflow
// output the fillets' faces tilt 6°–65° off the vertical.)
std::vector<std::uint8_t> upward_vertices(const TriangleMesh& mesh, const VertexFaces& vf,
                                                int up, double min_up_component) {
  std::vector<std::int8_t> face_up(mesh.triangles.size(), 0);  // 1 up, -1 not, 0 no normal
  parallel_chunks(mesh.triangles.size(), worker_count(mesh.triangles.size()),
                  [&](std::size_t, std::size_t begin, std::size_t end) {
                    for (std::size_t f = begin; f < end; ++f) {
                      const Triangle& t = mesh.triangles[f];
                      const Vec3& a = mesh.positions[t[0]];
                      const Vec3 cross = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
                      const double length = cross.norm();
                      if (length > 0.0 && std::isfinite(length))
                        face_up[f] = cross[up] > min_up_component * length ? 1 : -1;
                    }
                  });
  const std::size_t n = mesh.positions.size();
  std::vector<std::uint8_t> faces_up(n, 0);
  parallel_chunks(n, worker_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      bool any_up = false, all_up = true;
      for (std::int32_t f : vf.of(static_cast<std::int32_t>(v))) {
        any_up |= face_up[f] > 0;
        all_up &= face_up[f] >= 0;
      }
      faces_up[v] = any_up && all_up;
    }
  });
  std::vector<std::uint8_t> free_surface(n, 0);
  parallel_chunks(n, worker_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      bool inside = faces_up[v];
      for (std::int32_t f : vf.of(static_cast<std::int32_t>(v)))
        for (std::int32_t w : mesh.triangles[f]) inside = inside && faces_up[w];
      free_surface[v] = inside;
    }
  });
  return free_surface;
}

// Median of at most 100k values sampled evenly from `values` (which it reorders).
double sampled_median(std::span<double> values) {
  if (values.empty()) return 0.0;
  const std::size_t stride = std::max<std::size_t>(1, values.size() / 100000);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < values.size(); i += stride) values[kept++] = values[i];
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(kept / 2);
  std::nth_element(values.begin(), middle, values.begin() + static_cast<std::ptrdiff_t>(kept));
  return *middle;
}

// Patches: connected components of the upward vertices, joined along face edges.
struct Patches {
  std::vector<std::int32_t> of_vertex;  // patch index, −1 outside
  std::size_t count = 0;
};

Patches find_patches(const TriangleMesh& mesh, const std::vector<std::uint8_t>& upward) {
  DisjointSets sets(mesh.positions.size());
  for (const Triangle& t : mesh.triangles) {
    const bool up0 = upward[t[0]], up1 = upward[t[1]], up2 = upward[t[2]];
    // With all three upward, two edges join the face; its third edge would add nothing.
    if (up0 && up1) sets.join(t[0], t[1]);
    if (up1 && up2) sets.join(t[1], t[2]);
    if (up2 && up0 && !up1) sets.join(t[2], t[0]);
  }
  Patches patches;
  patches.of_vertex.assign(mesh.positions.size(), -1);
  std::vector<std::int32_t> index_of_root(mesh.positions.size(), -1);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (!upward[v]) continue;
    std::int32_t& index = index_of_root[sets.root(static_cast<std::int32_t>(v))];
    if (index < 0) index = static_cast<std::int32_t>(patches.count++);
    patches.of_vertex[v] = index;
  }
  return patches;
}

}  // namespace

FreeSurface select_free_surface(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                                double edge_length, const FreeSurfaceOptions& options) {
  const int up = static_cast<int>(options.up);
  FreeSurface surface;
  surface.selected = upward_vertices(mesh, vertex_faces, up, options.min_up_component);
  const Patches patches = find_patches(mesh, surface.selected);

  // The heights patch by patch in one array (a counting sort, in vertex order within a patch).
  std::vector<std::size_t> patch_begin(patches.count + 1, 0);
  for (std::int32_t p : patches.of_vertex)
    if (p >= 0) ++patch_begin[p + 1];
  std::vector<std::size_t> patch_size(patches.count);
  for (std::size_t p = 0; p < patches.count; ++p) patch_size[p] = patch_begin[p + 1];
  std::partial_sum(patch_begin.begin(), patch_begin.end(), patch_begin.begin());
  std::vector<double> heights(patch_begin.back());
  std::vector<std::size_t> fill(patch_begin.begin(), patch_begin.end() - 1);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    if (patches.of_vertex[v] >= 0) heights[fill[patches.of_vertex[v]]++] = mesh.positions[v][up];
  std::size_t largest = 0;
  for (std::size_t p = 1; p < patches.count; ++p)
    if (patch_size[p] > patch_size[largest]) largest = p;

  std::vector<double> median(patches.count);
  for (std::size_t p = 0; p < patches.count; ++p)
    median[p] = sampled_median(std::span(heights).subspan(patch_begin[p], patch_size[p]));
  surface.rest_height =
      options.rest_height.value_or(patches.count > 0 ? median[largest] : 0.0);

  std::vector<std::uint8_t> keep(patches.count, 0);
  for (std::size_t p = 0; p < patches.count; ++p) {
    keep[p] = p == largest || (patch_size[p] >= options.min_patch_vertices &&
                               median[p] >= surface.rest_height - options.max_depth * edge_length);
    surface.patches_kept += keep[p];
  }
  surface.patches_dropped = patches.count - surface.patches_kept;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    surface.selected[v] = patches.of_vertex[v] >= 0 && keep[patches.of_vertex[v]];
    surface.vertices += surface.selected[v];
  }
  return surface;
}

}  // namespace toonwater
