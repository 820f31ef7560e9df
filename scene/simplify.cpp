#include "scene/simplify.hpp"

#include "analyzer/closest_point.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
// After the mesh: QuadricT.hh uses OpenMesh's vector traits without including them.
#include <OpenMesh/Core/Geometry/QuadricT.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>

namespace toonwater {
namespace {

// Largest change of L·n and of the flow field s a collapse may make. Band and flow-region
// boundaries do not move at all (their levels are kept); these bound the rest: the shading
// between boundaries of the curvature view, and the normals' turn towards the light.
constexpr double max_l_dot_n_change = 0.05;
constexpr double max_flow_field_change = 0.25;
constexpr double max_face_turn_degrees = 45.0;
constexpr double max_aspect_ratio = 10.0;
// A boundary vertex is on a straight boundary when it lies this close to the line of its
// neighbours, relative to the tolerance.
constexpr double straight_boundary_fraction = 1e-3;
// A vertex of more faces is neither removed nor collapsed into. Every test of a collapse walks
// the faces of both ends, so a hub (the centre of a fan of 100,000 faces, as degenerate input
// has) made the simplification quadratic: 18 s for that fan. The aspect-ratio limit already
// refuses fans this dense (their faces' angles average below 6°), so no ordinary surface is
// affected.
constexpr int largest_collapsed_valence = 64;

// OpenMesh holds the connectivity; positions never move, and everything else the collapses
// read lives in flat arrays indexed like the mesh's handles.
struct StatusTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
};
using RenderMesh = OpenMesh::TriMesh_ArrayKernelT<StatusTraits>;
using HalfedgeHandle = RenderMesh::HalfedgeHandle;
using VertexHandle = RenderMesh::VertexHandle;
using Quadric = OpenMesh::Geometry::QuadricT<double>;

// Range of the original texture coordinates a vertex stands for: u_lo, u_hi, v_lo, v_hi.
using TextureRange = std::array<double, 4>;

TextureRange merged(const TextureRange& a, const TextureRange& b) {
  return {std::min(a[0], b[0]), std::max(a[1], b[1]), std::min(a[2], b[2]), std::max(a[3], b[3])};
}

bool straddles(double lo, double hi, const std::vector<double>& levels) {
  for (double level : levels)
    if (lo < hi && lo <= level && level <= hi) return true;
  return false;
}

// A triangle's height over its longest edge, divided by that edge: 1/aspect ratio, 0 when flat.
double inverse_aspect(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double longest2 =
      std::max({(a - b).squaredNorm(), (b - c).squaredNorm(), (c - a).squaredNorm()});
  return longest2 > 0 ? (b - a).cross(c - a).norm() / longest2 : 0.0;
}

// One collapse of a vertex into a neighbour, ordered by quadric error, then by edge length
// (on flat water every error is 0: the shortest edge first keeps the triangles round).
struct Collapse {
  double error = 0, length2 = 0;
  HalfedgeHandle halfedge;  // from the removed vertex to the kept one
  double bound = 0;         // the geometric bound of the faces it changes
};

bool earlier(const Collapse& a, const Collapse& b) {
  return a.error != b.error ? a.error < b.error : a.length2 < b.length2;
}

// The decimation, in passes over the vertices in index order (memory order, so the arrays
// are read nearly sequentially). A vertex collapses into the neighbour of its least error
// that every constraint allows; the vertices around the collapse then wait for the next pass,
// which spreads each pass's collapses evenly over the surface like a heap would, and are the
// only ones evaluated again there. Passes run until one collapses nothing.
class Decimation {
 public:
  Decimation(RenderMesh& mesh, const std::vector<Vec3>& positions,
             const std::vector<TextureCoordinate>& uv, const SimplifyOptions& options)
      : m_(mesh),
        p_(positions),
        o_(options),
        quadric_(positions.size()),
        range_(positions.size()),
        settled_(positions.size(), 0),
        mark_(positions.size(), 0),
        bound_(mesh.n_faces(), 0.0) {
    for (std::size_t v = 0; v < uv.size(); ++v)
      range_[v] = {uv[v][0], uv[v][0], uv[v][1], uv[v][1]};
    // Garland & Heckbert's quadrics: each face's plane, weighted by its area.
    for (auto f : m_.faces()) {
      const HalfedgeHandle h = m_.halfedge_handle(f);
      const int a = m_.from_vertex_handle(h).idx(), b = m_.to_vertex_handle(h).idx(),
                c = m_.to_vertex_handle(m_.next_halfedge_handle(h)).idx();
      const Vec3 n = (p_[b] - p_[a]).cross(p_[c] - p_[a]);
      const double area2 = n.norm();
      if (!(area2 > 0)) continue;
      const Vec3 u = n / area2;
      Quadric q(u[0], u[1], u[2], -u.dot(p_[a]));
      q *= 0.5 * area2;
      quadric_[a] += q, quadric_[b] += q, quadric_[c] += q;
    }
  }

