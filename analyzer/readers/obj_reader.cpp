// Wavefront OBJ: "v x y z [w | r g b [a]]" vertices and "f a a/b a/b/c a//c ..." faces, whose
// indices are 1-based or negative (relative to the vertices read so far). The other statements
// of the OBJ specification (vt, vn, vp, g, o, s, usemtl, mtllib, l, p, free-form geometry, ...)
// describe nothing the analyzer uses and are skipped. Any other line is an error: an unknown
// statement ("F 1 2 3", "f2 3 4") or bytes that are not text (a file cut short by a crash often
// ends in NUL bytes) would otherwise lose faces in silence.
#include "analyzer/readers/readers.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace toonwater::readers {
namespace {

// True when the line ends with a backslash: a continuation onto the next line, which OBJ allows
// but almost no exporter writes; rejected rather than misread.
bool continues_on_next_line(std::string_view content) {
  const std::size_t last = content.find_last_not_of(" \t\r\v\f");
  return last != std::string_view::npos && content[last] == '\\';
}

void read_vertex(const SourceFile& file, std::size_t line, Fields& fields, TriangleMesh& mesh) {
  const Vec3 point = read_point(file, line, fields);
  // Optional w or colour: numbers, not used.
  constexpr int max_optional_values = 4;
  int optional_values = 0;
  for (std::string_view field = fields.next(); !field.empty(); field = fields.next()) {
    if (++optional_values > max_optional_values)
      fail_at_line(file, line, "too many values on a vertex line");
    if (!parse_double(field)) fail_at_line(file, line, "malformed number " + quote(field));
  }
  if (mesh.positions.size() == max_vertex_count)
    fail_at_line(file, line, "more vertices than a mesh can index (2^31 - 1)");
  mesh.positions.push_back(point);
}

// The vertex index of a face corner "a", "a/b", "a/b/c" or "a//c". The texture and normal
// indices are not used, but must be integers where present.
std::string_view vertex_index_text(const SourceFile& file, std::size_t line,
                                   std::string_view corner) {
  const std::size_t slash = corner.find('/');
  if (slash == std::string_view::npos) return corner;
  const std::string_view rest = corner.substr(slash + 1);
  const std::size_t second_slash = rest.find('/');
  const std::string_view texture = rest.substr(0, second_slash);
  bool well_formed;
  if (second_slash == std::string_view::npos) {
    well_formed = parse_integer(texture).has_value();  // "a/b"
  } else {
    const std::string_view normal = rest.substr(second_slash + 1);  // "a/b/c" or "a//c"
    well_formed = (texture.empty() || parse_integer(texture)) && parse_integer(normal);
  }
  if (!well_formed) fail_at_line(file, line, "malformed face corner " + quote(corner));
  return corner.substr(0, slash);
}

// Positive indices may refer to vertices listed later in the file, so they are checked once all
// vertices are known; only the largest one matters.
struct ForwardReference {
  std::int64_t index = 0;  // 1-based
  std::size_t line = 0;
};

void read_face(const SourceFile& file, std::size_t line, Fields& fields, TriangleMesh& mesh,
               std::vector<std::int32_t>& corners, ForwardReference& largest_forward) {
  const auto vertices_so_far = static_cast<std::int64_t>(mesh.positions.size());
  corners.clear();
  for (std::string_view field = fields.next(); !field.empty(); field = fields.next()) {
    const std::optional<std::int64_t> index = parse_integer(vertex_index_text(file, line, field));
    if (!index) fail_at_line(file, line, "malformed face index " + quote(field));
    std::int64_t resolved;
    if (*index > 0) {
      if (*index > static_cast<std::int64_t>(max_vertex_count))
        fail_at_line(file, line, "face index " + std::to_string(*index) + " out of range");
      resolved = *index - 1;
      if (*index > vertices_so_far && *index > largest_forward.index)
        largest_forward = {*index, line};
    } else if (*index < 0) {
      resolved = vertices_so_far + *index;
      if (resolved < 0)
        fail_at_line(file, line,
                     "face index " + std::to_string(*index) + " out of range (only " +
                         std::to_string(vertices_so_far) + " vertices precede it)");
    } else {
      fail_at_line(file, line, "face index 0 is invalid (OBJ indices start at 1)");
    }
    corners.push_back(static_cast<std::int32_t>(resolved));
  }
  if (corners.size() < 3)
    fail_at_line(file, line,
                 "face has " + std::to_string(corners.size()) + " corners, needs at least 3");
  add_polygon(mesh, corners);
}

// The statements of the OBJ specification (Wavefront, Appendix B1 of the Advanced Visualizer
// manual) that carry no vertex or face of a surface. "call" (which includes another file's
// geometry) is not among them: it is rejected like an unknown statement.
bool is_skipped_statement(std::string_view keyword) {
  static constexpr std::string_view skipped[] = {
      "vt",        "vn",     "vp",     "g",     "o",        "s",        "mg",   "usemtl",
      "mtllib",    "usemap", "maplib", "l",     "p",        "cstype",   "deg",  "bmat",
      "step",      "curv",   "curv2",  "surf",  "parm",     "trim",     "hole", "scrv",
      "sp",        "end",    "con",    "bevel", "c_interp", "d_interp", "lod",  "shadow_obj",
      "trace_obj", "ctech",  "stech",  "csh"};
  for (const std::string_view s : skipped)
    if (keyword == s) return true;
  return false;
}

// Lines that start with "v " and "f ": a quick count to reserve the arrays exactly, since
// growing them by doubling would cost up to twice their size at the peak of a large read.
std::pair<std::size_t, std::size_t> count_vertex_and_face_lines(std::string_view bytes) {
  std::size_t vertices = 0, faces = 0;
  for (std::size_t start = 0; start < bytes.size();) {
    if (start + 1 < bytes.size() && (bytes[start + 1] == ' ' || bytes[start + 1] == '\t')) {
      vertices += bytes[start] == 'v';
      faces += bytes[start] == 'f';
    }
    const std::size_t end = bytes.find('\n', start);
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return {vertices, faces};
}

}  // namespace

InputMesh read_obj(const SourceFile& file) {
  InputMesh result;
  const auto [vertex_lines, face_lines] = count_vertex_and_face_lines(file.bytes);
  result.mesh.positions.reserve(vertex_lines);
  result.mesh.triangles.reserve(face_lines);
  std::vector<std::int32_t> corners;
  ForwardReference largest_forward;
  LineReader lines(file.bytes);
  std::string_view line;
  while (lines.next(line)) {
    const std::string_view content = strip_comment(line);
    Fields fields(content);
    const std::string_view keyword = fields.next();
    const bool is_vertex = keyword == "v";
    const bool is_face = keyword == "f";
    if (keyword.empty() || is_skipped_statement(keyword)) continue;
    if (!is_vertex && !is_face)
      fail_at_line(file, lines.line_number(), "unknown OBJ statement " + quote(keyword));
    if (continues_on_next_line(content))
      fail_at_line(file, lines.line_number(), "line continuation with '\\' is not supported");
    if (is_vertex) {
      read_vertex(file, lines.line_number(), fields, result.mesh);
    } else {
      read_face(file, lines.line_number(), fields, result.mesh, corners, largest_forward);
      ++result.polygon_count;
    }
  }
  const std::size_t vertex_count = result.mesh.positions.size();
  if (largest_forward.index > static_cast<std::int64_t>(vertex_count))
    fail_at_line(file, largest_forward.line,
                 "face index " + std::to_string(largest_forward.index) +
                     " out of range (the file has " + std::to_string(vertex_count) + " vertices)");
  return result;
}

}  // namespace toonwater::readers
