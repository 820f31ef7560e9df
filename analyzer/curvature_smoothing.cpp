// Jacobi smoothing of vertex fields; formula in curvature_smoothing.hpp.
//
// A step is a pass over the faces that adds each face's sum of its corners' terms (area times
// value) to its corners' sums, then a pass over the vertices that divides by the sums of the
// areas. The sums of the areas are the same every step: the first step sums them. Each vertex
// thus sums its faces in ascending order, as VertexFaces lists them (build_vertex_faces), and the
// result is the gather over its faces, bit for bit, read in a third of the loads: every face's
// corners once instead of once from each corner. The terms are computed where they are read,
// not stored: a smoothing holds two arrays beside the field (the sums), which at a million
// vertices is what keeps the analysis within its memory budget. The faces split over the cores,
// each chunk adding only to the vertices in its range (vertex_ranges, as the union-finds split
// them); a vertex that a face of another chunk touches would get its faces' sums in an order
// that depends on the threads, so these few, on the chunks' borders, gather over their faces
// instead.
#include "analyzer/curvature_smoothing.hpp"

#include "analyzer/disjoint_sets.hpp"
#include "common/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <span>

namespace toonwater {
namespace {

// The arrays of a smoothing, by plain pointers: through the unique_ptrs the compiler loaded the
// addresses again for every corner. A vertex's weight is its area where it is a member and 0
// elsewhere; its term, that weight times its value.
struct SmoothingArrays {
  const Triangle* triangles;
  const std::uint8_t* member;
  const double* area;
  const double* value;  // the values of the step's start
  double* term_sum;     // Σ over v's faces of their corners' terms
  double* weight_sum;   // Σ over v's faces of their corners' weights: the same every step

