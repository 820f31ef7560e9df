// A frame's foam as POV-Ray text; stated in foam_writer.hpp.
#include "scene/foam_writer.hpp"

#include "scene/pov_numbers.hpp"

namespace toonwater {

std::string foam_include(std::span<const FoamComponent> components, double density) {
  std::string s = "// Written by toonwater povgen: the foam of this frame.\n";
  if (components.empty()) return s;
  s += "#declare Foam_patches = blob {\n  threshold ";
  append_pov_number(s, density);
  s += "\n";
  for (const FoamComponent& c : components) {
    s += "  sphere { ";
    append_pov_vector(s, c.centre);
    s += ", ";
    append_pov_number(s, c.radius);
    s += ", ";
    append_pov_number(s, c.strength);
    s += " }\n";
  }
  s += "}\n";
  return s;
}

}  // namespace toonwater