  void run() {
    std::vector<int> work(p_.size()), next;
    for (std::size_t v = 0; v < work.size(); ++v) work[v] = static_cast<int>(v);
    std::vector<std::uint32_t> touched(p_.size(), 0);  // the last pass that changed it
    for (std::uint32_t pass = 1; !work.empty(); ++pass) {
      next.clear();
      auto touch = [&](VertexHandle w) {
        if (touched[w.idx()] != pass) next.push_back(w.idx());
        touched[w.idx()] = pass;
      };
      for (int v : work) {
        if (touched[v] == pass || settled_[v]) continue;
        const std::optional<Collapse> c = best_collapse(VertexHandle(v));
        if (!c) continue;
        const VertexHandle v1 = collapse(VertexHandle(v), *c);
        touch(v1);
        for (auto w : m_.vv_range(v1)) touch(w);
      }
      std::sort(next.begin(), next.end());
      work.swap(next);
    }
  }

 private:
  // One outgoing halfedge of the vertex being evaluated: its neighbour, and the face on its
  // left (-1 on the boundary) with that face's third corner and unit normal.
  struct Spoke {
    HalfedgeHandle halfedge;
    int to, face, third;
    Vec3 normal;
  };

  // The link condition of OpenMesh's TriConnectivity::is_collapse_ok and the topological tests
  // of its DecimaterT, for v0 whose neighbours carry mark_ == stamp_.
  bool topology_allows(HalfedgeHandle v0v1, bool v0_on_boundary) const {
    const HalfedgeHandle v1v0 = m_.opposite_halfedge_handle(v0v1);
    const VertexHandle v1 = m_.to_vertex_handle(v0v1);
    int vl = -1, vr = -1;
    for (const HalfedgeHandle h : {v0v1, v1v0}) {
      if (m_.is_boundary(h)) continue;
      const HalfedgeHandle h1 = m_.next_halfedge_handle(h), h2 = m_.next_halfedge_handle(h1);
      // A triangle hanging at one edge would leave a dangling edge.
      if (m_.is_boundary(m_.opposite_halfedge_handle(h1)) &&
          m_.is_boundary(m_.opposite_halfedge_handle(h2)))
        return false;
      (h == v0v1 ? vl : vr) = m_.to_vertex_handle(h1).idx();
    }
    if (vl == vr) return false;
    // The one-rings of v0 and v1 share vl and vr only.
    const HalfedgeHandle start = m_.halfedge_handle(v1);
    HalfedgeHandle h = start;
    do {
      const int u = m_.to_vertex_handle(h).idx();
      if (mark_[u] == stamp_ && u != vl && u != vr) return false;
      h = m_.cw_rotated_halfedge_handle(h);
    } while (h != start);
    // A boundary vertex only moves along its boundary; a tetrahedron stays one.
    if (v0_on_boundary && !m_.is_boundary(v0v1) && !m_.is_boundary(v1v0)) return false;
    return !(vl >= 0 && vr >= 0 && valence_three(vl) && valence_three(vr) && adjacent(vl, vr));
  }

