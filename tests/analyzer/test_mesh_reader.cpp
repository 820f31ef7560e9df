// Mesh readers: every format and variant reads to the expected positions and triangles, and every
// kind of bad input throws one line naming the file and the line (text) or record (binary).
#include "analyzer/mesh_reader.hpp"

#include "tests/support/largest_allocation.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <new>
#include <string>
#include <vector>

namespace toonwater {
namespace {

namespace fs = std::filesystem;
using test::largest_allocation;
using test::reset_largest_allocation;
using test::ScratchDir;
using test::write_text;

std::vector<Vec3> positions(std::initializer_list<std::array<double, 3>> xyz) {
  std::vector<Vec3> result;
  for (const auto& p : xyz) result.emplace_back(p[0], p[1], p[2]);
  return result;
}

// Bytes of a binary file in either byte order.
class Bytes {
 public:
  explicit Bytes(bool big_endian = false) : big_endian_(big_endian) {}
  template <class T>
  Bytes& put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (big_endian_ != (std::endian::native == std::endian::big))
      std::reverse(raw, raw + sizeof(T));
    data_.append(raw, sizeof(T));
    return *this;
  }
  Bytes& text(const std::string& s) {
    data_ += s;
    return *this;
  }
  const std::string& data() const { return data_; }

 private:
  bool big_endian_;
  std::string data_;
};

class MeshReader : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& contents) {
    const fs::path path = dir_ / name;
    write_text(path, contents);
    return path;
  }

  // The error read_mesh reports for `path`; fails the test if there is none.
  static std::string error_of(const fs::path& path) {
    try {
      read_mesh(path);
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      return message;
    }
    ADD_FAILURE() << "no error for " << path;
    return {};
  }

  // Checks that reading `contents` as `name` fails at `line` with a message containing `fragment`.
  void expect_line_error(const std::string& name, const std::string& contents, int line,
                         const std::string& fragment) {
    const fs::path path = write(name, contents);
    const std::string message = error_of(path);
    const std::string prefix = path.string() + ":" + std::to_string(line) + ": ";
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << "expected prefix " << prefix << "\n got " << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }

  // Checks that reading `contents` as `name` fails naming the file and containing each fragment.
  void expect_error(const std::string& name, const std::string& contents,
                    std::initializer_list<std::string> fragments) {
    const fs::path path = write(name, contents);
    const std::string message = error_of(path);
    EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
    for (const std::string& fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos) << fragment << " not in " << message;
  }

  ScratchDir dir_;
};

// ---- OBJ --------------------------------------------------------------------------------------

TEST_F(MeshReader, ObjQuadsAreFanTriangulatedInFileOrder) {
  const InputMesh input = read_mesh(write("quad.obj",
                                          "# a quad and a pentagon\n"
                                          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\n"
                                          "f 1 2 3 4\n"
                                          "f 1 4 5 3 2\n"));
  EXPECT_EQ(input.polygon_count, 2u);
  const std::vector<Triangle> expected{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 2}, {0, 2, 1}};
  EXPECT_EQ(input.mesh.triangles, expected);
  EXPECT_EQ(input.mesh.positions,
            positions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 0.5, 0}}));
}

TEST_F(MeshReader, ObjCornerFormsNegativeIndicesAndIgnoredStatements) {
  const InputMesh input = read_mesh(write("forms.obj",
                                          "mtllib scene.mtl\r\n"
                                          "o water\r\n"
                                          "v 0.1 0.2 0.30000000000000004 1.0\r\n"
                                          "v +1.2345678901234567 -2e-3 1E2 0.5 0.5 0.5\r\n"
                                          "v 7 8 9  # trailing comment\r\n"
                                          "vt 0 0\r\nvn 0 0 1\r\nvp 0.5\r\n"
                                          "g group\r\ns 1\r\nusemtl water\r\n"
                                          "f 1/1 2/1/1 3//1\r\n"
                                          "f -3 -2 -1\r\n"
                                          "l 1 2\r\np 3\r\n"
                                          "f 3 1 1\r\n"));  // repeated corner kept
  EXPECT_EQ(
      input.mesh.positions,
      positions({{0.1, 0.2, 0.30000000000000004}, {1.2345678901234567, -2e-3, 100}, {7, 8, 9}}));
  const std::vector<Triangle> expected{{0, 1, 2}, {0, 1, 2}, {2, 0, 0}};
  EXPECT_EQ(input.mesh.triangles, expected);
  EXPECT_EQ(input.polygon_count, 3u);
}

TEST_F(MeshReader, ObjFacesMayReferToLaterVertices) {
  const InputMesh input = read_mesh(write("forward.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"));
  EXPECT_EQ(input.mesh.triangles, std::vector<Triangle>({{0, 1, 2}}));
}

