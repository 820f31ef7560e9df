// Stanford PLY in ascii, binary_little_endian and binary_big_endian. The header declares elements
// (name, count) and their properties (scalars, or lists with a count type and an item type, of
// the eight PLY scalar types). The reader takes x, y, z of the "vertex" element and the
// "vertex_indices" (or "vertex_index") list of the "face" element; other properties and elements
// are skipped — in binary files by their sizes, so they must be well-formed too. ASCII records
// are read one per line, as every writer writes them, so that errors can name the line.
// Binary vertex records without lists, and face records whose only list is the index list (what
// writers write), are read in one loop per element with the types resolved once, on every core
// where the records have one size (vertices; faces that are all triangles); other layouts go
// property by property.
#include "analyzer/readers/readers.hpp"

#include "common/parallel.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace toonwater::readers {
namespace {

enum class PlyType : std::uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

std::optional<PlyType> parse_type(std::string_view name) {
  struct Named {
    std::string_view name, alias;
    PlyType type;
  };
  static constexpr std::array<Named, 8> types{{{"char", "int8", PlyType::int8},
                                               {"uchar", "uint8", PlyType::uint8},
                                               {"short", "int16", PlyType::int16},
                                               {"ushort", "uint16", PlyType::uint16},
                                               {"int", "int32", PlyType::int32},
                                               {"uint", "uint32", PlyType::uint32},
                                               {"float", "float32", PlyType::float32},
                                               {"double", "float64", PlyType::float64}}};
  for (const Named& t : types)
    if (name == t.name || name == t.alias) return t.type;
  return std::nullopt;
}

std::size_t size_of(PlyType type) {
  switch (type) {
    case PlyType::int8:
    case PlyType::uint8:
      return 1;
    case PlyType::int16:
    case PlyType::uint16:
      return 2;
    case PlyType::int32:
    case PlyType::uint32:
    case PlyType::float32:
      return 4;
    case PlyType::float64:
      return 8;
  }
  return 0;
}

bool is_integer(PlyType type) { return type != PlyType::float32 && type != PlyType::float64; }

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::float32;  // a list's item type
  bool is_list = false;
  PlyType count_type = PlyType::uint8;
  std::size_t header_line = 0;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  std::size_t header_line = 0;
};

enum class PlyFormat { ascii, binary_little_endian, binary_big_endian };

struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
};

// What the reader takes from the header: where x, y, z and the face's index list are.
struct PlyLayout {
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;  // absent in a point cloud
  std::array<std::size_t, 3> xyz{};  // property positions within the vertex element
  std::size_t indices = 0;           // property position within the face element
};

PlyProperty read_property(const SourceFile& file, std::size_t line, Fields& fields) {
  PlyProperty property;
  property.header_line = line;
  std::string_view type_name = fields.next();
  if (type_name == "list") {
    property.is_list = true;
    const std::string_view count_name = fields.next();
    const std::optional<PlyType> count_type = parse_type(count_name);
    if (!count_type) fail_at_line(file, line, "unknown property type " + quote(count_name));
    if (!is_integer(*count_type))
      fail_at_line(file, line, "a list's count type must be an integer type");
    property.count_type = *count_type;
    type_name = fields.next();
  }
  const std::optional<PlyType> type = parse_type(type_name);
  if (!type) fail_at_line(file, line, "unknown property type " + quote(type_name));
  property.type = *type;
  property.name = fields.next();
  if (property.name.empty()) fail_at_line(file, line, "property has no name");
  if (!fields.at_end()) fail_at_line(file, line, "unexpected values after the property name");
  return property;
}

