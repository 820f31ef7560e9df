// Flow lines: strokes along the water-flow regions (flow_regions.hpp), for cartoon water drawn
// with lines rather than (or on top of) filled regions.
//
// A stroke follows a region's contour, the iso-line s = +1 (ridges) or s = −1 (valleys) of the
// flow field, found triangle by triangle as in marching squares: where the field crosses the
// level along an edge, at x = xᵢ + t (xⱼ − xᵢ) with t = (λ − sᵢ)/(sⱼ − sᵢ), the same point for
// both faces of the edge, so the segments of neighbouring faces chain into polylines with no
// gap. Only faces whose three corners are on the free surface are traced: a contour that
// reaches the free surface's border ends there, and such an open stroke tapers over
// `taper_length` at each end; a closed one (a region inside the water) has no end.
//
// The same field draws the filled regions, so lines and regions agree to the pixel; both move
// continuously from frame to frame when the field does (flow_coherence.hpp).
#pragma once

#include "analyzer/flow_regions.hpp"
#include "analyzer/mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace toonwater {

struct FlowLine {
  std::int8_t sign = FlowLabel::ridge;  // ridge (+1) or valley (−1)
  bool closed = false;                  // the last point joins the first
  std::vector<Vec3> points;
  std::vector<double> taper;  // per point, in [0, 1]: width factor (0 at an open end)
};

// The width factor along an open line: rising linearly from 0 at each end over taper_length,
// or over half the line when it is shorter; 1 all along a closed one.
void set_taper(FlowLine& line, double taper_length);

// Contours of a flow field s (flow_regions.hpp: FlowRegions::field) at +1 and −1 over the free
// surface (FlowRegions::free_surface). `taper_length` in scene units.
std::vector<FlowLine> trace_flow_lines(const TriangleMesh& mesh, std::span<const double> field,
                                       std::span<const std::uint8_t> free_surface,
                                       double taper_length);

}  // namespace toonwater
