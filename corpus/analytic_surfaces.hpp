// Meshes of analytic surfaces with their exact curvature at every vertex, for accuracy tests,
// benchmarks and the error report. Normals point outward (closed surfaces) or up (+z, height
// fields); with that orientation H > 0 on a sphere and on the crests of a height field.
#pragma once

#include "analyzer/mesh.hpp"

#include <cstdint>
#include <vector>

namespace toonwater {

// Irregular triangulations of the same surface: every vertex moves by up to `fraction` of the
// local grid step in a random direction within the surface (the exact curvature follows it).
// Deterministic for a given seed; fraction 0 gives the regular mesh.
struct Jitter {
  double fraction = 0.0;
  std::uint32_t seed = 1;
};

struct AnalyticSurface {
  TriangleMesh mesh;
  std::vector<double> gaussian;  // exact K at each vertex
  std::vector<double> mean;      // exact H at each vertex
  std::vector<bool> interior;    // away from boundaries and seams: where errors are measured
};

// Loop-style subdivision of an icosahedron projected on the sphere: 10·4^s + 2 vertices.
AnalyticSurface make_icosphere(int subdivisions, double radius = 1.0, Jitter jitter = {});
// Latitude/longitude sphere, poles included in the errors (their fans are thin: 360°/segments).
AnalyticSurface make_uv_sphere(int rings, int segments, double radius = 1.0, Jitter jitter = {});
// Torus around the z axis, major radius R, minor radius r.
AnalyticSurface make_torus(int major_segments, int minor_segments, double R = 1.0, double r = 0.4,
                           Jitter jitter = {});
// Icosphere scaled to semi-axes a, b, c.
AnalyticSurface make_ellipsoid(int subdivisions, double a = 1.0, double b = 0.8, double c = 0.6,
                               Jitter jitter = {});
// Open cylinder around the z axis (K = 0, H = 1/(2r)); the rims are boundary.
AnalyticSurface make_cylinder(int segments, int rings, double radius = 1.0, double height = 2.0,
                              Jitter jitter = {});
// Saddle z = (x² − y²)/2 over [−h, h]², n×n vertices.
AnalyticSurface make_saddle(int n, double half_extent = 0.5, Jitter jitter = {});
// Height field z = A sin(kx) cos(ky) over [−h, h]², n×n vertices.
AnalyticSurface make_wave_field(int n, double amplitude = 0.1, double wave_number = 6.0,
                                double half_extent = 1.0, Jitter jitter = {});

}  // namespace toonwater