TEST_F(MeshReader, ByteOrderMarkIsSkipped) {
  const InputMesh input =
      read_mesh(write("bom.obj", "\xEF\xBB\xBFv 5 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_EQ(input.mesh.positions.size(), 3u);
  EXPECT_EQ(input.mesh.positions[0], Vec3(5, 0, 0));
}

TEST_F(MeshReader, ExtensionIsCaseInsensitive) {
  const InputMesh input = read_mesh(write("upper.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_EQ(input.mesh.triangles.size(), 1u);
}

const std::string triangle_obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST_F(MeshReader, ObjErrorsNameFileAndLine) {
  expect_line_error("a.obj", triangle_obj + "v 1 2x 3\n", 4, "malformed number '2x'");
  expect_line_error("b.obj", "# two\nv 1 2\n", 2, "vertex has 2 coordinates, expected 3");
  expect_line_error("c.obj", triangle_obj + "f 1 2\n", 4, "face has 2 corners");
  expect_line_error("d.obj", triangle_obj + "f 1 2 3\nf 1 2 4\nf 1 2 3\n", 5,
                    "face index 4 out of range");
  expect_line_error("e.obj", triangle_obj + "f -1 -2 -4\n", 4, "face index -4 out of range");
  expect_line_error("f.obj", triangle_obj + "f 0 1 2\n", 4, "face index 0 is invalid");
  expect_line_error("g.obj", "v 0 0 0\nv nan 0 0\n", 2, "NaN or infinite");
  expect_line_error("h.obj", "v 0 0 0\nv 1 -inf 0\n", 2, "NaN or infinite");
  expect_line_error("i.obj", "v 0 0 0\nv 1 1e999 0\n", 2, "NaN or infinite");
  expect_line_error("j.obj", triangle_obj + "f 1/x 2 3\n", 4, "malformed face corner '1/x'");
  expect_line_error("k.obj", triangle_obj + "f 1 2 \\\n 3\n", 4, "line continuation");
  expect_line_error("l.obj", triangle_obj + "f 1 2 3.5\n", 4, "malformed face index '3.5'");
}

// A statement the reader does not know would lose its faces in silence: "F" and "f2" are
// typing errors, NUL bytes what a crash leaves at the end of a file cut short.
TEST_F(MeshReader, ObjUnknownStatementsAndNulBytesAreErrors) {
  const std::string faces = "f 1 2 3\n";
  expect_line_error("upper.obj", triangle_obj + faces + "F 2 3 1\n", 5,
                    "unknown OBJ statement 'F'");
  expect_line_error("glued.obj", triangle_obj + "f2 3 1\n" + faces, 4,
                    "unknown OBJ statement 'f2'");
  expect_line_error("nul.obj", triangle_obj + faces + std::string(6, '\0') + "\n", 5,
                    "unknown OBJ statement '" + std::string(6, '?') + "'");
  expect_line_error("nul_end.obj", triangle_obj + faces + std::string(3, '\0'), 5,
                    "unknown OBJ statement '" + std::string(3, '?') + "'");
  expect_line_error("nul_prefix.obj", triangle_obj + std::string(2, '\0') + "f 1 2 3\n", 4,
                    "unknown OBJ statement");
  expect_line_error("call.obj", "call other.obj\n" + triangle_obj + faces, 1,
                    "unknown OBJ statement 'call'");
}

// The other text readers already refuse what they do not know; NUL bytes included.
TEST_F(MeshReader, TextFormatsRejectNulBytes) {
  const std::string nul(4, '\0');
  expect_line_error("nul.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n" + nul, 7,
                    "unexpected data after the last");
  expect_line_error("nul_vertex.off", "OFF\n3 1 0\n0 0 0\n" + nul + "\n1 0 0\n0 1 0\n3 0 1 2\n", 4,
                    "malformed number");
  const std::string ply_header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  expect_line_error("nul.ply", ply_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n" + nul, 14,
                    "unexpected data after the last element");
  const std::string stl =
      "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\nendsolid s\n";
  expect_line_error("nul.stl", stl + nul + "\n", 10,
                    "unexpected '" + std::string(4, '?') + "' in ASCII STL");
}

TEST_F(MeshReader, EmptyMeshesAreRejected) {
  expect_error("empty.obj", "", {"contains no faces"});
  expect_error("points.obj", triangle_obj, {"contains no faces"});
  expect_error("empty.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", {"contains no faces"});
  expect_error("empty.stl", "", {"contains no faces"});
}

TEST_F(MeshReader, MissingFileAndUnknownFormat) {
  const std::string missing = error_of(dir_ / "absent.obj");
  EXPECT_EQ(missing, (dir_ / "absent.obj").string() + ": cannot open: No such file or directory");
  expect_error("mesh.xyz", triangle_obj + "f 1 2 3\n", {"unknown mesh format '.xyz'"});
  fs::create_directory(dir_ / "folder.obj");
  EXPECT_NE(error_of(dir_ / "folder.obj").find("not a regular file"), std::string::npos);
}

TEST_F(MeshReader, FullDoublePrecisionIsKept) {
  // 1 + 2^-40 is not representable in float; OpenMesh's float parsing would round it away.
  const InputMesh input =
      read_mesh(write("precise.obj", "v 1.0000000000009095 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_EQ(input.mesh.positions[0].x(), 1.0 + std::ldexp(1.0, -40));
}

// ---- OFF --------------------------------------------------------------------------------------

TEST_F(MeshReader, OffWithCommentsColoursAndPolygons) {
  const InputMesh input = read_mesh(write("square.off",
                                          "# exported by hand\n"
                                          "COFF\n"
                                          "\n"
                                          "5 2 0  # counts\n"
                                          "0 0 0 255 0 0 255\n"
                                          "1 0 0 255 0 0 255\n"
                                          "# a comment between vertices\n"
                                          "1 1 0 255 0 0 255\n"
                                          "0 1 0 255 0 0 255\n"
                                          "0.5 2 0.25 255 0 0 255\n"
                                          "4 0 1 2 3 0.5 0.5 0.5\n"
                                          "3 3 2 4\n"));
  EXPECT_EQ(input.mesh.positions,
            positions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 2, 0.25}}));
  EXPECT_EQ(input.mesh.triangles, std::vector<Triangle>({{0, 1, 2}, {0, 2, 3}, {3, 2, 4}}));
  EXPECT_EQ(input.polygon_count, 2u);
}

TEST_F(MeshReader, OffHeaderVariants) {
  for (const std::string header : {"OFF 3 1 0\n", "OFF\n3 1\n", "3 1 3\n", "NOFF\n3 1 0\n"}) {
    const std::string normals = header.starts_with("NOFF") ? " 0 0 1" : "";
    const std::string text =
        header + "0 0 0" + normals + "\n1 0 0" + normals + "\n0 1 0" + normals + "\n3 0 1 2\n";
    const InputMesh input = read_mesh(write("variant.off", text));
    EXPECT_EQ(input.mesh.positions.size(), 3u) << header;
    EXPECT_EQ(input.mesh.triangles, std::vector<Triangle>({{0, 1, 2}})) << header;
  }
}

TEST_F(MeshReader, OffErrorsNameFileAndLine) {
  expect_line_error("a.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n", 5,
                    "file ends after 3 of 4 vertices");
  expect_line_error("b.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 6,
                    "file ends after 1 of 2 faces");
  expect_line_error("c.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", 6,
                    "face index 3 out of range (the file has 3 vertices)");
  expect_line_error("d.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 6, "face has 2 corners");
  expect_line_error("e.off", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", 4,
                    "vertex has 2 coordinates");
  expect_line_error("f.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 NaN 0\n3 0 1 2\n", 5, "NaN or infinite");
  expect_line_error("g.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", 7,
                    "unexpected data after the last");
  expect_line_error("h.off", "OFX\n3 1 0\n", 1, "not an OFF file");
  expect_line_error("i.off", "4OFF\n3 1 0\n", 1, "not three-dimensional");
  expect_line_error("j.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", 6,
                    "face declares 4 corners but lists 3");
}

TEST_F(MeshReader, HostileOffCountsAreRefusedWithoutAllocating) {
  reset_largest_allocation();
  expect_line_error("huge.off", "OFF\n2147483647 2147483647 0\n0 0 0\n", 3,
                    "file ends after 1 of 2147483647 vertices");
  EXPECT_LT(largest_allocation(), std::size_t{1} << 20);
  expect_line_error("huger.off", "OFF\n2147483648 1 0\n0 0 0\n", 2,
                    "exceeds what a mesh can index");
}

// ---- PLY --------------------------------------------------------------------------------------

TEST_F(MeshReader, AsciiPlySkipsOtherPropertiesAndElements) {
  const InputMesh input = read_mesh(write("mesh.ply",
                                          "ply\n"
                                          "format ascii 1.0\n"
                                          "comment other properties around x y z\n"
                                          "element vertex 4\n"
                                          "property float nx\n"
                                          "property double x\n"
                                          "property double y\n"
                                          "property list uchar float texcoords\n"
                                          "property double z\n"
                                          "property uchar red\n"
                                          "element edge 1\n"
                                          "property int vertex1\n"
                                          "property int vertex2\n"
                                          "element face 2\n"
                                          "property list uchar int vertex_index\n"
                                          "property uchar flags\n"
                                          "end_header\n"
                                          "9 0 0 2 0.5 0.5 0 255\n"
                                          "9 0.1 0 0 0 255\n"
                                          "9 1 1 1 7 0 255\n"
                                          "9 0 1 0 0 255\n"
                                          "0 1\n"
                                          "4 0 1 2 3 7\n"
                                          "3 3 2 0 7\n"));
  EXPECT_EQ(input.mesh.positions, positions({{0, 0, 0}, {0.1, 0, 0}, {1, 1, 0}, {0, 1, 0}}));
  EXPECT_EQ(input.mesh.triangles, std::vector<Triangle>({{0, 1, 2}, {0, 2, 3}, {3, 2, 0}}));
  EXPECT_EQ(input.polygon_count, 2u);
}

// A binary PLY with mixed types, lists to skip in the vertex and face elements, an element
// before the faces and one after, in the given byte order.
std::string binary_ply(bool big_endian) {
  Bytes b(big_endian);
  b.text(std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
         " 1.0\n"
         "element vertex 4\n"
         "property double x\n"
         "property float y\n"
         "property short z\n"
         "property list uchar float extra\n"
         "property uchar red\n"
         "element edge 2\n"
         "property int a\n"
         "property int b\n"
         "element face 2\n"
         "property uchar flags\n"
         "property list uchar uint vertex_indices\n"
         "element note 1\n"
         "property list ushort char text\n"
         "end_header\n");
  const double xs[4] = {0.1, 1.0, 1.0, -2.5};
  const float ys[4] = {0.0f, 0.25f, 1.0f, 1.0f};
  const std::int16_t zs[4] = {0, -3, 7, 300};
  for (int v = 0; v < 4; ++v) {
    b.put(xs[v]).put(ys[v]).put(zs[v]);
    b.put(std::uint8_t{2}).put(1.5f).put(2.5f);  // extra
    b.put(std::uint8_t{200});                    // red
  }
  b.put(std::int32_t{0}).put(std::int32_t{1}).put(std::int32_t{1}).put(std::int32_t{2});
  b.put(std::uint8_t{1}).put(std::uint8_t{3});
  b.put(std::uint32_t{0}).put(std::uint32_t{1}).put(std::uint32_t{2});
  b.put(std::uint8_t{0}).put(std::uint8_t{4});
  for (std::uint32_t i : {3u, 2u, 1u, 0u}) b.put(i);
  b.put(std::uint16_t{3}).text("hi!");
  return b.data();
}

TEST_F(MeshReader, BinaryPlyBothByteOrders) {
  for (const bool big_endian : {false, true}) {
    const InputMesh input = read_mesh(write("binary.ply", binary_ply(big_endian)));
    EXPECT_EQ(input.mesh.positions,
              positions({{0.1, 0, 0}, {1, 0.25, -3}, {1, 1, 7}, {-2.5, 1, 300}}))
        << "big endian " << big_endian;
    EXPECT_EQ(input.mesh.triangles, std::vector<Triangle>({{0, 1, 2}, {3, 2, 1}, {3, 1, 0}}));
    EXPECT_EQ(input.polygon_count, 2u);
  }
}

const std::string triangle_ply_header =
    "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
    "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
    "end_header\n";

std::string triangle_ply(float bad_y, std::int32_t last_index, std::uint8_t corners = 3) {
  Bytes b;
  b.text(triangle_ply_header);
  b.put(0.0f).put(0.0f).put(0.0f).put(1.0f).put(bad_y).put(0.0f).put(0.0f).put(1.0f).put(0.0f);
  b.put(corners).put(std::int32_t{0}).put(std::int32_t{1});
  if (corners > 2) b.put(last_index);
  return b.data();
}

// Vertex records of scalars only and face records with scalars on both sides of the index
// list: the layout most writers use, read without a type switch per value.
TEST_F(MeshReader, BinaryPlyScalarRecordsAroundTheLists) {
  for (const bool big_endian : {false, true}) {
    Bytes b(big_endian);
    b.text(std::string("ply\nformat ") +
           (big_endian ? "binary_big_endian" : "binary_little_endian") +
           " 1.0\nelement vertex 4\nproperty uchar red\nproperty float z\nproperty double x\n"
           "property short y\nelement face 2\nproperty short flags\n"
           "property list int ushort vertex_index\nproperty double quality\nend_header\n");
    const float zs[4] = {0.5f, -1.0f, 2.0f, 0.0f};
    const double xs[4] = {0.1, 1.0, 1.0, -2.5};
    const std::int16_t ys[4] = {0, -3, 7, 300};
    for (int v = 0; v < 4; ++v) b.put(std::uint8_t{9}).put(zs[v]).put(xs[v]).put(ys[v]);
    b.put(std::int16_t{-1}).put(std::int32_t{3});
    for (int i : {0, 1, 2}) b.put(static_cast<std::uint16_t>(i));
    b.put(0.5);
    b.put(std::int16_t{7}).put(std::int32_t{4});
    for (int i : {3, 2, 1, 0}) b.put(static_cast<std::uint16_t>(i));
    b.put(-0.5);
    const InputMesh input = read_mesh(write("scalar.ply", b.data()));
    EXPECT_EQ(input.mesh.positions,
              positions({{0.1, 0, 0.5}, {1, -3, -1}, {1, 7, 2}, {-2.5, 300, 0}}))
        << "big endian " << big_endian;
    EXPECT_EQ(input.mesh.triangles, std::vector<Triangle>({{0, 1, 2}, {3, 2, 1}, {3, 1, 0}}));
    EXPECT_EQ(input.polygon_count, 2u);
    const std::string whole = b.data();
    expect_error("cut_after.ply", whole.substr(0, whole.size() - 3), {"truncated", "face 1 of 2"});
  }
}

// A bad coordinate before the point where a file is cut is reported as the first error, as a
// reader going record by record would.
TEST_F(MeshReader, BinaryPlyBadCoordinateBeforeTheCutComesFirst) {
  const std::string whole = triangle_ply(std::nanf(""), 2);
  expect_error("nan_cut.ply", whole.substr(0, triangle_ply_header.size() + 32),
               {"NaN or infinite", "(vertex 1)"});
}

TEST_F(MeshReader, BinaryPlyErrorsNameTheRecord) {
  EXPECT_EQ(read_mesh(write("good.ply", triangle_ply(0.0f, 2))).mesh.triangles.size(), 1u);
  expect_error("nan.ply", triangle_ply(std::nanf(""), 2), {"NaN or infinite", "(vertex 1)"});
  expect_error("inf.ply", triangle_ply(INFINITY, 2), {"NaN or infinite", "(vertex 1)"});
  expect_error("index.ply", triangle_ply(0.0f, 3),
               {"face index 3 out of range (the file has 3 vertices)", "(face 0)"});
  expect_error("corners.ply", triangle_ply(0.0f, 2, 2), {"face has 2 corners", "(face 0)"});
  const std::string whole = triangle_ply(0.0f, 2);
  const std::string cut = whole.substr(0, triangle_ply_header.size() + 20);
  expect_error("cut.ply", cut,
               {"truncated", "vertex 1 of 3", "(byte offset " + std::to_string(cut.size()) + ")"});
  expect_error("cut_face.ply", whole.substr(0, whole.size() - 2), {"truncated", "face 0 of 1"});
  expect_error("long.ply", whole + "xy", {"2 unexpected bytes after the last element"});
}

// A grid of side x side vertices as a binary PLY, large enough to be read in several chunks;
// `last_face` is written as the final record (three corners or more).
std::string grid_ply(int side, std::vector<std::int32_t> last_face, float bad_x_at = -1,
                     int bad_vertex = -1) {
  const int faces = 2 * (side - 1) * (side - 1);
  Bytes b;
  b.text("ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(side * side) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
         std::to_string(faces + 1) + "\nproperty list uchar int vertex_indices\nend_header\n");
  for (int v = 0; v < side * side; ++v)
    b.put(v == bad_vertex ? bad_x_at : static_cast<float>(v % side))
        .put(static_cast<float>(v / side))
        .put(0.25f * static_cast<float>(v % 7));
  for (int i = 0; i + 1 < side; ++i)
    for (int j = 0; j + 1 < side; ++j) {
      const std::int32_t a = i * side + j;
      b.put(std::uint8_t{3}).put(a).put(a + 1).put(a + side);
      b.put(std::uint8_t{3}).put(a + 1).put(a + side + 1).put(a + side);
    }
  b.put(static_cast<std::uint8_t>(last_face.size()));
  for (const std::int32_t index : last_face) b.put(index);
  return b.data();
}

// Large files are read on every core: the same mesh, the same first error, whatever the split.
TEST_F(MeshReader, LargeBinaryPlyReadsInChunksAsRecordByRecord) {
  constexpr int side = 300;  // 90,000 vertices, 178,803 faces
  const InputMesh input = read_mesh(write("grid.ply", grid_ply(side, {0, 1, side})));
  ASSERT_EQ(input.mesh.positions.size(), std::size_t{side * side});
  for (const int v : {0, 1, side, side * side / 2 + 3, side * side - 1})
    EXPECT_EQ(input.mesh.positions[v], Vec3(v % side, v / side, 0.25 * (v % 7))) << v;
  const std::size_t faces = 2 * (side - 1) * (side - 1) + 1;
  ASSERT_EQ(input.mesh.triangles.size(), faces);
  EXPECT_EQ(input.polygon_count, faces);
  const std::int32_t last_cell = (side - 2) * side + side - 2;
  EXPECT_EQ(input.mesh.triangles[faces - 2],
            (Triangle{last_cell + 1, last_cell + side + 1, last_cell + side}));
  EXPECT_EQ(input.mesh.triangles.back(), (Triangle{0, 1, side}));

  // A quad as the last record: the faces are read record by record, the quad as two triangles.
  const InputMesh quad = read_mesh(write("quad.ply", grid_ply(side, {0, 1, side + 1, side})));
  EXPECT_EQ(quad.mesh.triangles.size(), faces + 1);
  EXPECT_EQ(quad.polygon_count, faces);
  EXPECT_EQ(std::vector<Triangle>(quad.mesh.triangles.begin(), quad.mesh.triangles.end() - 2),
            std::vector<Triangle>(input.mesh.triangles.begin(), input.mesh.triangles.end() - 1));

  expect_error("index.ply", grid_ply(side, {0, 1, side * side}),
               {"face index 90000 out of range", "(face " + std::to_string(faces - 1) + ")"});
  expect_error("nan.ply", grid_ply(side, {0, 1, side}, std::nanf(""), side * side - 5),
               {"NaN or infinite", "(vertex 89995)"});
}

TEST_F(MeshReader, PlyHeaderAndAsciiErrorsNameTheLine) {
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\n";
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  expect_line_error("a.ply", "plx\n", 1, "not a PLY file");
  expect_line_error("b.ply", header + "property flot x\n", 4, "unknown property type 'flot'");
  expect_line_error("c.ply", "ply\nformat ascii 1.0\nproperty float x\n", 3,
                    "property before any element");
  expect_line_error("d.ply", header + "property float x\nproperty float y\n" + faces, 3,
                    "vertex element has no property 'z'");
  expect_line_error("e.ply", header + xyz, 6, "no end_header");
  expect_line_error("f.ply", "ply\nformat binary_middle_endian 1.0\n", 2, "unknown PLY format");
  expect_line_error(
      "g.ply",
      header + xyz + "element face 1\nproperty list uchar float vertex_indices\nend_header\n", 8,
      "integer type");
  const std::string good = header + xyz + faces;
  expect_line_error("h.ply", good + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", 13,
                    "face index 3 out of range");
  expect_line_error("i.ply", good + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", 11, "NaN or infinite");
  expect_line_error("j.ply", good + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n", 11, "too few values");
  expect_line_error("k.ply", good + "0 0 0\n1 0 0\n", 11,
                    "file ends after 2 of 3 'vertex' records");
  expect_line_error("l.ply", good + "0 0 0\n1 0 0\n0 1 0\n", 12,
                    "file ends after 0 of 1 'face' records");
  expect_line_error("m.ply", good + "0 0 0\n1 0 0 0\n0 1 0\n3 0 1 2\n", 11, "too many values");
  expect_line_error("n.ply", good + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 13, "face has 2 corners");
}

TEST_F(MeshReader, HostilePlyCountsAreRefusedWithoutAllocating) {
  reset_largest_allocation();
  std::string text = triangle_ply_header;
  text.replace(text.find("vertex 3"), 8, "vertex 2000000000");
  text.replace(text.find("face 1"), 6, "face 2000000000");
  expect_error("huge.ply", text + std::string(64, '\0'), {"truncated", "vertex 5 of 2000000000"});
  EXPECT_LT(largest_allocation(), std::size_t{1} << 20);
  // A face claiming 255 corners in a file that holds two indices.
  std::string face = triangle_ply(0.0f, 2);
  face[face.size() - 13] = static_cast<char>(255);
  expect_error("corners.ply", face, {"truncated", "face 0 of 1"});
  EXPECT_LT(largest_allocation(), std::size_t{1} << 20);
}

// ---- STL --------------------------------------------------------------------------------------

TEST_F(MeshReader, AsciiStlIsATriangleSoup) {
  const InputMesh input = read_mesh(write("soup.stl",
                                          "solid two\n"
                                          "  facet normal 0 0 1\n"
                                          "    outer loop\n"
                                          "      vertex 0 0 0\n"
                                          "      vertex 1 0 0\n"
                                          "      vertex 0 1 0\n"
                                          "    endloop\n"
                                          "  endfacet\n"
                                          "  facet normal nan nan nan\n"
                                          "    outer loop\n"
                                          "      vertex 1 0 0\n"
                                          "      vertex 1 1 0\n"
                                          "      vertex 0 1 0.5e-1\n"
                                          "    endloop\n"
                                          "  endfacet\n"
                                          "endsolid two\n"));
  EXPECT_EQ(input.mesh.positions,
            positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.05}}));
  EXPECT_EQ(input.mesh.triangles, std::vector<Triangle>({{0, 1, 2}, {3, 4, 5}}));
  EXPECT_EQ(input.polygon_count, 2u);
}

std::string binary_stl(const std::vector<std::array<float, 9>>& facets, std::string header) {
  header.resize(80, ' ');
  Bytes b;
  b.text(header).put(static_cast<std::uint32_t>(facets.size()));
  for (const auto& corners : facets) {
    b.put(0.0f).put(0.0f).put(1.0f);
    for (float c : corners) b.put(c);
    b.put(std::uint16_t{0});
  }
  return b.data();
}

TEST_F(MeshReader, BinaryStlEvenWhenItStartsWithSolid) {
  const std::vector<std::array<float, 9>> facets{{0, 0, 0, 1, 0, 0, 0, 1, 0},
                                                 {1, 0, 0, 1, 1, 0, 0.5f, 1, 0.25f}};
  const InputMesh input = read_mesh(write("binary.stl", binary_stl(facets, "solid exported")));
  EXPECT_EQ(input.mesh.positions,
            positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {0.5, 1, 0.25}}));
  EXPECT_EQ(input.mesh.triangles, std::vector<Triangle>({{0, 1, 2}, {3, 4, 5}}));
  EXPECT_EQ(input.polygon_count, 2u);
}

TEST_F(MeshReader, StlErrors) {
  const std::vector<std::array<float, 9>> facets{{0, 0, 0, 1, 0, 0, 0, 1, 0},
                                                 {1, 0, 0, 1, std::nanf(""), 0, 0, 1, 0}};
  expect_error("nan.stl", binary_stl(facets, "binary"), {"NaN or infinite", "(facet 1)"});
  const std::string whole = binary_stl(facets, "solid but binary");
  expect_error(
      "cut.stl", whole.substr(0, whole.size() - 7),
      {"truncated", "promises 2 facets", "byte offset " + std::to_string(whole.size() - 7)});
  expect_error("short.stl", "abc", {"truncated"});
  const std::string facet_start = "solid s\nfacet normal 0 0 1\nouter loop\n";
  expect_line_error("a.stl", facet_start + "vertex 0 0 0\nvertex 1 0 0\nvertex 0 inf 0\n", 6,
                    "NaN or infinite");
  expect_line_error("b.stl", facet_start + "vertex 0 0 0\nvertex 1 0 0\nendloop\n", 6,
                    "facet has 2 vertices");
  expect_line_error("c.stl", facet_start + "vertex 0 0 0\nvertex 1 0 0\n", 5,
                    "ends inside a facet");
  expect_line_error("d.stl", facet_start + "vertex 0 0\n", 4, "vertex has 2 coordinates");
  expect_line_error("e.stl", "solid s\nvertex 0 0 0\n", 2, "unexpected 'vertex'");
  // Cut between two facets: each facet read is whole, only endsolid is missing.
  expect_line_error("f.stl",
                    facet_start + "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n",
                    8, "ends before endsolid");
}

// ---- Legacy VTK -------------------------------------------------------------------------------

// A unit square of two triangles and a quad beside it, as POLYDATA in ASCII.
const std::string square_vtk =
    "# vtk DataFile Version 3.0\n"
    "two triangles and a quad\n"
    "ASCII\n"
    "DATASET POLYDATA\n"
    "POINTS 6 double\n"
    "0 0 0  1 0 0  1 1 0\n"
    "0 1 0  2 0 0.5\n"
    "2 1 0.25\n"
    "POLYGONS 3 13\n"
    "3 0 1 2\n"
    "3 0 2 3\n"
    "4 1 4 5 2\n"
    "POINT_DATA 6\n"
    "SCALARS pressure float 1\n"
    "LOOKUP_TABLE default\n"
    "0 1 2 3 4 5\n";

const std::vector<Vec3> square_positions =
    positions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0.5}, {2, 1, 0.25}});
