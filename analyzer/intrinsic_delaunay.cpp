// Intrinsic Delaunay triangulation by edge flips; see intrinsic_delaunay.hpp.
//
// Halfedge 3f + c runs from faces[f][c] to faces[f][(c + 1) % 3]; twin[h] is the halfedge of
// the other face on that edge, or −1 on a boundary or non-manifold edge. A flip rewrites the two
// faces in place, so halfedge indices stay valid and repeated edges between the same two
// vertices (which intrinsic triangulations may have) need no special case.
#include "analyzer/intrinsic_delaunay.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace toonwater {
namespace {

// Flip only where the weight is negative beyond round-off: a cyclic quad (weight 0) gives the
// same Laplacian either way, and flipping it back and forth would not terminate.
constexpr double flip_tolerance = 1e-12;

// cot of the angle opposite edge `opposite` in a face with the other edges a, b.
double cotangent(double a, double b, double opposite) {
  return (a * a + b * b - opposite * opposite) / (2.0 * double_area_from_lengths(a, b, opposite));
}

double angle(double a, double b, double opposite) {
  return std::atan2(2.0 * double_area_from_lengths(a, b, opposite),
                    a * a + b * b - opposite * opposite);
}

}  // namespace

double double_area_from_lengths(double a, double b, double c) {
  if (a < b) std::swap(a, b);
  if (b < c) std::swap(b, c);
  if (a < b) std::swap(a, b);
  const double product = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return 0.5 * std::sqrt(std::max(product, 0.0));
}

IntrinsicTriangulation intrinsic_delaunay(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                                          double scale, double delta) {
  IntrinsicTriangulation result;
  auto& faces = result.faces;
  auto& lengths = result.lengths;
  std::vector<std::int32_t> intrinsic_index(mesh.triangles.size(), -1);  // of each mesh face
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    std::array<double, 3> l;
    for (int c = 0; c < 3; ++c)
      l[c] = ((mesh.positions[t[(c + 1) % 3]] - mesh.positions[t[c]]) * scale).norm();
    if (has_repeated_corner(t) || l[0] == 0.0 || l[1] == 0.0 || l[2] == 0.0) continue;
    for (double& x : l) x += delta;
    intrinsic_index[f] = static_cast<std::int32_t>(faces.size());
    faces.push_back(t);
    lengths.push_back(l);
  }

  // Twins, from the mesh's faces around each vertex: an edge held by exactly two faces, in
  // opposite directions, is an interior manifold edge.
  const std::size_t halfedges = 3 * faces.size();
  std::vector<std::int32_t> twin(halfedges, -1);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const std::int32_t a = faces[f][c], b = faces[f][(c + 1) % 3];
      int holders = 0;
      std::int32_t reverse = -1;
      for (std::int32_t g : vertex_faces.of(a)) {
        const std::int32_t i = intrinsic_index[g];
        if (i < 0) continue;
        const Triangle& t = faces[i];
        for (int k = 0; k < 3; ++k) {
          if (t[k] == b && t[(k + 1) % 3] == a) {
            ++holders;
            reverse = 3 * i + k;
          } else if (t[k] == a && t[(k + 1) % 3] == b) {
            ++holders;
          }
        }
      }
      if (holders == 2 && reverse >= 0) twin[3 * f + c] = reverse;
    }
  }

  auto length = [&](std::int32_t h) { return lengths[h / 3][h % 3]; };
  auto next = [](std::int32_t h) { return h - h % 3 + (h % 3 + 1) % 3; };
  auto edge_weight = [&](std::int32_t h) {  // cot α + cot β of the edge of h
    const std::int32_t g = twin[h];
    const double cot_k = cotangent(length(next(h)), length(next(next(h))), length(h));
    const double cot_l = cotangent(length(next(g)), length(next(next(g))), length(g));
    return cot_k + cot_l;
  };

  std::vector<std::int32_t> stack;
  for (std::size_t h = 0; h < halfedges; ++h)
    if (twin[h] > static_cast<std::int32_t>(h)) stack.push_back(static_cast<std::int32_t>(h));
  // Each flip strictly lowers the Dirichlet energy (Rippa), so this terminates; the cap only
  // guards against round-off cycling.
  const std::size_t max_flips = 10 * faces.size() + 100;
  while (!stack.empty() && result.flips < max_flips) {
    const std::int32_t h = stack.back();
    stack.pop_back();
    const std::int32_t g = twin[h];
    if (g < 0 || !(edge_weight(h) < -flip_tolerance)) continue;
    const std::int32_t f1 = h / 3, f2 = g / 3;
    if (f1 == f2) continue;
    // f1 = (i, j, k) with h = i→j; f2 = (j, i, l) with g = j→i.
    const std::int32_t h1 = next(h), h2 = next(h1), g1 = next(g), g2 = next(g1);
    const std::int32_t i = faces[f1][h % 3], j = faces[f1][h1 % 3], k = faces[f1][h2 % 3];
    const std::int32_t l = faces[f2][g2 % 3];
    if (k == l) continue;
    const double l_ij = length(h), l_jk = length(h1), l_ki = length(h2);
    const double l_il = length(g1), l_lj = length(g2);
    const double theta_j = angle(l_ij, l_jk, l_ki) + angle(l_ij, l_lj, l_il);
    const double theta_i = angle(l_ij, l_ki, l_jk) + angle(l_ij, l_il, l_lj);
    if (!(theta_j < std::numbers::pi && theta_i < std::numbers::pi)) continue;  // not convex
    const double diagonal =
        std::sqrt(std::max(l_jk * l_jk + l_lj * l_lj - 2.0 * l_jk * l_lj * std::cos(theta_j), 0.0));
    const std::int32_t t_jk = twin[h1], t_ki = twin[h2], t_il = twin[g1], t_lj = twin[g2];
    // f1 becomes (k, l, j): k→l, l→j, j→k; f2 becomes (l, k, i): l→k, k→i, i→l.
    faces[f1] = {k, l, j};
    lengths[f1] = {diagonal, l_lj, l_jk};
    faces[f2] = {l, k, i};
    lengths[f2] = {diagonal, l_ki, l_il};
    const std::int32_t a = 3 * f1, b = 3 * f2;
    auto link = [&](std::int32_t x, std::int32_t y) {
      twin[x] = y;
      if (y >= 0) twin[y] = x;
    };
    link(a, b);
    link(a + 1, t_lj);
    link(a + 2, t_jk);
    link(b + 1, t_ki);
    link(b + 2, t_il);
    for (std::int32_t e : {a + 1, a + 2, b + 1, b + 2})
      if (twin[e] >= 0) stack.push_back(e);
    ++result.flips;
  }

  // Faces per vertex, as compressed rows.
  VertexFaces& vf = result.vertex_faces;
  vf.offsets.assign(mesh.positions.size() + 1, 0);
  for (const Triangle& t : faces)
    for (std::int32_t v : t) ++vf.offsets[v + 1];
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) vf.offsets[v + 1] += vf.offsets[v];
  vf.face_indices.resize(vf.offsets.back());
  std::vector<std::int32_t> fill(vf.offsets.begin(), vf.offsets.end() - 1);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (std::int32_t v : faces[f]) vf.face_indices[fill[v]++] = static_cast<std::int32_t>(f);
  return result;
}

}  // namespace toonwater
