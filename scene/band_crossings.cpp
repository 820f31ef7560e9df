// The texture each face of the water needs; stated in band_crossings.hpp.
#include "scene/band_crossings.hpp"

#include <array>
#include <stdexcept>

namespace toonwater {

std::vector<FaceBands> face_bands(std::span<const Triangle> triangles,
                                  std::span<const TextureCoordinate> uv, const ToonLimits& limits) {
  if (limits.bands.size() != 2) throw std::invalid_argument("face_bands: three bands expected");
  std::vector<FaceBands> bands(triangles.size(), FaceBands::three);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    std::array<bool, 3> seen{};  // dark, medium, bright
    bool region = false;
    for (const int corner : triangles[f]) {
      const int c = toon_class(limits, uv[static_cast<std::size_t>(corner)]);
      if (c < limits.valley())
        seen[static_cast<std::size_t>(c)] = true;
      else
        region = true;
    }
    const auto [dark, medium, bright] = seen;
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
