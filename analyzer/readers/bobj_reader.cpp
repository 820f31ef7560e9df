// Blender Mantaflow's liquid mesh cache, `cache_fluid/mesh/fluid_mesh_NNNN.bobj.gz` (Mantaflow's
// writeBobjFile, fileio/iomeshes.cpp): one gzip stream of little-endian data —
//   int32 n, then n × 3 float32 vertex positions;
//   int32 m, then m × 3 float32 vertex normals (m = n as Mantaflow writes them);
//   int32 t, then t × 3 int32 vertex indices, 0-based;
// and, for vortex-sheet meshes only, extra chunks (an int32[4] id, then one float32 per vertex).
// The normals and anything after the triangles are skipped (the analyzer computes its own
// normals), but still inflated, so that a truncated or corrupt stream is caught by gzip's length
// and CRC check. There is no header: the file does not say its grid size or domain, so positions
// are read as stored, in Mantaflow's normalised domain coordinates (docs/inputs.md
// says how they relate to Blender's world space and how to pass the domain transform).
//
// Memory follows what the stream delivers, not what its counts claim: the data is inflated in
// fixed-size chunks and parsed as it arrives. A stream that inflates to more than
// max_expansion times the file's size is refused: deflate can expand up to 1032:1, which a
// crafted file (a gzip bomb) uses to make a reader allocate without bound, whereas mesh data
// compresses about 4:1 (the Mantaflow wake sequence re-encoded at Mantaflow's level 1: 4.1–4.3).
#include "analyzer/readers/readers.hpp"

#define ZLIB_CONST  // z_stream::next_in points to const bytes
#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>

namespace toonwater::readers {
namespace {

constexpr std::uint64_t max_expansion = 64;
constexpr std::size_t chunk_bytes = std::size_t{1} << 16;
constexpr std::size_t record_bytes = 12;  // three float32 or three int32

bool starts_with_gzip_magic(std::string_view bytes) {
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
         static_cast<unsigned char>(bytes[1]) == 0x8b;
}

// The decompressed bytes of a gzip file, delivered in order through read(). Several gzip members
// in a row (as `cat a.gz b.gz` makes) form one stream, as gzip itself treats them.
class GzipStream {
 public:
  explicit GzipStream(const SourceFile& file)
      : file_(file),
        input_(file.bytes),
        limit_(max_expansion * file.bytes.size()),
        buffer_(std::make_unique_for_overwrite<char[]>(chunk_bytes)) {
    if (!starts_with_gzip_magic(file.bytes))
      fail(file, "not a gzip file: it does not start with the gzip bytes 1f 8b (byte offset 0)");
    if (inflateInit2(&z_, 16 + MAX_WBITS) != Z_OK) fail(file, "cannot start zlib's inflate");
  }
  ~GzipStream() { inflateEnd(&z_); }
  GzipStream(const GzipStream&) = delete;
  GzipStream& operator=(const GzipStream&) = delete;

  // Copies the next `size` bytes to `out`; false when the stream ends first.
  bool read(char* out, std::size_t size) {
    while (size > 0) {
      if (begin_ == end_ && !refill()) return false;
      const std::size_t n = std::min(size, end_ - begin_);
      std::memcpy(out, buffer_.get() + begin_, n);
      begin_ += n;
      offset_ += n;
      out += n;
      size -= n;
    }
    return true;
  }

  // Inflates and discards the rest of the stream, which checks that it is complete and intact.
  void skip_rest() {
    offset_ += end_ - begin_;
    begin_ = end_;
    while (refill()) {
      offset_ += end_;
      begin_ = end_;
    }
  }

  // Decompressed bytes delivered so far.
  std::uint64_t offset() const { return offset_; }
  // True when read() failed because the file ends inside the gzip stream (not at its end).
  bool cut_short() const { return cut_short_; }
  // The most bytes the stream may inflate to; also a bound on what a count can really deliver.
  std::uint64_t limit() const { return limit_; }

 private:
  // Inflates the next chunk into the buffer; false at the end of the stream (or of the file).
  bool refill() {
    begin_ = end_ = 0;
    while (end_ == 0) {
      if (ended_ || cut_short_) return false;
      const auto fed = static_cast<uInt>(std::min<std::size_t>(input_.size(), UINT_MAX));
      z_.next_in = reinterpret_cast<const Bytef*>(input_.data());
      z_.avail_in = fed;
      z_.next_out = reinterpret_cast<Bytef*>(buffer_.get());
      z_.avail_out = static_cast<uInt>(chunk_bytes);
      const int status = inflate(&z_, Z_NO_FLUSH);
      input_.remove_prefix(fed - z_.avail_in);
      end_ = chunk_bytes - z_.avail_out;
      inflated_ += end_;
      if (inflated_ > limit_)
        fail(file_, "inflates to more than " + std::to_string(max_expansion) +
                        " times its size, which no mesh does (a gzip bomb?) (byte offset " +
                        std::to_string(inflated_) + " after decompression)");
      if (status == Z_STREAM_END) {
        if (input_.empty()) {
          ended_ = true;
        } else if (starts_with_gzip_magic(input_)) {
          inflateReset(&z_);  // the next gzip member continues the stream
        } else {
          fail(file_, std::to_string(input_.size()) +
                          " unexpected bytes after the gzip stream (byte offset " +
                          std::to_string(file_.bytes.size() - input_.size()) + ")");
        }
      } else if (status == Z_BUF_ERROR) {
        cut_short_ = true;  // no progress possible: the file ends inside the stream
      } else if (status != Z_OK) {
        fail(file_, std::string("corrupt gzip data: ") + (z_.msg ? z_.msg : "inflate failed") +
                        " (byte offset " + std::to_string(file_.bytes.size() - input_.size()) +
                        ")");
      }
    }
    return true;
  }