// Parses the header; `lines` is left at the first line after end_header.
PlyHeader read_header(const SourceFile& file, LineReader& lines) {
  std::string_view line;
  if (!lines.next(line) || line != "ply")
    fail_at_line(file, 1, "not a PLY file (the first line is not 'ply')");
  PlyHeader header;
  bool has_format = false;
  while (lines.next(line)) {
    const std::size_t number = lines.line_number();
    Fields fields(line);
    const std::string_view keyword = fields.next();
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      if (!has_format) fail_at_line(file, number, "the header has no format line");
      return header;
    }
    if (keyword == "format") {
      const std::string_view format = fields.next();
      if (format == "ascii")
        header.format = PlyFormat::ascii;
      else if (format == "binary_little_endian")
        header.format = PlyFormat::binary_little_endian;
      else if (format == "binary_big_endian")
        header.format = PlyFormat::binary_big_endian;
      else
        fail_at_line(file, number, "unknown PLY format " + quote(format));
      if (fields.next() != "1.0") fail_at_line(file, number, "unsupported PLY version");
      has_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      element.name = fields.next();
      const std::string_view count_field = fields.next();
      const std::optional<std::int64_t> count = parse_integer(count_field);
      if (element.name.empty() || !count || *count < 0 || !fields.at_end())
        fail_at_line(file, number, "malformed element line (expected 'element NAME COUNT')");
      element.count = static_cast<std::uint64_t>(*count);
      element.header_line = number;
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) fail_at_line(file, number, "property before any element");
      header.elements.back().properties.push_back(read_property(file, number, fields));
    } else {
      fail_at_line(file, number, "unknown header keyword " + quote(keyword));
    }
  }
  fail_at_line(file, lines.line_number(), "file ends inside the header (no end_header)");
}

std::size_t find_property(const PlyElement& element, std::string_view name) {
  const auto it = std::find_if(element.properties.begin(), element.properties.end(),
                               [&](const PlyProperty& p) { return p.name == name; });
  return static_cast<std::size_t>(it - element.properties.begin());
}

PlyLayout find_layout(const SourceFile& file, const PlyHeader& header) {
  PlyLayout layout;
  for (const PlyElement& element : header.elements) {
    const PlyElement** slot = element.name == "vertex" ? &layout.vertex
                              : element.name == "face" ? &layout.face
                                                       : nullptr;
    if (!slot) continue;
    if (*slot)
      fail_at_line(file, element.header_line, "second " + quote(element.name) + " element");
    *slot = &element;
  }
  if (!layout.vertex) fail(file, "has no vertex element");
  const PlyElement& vertex = *layout.vertex;
  if (vertex.count > max_vertex_count)
    fail_at_line(file, vertex.header_line,
                 "vertex count " + std::to_string(vertex.count) +
                     " exceeds what a mesh can index (2^31 - 1)");
  constexpr std::array<std::string_view, 3> axes{"x", "y", "z"};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const std::size_t at = find_property(vertex, axes[axis]);
    if (at == vertex.properties.size())
      fail_at_line(file, vertex.header_line, "vertex element has no property " + quote(axes[axis]));
    if (vertex.properties[at].is_list)
      fail_at_line(file, vertex.properties[at].header_line,
                   "property " + quote(axes[axis]) + " must not be a list");
    layout.xyz[axis] = at;
  }
  if (layout.face) {
    const PlyElement& face = *layout.face;
    std::size_t at = find_property(face, "vertex_indices");
    if (at == face.properties.size()) at = find_property(face, "vertex_index");
    if (at == face.properties.size())
      fail_at_line(file, face.header_line, "face element has no property vertex_indices");
    const PlyProperty& indices = face.properties[at];
    if (!indices.is_list || !is_integer(indices.type))
      fail_at_line(file, indices.header_line, "vertex_indices must be a list of an integer type");
    layout.indices = at;
  }
  return layout;
}

// Fewest bytes one record of `element` can take, for capped_reserve.
std::size_t min_record_bytes(const PlyElement& element, PlyFormat format) {
  std::size_t bytes = 0;
  for (const PlyProperty& p : element.properties) {
    if (format == PlyFormat::ascii)
      bytes += 2;  // a digit and a separator
    else
      bytes += size_of(p.is_list ? p.count_type : p.type);
  }
  return std::max<std::size_t>(bytes, 1);
}

std::string face_count_error(std::int64_t corner_count) {
  return "face has " + std::to_string(corner_count) + " corners, needs at least 3";
}

