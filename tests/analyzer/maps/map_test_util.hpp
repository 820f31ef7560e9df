// Helpers for the curvature-map tests: analysing analytic meshes and reading maps back.
#pragma once

#include "analyzer/analysis.hpp"
#include "analyzer/maps/map_planner.hpp"

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace toonwater::test {

inline Analysis analyse(const TriangleMesh& mesh, Axis up) {
  AnalyzeOptions options;
  options.flow.up = up;
  return analyze_mesh(mesh, options);
}

// A square box centred on the origin with an odd pixel count, so the centre pixel's centre is
// exactly the origin.
inline MapOptions centred_options(double half_extent, int size) {
  MapOptions options;
  options.box = MapBox{-half_extent, -half_extent, half_extent, half_extent};
  options.size = size;
  return options;
}

// An image read back with OpenImageIO, channels looked up by name (EXR sorts them).
struct ReadImage {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;  // interleaved, as float (uint8 scaled to 0–1)

  int channel(const std::string& name) const {
    for (int c = 0; c < spec.nchannels; ++c)
      if (spec.channelnames[c] == name) return c;
    ADD_FAILURE() << "no channel " << name;
    return 0;
  }
  float at(int x, int y, const std::string& name) const { return at(x, y, channel(name)); }
  float at(int x, int y, int c) const {
    return pixels[(static_cast<std::size_t>(y) * spec.width + x) * spec.nchannels + c];
  }
  // 8-bit colour of a PNG pixel.
  std::array<int, 3> rgb(int x, int y) const {
    return {static_cast<int>(std::lround(at(x, y, 0) * 255)),
            static_cast<int>(std::lround(at(x, y, 1) * 255)),
            static_cast<int>(std::lround(at(x, y, 2) * 255))};
  }
};

inline ReadImage read_image(const std::filesystem::path& path) {
  ReadImage image;
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    ADD_FAILURE() << "cannot open " << path << ": " << OIIO::geterror();
    return image;
  }
  image.spec = in->spec();
  image.pixels.resize(image.spec.image_pixels() * image.spec.nchannels);
  EXPECT_TRUE(
      in->read_image(0, 0, 0, image.spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()));
  return image;
}

inline std::array<int, 3> to_int(const std::array<std::uint8_t, 3>& c) {
  return {c[0], c[1], c[2]};
}

}  // namespace toonwater::test
