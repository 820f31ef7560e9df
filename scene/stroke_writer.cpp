#include "scene/stroke_writer.hpp"

#include "scene/pov_numbers.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace toonwater {
namespace {

// The points worth writing: consecutive repeats (a contour through a vertex) dropped.
FlowLine cleaned(const FlowLine& line) {
  FlowLine out;
  out.sign = line.sign;
  for (std::size_t i = 0; i < line.points.size(); ++i) {
    if (!out.points.empty() &&
        (line.points[i] - out.points.back()).norm() <= 1e-9 * (1.0 + line.points[i].norm()))
      continue;
    out.points.push_back(line.points[i]);
    out.taper.push_back(line.taper[i]);
  }
  out.closed = line.closed && out.points.size() > 2;
  return out;
}

void append_stroke(std::string& out, const FlowLine& line) {
  const std::size_t n = line.points.size();
  out += "  Toon_stroke(array[" + std::to_string(n) + "] {";
  for (std::size_t i = 0; i < n; ++i) {
    if (i) out += ',';
    append_pov_vector(out, line.points[i]);
  }
  out += "},\n    array[" + std::to_string(n) + "] {";
  for (std::size_t i = 0; i < n; ++i) {
    if (i) out += ',';
    append_pov_number(out, std::clamp(line.taper[i], 0.0, 1.0));
  }
  out += line.closed ? "}, 1)\n" : "}, 0)\n";
}

}  // namespace

void append_flow_lines(std::string& out, std::span<const FlowLine> lines) {
  for (const std::int8_t sign : {std::int8_t{FlowLabel::ridge}, std::int8_t{FlowLabel::valley}}) {
    std::string body;
    for (const FlowLine& raw : lines) {
      if (raw.sign != sign) continue;
      const FlowLine line = cleaned(raw);
      if (line.points.size() < 2 || *std::max_element(line.taper.begin(), line.taper.end()) <= 0.0)
        continue;
      append_stroke(body, line);
    }
    if (body.empty()) continue;
    out += sign == FlowLabel::ridge ? "#declare Water_ridge_lines = union {\n"
                                    : "#declare Water_valley_lines = union {\n";
    out += body;
    out += "}\n";
  }
}

}  // namespace toonwater
