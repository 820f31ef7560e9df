// Helpers for the povgen tests: test meshes (written with analyzer/obj_writer.hpp), running POV-Ray
// in a scene directory, and reading its PNGs back with OpenImageIO.
#pragma once

#include "analyzer/mesh.hpp"
#include "analyzer/obj_writer.hpp"  // write_obj, for the test meshes

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace toonwater::test {

// Square grid over [−h, h]² in the plane normal to y (y-up input), heights from `height(x, z)`,
// faces wound so that normals point up (+y).
TriangleMesh make_height_grid(int n, double half_extent,
                              const std::function<double(double, double)>& height);

// A UV sphere of the given radius and centre, outward normals.
TriangleMesh make_sphere(const Vec3& centre, double radius, int rings = 24, int segments = 48);

struct Povray {
  int exit_code = -1;
  std::string output;
};
// `cd dir && povray scene.ini <extra>`: the scene's colours are sRGB in and out, so PNG values
// of flat colours equal the configured colours.
Povray run_povray(const std::filesystem::path& dir, const std::string& extra = "");

using Rgb8 = std::array<int, 3>;
Rgb8 to_rgb8(double r, double g, double b);

// An 8-bit RGB image read with OpenImageIO.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // rgb, row by row from the top
  Rgb8 at(int x, int y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
    return {pixels[i], pixels[i + 1], pixels[i + 2]};
  }
};
Image read_image(const std::filesystem::path& path);

bool near(const Rgb8& a, const Rgb8& b, int tolerance = 1);

// 1 where the image's pixel is within `tolerance` of `colour`, else 0; row-major, its width wide.
std::vector<std::uint8_t> mask_of(const Image& image, const Rgb8& colour, int tolerance = 1);

}  // namespace toonwater::test
