// FLIP Fluids' (the Blender add-on's) surface mesh cache, `cache/bakefiles/NNNNNN.bobj`
// (TriangleMesh::getMeshFileDataBOBJ and loadBOBJ, src/engine/trianglemesh.cpp), uncompressed
// little-endian data:
//   int32 n, then n × 3 float32 vertex positions;
//   int32 t, then t × 3 int32 vertex indices, 0-based;
// and nothing after. Unlike Mantaflow's cache it is not gzip-compressed and holds no normals.
// Positions are read as stored, in the simulation's coordinates (docs/inputs.md says how the
// add-on places them in the world). The same folder holds attribute files with the same suffix
// ("velocity000001.bobj", "blur000001.bobj"), which a sequence pattern leaves out by its prefix.
#include "analyzer/readers/readers.hpp"

#include <cstdint>
#include <string>

namespace toonwater::readers {
namespace {

constexpr std::size_t count_bytes = 4;
constexpr std::size_t record_bytes = 12;  // three float32 or three int32

class FlipBobjParser {
 public:
  explicit FlipBobjParser(const SourceFile& file) : file_(file) {}

  InputMesh parse() {
    InputMesh result;
    TriangleMesh& mesh = result.mesh;
    const std::uint32_t vertices = read_count("vertex");
    const char* record = records("vertex", vertices);
    mesh.positions.reserve(vertices);
    for (std::uint32_t v = 0; v < vertices; ++v, record += record_bytes) {
      const Vec3 position(little_endian<float>(record), little_endian<float>(record + 4),
                          little_endian<float>(record + 8));
      if (!position.allFinite())
        fail(file_, "coordinate is NaN or infinite (vertex " + std::to_string(v) + ")");
      mesh.positions.push_back(position);
    }
    const std::uint32_t triangles = read_count("triangle");
    record = records("triangle", triangles);
    mesh.triangles.reserve(triangles);
    for (std::uint32_t t = 0; t < triangles; ++t, record += record_bytes) {
      Triangle triangle;
      for (int c = 0; c < 3; ++c) {
        triangle[c] = little_endian<std::int32_t>(record + 4 * c);
        if (triangle[c] < 0 || static_cast<std::uint32_t>(triangle[c]) >= vertices)
          fail(file_, "triangle " + std::to_string(t) + " refers to vertex " +
                          std::to_string(triangle[c]) + ", but there are " +
                          std::to_string(vertices) + " vertices (byte offset " +
                          std::to_string(offset_of(record) + 4 * c) + ")");
      }
      mesh.triangles.push_back(triangle);
    }
    result.polygon_count = triangles;
    if (offset_ != file_.bytes.size())
      fail(file_, std::to_string(file_.bytes.size() - offset_) +
                      " unexpected bytes after the triangles (byte offset " +
                      std::to_string(offset_) +
                      "); a Mantaflow mesh cache is gzip-compressed and named .bobj.gz");
    return result;
  }

 private:
  std::size_t remaining() const { return file_.bytes.size() - offset_; }
  std::size_t offset_of(const char* at) const {
    return static_cast<std::size_t>(at - file_.bytes.data());
  }

  std::uint32_t read_count(const std::string& what) {
    if (remaining() < count_bytes)
      fail(file_, "truncated: the file ends before the " + what + " count (byte offset " +
                      std::to_string(file_.bytes.size()) + ")");
    const auto count = little_endian<std::int32_t>(file_.bytes.data() + offset_);
    if (count < 0)
      fail(file_, "negative " + what + " count " + std::to_string(count) + " (byte offset " +
                      std::to_string(offset_) + ")");
    offset_ += count_bytes;
    return static_cast<std::uint32_t>(count);
  }

  // The first of `count` records, all of which the file holds; the offset moves past them.
  const char* records(const std::string& what, std::uint32_t count) {
    const std::uint64_t bytes = std::uint64_t{record_bytes} * count;
    if (bytes > remaining())
      fail(file_, "truncated: " + std::to_string(count) + " " + what + " records need " +
                      std::to_string(bytes) + " bytes from byte offset " + std::to_string(offset_) +
                      ", the file ends at byte offset " + std::to_string(file_.bytes.size()));
    const char* first = file_.bytes.data() + offset_;
    offset_ += static_cast<std::size_t>(bytes);
    return first;
  }

  const SourceFile& file_;
  std::size_t offset_ = 0;
};

}  // namespace

InputMesh read_flip_bobj(const SourceFile& file) { return FlipBobjParser(file).parse(); }

}  // namespace toonwater::readers
