// The OpenMesh adapter (analyzer/openmesh/openmesh_adapter.hpp) against analyze_mesh on the
// analytic corpus: the same values, bit for bit, on every vertex.
#include "analyzer/openmesh/openmesh_adapter.hpp"

#include "corpus/analytic_surfaces.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace toonwater::test {
namespace {

using openmesh::TriMesh;

std::vector<AnalyticSurface> corpus() {
  return {make_icosphere(3),     make_uv_sphere(24, 48), make_torus(48, 24), make_ellipsoid(3),
          make_cylinder(48, 12), make_saddle(33),        make_wave_field(61)};
}

TEST(OpenMeshAdapter, ConversionsKeepVerticesAndFacesInOrder) {
  for (const AnalyticSurface& s : corpus()) {
    const TriMesh om = openmesh::to_openmesh(s.mesh);
    ASSERT_EQ(om.n_vertices(), s.mesh.positions.size());
    ASSERT_EQ(om.n_faces(), s.mesh.triangles.size());
    const TriangleMesh back = openmesh::to_triangle_mesh(om);
    EXPECT_EQ(back.positions, s.mesh.positions);
    // A face may start at another corner; the cyclic order (the winding) is kept.
    for (std::size_t f = 0; f < back.triangles.size(); ++f) {
      const Triangle& a = s.mesh.triangles[f];
      const Triangle& b = back.triangles[f];
      const bool same =
          b == a || b == Triangle{a[1], a[2], a[0]} || b == Triangle{a[2], a[0], a[1]};
      EXPECT_TRUE(same) << "face " << f;
    }
  }
}

TEST(OpenMeshAdapter, AnalyzeWritesTheSameValuesAsAnalyzeMesh) {
  AnalyzeOptions options;
  for (const AnalyticSurface& s : corpus()) {
    TriMesh om = openmesh::to_openmesh(s.mesh);
    openmesh::analyze(om, options);
    const Analysis expected = analyze_mesh(s.mesh, options);
    OpenMesh::VPropHandleT<double> gaussian, mean, field;
    OpenMesh::VPropHandleT<int> label;
    ASSERT_TRUE(om.get_property_handle(gaussian, openmesh::gaussian_property));
    ASSERT_TRUE(om.get_property_handle(mean, openmesh::mean_property));
    ASSERT_TRUE(om.get_property_handle(field, openmesh::flow_field_property));
    ASSERT_TRUE(om.get_property_handle(label, openmesh::flow_label_property));
    for (auto v : om.vertices()) {
      const auto w = static_cast<std::size_t>(expected.input_to_surface[v.idx()]);
      EXPECT_EQ(om.property(gaussian, v), expected.curvature.gaussian[w]);
      EXPECT_EQ(om.property(mean, v), expected.curvature.mean[w]);
      EXPECT_EQ(om.property(field, v), expected.flow.field[w]);
      EXPECT_EQ(om.property(label, v), expected.flow.label[w]);
    }
  }
}

TEST(OpenMeshAdapter, UnitSphereCurvatureReadsBackFromTheProperties) {
  TriMesh om = openmesh::to_openmesh(make_icosphere(4).mesh);
  openmesh::analyze(om, AnalyzeOptions{});
  OpenMesh::VPropHandleT<double> gaussian, mean;
  ASSERT_TRUE(om.get_property_handle(gaussian, openmesh::gaussian_property));
  ASSERT_TRUE(om.get_property_handle(mean, openmesh::mean_property));
  for (auto v : om.vertices()) {
    EXPECT_NEAR(om.property(gaussian, v), 1.0, 0.05);
    EXPECT_NEAR(om.property(mean, v), 1.0, 0.05);
  }
}

TEST(OpenMeshAdapter, MeshWithDeletedElementsIsRefused) {
  TriMesh om = openmesh::to_openmesh(make_icosphere(1).mesh);
  om.request_vertex_status();
  om.request_edge_status();
  om.request_face_status();
  om.delete_vertex(TriMesh::VertexHandle(0));
  EXPECT_THROW(openmesh::to_triangle_mesh(om), std::invalid_argument);
}

}  // namespace
}  // namespace toonwater::test