std::string index_error(std::int64_t index, std::uint64_t vertex_count) {
  return "face index " + std::to_string(index) + " out of range (the file has " +
         std::to_string(vertex_count) + " vertices)";
}

// ---- ascii: one record per line ------------------------------------------------------------

class AsciiReader {
 public:
  AsciiReader(const SourceFile& file, LineReader& lines, const PlyLayout& layout)
      : file_(file), lines_(lines), layout_(layout) {}

  void read(const PlyElement& element, InputMesh& result) {
    for (std::uint64_t r = 0; r < element.count; ++r) {
      std::string_view line;
      do {
        if (!lines_.next(line))
          fail_at_line(file_, lines_.line_number(),
                       "file ends after " + std::to_string(r) + " of " +
                           std::to_string(element.count) + " " + quote(element.name) + " records");
      } while (Fields(line).at_end());
      Fields fields(line);
      if (&element == layout_.vertex)
        read_vertex(element, fields, result.mesh);
      else if (&element == layout_.face)
        read_face(element, fields, result);
      else
        skip_record(element, fields);
      if (!fields.at_end())
        fail_at_line(file_, lines_.line_number(),
                     "too many values in a " + quote(element.name) + " record");
    }
  }

 private:
  std::string_view next_value(const PlyElement& element, Fields& fields) {
    const std::string_view field = fields.next();
    if (field.empty())
      fail_at_line(file_, lines_.line_number(),
                   "too few values in a " + quote(element.name) + " record");
    return field;
  }

  void skip_value(const PlyElement& element, Fields& fields) {
    const std::string_view field = next_value(element, fields);
    if (!parse_double(field))
      fail_at_line(file_, lines_.line_number(), "malformed number " + quote(field));
  }

  std::int64_t list_count(const PlyElement& element, Fields& fields) {
    const std::string_view field = next_value(element, fields);
    const std::optional<std::int64_t> count = parse_integer(field);
    if (!count || *count < 0)
      fail_at_line(file_, lines_.line_number(), "malformed list count " + quote(field));
    return *count;
  }

  void skip_property(const PlyElement& element, const PlyProperty& property, Fields& fields) {
    const std::int64_t values = property.is_list ? list_count(element, fields) : 1;
    for (std::int64_t k = 0; k < values; ++k) skip_value(element, fields);
  }

  void skip_record(const PlyElement& element, Fields& fields) {
    for (const PlyProperty& property : element.properties) skip_property(element, property, fields);
  }

  void read_vertex(const PlyElement& element, Fields& fields, TriangleMesh& mesh) {
    Vec3 position;
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const auto axis = std::find(layout_.xyz.begin(), layout_.xyz.end(), p);
      if (axis == layout_.xyz.end()) {
        skip_property(element, element.properties[p], fields);
        continue;
      }
      position[axis - layout_.xyz.begin()] =
          parse_coordinate(file_, lines_.line_number(), next_value(element, fields));
    }
    mesh.positions.push_back(position);
  }

  void read_face(const PlyElement& element, Fields& fields, InputMesh& result) {
    const std::size_t line = lines_.line_number();
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      if (p != layout_.indices) {
        skip_property(element, element.properties[p], fields);
        continue;
      }
      const std::int64_t corner_count = list_count(element, fields);
      if (corner_count < 3) fail_at_line(file_, line, face_count_error(corner_count));
      corners_.clear();
      for (std::int64_t k = 0; k < corner_count; ++k) {
        const std::string_view field = next_value(element, fields);
        const std::optional<std::int64_t> index = parse_integer(field);
        if (!index) fail_at_line(file_, line, "malformed face index " + quote(field));
        if (*index < 0 || static_cast<std::uint64_t>(*index) >= layout_.vertex->count)
          fail_at_line(file_, line, index_error(*index, layout_.vertex->count));
        corners_.push_back(static_cast<std::int32_t>(*index));
      }
    }
    add_polygon(result.mesh, corners_);
    ++result.polygon_count;
  }

  const SourceFile& file_;
  LineReader& lines_;
  const PlyLayout& layout_;
  std::vector<std::int32_t> corners_;
};

