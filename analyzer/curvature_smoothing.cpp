// Jacobi smoothing of vertex fields; formula in curvature_smoothing.hpp.
//
// A step is a pass over the faces that adds each face's sum of its corners' terms (area and area
// times value) to its corners' sums, then a pass over the vertices that divides. Each vertex thus
// sums its faces in ascending order, as VertexFaces lists them (build_vertex_faces), and the
// result is the gather over its faces, bit for bit, read in a third of the loads: every face's
// corners once instead of once from each corner. The faces split over the cores, each chunk
// adding only to the vertices in its range (vertex_ranges, as the union-finds split them); a
// vertex that a face of another chunk touches would get its faces' sums in an order that
// depends on the threads, so these few, on the chunks' borders, gather over their faces instead.
#include "analyzer/curvature_smoothing.hpp"

#include "analyzer/disjoint_sets.hpp"
#include "common/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <utility>

namespace toonwater {
namespace {

// A vertex's two terms, or their sums over faces; zero off the members.
struct Terms {
  double weight, weighted;
  Terms& operator+=(const Terms& other) {
    weight += other.weight;
    weighted += other.weighted;
    return *this;
  }
};

Terms face_sum(const Terms& a, const Terms& b, const Terms& c) {
  return {a.weight + b.weight + c.weight, a.weighted + b.weighted + c.weighted};
}

}  // namespace

void smooth_vertex_field(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                         std::span<const double> vertex_area, std::span<const std::uint8_t> member,
                         std::vector<double>& values, int steps) {
  if (steps <= 0) return;
  const std::size_t n = values.size(), face_count = mesh.triangles.size();
  auto terms_of = [&](std::size_t v, double value) {
    return member[v] ? Terms{vertex_area[v], vertex_area[v] * value} : Terms{0.0, 0.0};
  };
  // Two buffers that trade roles every step: the terms the faces read, and their sums, which
  // the pass over the vertices turns into the next step's terms once it has read them. (Left
  // uninitialised by new: the threads that use them first fill them.)
  std::unique_ptr<Terms[]> terms(new Terms[n]), sums(new Terms[n]);
  const std::size_t workers = worker_count(n);
  parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      terms[v] = terms_of(v, values[v]);
      sums[v] = Terms{0.0, 0.0};
    }
  });
  const std::size_t face_chunks = worker_count(face_count);
  const std::vector<std::int32_t> range_begin = vertex_ranges(mesh.triangles, n, face_chunks);
  // The vertices a face of a chunk whose range does not hold them touches, found by the first
  // step's pass over the faces (the chunks are the same every step).
  std::vector<std::uint8_t> is_shared(n, 0);
  std::vector<std::vector<std::int32_t>> chunk_shared(face_chunks);
  for (int step = 0; step < steps; ++step) {
    parallel_chunks(face_count, face_chunks, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
      const std::int32_t low = range_begin[chunk];
      const auto size = static_cast<std::uint32_t>(range_begin[chunk + 1] - low);
      // The arrays by plain pointers: through the unique_ptrs the compiler loaded the address
      // again for every corner.
      const Terms* const term = terms.get();
      Terms* const sum_of = sums.get();
      for (std::size_t f = begin; f < end; ++f) {
        const Triangle& t = mesh.triangles[f];
        if (has_repeated_corner(t)) continue;  // not among the vertices' faces
        const Terms sum = face_sum(term[t[0]], term[t[1]], term[t[2]]);
        for (const std::int32_t v : t) {
          if (static_cast<std::uint32_t>(v - low) < size) {  // in the chunk's range
            sum_of[v] += sum;
          } else if (step == 0) {
            std::atomic_ref<std::uint8_t> shared(is_shared[v]);
            if (shared.load(std::memory_order_relaxed)) continue;
            shared.store(1, std::memory_order_relaxed);  // another chunk may list it too
            chunk_shared[chunk].push_back(v);
          }
        }
      }
    });
    if (step == 0)
      for (std::size_t chunk = 1; chunk < face_chunks; ++chunk)
        chunk_shared[0].insert(chunk_shared[0].end(), chunk_shared[chunk].begin(), chunk_shared[chunk].end());
    const std::vector<std::int32_t>& shared = chunk_shared[0];
    parallel_chunks(shared.size(), worker_count(shared.size()), [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        Terms sum{0.0, 0.0};
        for (const std::int32_t f : vertex_faces.of(shared[i])) {
          const Triangle& t = mesh.triangles[f];
          sum += face_sum(terms[t[0]], terms[t[1]], terms[t[2]]);
        }
        sums[shared[i]] = sum;
      }
    });
    const bool last = step + 1 == steps;
    parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        if (member[v] && sums[v].weight > 0.0) values[v] = sums[v].weighted / sums[v].weight;
        if (last) continue;
        sums[v] = terms_of(v, values[v]);
        terms[v] = Terms{0.0, 0.0};
      }
    });
    std::swap(terms, sums);
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
  for (std::size_t v = 0; v < n; ++v) {
    const double root =
        std::sqrt(std::max(field.mean[v] * field.mean[v] - field.gaussian[v], 0.0));
    field.k1[v] = field.mean[v] + root;
    field.k2[v] = field.mean[v] - root;
  }
}

}  // namespace toonwater
