// Legacy VTK (`.vtk`), as splashsurf writes its surface (`splashsurf_lib/src/io/vtk_format.rs`,
// `write_vtk`, through vtkio's legacy writer: version 4.2, BINARY, big-endian, an
// UNSTRUCTURED_GRID of triangles) and as VTK, ParaView and other tools write polygon data
// (VTK's "File Formats" document, "Simple Legacy Formats"):
//
//   # vtk DataFile Version 4.2        version line
//   any title                         one line
//   ASCII | BINARY                    binary data is big-endian, right after its header line
//   DATASET POLYDATA | UNSTRUCTURED_GRID
//   POINTS n float|double             3n numbers
//   POLYGONS c s | TRIANGLE_STRIPS c s          (POLYDATA) c cells "k i1 ... ik" in s integers
//   CELLS c s, then CELL_TYPES c                 (UNSTRUCTURED_GRID) the same cells, then their
//                                                types: 5 triangle, 9 quad, 7 polygon
//   POINT_DATA n | CELL_DATA c ...    attributes: the rest of the file, not read
//
// Version 5 files list a grid's cells as "CELLS c+1 s" followed by "OFFSETS type" (c + 1
// offsets) and "CONNECTIVITY type" (s indices, vtktypeint64 or vtktypeint32), also read.
// Polygons and quads are fan-triangulated, strips split into triangles of alternating winding
// so that all face one way. Vertices, lines and any cell type other than those above are not a
// surface: an error names the cell. Errors name the line in ASCII files, the byte offset in
// binary ones.
#include "analyzer/readers/readers.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace toonwater::readers {
namespace {

enum class Scalar { float32, float64, int32, int64 };

std::size_t size_of(Scalar type) {
  return type == Scalar::float32 || type == Scalar::int32 ? 4 : 8;
}

// A cell list as the file gives it: cell i's corners are corner[start[i]] to corner[start[i+1]).
struct Cells {
  std::vector<std::size_t> start{0};
  std::vector<std::int32_t> corner;
  std::size_t count() const { return start.size() - 1; }
  std::span<const std::int32_t> of(std::size_t i) const {
    return {corner.data() + start[i], start[i + 1] - start[i]};
  }
};

constexpr std::int64_t vtk_triangle = 5, vtk_polygon = 7, vtk_quad = 9;

class VtkParser {
 public:
  explicit VtkParser(const SourceFile& file) : file_(file), bytes_(file.bytes) {}

  InputMesh parse() {
    std::string_view line;
    if (!next_line(line, /*skip_blank=*/false) || !line.starts_with("# vtk DataFile Version"))
      fail_here("not a legacy VTK file: it does not start with \"# vtk DataFile Version\"");
    const std::string_view version = Fields(line.substr(22)).next();
    const std::optional<std::int64_t> major = parse_integer(version.substr(0, version.find('.')));
    if (!major) fail_here("unreadable VTK version " + quote(version));
    if (!next_line(line, false)) fail_here("truncated: the file ends before its title line");
    if (!next_line(line)) fail_here("truncated: the file ends before ASCII or BINARY");
    const std::string_view encoding = Fields(line).next();
    if (encoding == "BINARY")
      binary_ = true;
    else if (encoding != "ASCII")
      fail_here("expected ASCII or BINARY, found " + quote(line));

    bool polydata = false, grid = false;
    std::optional<Cells> cells;
    std::vector<std::int64_t> types;
    bool have_types = false;
    InputMesh result;
    std::optional<std::uint64_t> points;
    while (next_line(line)) {
      Fields fields(line);
      const std::string_view keyword = fields.next();
      if (keyword == "DATASET") {
        const std::string_view kind = fields.next();
        if (kind == "POLYDATA")
          polydata = true;
        else if (kind == "UNSTRUCTURED_GRID")
          grid = true;
        else
          fail_here("dataset " + quote(kind) +
                    " is not a surface toonwater reads (POLYDATA or UNSTRUCTURED_GRID)");
      } else if (keyword == "POINTS" && (polydata || grid) && !points) {
        points = count_field(fields, "point count");
        read_points(*points, scalar_field(fields, /*real=*/true), result.mesh);
      } else if ((keyword == "POLYGONS" || keyword == "TRIANGLE_STRIPS") && polydata && points &&
                 !cells) {
        const std::uint64_t count = count_field(fields, "cell count");
        cells = read_legacy_cells(count, count_field(fields, "cell list size"), *points);
        if (keyword == "TRIANGLE_STRIPS") types.assign(count, -1);  // strips, below
        have_types = true;
      } else if (keyword == "CELLS" && grid && points && !cells) {
        const std::uint64_t count = count_field(fields, "cell count");
        const std::uint64_t size = count_field(fields, "cell list size");
        cells = *major >= 5 ? read_offset_cells(count, size, *points)
                            : read_legacy_cells(count, size, *points);
      } else if (keyword == "CELL_TYPES" && grid && cells && !have_types) {
        const std::uint64_t count = count_field(fields, "cell type count");
        if (count != cells->count())
          fail_here(std::to_string(count) + " cell types for " + std::to_string(cells->count()) +
                    " cells");
        types.reserve(capped_reserve(count, remaining(), 1));
        read_values(count, Scalar::int32, "cell type",
                    [&](std::uint64_t, double, std::int64_t type) { types.push_back(type); });
        have_types = true;
      } else if (keyword == "VERTICES" || keyword == "LINES") {
        fail_here(std::string(keyword) + " cells are not a surface (POLYGONS or TRIANGLE_STRIPS)");
      } else if (keyword == "METADATA") {
        skip_metadata();
      } else if ((keyword == "POINT_DATA" || keyword == "CELL_DATA") && have_types) {
        break;  // attributes: nothing toonwater uses
      } else {
        fail_here("unexpected " + quote(line));
      }
    }
    if (!polydata && !grid) fail_here("truncated: the file ends before its DATASET line");
    if (!points) fail_here("truncated: the file ends before its POINTS");
    if (!cells) fail_here(grid ? "no CELLS: the grid has no faces" : "no POLYGONS: no faces");
    if (!have_types) fail_here("truncated: the file ends before its CELL_TYPES");
    add_faces(*cells, types, result);
    return result;
  }

