// A mesh prepared for the scene from its analysis (see prepared_surface.hpp).
#include "scene/prepared_surface.hpp"

#include "analyzer/flow_strokes.hpp"
#include "analyzer/topology.hpp"
#include "analyzer/vertex_normals.hpp"
#include "scene/axes.hpp"

#include <utility>

namespace toonwater {
namespace {

bool is_closed(const MeshTopology& t) { return t.boundary_edges == 0 && t.nonmanifold_edges == 0; }

}  // namespace

PreparedSurface prepare_surface(Analysis a, Axis up, const FlowConfig* flow, WaterShading shading,
                                WaterNormals normals, StrokePersistence* persistence) {
  PreparedSurface out;
  const bool toon_flow = flow && flow->enabled && shading == WaterShading::toon;
  if (toon_flow && flow->style != FlowStyle::regions) {
    // Before the shading normals are taken for the mesh: the strokes are carried along them.
    // Strokes taper over 3 % of the scene's size: resolution-free, like the field.
    const double taper_length = 0.03 * a.flow.scale_length;
    out.flow_lines = flow_strokes(a.surface, a.topology.vertex_faces, a.flow, taper_length);
    if (persistence)
      out.flow_lines =
          persistence->update(a.surface, a.flow, std::move(out.flow_lines), taper_length);
    for (FlowLine& line : out.flow_lines)
      for (Vec3& p : line.points) p = to_povray(p, up);
  }
  const bool smoothed = flow && !(shading == WaterShading::toon && normals == WaterNormals::mesh);
  // Smoothed: the flow stage's shading normals where it ran (flow_regions.hpp), smoothed over the
  // free surface at the scale of the cells; a curvature view's curvature normals. Otherwise the
  // mesh's own angle-weighted normals.
  const std::vector<Vec3> n = !smoothed ? angle_weighted_normals(a.surface, a.topology.vertex_faces)
                              : a.flow.shading_normal.empty() ? std::move(a.curvature.normal)
                                                              : std::move(a.flow.shading_normal);
  out.mesh = make_scene_mesh(a.surface, n, is_closed(a.topology), up);
  if (smoothed) out.normal_noise = a.flow.normal_noise;
  if (toon_flow) {
    out.flow_field = std::move(a.flow.field);
    out.ridge_vertices = a.flow.ridge_vertices;
    out.valley_vertices = a.flow.valley_vertices;
  } else if (flow && shading != WaterShading::toon) {
    out.view_values = shading == WaterShading::gaussian ? a.curvature.gaussian : a.curvature.mean;
  }  // else toon bands alone
  return out;
}

}  // namespace toonwater