  const SourceFile& file_;
  std::string_view input_;  // compressed bytes inflate has not consumed yet
  std::uint64_t limit_;
  z_stream z_{};
  std::unique_ptr<char[]> buffer_;
  std::size_t begin_ = 0, end_ = 0;  // undelivered bytes of the buffer
  std::uint64_t offset_ = 0;         // bytes delivered
  std::uint64_t inflated_ = 0;       // bytes inflated
  bool ended_ = false, cut_short_ = false;
};

class BobjParser {
 public:
  explicit BobjParser(const SourceFile& file) : file_(file), stream_(file) {}

  InputMesh parse() {
    InputMesh result;
    TriangleMesh& mesh = result.mesh;

    const std::uint32_t vertices = read_count("vertex");
    mesh.positions.reserve(reservable(vertices));
    for (std::uint32_t v = 0; v < vertices; ++v) {
      const char* xyz = read_record("vertex", v, vertices);
      const Vec3 position(little_endian<float>(xyz), little_endian<float>(xyz + 4),
                          little_endian<float>(xyz + 8));
      if (!position.allFinite())
        fail(file_, "coordinate is NaN or infinite (vertex " + std::to_string(v) + ")");
      mesh.positions.push_back(position);
    }

    const std::uint32_t normals = read_count("normal");
    for (std::uint32_t n = 0; n < normals; ++n) read_record("normal", n, normals);

    const std::uint32_t triangles = read_count("triangle");
    mesh.triangles.reserve(reservable(triangles));
    for (std::uint32_t t = 0; t < triangles; ++t) {
      const std::uint64_t record_offset = stream_.offset();
      const char* corners = read_record("triangle", t, triangles);
      Triangle triangle;
      for (int c = 0; c < 3; ++c) {
        triangle[c] = little_endian<std::int32_t>(corners + 4 * c);
        if (triangle[c] < 0 || static_cast<std::uint32_t>(triangle[c]) >= vertices)
          fail(file_, "triangle " + std::to_string(t) + " refers to vertex " +
                          std::to_string(triangle[c]) + ", but there are " +
                          std::to_string(vertices) + " vertices (byte offset " +
                          std::to_string(record_offset + 4 * c) + " after decompression)");
      }
      mesh.triangles.push_back(triangle);
    }
    result.polygon_count = triangles;

    stream_.skip_rest();
    if (stream_.cut_short())
      fail(file_,
           "truncated: the file ends inside the gzip stream, after the triangles (byte "
           "offset " +
               std::to_string(file_.bytes.size()) + ")");
    return result;
  }

 private:
  [[noreturn]] void fail_truncated(const std::string& where) {
    fail(file_,
         std::string("truncated: ") +
             (stream_.cut_short() ? "the file ends inside the gzip stream" : "the data ends") +
             " " + where + " (byte offset " + std::to_string(stream_.offset()) +
             " after decompression)");
  }

  std::uint32_t read_count(const std::string& what) {
    const std::uint64_t count_offset = stream_.offset();
    char raw[4];
    if (!stream_.read(raw, sizeof raw)) fail_truncated("before the " + what + " count");
    const std::int32_t count = little_endian<std::int32_t>(raw);
    if (count < 0)
      fail(file_, "negative " + what + " count " + std::to_string(count) + " (byte offset " +
                      std::to_string(count_offset) + " after decompression)");
    return static_cast<std::uint32_t>(count);
  }

  const char* read_record(const std::string& what, std::uint32_t index, std::uint32_t count) {
    if (!stream_.read(record_.data(), record_bytes))
      fail_truncated("in " + what + " " + std::to_string(index) + " of " + std::to_string(count));
    return record_.data();
  }

  // Room to reserve for `count` records: no more than the stream may still inflate to.
  std::size_t reservable(std::uint32_t count) const {
    return capped_reserve(count, stream_.limit() - std::min(stream_.limit(), stream_.offset()),
                          record_bytes);
  }

  const SourceFile& file_;
  GzipStream stream_;
  std::array<char, record_bytes> record_{};
};

}  // namespace

InputMesh read_bobj(const SourceFile& file) { return BobjParser(file).parse(); }

}  // namespace toonwater::readers