  // The valence of v, counted up to `limit` + 1 (a hub's whole fan is never walked).
  int valence_up_to(int v, int limit) const {
    int n = 0;
    for (auto h = m_.cvoh_iter(VertexHandle(v)); h.is_valid() && n <= limit; ++h) ++n;
    return n;
  }
  bool valence_three(int v) const { return valence_up_to(v, 3) == 3; }
  // Too many faces to be removed or collapsed into (largest_collapsed_valence).
  bool is_hub(int v) const {
    return valence_up_to(v, largest_collapsed_valence) > largest_collapsed_valence;
  }

  bool adjacent(int a, int b) const {
    for (auto w : m_.vv_range(VertexHandle(a)))
      if (w.idx() == b) return true;
    return false;
  }

  // On the boundary v0 may only slide into v1 along a straight boundary.
  bool straight_boundary(int v0, int v1) const {
    int other = -1, boundary_edges = 0;
    for (const Spoke& s : spokes_) {
      if (s.face >= 0 && !m_.is_boundary(m_.opposite_halfedge_handle(s.halfedge))) continue;
      ++boundary_edges;
      if (s.to != v1) other = s.to;
    }
    if (boundary_edges != 2 || other < 0) return false;
    const Vec3 &a = p_[other], &b = p_[v1], &p = p_[v0];
    const Vec3 ab = b - a;
    const double t = ab.dot(p - a) / ab.squaredNorm();
    if (!(t > 0.0 && t < 1.0)) return false;
    return (p - (a + t * ab)).norm() <= straight_boundary_fraction * o_.tolerance;
  }

  // The best legal collapse of v0, if any. A vertex whose textures or inherited bound forbid
  // every collapse stays so (both only grow as its neighbours collapse) and is settled.
  std::optional<Collapse> best_collapse(VertexHandle v0h) {
    const int v0 = v0h.idx();
    spokes_.clear();
    bool on_boundary = false;
    const HalfedgeHandle start = m_.halfedge_handle(v0h);
    if (!start.is_valid()) {  // in no face
      settled_[v0] = 1;
      return std::nullopt;
    }
    if (is_hub(v0)) {
      settled_[v0] = 1;
      return std::nullopt;
    }
    HalfedgeHandle h = start;
    do {
      Spoke s{h, m_.to_vertex_handle(h).idx(), -1, -1, Vec3::Zero()};
      if (m_.is_boundary(h)) {
        on_boundary = true;
      } else {
        s.face = m_.face_handle(h).idx();
        s.third = m_.to_vertex_handle(m_.next_halfedge_handle(h)).idx();
        s.normal = (p_[s.to] - p_[v0]).cross(p_[s.third] - p_[v0]).normalized();
      }
      spokes_.push_back(s);
      h = m_.cw_rotated_halfedge_handle(h);
    } while (h != start);
    // v0 needs two faces at least.
    if (spokes_.size() < 3) return std::nullopt;

    TextureRange r = range_[v0];
    double inherited = 0, old_inverse_aspect = 1;
    ++stamp_;
    for (const Spoke& s : spokes_) {
      r = merged(r, range_[s.to]);
      mark_[s.to] = stamp_;
      if (s.face < 0) continue;
      inherited = std::max(inherited, bound_[s.face]);
      old_inverse_aspect =
          std::min(old_inverse_aspect, inverse_aspect(p_[v0], p_[s.to], p_[s.third]));
    }
    if (r[1] - r[0] > o_.u_tolerance || r[3] - r[2] > o_.v_tolerance ||
        straddles(r[0], r[1], o_.u_levels) || straddles(r[2], r[3], o_.v_levels) ||
        inherited > o_.tolerance) {
      settled_[v0] = 1;
      return std::nullopt;
    }

    candidates_.clear();
    for (const Spoke& s : spokes_) {
      if (on_boundary && !straight_boundary(v0, s.to)) continue;
      if (is_hub(s.to)) continue;
      const Vec3& p1 = p_[s.to];
      Collapse c;
      c.halfedge = s.halfedge;
      c.error = (quadric_[v0] + quadric_[s.to])(OpenMesh::Vec3d(p1[0], p1[1], p1[2]));
      c.length2 = (p1 - p_[v0]).squaredNorm();
      candidates_.push_back(c);
    }
    std::sort(candidates_.begin(), candidates_.end(), earlier);

    const double min_cos = std::cos(max_face_turn_degrees * std::numbers::pi / 180.0);
    const double allowed2 = (o_.tolerance - inherited) * (o_.tolerance - inherited);
    for (Collapse& c : candidates_) {
      const int v1 = m_.to_vertex_handle(c.halfedge).idx();
      const Vec3& p1 = p_[v1];
      // The faces v0 leaves, with v1 in its place: no flip, no new sliver, near the old ones.
      double nearest2 = std::numeric_limits<double>::infinity(), new_inverse_aspect = 1;
      bool legal = true;
      for (const Spoke& s : spokes_) {
        if (s.face < 0 || s.to == v1 || s.third == v1) continue;
        const Vec3 &a = p_[s.to], &b = p_[s.third];
        const Vec3 n = (a - p1).cross(b - p1);
        const double area2 = n.norm();
        if (!(area2 > 0) || n.dot(s.normal) < min_cos * area2) {
          legal = false;
          break;
        }
        new_inverse_aspect = std::min(new_inverse_aspect, inverse_aspect(p1, a, b));
        nearest2 = std::min(nearest2, closest_point_on_triangle(p_[v0], p1, a, b).distance2);
      }
      if (!legal || nearest2 > allowed2) continue;
      if (!(new_inverse_aspect > old_inverse_aspect || new_inverse_aspect > 1.0 / max_aspect_ratio))
        continue;
      if (!topology_allows(c.halfedge, on_boundary)) continue;
      c.bound = inherited + std::sqrt(nearest2);
      return c;
    }
    return std::nullopt;
  }

