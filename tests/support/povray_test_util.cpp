#include "tests/support/povray_test_util.hpp"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <stdexcept>

namespace toonwater::test {

TriangleMesh make_height_grid(int n, double h,
                              const std::function<double(double, double)>& height) {
  TriangleMesh m;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = -h + 2 * h * i / (n - 1), z = -h + 2 * h * j / (n - 1);
      m.positions.emplace_back(x, height(x, z), z);
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      // (c − a) × (b − a) points up for x along i and z along j.
      m.triangles.push_back({a, c, b});
      m.triangles.push_back({b, c, d});
    }
  return m;
}

TriangleMesh make_sphere(const Vec3& centre, double radius, int rings, int segments) {
  TriangleMesh m;
  m.positions.push_back(centre + Vec3(0, radius, 0));
  for (int r = 1; r < rings; ++r) {
    const double theta = std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * std::numbers::pi * s / segments;
      m.positions.push_back(centre + radius * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                   std::sin(theta) * std::sin(phi)));
    }
  }
  m.positions.push_back(centre - Vec3(0, radius, 0));
  const int south = static_cast<int>(m.positions.size()) - 1;
  auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) {
    m.triangles.push_back({0, ring(1, s + 1), ring(1, s)});
    m.triangles.push_back({south, ring(rings - 1, s), ring(rings - 1, s + 1)});
  }
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const int a = ring(r, s), b = ring(r, s + 1), c = ring(r + 1, s), d = ring(r + 1, s + 1);
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({b, d, c});
    }
  return m;
}

Povray run_povray(const std::filesystem::path& dir, const std::string& extra) {
  const std::string command =
      "cd '" + dir.string() + "' && povray scene.ini +WT1 " + extra + " 2>&1";
  Povray result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run povray");
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    result.output.append(buffer, n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

Rgb8 to_rgb8(double r, double g, double b) {
  auto q = [](double v) { return static_cast<int>(std::lround(v * 255.0)); };
  return {q(r), q(g), q(b)};
}

Image read_image(const std::filesystem::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw std::runtime_error("cannot open " + path.string() + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  Image image;
  image.width = spec.width;
  image.height = spec.height;
  image.pixels.resize(static_cast<std::size_t>(spec.width) * spec.height * 3);
  // Channels 0-2 as 8-bit, whatever else the file holds.
  if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, image.pixels.data()))
    throw std::runtime_error("cannot read " + path.string() + ": " + in->geterror());
  return image;
}

bool near(const Rgb8& a, const Rgb8& b, int tolerance) {
  for (int i = 0; i < 3; ++i)
    if (std::abs(a[i] - b[i]) > tolerance) return false;
  return true;
}

std::vector<std::uint8_t> mask_of(const Image& image, const Rgb8& colour, int tolerance) {
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(image.width) * image.height, 0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      mask[static_cast<std::size_t>(y) * image.width + x] = near(image.at(x, y), colour, tolerance);
  return mask;
}

}  // namespace toonwater::test