// ---- binary: fixed-size scalars in the file's byte order ------------------------------------

// fn.template operator()<T>() with T the C++ type of a PLY type (float64 after the switch, so
// that every path returns).
template <class Fn>
auto dispatch(PlyType type, Fn&& fn) {
  switch (type) {
    case PlyType::int8:
      return fn.template operator()<std::int8_t>();
    case PlyType::uint8:
      return fn.template operator()<std::uint8_t>();
    case PlyType::int16:
      return fn.template operator()<std::int16_t>();
    case PlyType::uint16:
      return fn.template operator()<std::uint16_t>();
    case PlyType::int32:
      return fn.template operator()<std::int32_t>();
    case PlyType::uint32:
      return fn.template operator()<std::uint32_t>();
    case PlyType::float32:
      return fn.template operator()<float>();
    case PlyType::float64:
      break;
  }
  return fn.template operator()<double>();
}

class BinaryReader {
 public:
  BinaryReader(const SourceFile& file, std::string_view body, bool big_endian,
               const PlyLayout& layout)
      : file_(file),
        begin_(file.bytes.data()),
        position_(body.data()),
        end_(body.data() + body.size()),
        swap_bytes_(big_endian != (std::endian::native == std::endian::big)),
        layout_(layout) {}

  void read(const PlyElement& element, InputMesh& result) {
    element_ = &element;
    const bool all_scalar = std::none_of(element.properties.begin(), element.properties.end(),
                                         [](const PlyProperty& p) { return p.is_list; });
    if (&element != layout_.vertex && &element != layout_.face && all_scalar) {
      // Records of fixed size: skip the whole element at once.
      std::size_t record_size = 0;
      for (const PlyProperty& p : element.properties) record_size += size_of(p.type);
      const auto remaining = static_cast<std::size_t>(end_ - position_);
      if (record_size != 0 && element.count > remaining / record_size) {
        record_ = remaining / record_size;
        truncated();
      }
      position_ += element.count * record_size;
      return;
    }
    if (&element == layout_.vertex && all_scalar) {
      read_fixed_vertices(result.mesh);
      return;
    }
    if (&element == layout_.face && face_list_is_only_list()) {
      dispatch_integer(layout_.face->properties[layout_.indices].count_type, [&]<class Count>() {
        dispatch_integer(layout_.face->properties[layout_.indices].type,
                         [&]<class Index>() { read_faces<Count, Index>(result); });
      });
      return;
    }
    for (record_ = 0; record_ < element.count; ++record_) {
      if (&element == layout_.vertex)
        read_vertex(result.mesh);
      else if (&element == layout_.face)
        read_face(result);
      else
        for (const PlyProperty& p : element.properties) skip_property(p);
    }
  }

  // Bytes after the last element.
  std::size_t unread_bytes() const { return static_cast<std::size_t>(end_ - position_); }

 private:
  // "vertex 12", "face 12" or "'edge' record 12": the record being read, for messages.
  std::string record_label() const {
    const bool known = element_ == layout_.vertex || element_ == layout_.face;
    return (known ? element_->name : quote(element_->name) + " record") + " " +
           std::to_string(record_);
  }

  [[noreturn]] void truncated() const {
    fail(file_, "truncated: the data ends inside " + record_label() + " of " +
                    std::to_string(element_->count) + " (byte offset " +
                    std::to_string(file_.bytes.size()) + ")");
  }

  template <class T>
  T read_raw() {
    if (static_cast<std::size_t>(end_ - position_) < sizeof(T)) truncated();
    const T value = load<T>(position_);
    position_ += sizeof(T);
    return value;
  }

  double read_number(PlyType type) {
    return dispatch(type, [&]<class T>() { return static_cast<double>(read_raw<T>()); });
  }

