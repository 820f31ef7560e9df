// Huge and hostile mesh files: counts in headers that the data does not back (2^31 vertices,
// 2^32 facets, list counts of 2^31), faces with 10^6 corners. The reader must fail with a clear
// message or read what is there, and never allocate from an unchecked count: this executable
// records the largest single allocation (tests/support/largest_allocation.hpp), which must stay
// proportional to the file's real size.
#include "analyzer/mesh_reader.hpp"
#include "tests/support/largest_allocation.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>

namespace toonwater::test {
namespace {

struct Outcome {
  std::string error;  // empty when the file was read
  std::size_t triangles = 0;
  std::size_t largest = 0;  // bytes, the largest single allocation while reading
};

Outcome read(const ScratchDir& dir, const std::string& name, const std::string& bytes) {
  write_text(dir / name, bytes);
  reset_largest_allocation();
  Outcome out;
  try {
    out.triangles = read_mesh(dir / name).mesh.triangles.size();
  } catch (const InputError& e) {
    out.error = e.what();
  }
  out.largest = largest_allocation();
  return out;
}

// What "proportional to the real data" allows: a few times the file's size, plus a page.
std::size_t allowance(const std::string& bytes) { return 16 * bytes.size() + 4096; }

std::string le32(std::uint32_t v) {
  std::string s(4, '\0');
  for (int i = 0; i < 4; ++i) s[i] = static_cast<char>((v >> (8 * i)) & 0xff);
  return s;
}

const std::string ply_vertices =
    "element vertex %V\nproperty float x\nproperty float y\nproperty float z\n";

std::string ply_header(const std::string& format, const std::string& vertices,
                       const std::string& faces, const std::string& list = "uchar int") {
  std::string h = "ply\nformat " + format + " 1.0\n" + ply_vertices;
  h.replace(h.find("%V"), 2, vertices);
  return h + "element face " + faces + "\nproperty list " + list + " vertex_indices\nend_header\n";
}

TEST(HostileInputs, PlyHeaderClaiming2To31VerticesFailsWithoutAllocatingThem) {
  ScratchDir dir;
  for (const char* format : {"ascii", "binary_little_endian"}) {
    SCOPED_TRACE(format);
    const bool ascii = std::string(format) == "ascii";
    const std::string body =
        ascii ? "0 0 0\n1 0 0\n0 1 0\n" : std::string(36, '\0') + "\x03" + std::string(12, '\0');
    const std::string file = ply_header(format, "2147483647", "1") + body;
    const Outcome o = read(dir, "big.ply", file);
    EXPECT_NE(o.error.find("big.ply"), std::string::npos) << o.error;
    EXPECT_NE(o.error.find(ascii ? "file ends after 3 of 2147483647" : "truncated"),
              std::string::npos)
        << o.error;
    EXPECT_LT(o.largest, allowance(file));
  }
  const Outcome too_many = read(dir, "more.ply", ply_header("ascii", "2147483648", "0"));
  EXPECT_NE(
      too_many.error.find("more.ply:3: vertex count 2147483648 exceeds what a mesh can index"),
      std::string::npos)
      << too_many.error;
}

TEST(HostileInputs, PlyFaceAndListCountsBeyondTheDataFailWithoutAllocatingThem) {
  ScratchDir dir;
  const std::string vertices(36, '\0');
  // 2^63 - 1 faces, then a face whose uint list count claims 2^32 - 1 corners.
  for (const std::string& file : {ply_header("binary_little_endian", "3", "9223372036854775807") +
                                      vertices + "\x03" + std::string(12, '\0'),
                                  ply_header("binary_little_endian", "3", "1", "uint int") +
                                      vertices + le32(0xffffffffu) + std::string(12, '\0')}) {
    const Outcome o = read(dir, "faces.ply", file);
    EXPECT_NE(o.error.find("faces.ply: truncated"), std::string::npos) << o.error;
    EXPECT_LT(o.largest, allowance(file));
  }
}

// A binary body may be empty and the header may end without a newline: the reader then starts
// at the very end of the file, and a face element with a property before its list must not
// step from there. GCC's sanitizer does not check offsets from a null pointer; the fuzzer's
// clang build does, and starts from the same file (tests/fuzz/regressions/ply).
TEST(HostileInputs, BinaryPlyEndingAtItsHeaderIsReadOrRefusedCleanly) {
  ScratchDir dir;
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
      "property float y\nproperty float z\nelement face 0\nproperty uchar flags\n"
      "property list uchar int vertex_indices\nend_header";
  for (const std::string& file : {header, header + "\n"}) {
    const Outcome o = read(dir, "empty.ply", file);
    EXPECT_EQ(o.triangles, 0u);
    EXPECT_NE(o.error.find("empty.ply: contains no faces"), std::string::npos) << o.error;
  }
}

TEST(HostileInputs, OffHeaderClaiming2To31VerticesFailsWithoutAllocatingThem) {
  ScratchDir dir;
  const std::string file = "OFF\n2147483647 2147483647 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const Outcome o = read(dir, "big.off", file);
  EXPECT_NE(o.error.find("big.off:"), std::string::npos) << o.error;
  EXPECT_NE(o.error.find("of 2147483647 vertices"), std::string::npos) << o.error;
  EXPECT_LT(o.largest, allowance(file));
  const Outcome more = read(dir, "more.off", "OFF\n4294967296 1 0\n");
  EXPECT_NE(more.error.find("more.off:2: vertex count 4294967296 exceeds"), std::string::npos)
      << more.error;
}

TEST(HostileInputs, StlHeaderClaiming2To32FacetsFailsWithoutAllocatingThem) {
  ScratchDir dir;
  for (const std::uint32_t facets : {0xffffffffu, 715827883u /* 3 * facets > 2^31 - 1 */}) {
    const std::string file = std::string(80, 'x') + le32(facets) + std::string(50, '\0');
    const Outcome o = read(dir, "big.stl", file);
    EXPECT_NE(o.error.find("big.stl: truncated: the binary STL header promises " +
                           std::to_string(facets) + " facets"),
              std::string::npos)
        << o.error;
    EXPECT_LT(o.largest, allowance(file));
  }
}

TEST(HostileInputs, FaceWithAMillionCornersIsReadInMemoryProportionalToIt) {
  ScratchDir dir;
  constexpr int corners = 1000000;
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
  for (int i = 0; i < corners; ++i) (obj += ' ') += std::to_string(1 + i % 3);
  obj += "\n";
  const Outcome o = read(dir, "fan.obj", obj);
  EXPECT_EQ(o.error, "");
  EXPECT_EQ(o.triangles, static_cast<std::size_t>(corners - 2));
  EXPECT_LT(o.largest, allowance(obj));

  std::string off = "OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n" + std::to_string(corners);
  for (int i = 0; i < corners; ++i) (off += ' ') += std::to_string(i % 3);
  off += "\n";
  const Outcome fan = read(dir, "fan.off", off);
  EXPECT_EQ(fan.error, "");
  EXPECT_EQ(fan.triangles, static_cast<std::size_t>(corners - 2));
  EXPECT_LT(fan.largest, allowance(off));
  // A face that declares a million corners and lists three.
  const Outcome short_face =
      read(dir, "short.off", "OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n1000000 0 1 2\n");
  EXPECT_NE(short_face.error.find("short.off:6: face declares 1000000 corners but lists 3"),
            std::string::npos)
      << short_face.error;
}

TEST(HostileInputs, ObjIndexBeyondTheVerticesIsAnErrorNotAnAllocation) {
  ScratchDir dir;
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2147483647\n";
  const Outcome o = read(dir, "far.obj", obj);
  EXPECT_NE(o.error.find("far.obj:4: face index 2147483647 out of range (the file has 3 vertices)"),
            std::string::npos)
      << o.error;
  EXPECT_LT(o.largest, allowance(obj));
}

}  // namespace
}  // namespace toonwater::test
