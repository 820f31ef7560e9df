// toonwater for OpenMesh (and OpenFlipper) users: the analysis of an OpenMesh triangle mesh with
// double-precision traits, its results written back as named vertex properties that other
// OpenMesh tools read:
//
//   "toonwater:gaussian"    double   K (curvature.hpp)
//   "toonwater:mean"        double   H, signed
//   "toonwater:flow_field"  double   s (flow_regions.hpp); a flow region where |s| >= 1
//   "toonwater:flow_label"  int      FlowLabel (1 ridge, −1 valley, 0 none)
//
// Values are per vertex of the given mesh, in its order, identical to analyze_mesh's on the
// same vertices and faces (coincident vertices are welded for the analysis and each copy gets
// its welded vertex's values). The mesh must hold no deleted elements (garbage_collection()).
#pragma once

#include "analyzer/analysis.hpp"
#include "analyzer/mesh.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace toonwater::openmesh {

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

inline constexpr const char* gaussian_property = "toonwater:gaussian";
inline constexpr const char* mean_property = "toonwater:mean";
inline constexpr const char* flow_field_property = "toonwater:flow_field";
inline constexpr const char* flow_label_property = "toonwater:flow_label";

// One pass over the vertices and one over the faces; throws std::invalid_argument for a mesh
// with deleted elements.
TriangleMesh to_triangle_mesh(const TriMesh& mesh);
TriMesh to_openmesh(const TriangleMesh& mesh);

// Runs analyze_mesh and writes the properties above (created, or overwritten where present).
// Returns the analysis, per welded vertex, for its summary figures.
Analysis analyze(TriMesh& mesh, const AnalyzeOptions& options);

}  // namespace toonwater::openmesh
