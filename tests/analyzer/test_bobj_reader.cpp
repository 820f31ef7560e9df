// Mantaflow's .bobj.gz mesh cache: files written here with zlib, as Mantaflow's writeBobjFile
// writes them, read back exactly; every kind of damage (not gzip, a cut or corrupt stream, data
// shorter than its counts, bad indices, NaN) is one line naming the file and where; hostile
// counts and gzip bombs allocate nothing large; and analyze and povgen take numbered sequences.
// FLIP Fluids' uncompressed .bobj likewise, and a bake's folder of attribute files beside it.
#include "corpus/analytic_surfaces.hpp"
#include "analyzer/mesh_reader.hpp"
#include "analyzer/obj_writer.hpp"
#include "tests/support/largest_allocation.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
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
using test::read_text;
using test::reset_largest_allocation;
using test::run_toonwater;
using test::ScratchDir;
using test::write_text;

using Float3 = std::array<float, 3>;

// Little-endian bytes, as Mantaflow writes them on every platform it runs on.
class Data {
 public:
  template <class T>
  Data& put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(raw, raw + sizeof(T));
    bytes_.append(raw, sizeof(T));
    return *this;
  }
  Data& put(const Float3& v) { return put(v[0]).put(v[1]).put(v[2]); }
  Data& put(const Triangle& t) { return put(t[0]).put(t[1]).put(t[2]); }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

// The uncompressed contents of a .bobj.gz: counts, positions, normals, triangles.
std::string bobj_data(const std::vector<Float3>& positions,
                      const std::vector<Triangle>& triangles) {
  Data d;
  d.put(static_cast<std::int32_t>(positions.size()));
  for (const Float3& p : positions) d.put(p);
  d.put(static_cast<std::int32_t>(positions.size()));
  for (const Float3& p : positions) {
    const float length = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    d.put(Float3{p[0] / length, p[1] / length, p[2] / length});
  }
  d.put(static_cast<std::int32_t>(triangles.size()));
  for (const Triangle& t : triangles) d.put(t);
  return d.bytes();
}

// One gzip member holding `data`; level 1 is what Mantaflow uses ("wb1").
std::string gzip(const std::string& data, int level = 1) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, level, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&z, static_cast<uLong>(data.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

// A tetrahedron with outward triangles; its coordinates are exact in float.
const std::vector<Float3> tetra_positions{
    {0.25f, -0.125f, 0.5f}, {-0.375f, 0.0625f, 0.5f}, {0.0f, 0.3125f, 0.5f}, {0.0f, 0.0f, -0.25f}};
const std::vector<Triangle> tetra_triangles{{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};

class BobjReader : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& bytes) {
    const fs::path path = dir_ / name;
    write_text(path, bytes);
    return path;
  }

  // Checks that reading `bytes` as NAME (default broken.bobj.gz) fails with one line that starts
  // with the path and contains every fragment.
  void expect_error(const std::string& bytes, std::initializer_list<std::string> fragments,
                    const std::string& name = "broken.bobj.gz") {
    const fs::path path = write(name, bytes);
    try {
      read_mesh(path);
      ADD_FAILURE() << "no error; expected " << *fragments.begin();
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
      for (const std::string& fragment : fragments)
        EXPECT_NE(message.find(fragment), std::string::npos) << fragment << " not in " << message;
    }
  }

  ScratchDir dir_;
};

void expect_tetrahedron(const InputMesh& input) {
  ASSERT_EQ(input.mesh.positions.size(), tetra_positions.size());
  for (std::size_t v = 0; v < tetra_positions.size(); ++v)
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_EQ(input.mesh.positions[v][axis], double{tetra_positions[v][axis]}) << v;
  EXPECT_EQ(input.mesh.triangles, tetra_triangles);
  EXPECT_EQ(input.polygon_count, tetra_triangles.size());
}

TEST_F(BobjReader, TetrahedronRoundTrip) {
  expect_tetrahedron(read_mesh(
      write("fluid_mesh_0001.bobj.gz", gzip(bobj_data(tetra_positions, tetra_triangles)))));
}