  // Counts and indices, which the header check guarantees to be of an integer type.
  std::int64_t read_integer(PlyType type) {
    return dispatch(type, [&]<class T>() -> std::int64_t {
      if constexpr (std::is_integral_v<T>)
        return read_raw<T>();
      else
        return 0;
    });
  }

  std::int64_t list_count(const PlyProperty& property) {
    const std::int64_t count = read_integer(property.count_type);
    if (count < 0)
      fail(file_, "negative list count " + std::to_string(count) + " (" + record_label() +
                      ", byte offset " + std::to_string(position_ - begin_) + ")");
    return count;
  }

  void skip_property(const PlyProperty& property) {
    if (!property.is_list) {
      skip(size_of(property.type));
      return;
    }
    const auto count = static_cast<std::uint64_t>(list_count(property));
    const std::size_t item_size = size_of(property.type);
    if (count > static_cast<std::size_t>(end_ - position_) / item_size) truncated();
    position_ += count * item_size;
  }

  void skip(std::size_t bytes) {
    if (static_cast<std::size_t>(end_ - position_) < bytes) truncated();
    position_ += bytes;
  }

  // A scalar of type T at `at`, in the file's byte order; the caller checked the bounds.
  template <class T>
  T load(const char* at) const {
    std::array<char, sizeof(T)> bytes;
    std::memcpy(bytes.data(), at, sizeof(T));
    if (swap_bytes_) std::reverse(bytes.begin(), bytes.end());
    return std::bit_cast<T>(bytes);
  }

  // dispatch for an integer PLY type; a float type, which the header check excludes where this
  // is called, calls nothing.
  template <class Fn>
  static void dispatch_integer(PlyType type, Fn&& fn) {
    dispatch(type, [&]<class T>() {
      if constexpr (std::is_integral_v<T>) fn.template operator()<T>();
    });
  }

  double load_number(PlyType type, const char* at) const {
    return dispatch(type, [&]<class T>() { return static_cast<double>(load<T>(at)); });
  }