const std::vector<Triangle> square_triangles{{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 2}};

// The same surface as splashsurf writes it through vtkio: version 4.2, BINARY, big-endian
// float points, an UNSTRUCTURED_GRID whose cells are int32 lists and int32 types (5 triangle,
// 9 quad), then a point attribute. `cut` leaves the file at that many bytes.
std::string square_vtk_binary(std::int32_t quad_type = 9, float nan_at = 0) {
  Bytes b(/*big_endian=*/true);
  b.text("# vtk DataFile Version 4.2\nmesh\nBINARY\n\nDATASET UNSTRUCTURED_GRID\nPOINTS 6 float\n");
  for (const Vec3& p : square_positions)
    for (int axis = 0; axis < 3; ++axis) b.put(static_cast<float>(p[axis]) + nan_at);
  b.text("\n\nCELLS 3 13\n");
  for (const std::int32_t v : {3, 0, 1, 2, 3, 0, 2, 3, 4, 1, 4, 5, 2}) b.put(v);
  b.text("\n\nCELL_TYPES 3\n");
  for (const std::int32_t t : {5, 5, quad_type}) b.put(t);
  b.text("\n\nPOINT_DATA 6\nSCALARS id int 1\nLOOKUP_TABLE default\n");
  for (std::int32_t v = 0; v < 6; ++v) b.put(v);
  b.text("\n");
  return b.data();
}