 private:
  // The next line (without its terminator), blank ones skipped unless !skip_blank; false at the
  // end of the file.
  bool next_line(std::string_view& line, bool skip_blank = true) {
    while (pos_ < bytes_.size()) {
      line_start_ = pos_;
      line_number_ = line_;
      std::size_t end = bytes_.find('\n', pos_);
      if (end == std::string_view::npos) end = bytes_.size();
      line = bytes_.substr(pos_, end - pos_);
      if (line.ends_with('\r')) line.remove_suffix(1);
      pos_ = std::min(end + 1, bytes_.size());
      ++line_;
      if (!skip_blank || line.find_first_not_of(" \t") != std::string_view::npos) return true;
    }
    line_start_ = pos_;
    return false;
  }

  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

  [[noreturn]] void fail_here(const std::string& message) const { fail_at(message, line_start_); }
  // An error at the line of what was read last in an ASCII file, at `offset` in a binary one
  // (whose line numbers, after the first binary block, count nothing a reader can find).
  [[noreturn]] void fail_at(const std::string& message, std::size_t offset) const {
    if (!binary_) fail_at_line(file_, line_number_, message);
    fail(file_, message + " (byte offset " + std::to_string(offset) + ")");
  }

  std::size_t remaining() const { return bytes_.size() - pos_; }

  std::uint64_t count_field(Fields& fields, const std::string& what) {
    const std::string_view field = fields.next();
    const std::optional<std::int64_t> count = parse_integer(field);
    if (!count || *count < 0) fail_here("bad " + what + " " + quote(field));
    return static_cast<std::uint64_t>(*count);
  }

  Scalar scalar_field(Fields& fields, bool real) {
    const std::string_view name = fields.next();
    if (real && name == "float") return Scalar::float32;
    if (real && name == "double") return Scalar::float64;
    if (!real && (name == "vtktypeint64" || name == "long")) return Scalar::int64;
    if (!real && (name == "vtktypeint32" || name == "int")) return Scalar::int32;
    fail_here("values of type " + quote(name) + " are not read here (" +
              (real ? "float or double" : "vtktypeint64 or vtktypeint32") + ")");
  }

