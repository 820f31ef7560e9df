// A frame's bubbles as POV-Ray text; stated in bubble_writer.hpp.
#include "scene/bubble_writer.hpp"

#include "scene/pov_numbers.hpp"

namespace toonwater {

std::string bubble_include(std::span<const Droplet> bubbles, const ScreenProjection& screen,
                           double line_pixels) {
  std::string s = "// Written by toonwater povgen: the bubbles of this frame.\n";
  s += "#declare Water_bubbles = union {\n";
  for (const Droplet& b : bubbles) {
    s += "  Toon_bubble(";
    append_pov_vector(s, b.centre);
    s += ", ";
    append_pov_number(s, b.radius);
    s += ", ";
    append_pov_number(s, line_pixels * screen.pixel_size(b.centre));
    s += ")\n";
  }
  s += "}\n";
  return s;
}

}  // namespace toonwater