  // Vertex records of fixed size (no list property): straight into the position array. The
  // records the data holds in full are read first, so that a bad coordinate before the end of
  // a truncated file is reported as a read record by record would report it.
  void read_fixed_vertices(TriangleMesh& mesh) {
    const std::vector<PlyProperty>& properties = layout_.vertex->properties;
    std::size_t record_size = 0;
    std::array<std::size_t, 3> offset{};
    for (std::size_t p = 0; p < properties.size(); ++p) {
      for (std::size_t axis = 0; axis < 3; ++axis)
        if (layout_.xyz[axis] == p) offset[axis] = record_size;
      record_size += size_of(properties[p].type);
    }
    const std::array<PlyType, 3> type{properties[layout_.xyz[0]].type,
                                      properties[layout_.xyz[1]].type,
                                      properties[layout_.xyz[2]].type};
    const std::uint64_t complete = std::min<std::uint64_t>(
        layout_.vertex->count, static_cast<std::size_t>(end_ - position_) / record_size);
    const std::size_t first = mesh.positions.size();
    mesh.positions.resize(first + complete);
    Vec3* out = mesh.positions.data() + first;
    const bool all_float =
        type[0] == PlyType::float32 && type[1] == PlyType::float32 && type[2] == PlyType::float32;
    // On every core; each chunk notes its first bad record, and the first of all is reported.
    const std::size_t chunks = chunk_count(complete);
    std::vector<std::uint64_t> first_bad(chunks, complete);
    parallel_chunks(complete, chunks, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
      const char* record = position_ + begin * record_size;
      for (std::size_t r = begin; r < end; ++r, record += record_size) {
        Vec3& position = out[r];
        if (all_float) {
          position = {load<float>(record + offset[0]), load<float>(record + offset[1]),
                      load<float>(record + offset[2])};
        } else {
          for (std::size_t axis = 0; axis < 3; ++axis)
            position[axis] = load_number(type[axis], record + offset[axis]);
        }
        if (!position.allFinite()) {
          first_bad[chunk] = r;
          return;
        }
      }
    });
    record_ = *std::min_element(first_bad.begin(), first_bad.end());
    if (record_ < complete)
      fail(file_, "coordinate is NaN or infinite (vertex " + std::to_string(record_) + ")");
    position_ += complete * record_size;
    if (complete < layout_.vertex->count) truncated();
  }

  // The face element's only list is its index list: its other properties are skipped by size.
  bool face_list_is_only_list() const {
    const std::vector<PlyProperty>& properties = layout_.face->properties;
    for (std::size_t p = 0; p < properties.size(); ++p)
      if (p != layout_.indices && properties[p].is_list) return false;
    return true;
  }

  // Face records that are all triangles have one size, so they can be read on every core: true
  // when every record is a triangle whose indices are in range and the data holds them all.
  // Otherwise nothing is read, and read_faces reads record by record, with its own messages.
  template <class Count, class Index>
  bool read_triangle_records(std::size_t before, std::size_t after, InputMesh& result) {
    const std::size_t record_size = before + sizeof(Count) + 3 * sizeof(Index) + after;
    const std::uint64_t count = layout_.face->count;
    if (count > static_cast<std::size_t>(end_ - position_) / record_size) return false;
    const std::uint64_t vertex_count = layout_.vertex->count;
    std::vector<Triangle>& triangles = result.mesh.triangles;
    const std::size_t first = triangles.size();
    triangles.resize(first + count);
    Triangle* out = triangles.data() + first;
    const std::size_t chunks = chunk_count(count);
    std::vector<std::uint8_t> all_triangles(chunks, 1);
    parallel_chunks(count, chunks, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
      for (std::size_t f = begin; f < end; ++f) {
        const char* record = position_ + f * record_size + before;
        if (load<Count>(record) != 3) {
          all_triangles[chunk] = 0;
          return;
        }
        for (std::size_t k = 0; k < 3; ++k) {
          const auto index =
              static_cast<std::int64_t>(load<Index>(record + sizeof(Count) + k * sizeof(Index)));
          if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count) {
            all_triangles[chunk] = 0;
            return;
          }
          out[f][k] = static_cast<std::int32_t>(index);
        }
      }
    });
    if (std::find(all_triangles.begin(), all_triangles.end(), 0) != all_triangles.end()) {
      triangles.resize(first);
      return false;
    }
    position_ += count * record_size;
    record_ = count;
    result.polygon_count += count;
    return true;
  }

  // Face records with the index list as the only list, its count of type Count and its items of
  // type Index; the same checks and messages as read_face, without a type switch per value.
  template <class Count, class Index>
  void read_faces(InputMesh& result) {
    const std::vector<PlyProperty>& properties = layout_.face->properties;
    std::size_t before = 0, after = 0;  // bytes of the scalar properties around the list
    for (std::size_t p = 0; p < properties.size(); ++p)
      if (p != layout_.indices)
        (p < layout_.indices ? before : after) += size_of(properties[p].type);
    if (read_triangle_records<Count, Index>(before, after, result)) return;
    const std::uint64_t vertex_count = layout_.vertex->count;
    std::vector<Triangle>& triangles = result.mesh.triangles;
    for (record_ = 0; record_ < layout_.face->count; ++record_) {
      if (static_cast<std::size_t>(end_ - position_) < before + sizeof(Count)) {
        position_ = end_;
        truncated();
      }
      const auto corner_count = static_cast<std::int64_t>(load<Count>(position_ + before));
      position_ += before + sizeof(Count);
      if (corner_count < 0)
        fail(file_, "negative list count " + std::to_string(corner_count) + " (" + record_label() +
                        ", byte offset " + std::to_string(position_ - begin_) + ")");
      if (corner_count < 3)
        fail(file_, face_count_error(corner_count) + " (face " + std::to_string(record_) + ")");
      const auto available = static_cast<std::size_t>(end_ - position_) / sizeof(Index);
      // Indices the data holds, checked before the truncation is reported (as read_face does).
      const std::size_t readable = std::min<std::uint64_t>(corner_count, available);
      corners_.clear();
      for (std::size_t k = 0; k < readable; ++k) {
        const auto index = static_cast<std::int64_t>(load<Index>(position_ + k * sizeof(Index)));
        if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count)
          fail(file_, index_error(index, vertex_count) + " (face " + std::to_string(record_) + ")");
        corners_.push_back(static_cast<std::int32_t>(index));
      }
      if (readable < static_cast<std::uint64_t>(corner_count)) truncated();
      position_ += readable * sizeof(Index);
      if (static_cast<std::size_t>(end_ - position_) < after) truncated();
      position_ += after;
      if (corners_.size() == 3)
        triangles.push_back({corners_[0], corners_[1], corners_[2]});
      else
        add_polygon(result.mesh, corners_);
      ++result.polygon_count;
    }
  }

  void read_vertex(TriangleMesh& mesh) {
    const std::vector<PlyProperty>& properties = layout_.vertex->properties;
    Vec3 position;
    for (std::size_t p = 0; p < properties.size(); ++p) {
      const auto axis = std::find(layout_.xyz.begin(), layout_.xyz.end(), p);
      if (axis == layout_.xyz.end())
        skip_property(properties[p]);
      else
        position[axis - layout_.xyz.begin()] = read_number(properties[p].type);
    }
    if (!position.allFinite())
      fail(file_, "coordinate is NaN or infinite (vertex " + std::to_string(record_) + ")");
    mesh.positions.push_back(position);
  }

  void read_face(InputMesh& result) {
    const std::vector<PlyProperty>& properties = layout_.face->properties;
    const std::uint64_t vertex_count = layout_.vertex->count;
    for (std::size_t p = 0; p < properties.size(); ++p) {
      if (p != layout_.indices) {
        skip_property(properties[p]);
        continue;
      }
      const std::int64_t corner_count = list_count(properties[p]);
      const std::string face = " (face " + std::to_string(record_) + ")";
      if (corner_count < 3) fail(file_, face_count_error(corner_count) + face);
      corners_.clear();
      for (std::int64_t k = 0; k < corner_count; ++k) {
        const std::int64_t index = read_integer(properties[p].type);
        if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count)
          fail(file_, index_error(index, vertex_count) + face);
        corners_.push_back(static_cast<std::int32_t>(index));
      }
    }
    add_polygon(result.mesh, corners_);
    ++result.polygon_count;
  }

  const SourceFile& file_;
  const char* begin_;
  const char* position_;
  const char* end_;
  bool swap_bytes_;
  const PlyLayout& layout_;
  const PlyElement* element_ = nullptr;
  std::uint64_t record_ = 0;
  std::vector<std::int32_t> corners_;
};

}  // namespace