void expect_square(const InputMesh& input) {
  EXPECT_EQ(input.mesh.positions, square_positions);
  EXPECT_EQ(input.mesh.triangles, square_triangles);
  EXPECT_EQ(input.polygon_count, 3u);
}

TEST_F(MeshReader, VtkAsciiPolydataAndBinaryGridAsSplashsurfWritesIt) {
  expect_square(read_mesh(write("square.vtk", square_vtk)));
  expect_square(read_mesh(write("fluid_surface.VTK", square_vtk_binary())));
  // The same cells as CELLS and CELL_TYPES of a grid, in ASCII.
  std::string grid = square_vtk;
  grid.replace(grid.find("POLYDATA"), 8, "UNSTRUCTURED_GRID");
  grid.replace(grid.find("POLYGONS"), 8, "CELLS");
  grid.insert(grid.find("POINT_DATA"), "CELL_TYPES 3\n5\n5\n9\n");
  expect_square(read_mesh(write("grid.vtk", grid)));
}

TEST_F(MeshReader, VtkVersion5OffsetsAndConnectivity) {
  const std::string ascii =
      "# vtk DataFile Version 5.1\nvtk output\nASCII\nDATASET UNSTRUCTURED_GRID\n"
      "POINTS 6 float\n0 0 0 1 0 0 1 1 0 0 1 0 2 0 0.5 2 1 0.25\n"
      "CELLS 4 10\nOFFSETS vtktypeint64\n0 3 6 10\nCONNECTIVITY vtktypeint64\n"
      "0 1 2 0 2 3 1 4 5 2\nCELL_TYPES 3\n5\n5\n9\n";
  expect_square(read_mesh(write("v5.vtk", ascii)));

  Bytes b(true);
  b.text(
      "# vtk DataFile Version 5.1\nvtk output\nBINARY\nDATASET UNSTRUCTURED_GRID\n"
      "POINTS 6 double\n");
  for (const Vec3& p : square_positions)
    for (int axis = 0; axis < 3; ++axis) b.put(p[axis]);
  b.text("\nCELLS 4 10\nOFFSETS vtktypeint64\n");
  for (const std::int64_t o : {0, 3, 6, 10}) b.put(o);
  b.text("\nCONNECTIVITY vtktypeint32\n");
  for (const std::int32_t v : {0, 1, 2, 0, 2, 3, 1, 4, 5, 2}) b.put(v);
  b.text("\nMETADATA\nINFORMATION 0\n\nCELL_TYPES 3\n");
  for (const std::int32_t t : {5, 5, 9}) b.put(t);
  b.text("\n");
  expect_square(read_mesh(write("v5.vtk", b.data())));
}

