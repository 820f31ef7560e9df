// Curvature from osculating jets: Cazals and Pouget, "Estimating Differential Quantities Using
// Polynomial Fitting of Osculating Jets", Computer Aided Geometric Design 22(2), 2005.
//
// At each vertex p, in a frame (u, v, w) whose w axis is the angle-weighted vertex normal n̂ and
// whose lengths are divided by the neighbourhood's radius ρ, the cubic height function
//   w(u, v) = Σ_{i+j≤3} c_ij uⁱ vʲ
// is fitted by least squares to p and its two-ring neighbours. The curvature is that of the
// graph at the origin (W = sqrt(1 + w_u² + w_v²)):
//   K = (w_uu w_vv − w_uv²) / (W⁴ ρ²)
//   H = −((1 + w_v²) w_uu − 2 w_u w_v w_uv + (1 + w_u²) w_vv) / (2 W³ ρ)
//   k1,2 = H ± sqrt(max(H² − K, 0))
// with the sign convention of curvature.hpp (H > 0 on a sphere with outward normals).
//
// The fit uses the positions only, not the triangulation's angles, so its error falls as O(h²)
// on irregular triangulations too (Cazals and Pouget, Thm. 2), where the cotangent H does not
// converge. It costs a 10×10 least-squares solve per vertex.
#pragma once

#include "analyzer/curvature.hpp"
#include "analyzer/mesh.hpp"
#include "analyzer/topology.hpp"

namespace toonwater {

// Same field as compute_curvature: the normals and mixed areas are the one-ring estimator's;
// K, H, k1 and k2 come from the jets. `mesh` should be consistently oriented.
CurvatureField compute_curvature_jet(const TriangleMesh& mesh, const MeshTopology& topology);

}  // namespace toonwater
