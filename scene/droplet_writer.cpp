// A frame's spray droplets as POV-Ray text; stated in droplet_writer.hpp.
#include "scene/droplet_writer.hpp"

#include "scene/pov_numbers.hpp"

namespace toonwater {

std::string spray_include(std::span<const Droplet> droplets, const ScreenProjection& screen,
                          const LightGeometry& light, double line_pixels) {
  std::string s = "// Written by toonwater povgen: the spray's droplets of this frame.\n";
  s += "#declare Spray_droplets = union {\n";
  for (const Droplet& d : droplets) {
    // L·n from the droplet's centre: a point light's direction differs from drop to drop.
    const Vec3 to_light = light.parallel ? light.vector : light.vector - d.centre;
    const Vec3 l = to_light.norm() > 0.0 ? to_light.normalized() : Vec3::UnitY();
    s += "  Toon_droplet(";
    append_pov_vector(s, d.centre);
    s += ", ";
    append_pov_number(s, d.radius);
    s += ", ";
    append_pov_vector(s, d.tail);
    s += ", ";
    append_pov_number(s, line_pixels * screen.pixel_size(d.centre));
    s += ", ";
    append_pov_vector(s, l);
    s += ")\n";
  }
  s += "}\n";
  return s;
}

}  // namespace toonwater
