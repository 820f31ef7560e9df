// View and colour ranges shared by the maps of a frame or a sequence (see map_planner.hpp).
#include "analyzer/maps/map_planner.hpp"

#include "analyzer/flow_regions.hpp"
#include "analyzer/mesh_reader.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace toonwater {

void MapPlanner::add(const Analysis& analysis) {
  const double edge = analysis.flow.median_edge_length > 0.0 ? analysis.flow.median_edge_length
                                                             : median_edge_length(analysis.surface);
  add(analysis.surface, analysis.curvature, analysis.flow.free_surface, edge);
}

void MapPlanner::add(const TriangleMesh& surface, const CurvatureField& curvature,
                     std::span<const std::uint8_t> free_surface, double median_edge) {
  ++frames_;
  ranges_.add_edge_length(median_edge);

  const Vec3 u_axis = map_u_axis(up_), v_axis = map_v_axis(up_);
  const Vec3 up_axis = u_axis.cross(v_axis);
  for (const Triangle& t : surface.triangles) {
    if (!on_mapped_surface(free_surface, t)) continue;
    const Vec3 &p0 = surface.positions[t[0]], &p1 = surface.positions[t[1]],
               &p2 = surface.positions[t[2]];
    const double projected_area = 0.5 * (p1 - p0).cross(p2 - p0).dot(up_axis);
    if (!(projected_area > 0.0) || !std::isfinite(projected_area)) continue;
    for (std::int32_t v : t) {
      const Vec3& p = surface.positions[v];
      const double u = p.dot(u_axis), w = p.dot(v_axis);
      if (!has_extent_) {
        extent_ = {u, w, u, w};
        has_extent_ = true;
      }
      extent_.u_min = std::min(extent_.u_min, u);
      extent_.u_max = std::max(extent_.u_max, u);
      extent_.v_min = std::min(extent_.v_min, w);
      extent_.v_max = std::max(extent_.v_max, w);
      ranges_.add(curvature.gaussian[v], curvature.mean[v], projected_area / 3.0);
    }
  }
}

MapView MapPlanner::view(const MapOptions& options) const {
  if (!options.box && !has_extent_)
    throw InputError(std::string("maps: no free-surface face faces up along +") +
                     "xyz"[static_cast<int>(up_)] +
                     ", so there is no top-down map (is the up axis right?)");
  MapView view;
  view.up = up_;
  view.box = options.box.value_or(extent_);
  const double u_extent = view.box.u_max - view.box.u_min;
  const double v_extent = view.box.v_max - view.box.v_min;
  if (!(u_extent >= 0.0 && v_extent >= 0.0) || !std::isfinite(u_extent + v_extent))
    throw InputError("maps: the map box is empty or not finite");
  const double longer = std::max(u_extent, v_extent);
  const int max_size = std::max(1, options.max_size);
  double pixel_size = 0.0;
  if (options.size) {
    pixel_size = longer / std::clamp(*options.size, 1, max_size);
  } else {
    pixel_size = ranges_.median_edge() / std::max(options.pixels_per_edge, 1e-6);
    if (pixel_size > 0.0) pixel_size = std::max(pixel_size, longer / max_size);
  }
  if (!(pixel_size > 0.0)) pixel_size = longer > 0.0 ? longer : 1.0;  // a point or a line
  auto pixels = [&](double extent) {
    return std::clamp(static_cast<int>(std::ceil(extent / pixel_size - 1e-9)), 1, max_size);
  };
  view.width = pixels(u_extent);
  view.height = pixels(v_extent);
  view.pixel_size = pixel_size;
  // Centre the pixel grid on the box: it may stick out by less than a pixel.
  const double u_pad = 0.5 * (view.width * pixel_size - u_extent);
  const double v_pad = 0.5 * (view.height * pixel_size - v_extent);
  view.box = {view.box.u_min - u_pad, view.box.v_min - v_pad, view.box.u_max + u_pad,
              view.box.v_max + v_pad};
  return view;
}

MapRanges MapPlanner::ranges(double percentile) const { return ranges_.ranges(percentile); }

}  // namespace toonwater
