#include "povgen/simplify.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

namespace toonwater::povgen {
namespace {

// Largest change of L·n and of the flow field s a collapse may make. Band and flow-region
// boundaries do not move at all (their levels are kept); these bound the rest: the shading
// between boundaries of the curvature view, and the normals' turn towards the light.
constexpr double max_l_dot_n_change = 0.05;
constexpr double max_flow_field_change = 0.25;
constexpr double max_face_turn_degrees = 45.0;
constexpr float max_aspect_ratio = 10.0f;
// A boundary vertex is on a straight boundary when it lies this close to the line of its
// neighbours, relative to the tolerance.
constexpr double straight_boundary_fraction = 1e-3;

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};
using RenderMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

// Range of the original texture coordinates a vertex stands for: u_lo, u_hi, v_lo, v_hi.
using TextureRange = std::array<double, 4>;

Vec3 eigen(const OpenMesh::Vec3d& p) { return Vec3(p[0], p[1], p[2]); }

// Squared distance from p to the triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
double point_triangle_squared(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).squaredNorm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).squaredNorm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).squaredNorm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).squaredNorm();
}

bool straddles(double lo, double hi, const std::vector<double>& levels) {
  for (double level : levels)
    if (lo < hi && lo <= level && level <= hi) return true;
  return false;
}

// The geometric, texture and boundary constraints described in simplify.hpp.
template <class MeshT>
class ModToonBoundT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModToonBoundT, MeshT, ToonBound);

  explicit ModToonBoundT(MeshT& mesh) : Base(mesh, true) {}

  void configure(const SimplifyOptions& options, OpenMesh::VPropHandleT<TextureRange> ranges) {
    options_ = &options;
    ranges_ = ranges;
  }

  void initialize() override {
    if (!bounds_.is_valid()) Base::mesh().add_property(bounds_);
    for (auto f : Base::mesh().faces()) Base::mesh().property(bounds_, f) = 0.0;
  }

  float collapse_priority(const CollapseInfo& ci) override {
    return boundary_allows(ci) && textures_allow(ci) && geometric_bound(ci) <= options_->tolerance
               ? float(Base::LEGAL_COLLAPSE)
               : float(Base::ILLEGAL_COLLAPSE);
  }

  void preprocess_collapse(const CollapseInfo& ci) override { pending_bound_ = geometric_bound(ci); }

  void postprocess_collapse(const CollapseInfo& ci) override {
    MeshT& m = Base::mesh();
    TextureRange& r1 = m.property(ranges_, ci.v1);
    r1 = merged(r1, m.property(ranges_, ci.v0));
    // Faces of v1 that did not change get the bound too: larger than theirs, so still a bound.
    for (auto f : m.vf_range(ci.v1))
      m.property(bounds_, f) = std::max(m.property(bounds_, f), pending_bound_);
  }

 private:
  static TextureRange merged(const TextureRange& a, const TextureRange& b) {
    return {std::min(a[0], b[0]), std::max(a[1], b[1]), std::min(a[2], b[2]), std::max(a[3], b[3])};
  }

  bool boundary_allows(const CollapseInfo& ci) {
    MeshT& m = Base::mesh();
    if (!m.is_boundary(ci.v0)) return true;
    if (!m.is_boundary(m.edge_handle(ci.v0v1))) return false;
    typename MeshT::VertexHandle other;
    int boundary_edges = 0;
    for (auto h : m.voh_range(ci.v0)) {
      if (!m.is_boundary(m.edge_handle(h))) continue;
      ++boundary_edges;
      if (m.to_vertex_handle(h) != ci.v1) other = m.to_vertex_handle(h);
    }
    if (boundary_edges != 2 || !other.is_valid()) return false;
    const Vec3 a = eigen(m.point(other)), b = eigen(ci.p1), p = eigen(ci.p0);
    const Vec3 ab = b - a;
    const double t = ab.dot(p - a) / ab.squaredNorm();
    if (!(t > 0.0 && t < 1.0)) return false;
    return (p - (a + t * ab)).norm() <= straight_boundary_fraction * options_->tolerance;
  }

  bool textures_allow(const CollapseInfo& ci) {
    MeshT& m = Base::mesh();
    TextureRange r = merged(m.property(ranges_, ci.v0), m.property(ranges_, ci.v1));
    for (auto w : m.vv_range(ci.v0)) r = merged(r, m.property(ranges_, w));
    return r[1] - r[0] <= options_->u_tolerance && r[3] - r[2] <= options_->v_tolerance &&
           !straddles(r[0], r[1], options_->u_levels) && !straddles(r[2], r[3], options_->v_levels);
  }

  // The bound on the distance of the original surface to the faces this collapse changes.
  double geometric_bound(const CollapseInfo& ci) {
    MeshT& m = Base::mesh();
    const Vec3 p0 = eigen(ci.p0), p1 = eigen(ci.p1);
    double inherited = 0, nearest = std::numeric_limits<double>::infinity();
    for (auto f : m.vf_range(ci.v0)) {
      inherited = std::max(inherited, m.property(bounds_, f));
      if (f == ci.fl || f == ci.fr) continue;
      std::array<Vec3, 3> corner;
      int k = 0;
      for (auto v : m.fv_range(f)) corner[k++] = v == ci.v0 ? p1 : eigen(m.point(v));
      nearest = std::min(nearest, point_triangle_squared(p0, corner[0], corner[1], corner[2]));
    }
    return inherited + std::sqrt(nearest);
  }

  const SimplifyOptions* options_ = nullptr;
  OpenMesh::VPropHandleT<TextureRange> ranges_;
  OpenMesh::FPropHandleT<double> bounds_;
  double pending_bound_ = 0;
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

