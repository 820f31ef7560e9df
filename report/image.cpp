#include "report/image.hpp"

#include "images/image_codec.hpp"

#include <stdexcept>

namespace toonwater::report {

Image read_rgb(const std::filesystem::path& path) {
  const ImageCodec& codec = image_codec();
  try {
    RgbFloatImage read = codec.read_rgb(path.string());
    return {read.width, read.height, std::move(read.rgb)};
  } catch (const std::runtime_error&) {
    throw std::runtime_error(path.string() + ": cannot read the rendered image");
  }
}

std::size_t pixels_without_neighbour(const std::vector<std::uint8_t>& from,
                                     const std::vector<std::uint8_t>& to, int width, int reach) {
  const int height = width > 0 ? static_cast<int>(from.size()) / width : 0;
  std::size_t lost = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (!from[static_cast<std::size_t>(y) * width + x]) continue;
      bool kept = false;
      for (int dy = -reach; dy <= reach && !kept; ++dy)
        for (int dx = -reach; dx <= reach && !kept; ++dx) {
          const int xx = x + dx, yy = y + dy;
          kept = dx * dx + dy * dy <= reach * reach && xx >= 0 && yy >= 0 && xx < width &&
                 yy < height && to[static_cast<std::size_t>(yy) * width + xx];
        }
      lost += !kept;
    }
  return lost;
}

template <class T>
DisjointSets join_pieces(const std::vector<T>& values, int width, T unset, bool corners) {
  const int height = width > 0 ? static_cast<int>(values.size()) / width : 0;
  DisjointSets pieces(values.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const auto i = static_cast<std::int32_t>(y * width + x);
      if (values[i] == unset) continue;
      for (const auto& [dx, dy] : {std::pair{1, 0}, {0, 1}, {-1, 1}, {1, 1}}) {
        if (!corners && dx != 0 && dy != 0) continue;
        const int xx = x + dx, yy = y + dy;
        const auto j = static_cast<std::int32_t>(yy * width + xx);
        if (xx >= 0 && xx < width && yy < height && values[j] == values[i]) pieces.join(i, j);
      }
    }
  return pieces;
}
template DisjointSets join_pieces(const std::vector<std::int8_t>&, int, std::int8_t, bool);
template DisjointSets join_pieces(const std::vector<std::uint8_t>&, int, std::uint8_t, bool);

std::size_t pieces_of(const std::vector<std::uint8_t>& mask, int width) {
  DisjointSets pieces = join_pieces<std::uint8_t>(mask, width, 0, true);
  std::size_t count = 0;
  for (std::size_t i = 0; i < mask.size(); ++i)
    count += mask[i] && pieces.root(static_cast<std::int32_t>(i)) == static_cast<std::int32_t>(i);
  return count;
}

}  // namespace toonwater::report
