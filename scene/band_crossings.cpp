// Faces where dark meets bright; stated in band_crossings.hpp.
#include "scene/band_crossings.hpp"

namespace toonwater {

bool dark_meets_bright(const std::array<double, 3>& u, double key_medium, double key_bright) {
  bool dark = false, medium = false, bright = false;
  for (const double key : u) {
    if (key <= key_medium)
      dark = true;
    else if (key <= key_bright)
      medium = true;
    else
      bright = true;
  }
  return dark && bright && !medium;
}

std::vector<bool> dark_bright_faces(std::span<const Triangle> triangles,
                                    std::span<const TextureCoordinate> uv, double key_medium,
                                    double key_bright) {
  std::vector<bool> marked(triangles.size(), false);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    marked[f] = dark_meets_bright({uv[t[0]][0], uv[t[1]][0], uv[t[2]][0]}, key_medium, key_bright);
  }
  return marked;
}

}  // namespace toonwater