TEST_F(MeshReader, VtkTriangleStripsKeepOneWinding) {
  // A strip along a row of a flat grid: every triangle must face -z, as the first does.
  const InputMesh strip =
      read_mesh(write("strip.vtk",
                      "# vtk DataFile Version 2.0\nstrip\nASCII\nDATASET POLYDATA\nPOINTS 6 float\n"
                      "0 0 0 0 1 0 1 0 0 1 1 0 2 0 0 2 1 0\nTRIANGLE_STRIPS 1 7\n6 0 1 2 3 4 5\n"));
  ASSERT_EQ(strip.mesh.triangles.size(), 4u);
  for (const Triangle& t : strip.mesh.triangles) {
    const Vec3& a = strip.mesh.positions[t[0]];
    const Vec3 normal = (strip.mesh.positions[t[1]] - a).cross(strip.mesh.positions[t[2]] - a);
    EXPECT_LT(normal.z(), 0.0) << t[0] << " " << t[1] << " " << t[2];
  }
}

TEST_F(MeshReader, VtkEveryTruncationOfTheGeometryIsAnError) {
  const std::string whole = square_vtk_binary();
  const std::size_t geometry_end = whole.find("\n\nPOINT_DATA");  // after the cell types
  for (std::size_t size = 0; size < geometry_end; ++size) {
    const fs::path path = write("cut.vtk", whole.substr(0, size));
    try {
      read_mesh(path);
      ADD_FAILURE() << "no error for a cut at byte " << size << " of " << geometry_end;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path.string() + ":", 0), 0u) << e.what();
    }
  }
}

