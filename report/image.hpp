// An RGB image read back from a render (the image codec, images/image_codec.hpp), for
// measurements on rendered pixels.
#pragma once

#include "analyzer/disjoint_sets.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace toonwater::report {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  // row-major, 3 channels in [0, 1] (as encoded in the file)
  std::array<float, 3> pixel(int x, int y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

// Throws std::runtime_error naming the file when it cannot be read or has fewer than 3 channels.
Image read_rgb(const std::filesystem::path& path);

// How many pixels set in the mask `from` have no pixel set in `to` within `reach` pixels
// (Euclidean): what a picture loses from one frame to the next. Masks are row-major, `width`
// wide, 1 where set, and of one size.
std::size_t pixels_without_neighbour(const std::vector<std::uint8_t>& from,
                                     const std::vector<std::uint8_t>& to, int width, int reach);

// The pieces of equal values other than `unset` in a row-major grid `width` wide, joined across
// their sides, and across their corners too when `corners` (for int8_t and uint8_t values).
template <class T>
DisjointSets join_pieces(const std::vector<T>& values, int width, T unset, bool corners);

// How many pieces the pixels set in `mask` (row-major, `width` wide) make, joined across their
// sides and corners (8-connected).
std::size_t pieces_of(const std::vector<std::uint8_t>& mask, int width);

}  // namespace toonwater::report