TEST_F(BobjReader, IcosphereRoundTripAtEveryCompressionLevel) {
  const AnalyticSurface sphere = make_icosphere(4, 0.4);  // 2562 vertices: several inflate chunks
  std::vector<Float3> positions;
  for (const Vec3& p : sphere.mesh.positions)
    positions.push_back(
        {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
  for (const int level : {0, 1, 9}) {
    const InputMesh input = read_mesh(
        write("sphere.bobj.gz", gzip(bobj_data(positions, sphere.mesh.triangles), level)));
    ASSERT_EQ(input.mesh.positions.size(), positions.size());
    for (std::size_t v = 0; v < positions.size(); ++v)
      ASSERT_EQ(input.mesh.positions[v], Vec3(positions[v][0], positions[v][1], positions[v][2]));
    EXPECT_EQ(input.mesh.triangles, sphere.mesh.triangles) << "level " << level;
  }
}

TEST_F(BobjReader, ExtensionIsCaseInsensitiveAndNeedsBothParts) {
  const std::string file = gzip(bobj_data(tetra_positions, tetra_triangles));
  expect_tetrahedron(read_mesh(write("FLUID_MESH_0001.BOBJ.GZ", file)));
  const fs::path plain_gz = write("fluid_mesh_0001.gz", file);
  EXPECT_THROW(read_mesh(plain_gz), InputError) << "a .gz that does not say .bobj";
}

TEST_F(BobjReader, VortexSheetChunksAfterTheTrianglesAreIgnored) {
  Data extra;
  for (const std::int32_t id : {0, int{'v'}, int{'d'}, int{'e'}}) extra.put(id);
  for (std::size_t v = 0; v < tetra_positions.size(); ++v) extra.put(0.5f);
  for (const std::int32_t id : {0, int{'v'}, int{'x'}, int{'f'}}) extra.put(id);
  for (std::size_t v = 0; v < tetra_positions.size(); ++v) extra.put(1.0f);
  expect_tetrahedron(read_mesh(
      write("sheet.bobj.gz", gzip(bobj_data(tetra_positions, tetra_triangles) + extra.bytes()))));
}

TEST_F(BobjReader, ConcatenatedGzipMembersFormOneStream) {
  const std::string data = bobj_data(tetra_positions, tetra_triangles);
  const std::size_t split = 30;  // inside vertex 2
  expect_tetrahedron(
      read_mesh(write("members.bobj.gz", gzip(data.substr(0, split)) + gzip(data.substr(split)))));
}

TEST_F(BobjReader, DamagedGzipStreams) {
  const std::string good = gzip(bobj_data(tetra_positions, tetra_triangles));
  expect_error(bobj_data(tetra_positions, tetra_triangles), {"not a gzip file", "(byte offset 0)"});
  expect_error("", {"not a gzip file"});
  expect_error(good.substr(0, good.size() / 2),
               {"truncated: the file ends inside the gzip stream", "after decompression"});
  // Only the 8-byte trailer (CRC and length) is missing: the mesh is all there, but unverified.
  expect_error(good.substr(0, good.size() - 8), {"truncated", "after the triangles"});
  std::string bad_crc = good;
  bad_crc[bad_crc.size() - 8] = static_cast<char>(bad_crc[bad_crc.size() - 8] ^ 0x5a);
  expect_error(bad_crc, {"corrupt gzip data", "incorrect data check"});
  std::string bad_deflate = good;
  bad_deflate[10] = static_cast<char>(0xff);  // the first deflate block header: invalid type
  expect_error(bad_deflate, {"corrupt gzip data"});
  expect_error(good + "junk", {"4 unexpected bytes after the gzip stream",
                               "(byte offset " + std::to_string(good.size()) + ")"});
}

TEST_F(BobjReader, DataShorterThanItsCountsNamesWhereItEnds) {
  const std::string data = bobj_data(tetra_positions, tetra_triangles);
  expect_error(gzip(""), {"the data ends before the vertex count", "(byte offset 0 after"});
  expect_error(gzip(data.substr(0, 4 + 12 * 2 + 5)),
               {"truncated: the data ends in vertex 2 of 4", "(byte offset 33 after"});
  expect_error(gzip(data.substr(0, 4 + 48)), {"the data ends before the normal count"});
  expect_error(gzip(data.substr(0, 4 + 48 + 4 + 12 * 3)), {"in normal 3 of 4"});
  expect_error(gzip(data.substr(0, data.size() - 1)), {"in triangle 3 of 4"});
}

TEST_F(BobjReader, BadCountsIndicesAndCoordinates) {
  Data negative;
  negative.put(std::int32_t{0}).put(std::int32_t{0}).put(std::int32_t{-3});
  expect_error(gzip(negative.bytes()), {"negative triangle count -3", "(byte offset 8 after"});

  for (const std::int32_t index : {4, -1}) {
    std::vector<Triangle> triangles = tetra_triangles;
    triangles[1][2] = index;
    expect_error(
        gzip(bobj_data(tetra_positions, triangles)),
        {"triangle 1 refers to vertex " + std::to_string(index) + ", but there are 4 vertices"});
  }

  for (const float bad :
       {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    std::vector<Float3> positions = tetra_positions;
    positions[2][1] = bad;
    expect_error(gzip(bobj_data(positions, tetra_triangles)),
                 {"coordinate is NaN or infinite (vertex 2)"});
  }

  // Mantaflow writes an empty file (three zero counts) for a frame without liquid.
  expect_error(gzip(bobj_data({}, {})), {"contains no faces"});
}

TEST_F(BobjReader, HostileCountsAllocateOnlyWhatTheDataHolds) {
  Data vertices;  // claims 2^31 - 1 vertices, holds 3
  vertices.put(std::numeric_limits<std::int32_t>::max());
  for (int v = 0; v < 3; ++v) vertices.put(tetra_positions[v]);
  Data triangles;  // claims 2^31 - 1 triangles, holds 1
  triangles.put(std::int32_t{3});
  for (int v = 0; v < 3; ++v) triangles.put(tetra_positions[v]);
  triangles.put(std::int32_t{0}).put(std::numeric_limits<std::int32_t>::max());
  triangles.put(Triangle{0, 1, 2});

  reset_largest_allocation();
  expect_error(gzip(vertices.bytes()), {"the data ends in vertex 3 of 2147483647"});
  expect_error(gzip(triangles.bytes()), {"the data ends in triangle 1 of 2147483647"});
  EXPECT_LT(largest_allocation(), std::size_t{1} << 20);
}

TEST_F(BobjReader, GzipBombIsRefusedEarly) {
  // A header claiming 2^31 - 1 vertices followed by 32 MiB of zeros, which deflate shrinks about
  // 1000-fold; read naively, it would fill 768 MiB of positions from a 32 kB file.
  Data header;
  header.put(std::numeric_limits<std::int32_t>::max());
  const std::string bomb = gzip(header.bytes() + std::string(std::size_t{32} << 20, '\0'), 9);
  ASSERT_LT(bomb.size(), std::size_t{64} << 10);

  reset_largest_allocation();
  expect_error(bomb, {"inflates to more than 64 times its size", "gzip bomb"});
  // Nothing beyond 64 times the file's size is inflated, so positions stay under 128 times it.
  EXPECT_LT(largest_allocation(), 128 * bomb.size());
}

// ---- FLIP Fluids' .bobj: uncompressed, no normals -------------------------------------------

// A FLIP Fluids .bobj as TriangleMesh::getMeshFileDataBOBJ writes it: counts, positions,
// triangles, nothing else.
std::string flip_bobj_data(const std::vector<Float3>& positions,
                           const std::vector<Triangle>& triangles) {
  Data d;
  d.put(static_cast<std::int32_t>(positions.size()));
  for (const Float3& p : positions) d.put(p);
  d.put(static_cast<std::int32_t>(triangles.size()));
  for (const Triangle& t : triangles) d.put(t);
  return d.bytes();
}

TEST_F(BobjReader, FlipFluidsTetrahedronRoundTrip) {
  expect_tetrahedron(
      read_mesh(write("000001.bobj", flip_bobj_data(tetra_positions, tetra_triangles))));
  expect_tetrahedron(
      read_mesh(write("000002.BOBJ", flip_bobj_data(tetra_positions, tetra_triangles))));
}

TEST_F(BobjReader, FlipFluidsEveryTruncationIsAnError) {
  const std::string file = flip_bobj_data(tetra_positions, tetra_triangles);
  for (std::size_t size = 0; size < file.size(); ++size)
    expect_error(file.substr(0, size), {"truncated", "byte offset"}, "cut.bobj");
}

TEST_F(BobjReader, FlipFluidsBadCountsIndicesCoordinatesAndTrailingBytes) {
  Data negative;
  negative.put(std::int32_t{-4});
  expect_error(negative.bytes(), {"negative vertex count -4 (byte offset 0)"}, "bad.bobj");

  std::vector<Triangle> bad_index = tetra_triangles;
  bad_index[2][1] = 4;
  // The index is the second corner of the third triangle: 4 + 48 + 4 + 2 * 12 + 4 bytes in.
  expect_error(flip_bobj_data(tetra_positions, bad_index),
               {"triangle 2 refers to vertex 4, but there are 4 vertices (byte offset 84)"},
               "bad.bobj");
  bad_index[2][1] = -1;
  expect_error(flip_bobj_data(tetra_positions, bad_index), {"triangle 2 refers to vertex -1"},
               "bad.bobj");

  std::vector<Float3> nan_positions = tetra_positions;
  nan_positions[3][1] = std::numeric_limits<float>::quiet_NaN();
  expect_error(flip_bobj_data(nan_positions, tetra_triangles),
               {"coordinate is NaN or infinite (vertex 3)"}, "bad.bobj");

  expect_error(flip_bobj_data(tetra_positions, tetra_triangles) + "x",
               {"1 unexpected bytes after the triangles (byte offset 104)"}, "bad.bobj");
  // Mantaflow's layout, decompressed and named .bobj: its normals are taken for the triangle
  // count, which its data cannot hold, or leave bytes over; either way it is refused.
  expect_error(bobj_data(tetra_positions, tetra_triangles), {"bad.bobj: "}, "bad.bobj");
}

TEST_F(BobjReader, FlipFluidsHostileCountsAllocateNothingLarge) {
  Data vertices;  // claims 2^31 - 1 vertices, holds 3
  vertices.put(std::numeric_limits<std::int32_t>::max());
  for (int v = 0; v < 3; ++v) vertices.put(tetra_positions[v]);
  reset_largest_allocation();
  expect_error(vertices.bytes(), {"truncated: 2147483647 vertex records need"}, "huge.bobj");
  EXPECT_LT(largest_allocation(), std::size_t{1} << 20);
}

// ---- Sequences through the command line ---------------------------------------------------

// A wavy square sheet of n × n vertices in Mantaflow's normalised coordinates (z up), frame f.
std::string wave_frame(int n, int frame) {
  std::vector<Float3> positions;
  std::vector<Triangle> triangles;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float x = static_cast<float>(i) / static_cast<float>(n - 1) - 0.5f;
      const float y = static_cast<float>(j) / static_cast<float>(n - 1) - 0.5f;
      positions.push_back({x, y, 0.05f * std::sin(12.0f * x + static_cast<float>(frame))});
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const std::int32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      triangles.push_back({a, b, d});
      triangles.push_back({a, d, c});
    }
  return gzip(bobj_data(positions, triangles));
}

TEST_F(BobjReader, AnalyzeReadsACacheFrameInWorldCoordinates) {
  const fs::path cache = dir_ / "cache_fluid" / "mesh";
  fs::create_directories(cache);
  write_text(cache / "fluid_mesh_0007.bobj.gz", wave_frame(21, 7));
  // The same surface in world coordinates for a domain 4 m across centred at (1, -2, 0.5): the
  // map x -> 4 x + (1, -2, 0.5) is exact in double for these float coordinates.
  const InputMesh cached = read_mesh(cache / "fluid_mesh_0007.bobj.gz");
  TriangleMesh world = cached.mesh;
  for (Vec3& p : world.positions) p = 4.0 * p + Vec3(1, -2, 0.5);
  write_obj(dir_ / "world.obj", world);

  const auto analyze = [&](std::vector<std::string> args, const std::string& csv) {
    args.insert(args.end(), {"--up", "z", "--csv", (dir_ / csv).string()});
    const test::CommandResult r = run_toonwater(args);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return read_text(dir_ / csv);
  };
  const std::string expected = analyze({"analyze", (dir_ / "world.obj").string()}, "obj.csv");
  const std::string bobj = (cache / "fluid_mesh_0007.bobj.gz").string();
  EXPECT_EQ(analyze({"analyze", bobj, "--scale", "4", "--translate", "1,-2,0.5"}, "a.csv"),
            expected);
  EXPECT_EQ(analyze({"analyze", bobj, "--transform", "4,0,0,1,0,4,0,-2,0,0,4,0.5"}, "b.csv"),
            expected);
  EXPECT_NE(expected.find("\n1,-2,"), std::string::npos) << "the centre vertex, in world space";
}

TEST_F(BobjReader, PovgenTakesNumberedAndGlobbedCacheSequences) {
  const fs::path cache = dir_ / "mesh";
  fs::create_directories(cache);
  write_text(cache / "fluid_mesh_0001.bobj.gz", wave_frame(15, 1));
  write_text(cache / "fluid_mesh_0002.bobj.gz", wave_frame(15, 2));
  write_text(cache / "fluid_mesh_0003.bobj", "not part of the sequence");
  for (const std::string pattern : {"fluid_mesh_####.bobj.gz", "fluid_mesh_*.bobj.gz"}) {
    const fs::path out = dir_ / "scene";
    fs::remove_all(out);
    const test::CommandResult r = run_toonwater(
        {"povgen", "--up", "z", "--water", (cache / pattern).string(), "--out", out.string()});
    ASSERT_EQ(r.exit_code, 0) << pattern << "\n" << r.output;
    ASSERT_TRUE(fs::exists(out / "water_0001.inc") && fs::exists(out / "water_0002.inc"))
        << pattern;
    EXPECT_FALSE(fs::exists(out / "water_0003.inc")) << pattern;
    EXPECT_NE(read_text(out / "water_0001.inc"), read_text(out / "water_0002.inc")) << pattern;
  }
}

TEST_F(BobjReader, PovgenTakesAFlipFluidsBakeAndLeavesItsAttributeFilesOut) {
  // bakefiles/ as the add-on writes it: the surface NNNNNN.bobj beside attribute files with the
  // same suffix.
  const fs::path bakefiles = dir_ / "cache" / "bakefiles";
  fs::create_directories(bakefiles);
  TriangleMesh surface;
  for (int frame = 1; frame <= 2; ++frame) {
    const InputMesh sheet = read_mesh(write("frame.bobj.gz", wave_frame(15, frame)));
    std::vector<Float3> positions;
    for (const Vec3& p : sheet.mesh.positions)
      positions.push_back(
          {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
    const std::string stem = "00000" + std::to_string(frame);
    write_text(bakefiles / (stem + ".bobj"), flip_bobj_data(positions, sheet.mesh.triangles));
    write_text(bakefiles / ("velocity" + stem + ".bobj"), "not a surface");
    write_text(bakefiles / ("blur" + stem + ".bobj"), "not a surface");
    if (frame == 2) surface = sheet.mesh;
  }
  const fs::path out = dir_ / "scene";
  const test::CommandResult r =
      run_toonwater({"povgen", "--up", "z", "--water", (bakefiles / "######.bobj").string(),
                     "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "water_0001.inc") && fs::exists(out / "water_0002.inc"));
  EXPECT_NE(read_text(out / "water_0001.inc"), read_text(out / "water_0002.inc"));

  // analyze reads a frame as the same surface an OBJ of it gives.
  write_obj(dir_ / "frame2.obj", surface);
  const auto csv_of = [&](const fs::path& input, const std::string& csv) {
    const test::CommandResult a =
        run_toonwater({"analyze", input.string(), "--up", "z", "--csv", (dir_ / csv).string()});
    EXPECT_EQ(a.exit_code, 0) << a.output;
    return read_text(dir_ / csv);
  };
  EXPECT_EQ(csv_of(bakefiles / "000002.bobj", "flip.csv"), csv_of(dir_ / "frame2.obj", "obj.csv"));
}

}  // namespace
}  // namespace toonwater