  double weight(std::int32_t v) const { return member[v] ? area[v] : 0.0; }
  // Not 0 · value where v is no member: its value may be inf.
  double term(std::int32_t v) const { return member[v] ? area[v] * value[v] : 0.0; }
};

// One face's corners' terms (and, in the first step, weights) added to those of its corners in
// [low, low + size); the others are listed in `shared` (first step) or left to the gather.
template <bool with_weights>
void add_faces(const SmoothingArrays& a, std::size_t begin, std::size_t end, std::int32_t low,
               std::uint32_t size, std::span<std::uint8_t> is_shared,
               std::vector<std::int32_t>& shared) {
  for (std::size_t f = begin; f < end; ++f) {
    const Triangle& t = a.triangles[f];
    if (has_repeated_corner(t)) continue;  // not among the vertices' faces
    const double term = a.term(t[0]) + a.term(t[1]) + a.term(t[2]);
    double weight = 0.0;
    if constexpr (with_weights) weight = a.weight(t[0]) + a.weight(t[1]) + a.weight(t[2]);
    for (const std::int32_t v : t) {
      if (static_cast<std::uint32_t>(v - low) < size) {  // in the chunk's range
        a.term_sum[v] += term;
        if constexpr (with_weights) a.weight_sum[v] += weight;
      } else if constexpr (with_weights) {
        std::atomic_ref<std::uint8_t> listed(is_shared[static_cast<std::size_t>(v)]);
        if (listed.load(std::memory_order_relaxed)) continue;
        listed.store(1, std::memory_order_relaxed);  // another chunk may list it too
        shared.push_back(v);
      }
    }
  }
}

void smooth_values(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                   std::span<const double> vertex_area, std::span<const std::uint8_t> member,
                   std::vector<double>& values, int steps) {
  if (steps <= 0) return;
  const std::size_t n = values.size(), face_count = mesh.triangles.size();
  // Left uninitialised by new: the threads that use them first fill them.
  std::unique_ptr<double[]> weight_sum(new double[n]);
  std::unique_ptr<double[]> term_sum(new double[n]);
  const SmoothingArrays a{mesh.triangles.data(), member.data(),  vertex_area.data(),
                          values.data(),         term_sum.get(), weight_sum.get()};
  const std::size_t workers = chunk_count(n);
  parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      term_sum[v] = 0.0;
      weight_sum[v] = 0.0;
    }
  });
  const std::size_t face_chunks = chunk_count(face_count);
  const std::vector<std::int32_t> range_begin = vertex_ranges(mesh.triangles, n, face_chunks);
  // The vertices a face of a chunk whose range does not hold them touches, found by the first
  // step's pass over the faces (the chunks are the same every step).
  std::vector<std::uint8_t> is_shared(n, 0);
  std::vector<std::vector<std::int32_t>> chunk_shared(face_chunks);
  for (int step = 0; step < steps; ++step) {
    parallel_chunks(face_count, face_chunks,
                    [&](std::size_t chunk, std::size_t begin, std::size_t end) {
                      const std::int32_t low = range_begin[chunk];
                      const auto size = static_cast<std::uint32_t>(range_begin[chunk + 1] - low);
                      if (step == 0)
                        add_faces<true>(a, begin, end, low, size, is_shared, chunk_shared[chunk]);
                      else
                        add_faces<false>(a, begin, end, low, size, is_shared, chunk_shared[chunk]);
                    });
    if (step == 0)
      for (std::size_t chunk = 1; chunk < face_chunks; ++chunk)
        chunk_shared[0].insert(chunk_shared[0].end(), chunk_shared[chunk].begin(),
                               chunk_shared[chunk].end());
    const std::vector<std::int32_t>& shared = chunk_shared[0];
    parallel_chunks(shared.size(), chunk_count(shared.size()),
                    [&](std::size_t, std::size_t begin, std::size_t end) {
                      for (std::size_t i = begin; i < end; ++i) {
                        double term_total = 0.0;
                        double weight_total = 0.0;
                        for (const std::int32_t f : vertex_faces.of(shared[i])) {
                          const Triangle& t = mesh.triangles[f];
                          term_total += a.term(t[0]) + a.term(t[1]) + a.term(t[2]);
                          if (step == 0)
                            weight_total += a.weight(t[0]) + a.weight(t[1]) + a.weight(t[2]);
                        }
                        term_sum[shared[i]] = term_total;
                        if (step == 0) weight_sum[shared[i]] = weight_total;
                      }
                    });
    const bool last = step + 1 == steps;
    parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        if (member[v] && weight_sum[v] > 0.0) values[v] = term_sum[v] / weight_sum[v];
        if (!last) term_sum[v] = 0.0;
      }
    });
  }
}

}  // namespace

void smooth_vertex_field(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                         std::span<const double> vertex_area, std::span<const std::uint8_t> member,
                         std::vector<double>& values, int steps) {
  smooth_values(mesh, vertex_faces, vertex_area, member, values, steps);
}

void smooth_vertex_field(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                         std::span<const double> vertex_area, std::span<const std::uint8_t> member,
                         std::vector<Vec3>& values, int steps) {
  // A component at a time: the sums of one component need a third of a vector's memory, and a
  // vector's components are smoothed independently anyway.
  std::vector<double> component(values.size());
  for (int axis = 0; axis < 3; ++axis) {
    for (std::size_t v = 0; v < values.size(); ++v) component[v] = values[v][axis];
    smooth_values(mesh, vertex_faces, vertex_area, member, component, steps);
    for (std::size_t v = 0; v < values.size(); ++v) values[v][axis] = component[v];
  }
}

void smooth_curvature(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                      CurvatureField& field, int steps) {
  if (steps <= 0) return;
  const std::size_t n = field.gaussian.size();
  std::vector<std::uint8_t> defined(n);
  for (std::size_t v = 0; v < n; ++v) defined[v] = field.status[v] != CurvatureStatus::undefined;
  smooth_vertex_field(mesh, vertex_faces, field.area, defined, field.gaussian, steps);
  smooth_vertex_field(mesh, vertex_faces, field.area, defined, field.mean, steps);
}

}  // namespace toonwater