  // Reads `count` values of `type`, ASCII tokens or big-endian binary, and gives each to
  // sink(index, as a double, as an integer). Integers must be integers and reals finite.
  template <class Sink>
  void read_values(std::uint64_t count, Scalar type, const std::string& what, Sink&& sink) {
    const bool real = type == Scalar::float32 || type == Scalar::float64;
    if (binary_) {
      const std::uint64_t bytes = count * size_of(type);
      if (count > remaining() || bytes > remaining())
        fail(file_, "truncated: " + std::to_string(count) + " " + what + " values need " +
                        std::to_string(bytes) + " bytes from byte offset " + std::to_string(pos_) +
                        ", the file ends at byte offset " + std::to_string(bytes_.size()));
      for (std::uint64_t i = 0; i < count; ++i, pos_ += size_of(type)) {
        const char* at = bytes_.data() + pos_;
        switch (type) {
          case Scalar::float32:
            sink(i, big_endian<float>(at), 0);
            break;
          case Scalar::float64:
            sink(i, big_endian<double>(at), 0);
            break;
          case Scalar::int32:
            sink(i, 0.0, big_endian<std::int32_t>(at));
            break;
          case Scalar::int64:
            sink(i, 0.0, big_endian<std::int64_t>(at));
            break;
        }
      }
      return;
    }
    for (std::uint64_t i = 0; i < count; ++i) {
      const std::string_view token = next_token();
      if (token.empty())
        fail_at_line(file_, line_number_,
                     "truncated: the file ends in " + what + " value " + std::to_string(i) +
                         " of " + std::to_string(count));
      if (real) {
        const std::optional<double> value = parse_double(token);
        if (!value) fail_at_line(file_, line_number_, "bad " + what + " value " + quote(token));
        sink(i, *value, 0);
      } else {
        const std::optional<std::int64_t> value = parse_integer(token);
        if (!value) fail_at_line(file_, line_number_, "bad " + what + " value " + quote(token));
        sink(i, 0.0, *value);
      }
    }
  }

  template <class T>
  static T big_endian(const char* bytes) {
    std::array<char, sizeof(T)> raw;
    std::memcpy(raw.data(), bytes, sizeof(T));
    if constexpr (std::endian::native == std::endian::little) std::reverse(raw.begin(), raw.end());
    return std::bit_cast<T>(raw);
  }

  // The next whitespace-separated token of ASCII data, across lines; empty at the end.
  std::string_view next_token() {
    for (; pos_ < bytes_.size() && is_space(bytes_[pos_]); ++pos_)
      if (bytes_[pos_] == '\n') ++line_;
    if (pos_ < bytes_.size()) line_number_ = line_;
    const std::size_t begin = pos_;
    while (pos_ < bytes_.size() && !is_space(bytes_[pos_])) ++pos_;
    return bytes_.substr(begin, pos_ - begin);
  }

  void read_points(std::uint64_t count, Scalar type, TriangleMesh& mesh) {
    if (count > max_vertex_count)
      fail_here(std::to_string(count) + " points are more than a mesh can index");
    mesh.positions.reserve(capped_reserve(count, remaining(), binary_ ? 3 * size_of(type) : 6));
    Vec3 point;
    read_values(3 * count, type, "point", [&](std::uint64_t i, double value, std::int64_t) {
      if (!std::isfinite(value))
        fail_at("coordinate is NaN or infinite (point " + std::to_string(i / 3) + ")", pos_);
      point[static_cast<int>(i % 3)] = value;
      if (i % 3 == 2) mesh.positions.push_back(point);
    });
  }

  std::int32_t corner_index(std::int64_t index, std::uint64_t points, std::size_t cell) const {
    if (index < 0 || static_cast<std::uint64_t>(index) >= points)
      fail_at("cell " + std::to_string(cell) + " refers to point " + std::to_string(index) +
                  ", but there are " + std::to_string(points) + " points",
              pos_);
    return static_cast<std::int32_t>(index);
  }

  // c cells "k i1 ... ik" in `size` 32-bit integers.
  Cells read_legacy_cells(std::uint64_t count, std::uint64_t size, std::uint64_t points) {
    Cells cells;
    cells.start.reserve(capped_reserve(count, remaining(), 4) + 1);
    cells.corner.reserve(capped_reserve(size, remaining(), binary_ ? 4 : 2));
    std::uint64_t left = 0;  // corners still to come in the current cell
    read_values(size, Scalar::int32, "cell", [&](std::uint64_t, double, std::int64_t value) {
      if (left == 0) {
        if (cells.count() == count)
          fail_here("the cell list holds more than its " + std::to_string(count) + " cells");
        if (value < 0) fail_here("cell " + std::to_string(cells.count()) + " has a negative size");
        left = static_cast<std::uint64_t>(value);
        cells.start.push_back(cells.corner.size());
        if (left == 0) return;
      } else {
        cells.corner.push_back(corner_index(value, points, cells.count() - 1));
        cells.start.back() = cells.corner.size();
        --left;
      }
    });
    if (left != 0 || cells.count() != count)
      fail_here("the cell list of " + std::to_string(size) + " integers does not hold its " +
                std::to_string(count) + " cells");
    return cells;
  }