SimplifyOptions simplify_options(const WaterConfig& water, std::pair<double, double> band_thresholds,
                                 const FlowConfig* flow, double tolerance) {
  SimplifyOptions o;
  o.tolerance = tolerance;
  const bool toon = water.shading == WaterShading::toon;
  // u = 0.5 + 0.4999 · L·n (or · value / range in the curvature view), v = flow_coordinate(s).
  o.u_tolerance = 0.4999 * max_l_dot_n_change;
  const auto [t_bright, t_medium] = band_thresholds;
  if (toon) o.u_levels = {0.5 + 0.4999 * t_medium, 0.5 + 0.4999 * t_bright};
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

SimplifyStats simplify_surface(PreparedSurface& surface, const std::vector<TextureCoordinate>& uv,
                               const SimplifyOptions& options) {
  SceneMesh& mesh = surface.mesh;
  SimplifyStats stats;
  stats.faces_before = stats.faces_after = mesh.triangles.size();
  if (!(options.tolerance > 0.0) || mesh.triangles.empty() || uv.size() != mesh.positions.size())
    return stats;

  RenderMesh m;
  if (!build_render_mesh(mesh, m)) return stats;
  m.request_vertex_status();
  m.request_edge_status();
  m.request_face_status();
  m.request_face_normals();
  m.update_face_normals();
  OpenMesh::VPropHandleT<TextureRange> ranges;
  m.add_property(ranges);
  for (auto v : m.vertices()) {
    const TextureCoordinate& c = uv[v.idx()];
    m.property(ranges, v) = {c[0], c[0], c[1], c[1]};
  }

  using Decimater = OpenMesh::Decimater::DecimaterT<RenderMesh>;
  Decimater decimater(m);
  OpenMesh::Decimater::ModQuadricT<RenderMesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalFlippingT<RenderMesh>::Handle flipping;
  OpenMesh::Decimater::ModAspectRatioT<RenderMesh>::Handle aspect;
  typename ModToonBoundT<RenderMesh>::Handle bound;
  // Constraints run in this order and stop at the first refusal: the most selective first.
  decimater.add(bound);
  decimater.add(flipping);
  decimater.add(aspect);
  decimater.add(quadric);
  decimater.module(quadric).unset_max_err();  // the priority; the bound is ModToonBoundT's
  decimater.module(flipping).set_max_normal_deviation(max_face_turn_degrees);
  decimater.module(aspect).set_aspect_ratio(max_aspect_ratio);
  decimater.module(bound).configure(options, ranges);
  if (!decimater.initialize()) return stats;
  decimater.decimate();

  // The kept vertices (those of a kept face), in their original order.
  std::vector<int> new_index(mesh.positions.size(), -1);
  std::vector<Triangle> triangles;
  triangles.reserve(m.n_faces());
  for (auto f : m.faces()) {
    if (m.status(f).deleted()) continue;
    Triangle t{};
    int k = 0;
    for (auto v : m.fv_range(f)) t[k++] = v.idx();
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
  stats.faces_after = mesh.triangles.size();
  stats.simplified = true;
  return stats;
}

SimplifyStats simplify_water(PreparedSurface& surface, const LightGeometry& light,
                             const SceneLayout& layout, const FlowConfig* flow) {
  const auto start = std::chrono::steady_clock::now();
  const CameraReach camera = camera_reach(layout, surface.mesh.min, surface.mesh.max);
  const double tolerance = screen_tolerance(layout.config->water.simplify, camera.nearest_distance,
                                            camera.angle_degrees, camera.width, camera.height);
  SimplifyStats stats = simplify_surface(
      surface, texture_coordinates(surface, light),
      simplify_options(layout.config->water, water_thresholds(layout), flow, tolerance));
  stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace toonwater::povgen
