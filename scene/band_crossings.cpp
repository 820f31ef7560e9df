// The texture each face of the water needs; stated in band_crossings.hpp.
#include "scene/band_crossings.hpp"

namespace toonwater {

std::vector<FaceBands> face_bands(std::span<const Triangle> triangles,
                                  std::span<const TextureCoordinate> uv, double key_medium,
                                  double key_bright,
                                  std::optional<std::pair<double, double>> flow_keys) {
  std::vector<FaceBands> bands(triangles.size(), FaceBands::three);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    bool region = false, dark = false, medium = false, bright = false;
    for (const int corner : triangles[f]) {
      const TextureCoordinate& c = uv[static_cast<std::size_t>(corner)];
      if (flow_keys && (c[1] <= flow_keys->first || c[1] >= flow_keys->second))
        region = true;
      else if (c[0] <= key_medium)
        dark = true;
      else if (c[0] <= key_bright)
        medium = true;
      else
        bright = true;
    }
    const int band_kinds = int{dark} + int{medium} + int{bright};
    if (dark && bright && !medium)
      bands[f] = FaceBands::two;
    else if (region && band_kinds == 1)
      bands[f] = dark     ? FaceBands::only_dark
                 : medium ? FaceBands::only_medium
                          : FaceBands::only_bright;
  }
  return bands;
}

}  // namespace toonwater
