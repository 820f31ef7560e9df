// STL, binary and ASCII. Every facet corner becomes its own vertex, in file order (a triangle
// soup; the analyzer welds it). Binary: an 80-byte header, a little-endian uint32 facet count,
// then 50 bytes per facet (normal, three corners as float32, a uint16 attribute). Binary files
// may also begin with "solid", so a file is binary exactly when its size is 84 + 50·count;
// otherwise it must be ASCII: "solid", then "facet normal ..", "outer loop", "vertex x y z" ×3,
// "endloop", "endfacet", and "endsolid".
#include "analyzer/readers/readers.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace toonwater::readers {
namespace {

constexpr std::size_t binary_header_bytes = 84;
constexpr std::size_t binary_facet_bytes = 50;

std::uint32_t binary_facet_count(const SourceFile& file) {
  return little_endian<std::uint32_t>(file.bytes.data() + 80);
}

bool is_binary(const SourceFile& file) {
  const std::size_t size = file.bytes.size();
  return size >= binary_header_bytes &&
         (size - binary_header_bytes) / binary_facet_bytes == binary_facet_count(file) &&
         (size - binary_header_bytes) % binary_facet_bytes == 0;
}

// ASCII STL starts with "solid" and is text. A binary header may start with "solid" too, but its
// facet count (bytes 80–83) holds a zero byte for any count below 2^24, so a truncated binary
// file is still recognised as binary and reported as truncated.
bool is_ascii(const SourceFile& file) {
  const std::string_view start = file.bytes.substr(0, binary_header_bytes);
  return Fields(start).next() == "solid" && start.find('\0') == std::string_view::npos;
}

InputMesh read_binary(const SourceFile& file) {
  const std::uint32_t facets = binary_facet_count(file);
  if (std::uint64_t{3} * facets > max_vertex_count)
    fail(file, std::to_string(facets) + " facets have more corners than a mesh can index");
  InputMesh result;
  TriangleMesh& mesh = result.mesh;
  mesh.positions.reserve(std::size_t{3} * facets);
  mesh.triangles.reserve(facets);
  const char* facet = file.bytes.data() + binary_header_bytes;
  for (std::uint32_t f = 0; f < facets; ++f, facet += binary_facet_bytes) {
    const char* corner = facet + 12;  // after the normal
    const auto first = static_cast<std::int32_t>(mesh.positions.size());
    for (int c = 0; c < 3; ++c, corner += 12) {
      const Vec3 position(little_endian<float>(corner), little_endian<float>(corner + 4),
                          little_endian<float>(corner + 8));
      if (!position.allFinite())
        fail(file, "coordinate is NaN or infinite (facet " + std::to_string(f) + ")");
      mesh.positions.push_back(position);
    }
    mesh.triangles.push_back({first, first + 1, first + 2});
  }
  result.polygon_count = facets;
  return result;
}

InputMesh read_ascii(const SourceFile& file) {
  InputMesh result;
  TriangleMesh& mesh = result.mesh;
  std::vector<std::int32_t> loop;  // the current facet's corners
  bool in_solid = false, in_facet = false, in_loop = false;
  LineReader lines(file.bytes);
  std::string_view line;
  while (lines.next(line)) {
    const std::size_t number = lines.line_number();
    Fields fields(line);
    const std::string_view keyword = fields.next();
    const auto unexpected = [&] {
      fail_at_line(file, number, "unexpected " + quote(keyword) + " in ASCII STL");
    };
    if (keyword.empty()) continue;
    if (keyword == "solid") {
      if (in_solid) unexpected();
      in_solid = true;
    } else if (keyword == "endsolid") {
      if (!in_solid || in_facet) unexpected();
      in_solid = false;
    } else if (keyword == "facet") {
      // The normal is recomputed by the analyzer; exporters write nan for degenerate facets.
      if (!in_solid || in_facet) unexpected();
      in_facet = true;
    } else if (keyword == "outer") {
      if (!in_facet || in_loop || fields.next() != "loop") unexpected();
      in_loop = true;
      loop.clear();
    } else if (keyword == "vertex") {
      if (!in_loop) unexpected();
      const Vec3 point = read_point(file, number, fields);
      if (!fields.at_end()) fail_at_line(file, number, "too many values on a vertex line");
      if (mesh.positions.size() == max_vertex_count)
        fail_at_line(file, number, "more vertices than a mesh can index (2^31 - 1)");
      loop.push_back(static_cast<std::int32_t>(mesh.positions.size()));
      mesh.positions.push_back(point);
    } else if (keyword == "endloop") {
      if (!in_loop) unexpected();
      if (loop.size() < 3)
        fail_at_line(file, number,
                     "facet has " + std::to_string(loop.size()) + " vertices, needs at least 3");
      add_polygon(mesh, loop);
      ++result.polygon_count;
      in_loop = false;
    } else if (keyword == "endfacet") {
      if (!in_facet || in_loop) unexpected();
      in_facet = false;
    } else {
      unexpected();
    }
  }
  if (in_facet) fail_at_line(file, lines.line_number(), "truncated: the file ends inside a facet");
  // A file cut between two facets reads as whole facets: only the missing endsolid tells.
  if (in_solid) fail_at_line(file, lines.line_number(), "truncated: the file ends before endsolid");
  return result;
}

}  // namespace

InputMesh read_stl(const SourceFile& file) {
  if (is_binary(file)) return read_binary(file);
  if (file.bytes.empty()) return {};
  if (is_ascii(file)) return read_ascii(file);
  if (file.bytes.size() < binary_header_bytes)
    fail(file, "truncated: a binary STL needs at least 84 bytes, the file has " +
                   std::to_string(file.bytes.size()) + " (byte offset " +
                   std::to_string(file.bytes.size()) + ")");
  const std::uint64_t expected =
      binary_header_bytes + std::uint64_t{binary_facet_bytes} * binary_facet_count(file);
  if (file.bytes.size() < expected)
    fail(file, "truncated: the binary STL header promises " +
                   std::to_string(binary_facet_count(file)) + " facets (" +
                   std::to_string(expected) + " bytes), the file ends at byte offset " +
                   std::to_string(file.bytes.size()));
  fail(file, std::to_string(file.bytes.size() - expected) +
                 " unexpected bytes after the last facet of a binary STL (byte offset " +
                 std::to_string(expected) + ")");
}

}  // namespace toonwater::readers