InputMesh read_ply(const SourceFile& file) {
  LineReader lines(file.bytes);
  const PlyHeader header = read_header(file, lines);
  const PlyLayout layout = find_layout(file, header);
  const std::string_view body = lines.rest();

  InputMesh result;
  result.mesh.positions.reserve(capped_reserve(layout.vertex->count, body.size(),
                                               min_record_bytes(*layout.vertex, header.format)));
  if (layout.face)
    result.mesh.triangles.reserve(capped_reserve(layout.face->count, body.size(),
                                                 min_record_bytes(*layout.face, header.format)));

  if (header.format == PlyFormat::ascii) {
    AsciiReader reader(file, lines, layout);
    for (const PlyElement& element : header.elements) reader.read(element, result);
    std::string_view line;
    while (lines.next(line))
      if (!Fields(line).at_end())
        fail_at_line(file, lines.line_number(), "unexpected data after the last element");
  } else {
    BinaryReader reader(file, body, header.format == PlyFormat::binary_big_endian, layout);
    for (const PlyElement& element : header.elements) reader.read(element, result);
    if (reader.unread_bytes() != 0)
      fail(file, std::to_string(reader.unread_bytes()) +
                     " unexpected bytes after the last element (byte offset " +
                     std::to_string(file.bytes.size() - reader.unread_bytes()) + ")");
  }
  return result;
}

}  // namespace toonwater::readers
