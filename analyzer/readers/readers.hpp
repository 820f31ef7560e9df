// Internal to the mesh readers: one reader per format, and the parsing helpers they share
// (implemented in analyzer/mesh_reader.cpp). Every reader gets the whole file in memory and
// reports problems through fail()/fail_at_line(), which throw InputError with one line of text.
#pragma once

#include "analyzer/mesh_reader.hpp"
#include "analyzer/particles.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace toonwater::readers {

// A whole input file in memory, and the name that error messages give it.
struct SourceFile {
  std::string name;
  std::string_view bytes;
};

// The whole file (one pread per core), its size in `size`; fails naming the file when it cannot
// be opened or read, is not a regular file, or is larger than the machine's memory.
std::unique_ptr<char[]> load_file(const SourceFile& file, std::size_t& size);
// Fails naming the file unless it is a regular file (a reader that opens it itself: OpenVDB).
void check_regular_file(const SourceFile& file);
// The file's extension in lower case ("" when it has none).
std::string lowercase_extension(const std::filesystem::path& path);
// "NAME: cannot open: No such file or directory" and the like, from an errno value.
[[noreturn]] void fail_errno(const SourceFile& file, std::string_view what, int error);

// "NAME: message" (binary formats say where in the message: "(vertex 12)", "(byte offset 96)").
[[noreturn]] void fail(const SourceFile& file, std::string_view message);
// "NAME:LINE: message" (text formats; lines count from 1).
[[noreturn]] void fail_at_line(const SourceFile& file, std::size_t line, std::string_view message);

// A field of the file quoted for an error message: at most 40 characters, control and non-ASCII
// bytes shown as '?', so a message stays one readable line whatever the file contains.
std::string quote(std::string_view field);

// The lines of a text, without their "\n" or "\r\n" terminators. A UTF-8 byte order mark at
// the start is skipped: it would otherwise hide the first line's keyword.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : rest_(text) {
    if (rest_.starts_with("\xEF\xBB\xBF")) rest_.remove_prefix(3);
  }

  // The next line; false at the end of the text.
  bool next(std::string_view& line);
  // The number of the line last returned by next() (0 before the first).
  std::size_t line_number() const { return line_number_; }
  // The text after the line last returned.
  std::string_view rest() const { return rest_; }

 private:
  std::string_view rest_;
  std::size_t line_number_ = 0;
};

// The part of a line before a '#' comment.
std::string_view strip_comment(std::string_view line);

// Whitespace-separated fields of one line.
class Fields {
 public:
  explicit Fields(std::string_view line) : rest_(line) {}

  // The next field; empty when none is left.
  std::string_view next();
  bool at_end();

 private:
  std::string_view rest_;
};

// The whole field as a number (an optional leading '+' is accepted); nullopt when the field is
// not a number or, for integers, does not fit. parse_double accepts "nan" and "inf", which
// parse_coordinate then rejects.
std::optional<double> parse_double(std::string_view field);
std::optional<std::int64_t> parse_integer(std::string_view field);

// A vertex coordinate of a text format: a finite number, or an error at `line`.
double parse_coordinate(const SourceFile& file, std::size_t line, std::string_view field);

// The next three fields as a finite point; "vertex has N coordinates, expected 3" when short.
Vec3 read_point(const SourceFile& file, std::size_t line, Fields& fields);

// How many records to reserve room for when a header declares `declared` of them: never more than
// the remaining bytes could hold at `min_record_bytes` each, so a hostile header cannot make the
// reader allocate memory the file does not back.
std::size_t capped_reserve(std::uint64_t declared, std::size_t remaining_bytes,
                           std::size_t min_record_bytes);

// A value of type T stored little-endian at `bytes` (which need not be aligned).
template <class T>
T little_endian(const char* bytes) {
  std::array<char, sizeof(T)> raw;
  std::memcpy(raw.data(), bytes, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(raw.begin(), raw.end());
  return std::bit_cast<T>(raw);
}

// The largest vertex count a TriangleMesh can index.
inline constexpr std::uint64_t max_vertex_count = 2147483647;

// Appends a polygon as a fan of triangles (c0, ci, ci+1); corners.size() >= 3.
void add_polygon(TriangleMesh& mesh, std::span<const std::int32_t> corners);

InputMesh read_obj(const SourceFile& file);
InputMesh read_off(const SourceFile& file);
InputMesh read_ply(const SourceFile& file);
InputMesh read_stl(const SourceFile& file);
InputMesh read_bobj(const SourceFile& file);       // Mantaflow .bobj.gz
InputMesh read_flip_bobj(const SourceFile& file);  // FLIP Fluids .bobj
InputMesh read_vtk(const SourceFile& file);        // legacy VTK, as splashsurf writes it

// A FLIP Fluids whitewater file (.wwp) of particles of one kind.
ParticleSet read_wwp(const SourceFile& file, ParticleKind kind);

}  // namespace toonwater::readers