  // Collapses v0 and returns the vertex it went into.
  VertexHandle collapse(VertexHandle v0h, const Collapse& c) {
    const int v0 = v0h.idx();
    const VertexHandle v1h = m_.to_vertex_handle(c.halfedge);
    const int v1 = v1h.idx();
    m_.collapse(c.halfedge);
    settled_[v0] = 1;
    quadric_[v1] += quadric_[v0];
    range_[v1] = merged(range_[v1], range_[v0]);
    // Faces of v1 that did not change get the bound too: larger than theirs, so still a bound.
    for (auto f : m_.vf_range(v1h)) bound_[f.idx()] = std::max(bound_[f.idx()], c.bound);
    return v1h;
  }

  RenderMesh& m_;
  const std::vector<Vec3>& p_;
  const SimplifyOptions& o_;
  std::vector<Quadric> quadric_;
  std::vector<TextureRange> range_;
  std::vector<std::uint8_t> settled_;  // removed, or refused for good
  std::vector<std::uint32_t> mark_;    // == stamp_: a neighbour of the vertex being evaluated
  std::uint32_t stamp_ = 0;
  std::vector<double> bound_;  // per face: the estimate of its distance (simplify.hpp)
  std::vector<Spoke> spokes_;
  std::vector<Collapse> candidates_;
};

// Builds the OpenMesh mesh of `mesh`; false when OpenMesh refuses a face (non-manifold).
bool build_render_mesh(const SceneMesh& mesh, RenderMesh& out) {
  out.reserve(mesh.positions.size(), mesh.triangles.size() * 3 / 2 + 16, mesh.triangles.size());
  for (const Vec3& p : mesh.positions) out.add_vertex(OpenMesh::Vec3d(p.x(), p.y(), p.z()));
  // OpenMesh reports each refused face on its error stream: the frame passes through instead.
  omerr().disable();
  bool ok = true;
  for (const Triangle& t : mesh.triangles) {
    const auto f = out.add_face(RenderMesh::VertexHandle(t[0]), RenderMesh::VertexHandle(t[1]),
                                RenderMesh::VertexHandle(t[2]));
    if (!f.is_valid()) {
      ok = false;
      break;
    }
  }
  omerr().enable();
  return ok;
}

template <class T>
std::vector<T> select(const std::vector<T>& values, const std::vector<int>& kept) {
  if (values.empty()) return {};
  std::vector<T> out(kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) out[i] = values[kept[i]];
  return out;
}

}  // namespace

