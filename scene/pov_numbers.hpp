// Numbers and vectors as the generated POV-Ray text writes them: 7 significant digits (POV-Ray
// computes geometry in single precision anyway), never NaN or infinity.
#pragma once

#include "analyzer/mesh.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>

namespace toonwater {

inline void append_pov_number(std::string& out, double v) {
  if (!std::isfinite(v)) throw std::logic_error("POV-Ray text: non-finite number");
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 7);
  out.append(buf, r.ptr);
}

inline void append_pov_vector(std::string& out, const Vec3& p) {
  out += '<';
  append_pov_number(out, p.x());
  out += ',';
  append_pov_number(out, p.y());
  out += ',';
  append_pov_number(out, p.z());
  out += '>';
}

}  // namespace toonwater
