#include "analyzer/openmesh/openmesh_adapter.hpp"

#include <stdexcept>
#include <string>

namespace toonwater::openmesh {
namespace {

template <class T>
OpenMesh::VPropHandleT<T> vertex_property(TriMesh& mesh, const char* name) {
  OpenMesh::VPropHandleT<T> handle;
  if (!mesh.get_property_handle(handle, name)) mesh.add_property(handle, name);
  mesh.property(handle).set_persistent(true);  // saved with the mesh by OpenMesh's writers
  return handle;
}

}  // namespace

TriangleMesh to_triangle_mesh(const TriMesh& mesh) {
  bool deleted = false;
  if (mesh.has_vertex_status())
    for (auto v : mesh.all_vertices()) deleted |= mesh.status(v).deleted();
  if (mesh.has_face_status())
    for (auto f : mesh.all_faces()) deleted |= mesh.status(f).deleted();
  if (deleted)
    throw std::invalid_argument("OpenMesh mesh has deleted elements: call garbage_collection()");
  TriangleMesh out;
  out.positions.resize(mesh.n_vertices());
  for (auto v : mesh.all_vertices()) {
    const OpenMesh::Vec3d& p = mesh.point(v);
    out.positions[v.idx()] = Vec3(p[0], p[1], p[2]);
  }
  out.triangles.resize(mesh.n_faces());
  for (auto f : mesh.all_faces()) {
    auto h = mesh.halfedge_handle(f);
    Triangle& t = out.triangles[f.idx()];
    for (int k = 0; k < 3; ++k, h = mesh.next_halfedge_handle(h))
      t[k] = mesh.to_vertex_handle(h).idx();
  }
  return out;
}

TriMesh to_openmesh(const TriangleMesh& mesh) {
  TriMesh out;
  out.reserve(mesh.positions.size(), mesh.triangles.size() * 3 / 2, mesh.triangles.size());
  for (const Vec3& p : mesh.positions) out.add_vertex(OpenMesh::Vec3d(p.x(), p.y(), p.z()));
  for (const Triangle& t : mesh.triangles) {
    const auto f = out.add_face(TriMesh::VertexHandle(t[0]), TriMesh::VertexHandle(t[1]),
                                TriMesh::VertexHandle(t[2]));
    if (!f.is_valid())
      throw std::invalid_argument("OpenMesh refuses face " +
                                  std::to_string(&t - mesh.triangles.data()) +
                                  " (non-manifold or repeated)");
  }
  return out;
}

Analysis analyze(TriMesh& mesh, const AnalyzeOptions& options) {
  Analysis a = analyze_mesh(to_triangle_mesh(mesh), options);
  const auto gaussian = vertex_property<double>(mesh, gaussian_property);
  const auto mean = vertex_property<double>(mesh, mean_property);
  const auto field = vertex_property<double>(mesh, flow_field_property);
  const auto label = vertex_property<int>(mesh, flow_label_property);
  const bool flow = !a.flow.field.empty();
  for (auto v : mesh.vertices()) {
    const std::size_t s = static_cast<std::size_t>(a.input_to_surface[v.idx()]);
    mesh.property(gaussian, v) = a.curvature.gaussian[s];
    mesh.property(mean, v) = a.curvature.mean[s];
    mesh.property(field, v) = flow ? a.flow.field[s] : 0.0;
    mesh.property(label, v) = flow ? a.flow.label[s] : 0;
  }
  return a;
}

}  // namespace toonwater::openmesh