  // Version 5: "OFFSETS type" with `offsets` values, then "CONNECTIVITY type" with `size`.
  Cells read_offset_cells(std::uint64_t offsets, std::uint64_t size, std::uint64_t points) {
    std::string_view line;
    if (!next_line(line) || Fields(line).next() != "OFFSETS")
      fail_here("expected OFFSETS after a version 5 CELLS line");
    Fields offset_fields(line);
    offset_fields.next();
    Cells cells;
    cells.start.clear();
    cells.start.reserve(capped_reserve(offsets, remaining(), binary_ ? 4 : 2));
    read_values(offsets, scalar_field(offset_fields, false), "offset",
                [&](std::uint64_t i, double, std::int64_t value) {
                  const std::uint64_t previous = i == 0 ? 0 : cells.start.back();
                  if (value < 0 || static_cast<std::uint64_t>(value) < previous ||
                      static_cast<std::uint64_t>(value) > size || (i == 0 && value != 0))
                    fail_here("offset " + std::to_string(i) + " (" + std::to_string(value) +
                              ") is not between the one before it and " + std::to_string(size));
                  cells.start.push_back(static_cast<std::size_t>(value));
                });
    if (cells.start.empty() || cells.start.back() != size)
      fail_here("the last offset is not the connectivity's size " + std::to_string(size));
    if (!next_line(line) || Fields(line).next() != "CONNECTIVITY")
      fail_here("expected CONNECTIVITY after the OFFSETS");
    Fields connectivity_fields(line);
    connectivity_fields.next();
    cells.corner.reserve(capped_reserve(size, remaining(), binary_ ? 4 : 2));
    std::size_t cell = 0;
    read_values(size, scalar_field(connectivity_fields, false), "connectivity",
                [&](std::uint64_t i, double, std::int64_t value) {
                  while (cells.start[cell + 1] <= i) ++cell;
                  cells.corner.push_back(corner_index(value, points, cell));
                });
    return cells;
  }

  void skip_metadata() {
    std::string_view line;
    while (next_line(line, false) && line.find_first_not_of(" \t") != std::string_view::npos) {
    }
  }

  // The faces of the cells: `types` empty for POLYGONS, -1 each for TRIANGLE_STRIPS, else VTK's.
  void add_faces(const Cells& cells, const std::vector<std::int64_t>& types, InputMesh& result) {
    TriangleMesh& mesh = result.mesh;
    for (std::size_t i = 0; i < cells.count(); ++i) {
      const std::span<const std::int32_t> corners = cells.of(i);
      const std::int64_t type = types.empty() ? vtk_polygon : types[i];
      const auto cell_error = [&](const std::string& what) {
        fail(file_, "cell " + std::to_string(i) + " " + what);
      };
      if (type == -1) {  // a triangle strip
        if (corners.size() < 3) cell_error("is a strip of fewer than 3 points");
        for (std::size_t k = 0; k + 2 < corners.size(); ++k)
          mesh.triangles.push_back(k % 2 == 0
                                       ? Triangle{corners[k], corners[k + 1], corners[k + 2]}
                                       : Triangle{corners[k + 1], corners[k], corners[k + 2]});
        result.polygon_count += corners.size() - 2;
        continue;
      }
      if (type != vtk_triangle && type != vtk_quad && type != vtk_polygon)
        cell_error("is of VTK cell type " + std::to_string(type) +
                   ", not a surface face (5 triangle, 9 quad or 7 polygon)");
      const std::size_t needed = type == vtk_triangle ? 3 : type == vtk_quad ? 4 : 0;
      if (needed ? corners.size() != needed : corners.size() < 3)
        cell_error("has " + std::to_string(corners.size()) + " points, which its type " +
                   std::to_string(type) + " does not allow");
      add_polygon(mesh, corners);
      ++result.polygon_count;
    }
  }

  const SourceFile& file_;
  std::string_view bytes_;
  std::size_t pos_ = 0;
  std::size_t line_start_ = 0;   // where the line last read starts
  std::size_t line_ = 1;         // the line at pos_, in an ASCII file
  std::size_t line_number_ = 1;  // the line of the line or value last read
  bool binary_ = false;
};

}  // namespace

InputMesh read_vtk(const SourceFile& file) { return VtkParser(file).parse(); }

}  // namespace toonwater::readers
