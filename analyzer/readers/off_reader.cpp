// Object File Format (Geomview): an optional header keyword [ST][C][N]OFF, the counts
// "vertices faces [edges]" (on the header line or the next), then one vertex per line
// "x y z [normal, colour or texture values]" and one face per line "n i0 ... i(n-1) [colour]"
// with 0-based indices. '#' starts a comment. 4OFF, nOFF and binary OFF are rejected.
#include "analyzer/readers/readers.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace toonwater::readers {
namespace {

// The next line that holds anything but a comment; false at the end of the file.
bool next_record(LineReader& lines, std::string_view& content) {
  std::string_view line;
  while (lines.next(line)) {
    content = strip_comment(line);
    if (!Fields(content).at_end()) return true;
  }
  return false;
}

void check_header_keyword(const SourceFile& file, std::size_t line, std::string_view keyword) {
  const bool ends_in_off = keyword.size() >= 3 && keyword.substr(keyword.size() - 3) == "OFF";
  const std::string_view prefix = keyword.substr(0, keyword.size() - (ends_in_off ? 3 : 0));
  if (ends_in_off && prefix.find_first_not_of("STCN") == std::string_view::npos) return;
  if (ends_in_off && prefix.find_first_of("4n") != std::string_view::npos)
    fail_at_line(file, line, quote(keyword) + " (not three-dimensional) OFF is not supported");
  fail_at_line(file, line, "not an OFF file: unknown header " + quote(keyword));
}

std::uint64_t read_count(const SourceFile& file, std::size_t line, std::string_view field,
                         const char* what) {
  const std::optional<std::int64_t> count = parse_integer(field);
  if (!count || *count < 0)
    fail_at_line(file, line, std::string("malformed ") + what + " count " + quote(field));
  return static_cast<std::uint64_t>(*count);
}

struct OffCounts {
  std::uint64_t vertices = 0;
  std::uint64_t faces = 0;
};

// Reads the header keyword (if any) and the counts; an empty file has zero of each.
OffCounts read_header(const SourceFile& file, LineReader& lines) {
  std::string_view content;
  if (!next_record(lines, content)) return {};
  Fields fields(content);
  std::string_view field = fields.next();
  if (!parse_integer(field)) {
    check_header_keyword(file, lines.line_number(), field);
    if (fields.at_end()) {
      if (!next_record(lines, content))
        fail_at_line(file, lines.line_number(), "file ends before the vertex and face counts");
      fields = Fields(content);
    }
    field = fields.next();
    if (field == "BINARY") fail_at_line(file, lines.line_number(), "binary OFF is not supported");
  }
  const std::size_t line = lines.line_number();
  OffCounts counts;
  counts.vertices = read_count(file, line, field, "vertex");
  field = fields.next();
  if (field.empty()) fail_at_line(file, line, "missing face count");
  counts.faces = read_count(file, line, field, "face");
  field = fields.next();
  if (!field.empty()) read_count(file, line, field, "edge");  // unused, but must be a count
  if (!fields.at_end()) fail_at_line(file, line, "unexpected values after the counts");
  if (counts.vertices > max_vertex_count)
    fail_at_line(file, line,
                 "vertex count " + std::to_string(counts.vertices) +
                     " exceeds what a mesh can index (2^31 - 1)");
  return counts;
}

void read_vertex(const SourceFile& file, std::size_t line, Fields& fields, TriangleMesh& mesh) {
  const Vec3 point = read_point(file, line, fields);
  // Normal, colour or texture coordinates ([ST][C][N]OFF): numbers, not used.
  for (std::string_view field = fields.next(); !field.empty(); field = fields.next())
    if (!parse_double(field)) fail_at_line(file, line, "malformed number " + quote(field));
  mesh.positions.push_back(point);
}

void read_face(const SourceFile& file, std::size_t line, Fields& fields, std::uint64_t vertex_count,
               TriangleMesh& mesh, std::vector<std::int32_t>& corners) {
  const std::string_view count_field = fields.next();
  const std::optional<std::int64_t> corner_count = parse_integer(count_field);
  if (!corner_count) fail_at_line(file, line, "malformed corner count " + quote(count_field));
  if (*corner_count < 3)
    fail_at_line(file, line,
                 "face has " + std::to_string(*corner_count) + " corners, needs at least 3");
  corners.clear();
  for (std::int64_t k = 0; k < *corner_count; ++k) {
    const std::string_view field = fields.next();
    if (field.empty())
      fail_at_line(file, line,
                   "face declares " + std::to_string(*corner_count) + " corners but lists " +
                       std::to_string(k));
    const std::optional<std::int64_t> index = parse_integer(field);
    if (!index) fail_at_line(file, line, "malformed face index " + quote(field));
    if (*index < 0 || static_cast<std::uint64_t>(*index) >= vertex_count)
      fail_at_line(file, line,
                   "face index " + std::to_string(*index) + " out of range (the file has " +
                       std::to_string(vertex_count) + " vertices)");
    corners.push_back(static_cast<std::int32_t>(*index));
  }
  // An optional colour: a colour-map index or 3–4 components.
  constexpr int max_colour_values = 4;
  int colour_values = 0;
  for (std::string_view field = fields.next(); !field.empty(); field = fields.next()) {
    if (++colour_values > max_colour_values)
      fail_at_line(file, line, "too many values after the face's corners");
    if (!parse_double(field)) fail_at_line(file, line, "malformed number " + quote(field));
  }
  add_polygon(mesh, corners);
}

}  // namespace

InputMesh read_off(const SourceFile& file) {
  LineReader lines(file.bytes);
  const OffCounts counts = read_header(file, lines);

  InputMesh result;
  TriangleMesh& mesh = result.mesh;
  constexpr std::size_t min_vertex_line = 6;  // "0 0 0\n"
  constexpr std::size_t min_face_line = 8;    // "3 0 1 2\n"
  mesh.positions.reserve(capped_reserve(counts.vertices, lines.rest().size(), min_vertex_line));
  mesh.triangles.reserve(capped_reserve(counts.faces, lines.rest().size(), min_face_line));

  std::string_view content;
  for (std::uint64_t v = 0; v < counts.vertices; ++v) {
    if (!next_record(lines, content))
      fail_at_line(file, lines.line_number(),
                   "file ends after " + std::to_string(v) + " of " +
                       std::to_string(counts.vertices) + " vertices");
    Fields fields(content);
    read_vertex(file, lines.line_number(), fields, mesh);
  }
  std::vector<std::int32_t> corners;
  for (std::uint64_t f = 0; f < counts.faces; ++f) {
    if (!next_record(lines, content))
      fail_at_line(file, lines.line_number(),
                   "file ends after " + std::to_string(f) + " of " + std::to_string(counts.faces) +
                       " faces");
    Fields fields(content);
    read_face(file, lines.line_number(), fields, counts.vertices, mesh, corners);
    ++result.polygon_count;
  }
  if (next_record(lines, content))
    fail_at_line(file, lines.line_number(),
                 "unexpected data after the last of the " + std::to_string(counts.faces) +
                     " faces the header declares");
  return result;
}

}  // namespace toonwater::readers