SimplifyOptions simplify_options(const WaterConfig& water,
                                 std::pair<double, double> band_thresholds, const FlowConfig* flow,
                                 double tolerance) {
  SimplifyOptions o;
  o.tolerance = tolerance;
  const bool toon = water.shading == WaterShading::toon;
  // u = 0.5 + 0.4999 · L·n (or · value / range in the curvature view), v = flow_coordinate(s).
  o.u_tolerance = 0.4999 * max_l_dot_n_change;
  const auto [t_bright, t_medium] = band_thresholds;
  if (toon) o.u_levels = {band_coordinate(t_medium), band_coordinate(t_bright)};
  o.v_tolerance = flow_coordinate(max_flow_field_change) - flow_coordinate(0.0);
  if (toon && flow && flow->enabled) o.v_levels = {flow_coordinate(-1.0), flow_coordinate(1.0)};
  return o;
}

double screen_tolerance(double pixels, double nearest_distance, double angle_degrees, int width,
                        int height) {
  if (!(pixels > 0.0) || !(nearest_distance > 0.0) || width <= 0 || height <= 0) return 0.0;
  const double tan_x = std::tan(0.5 * angle_degrees * std::numbers::pi / 180.0);
  const double tan_y = tan_x * height / width;
  const double focal_pixels = width / (2.0 * tan_x);
  const double cos2 = 1.0 / (1.0 + tan_x * tan_x + tan_y * tan_y);
  return pixels * nearest_distance * cos2 / focal_pixels;
}

SimplifyStats simplify_surface(PreparedSurface& surface, std::vector<TextureCoordinate>& uv,
                               const SimplifyOptions& options) {
  SceneMesh& mesh = surface.mesh;
  SimplifyStats stats;
  stats.faces_before = stats.faces_after = mesh.triangles.size();
  if (!(options.tolerance > 0.0) || mesh.triangles.empty() || uv.size() != mesh.positions.size())
    return stats;

  RenderMesh m;
  if (!build_render_mesh(mesh, m)) return stats;
  Decimation(m, mesh.positions, uv, options).run();

  // The kept vertices (those of a kept face), in their original order.
  std::vector<int> new_index(mesh.positions.size(), -1);
  std::vector<Triangle> triangles;
  triangles.reserve(m.n_faces());
  for (auto f : m.faces()) {
    if (m.status(f).deleted()) continue;
    const HalfedgeHandle h = m.halfedge_handle(f);
    const Triangle t{m.from_vertex_handle(h).idx(), m.to_vertex_handle(h).idx(),
                     m.to_vertex_handle(m.next_halfedge_handle(h)).idx()};
    triangles.push_back(t);
    for (int v : t) new_index[v] = 0;
  }
  std::vector<int> kept;
  for (std::size_t v = 0; v < new_index.size(); ++v)
    if (new_index[v] == 0) {
      new_index[v] = static_cast<int>(kept.size());
      kept.push_back(static_cast<int>(v));
    }
  for (Triangle& t : triangles)
    for (int& v : t) v = new_index[v];

  mesh.positions = select(mesh.positions, kept);
  mesh.normals = select(mesh.normals, kept);
  mesh.triangles = std::move(triangles);
  surface.flow_field = select(surface.flow_field, kept);
  surface.view_values = select(surface.view_values, kept);
  uv = select(uv, kept);
  stats.faces_after = mesh.triangles.size();
  stats.simplified = true;
  return stats;
}

SimplifyStats simplify_water(PreparedSurface& surface, std::vector<TextureCoordinate>& uv,
                             const SceneLayout& layout, const FlowConfig* flow) {
  const CameraReach camera = camera_reach(layout, surface.mesh.min, surface.mesh.max);
  const double tolerance = screen_tolerance(layout.config->water.simplify, camera.nearest_distance,
                                            camera.angle_degrees, camera.width, camera.height);
  return simplify_surface(
      surface, uv,
      simplify_options(layout.config->water, water_thresholds(layout), flow, tolerance));
}

}  // namespace toonwater
