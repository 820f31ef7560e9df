// POV-Ray text for flow lines (analyzer/flow_lines.hpp):
//
//   #declare Water_ridge_lines = union {
//     Toon_stroke(array[N] { <x,y,z>, ... }, array[N] { taper, ... }, closed)
//     ...
//   }
//
// and the same for Water_valley_lines; a sign with no line declares nothing, so the scene tests
// `#ifdef`. Toon_stroke (templates/toon.inc) sweeps spheres and cones along the points with a
// radius of half the line width in pixels at each point's distance from the camera, times the
// taper, so strokes are as wide on screen near and far. Points are in POV-Ray's frame, with 7
// significant digits (POV-Ray computes in single precision for geometry of this kind anyway).
#pragma once

#include "analyzer/flow_lines.hpp"

#include <span>
#include <string>

namespace toonwater {

// `lines` in POV-Ray's frame. Repeated points are dropped; a line left with fewer than two
// points, or with no width anywhere, is not written.
void append_flow_lines(std::string& out, std::span<const FlowLine> lines);

}  // namespace toonwater