TEST_F(MeshReader, VtkErrorsNameTheFileAndWhere) {
  expect_error("tetra.vtk", square_vtk_binary(10),
               {"cell 2 is of VTK cell type 10, not a surface face"});
  expect_error("nan.vtk", square_vtk_binary(9, std::numeric_limits<float>::quiet_NaN()),
               {"coordinate is NaN or infinite (point 0) (byte offset 81)"});
  std::string bad_index = square_vtk;
  bad_index.replace(bad_index.find("4 1 4 5 2"), 9, "4 1 4 6 2");
  expect_line_error("index.vtk", bad_index, 12, "cell 2 refers to point 6, but there are 6");
  std::string lines = square_vtk;
  lines.replace(lines.find("POLYGONS 3 13"), 13, "LINES 3 13");
  expect_line_error("lines.vtk", lines, 9, "LINES cells are not a surface");
  expect_line_error("image.vtk",
                    "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n", 4,
                    "dataset 'STRUCTURED_POINTS' is not a surface");
  expect_line_error("xml.vtk", "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\">\n", 1,
                    "not a legacy VTK file");
  std::string short_list = square_vtk;
  short_list.replace(short_list.find("POLYGONS 3 13"), 13, "POLYGONS 3 12");
  expect_line_error("short.vtk", short_list, 12, "does not hold its 3 cells");
  std::string ints = square_vtk;
  ints.replace(ints.find("POINTS 6 double"), 15, "POINTS 6 int");
  expect_line_error("ints.vtk", ints, 5, "values of type 'int' are not read here");
}

TEST_F(MeshReader, VtkHostileCountsAllocateNothingLarge) {
  Bytes b(true);
  b.text("# vtk DataFile Version 4.2\nmesh\nBINARY\nDATASET POLYDATA\nPOINTS 2000000000 float\n");
  for (int i = 0; i < 9; ++i) b.put(0.0f);
  reset_largest_allocation();
  expect_error("huge.vtk", b.data(), {"truncated: 6000000000 point values need"});
  const std::string ascii =
      "# vtk DataFile Version 4.2\nmesh\nASCII\nDATASET POLYDATA\n"
      "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1000000000 4000000000\n"
      "3 0 1 2\n";
  expect_line_error("huge_cells.vtk", ascii, 8, "truncated: the file ends in cell value 4");
  EXPECT_LT(largest_allocation(), std::size_t{1} << 20);
}

}  // namespace
}  // namespace toonwater
