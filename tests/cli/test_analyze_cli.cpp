// `toonwater analyze` as a user runs it: bad input gives one line naming the file (and line) and a
// non-zero exit without touching existing outputs; a good run writes one row per input vertex.
#include "analyzer/mesh_reader.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace toonwater {
namespace {

namespace fs = std::filesystem;
using test::entries;
using test::read_text;
using test::run_toonwater;
using test::ScratchDir;
using test::write_text;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream stream(text);
  for (std::string line; std::getline(stream, line);) lines.push_back(line);
  return lines;
}

const std::string good_csv = "x,y,z,gaussian,mean,k1,k2,area,label,flow\n0,0,0,0,0,0,0,0,0,0\n";

class AnalyzeCli : public ::testing::Test {
 protected:
  // Runs analyze on a mesh with `contents`, asking for a CSV over an existing good one, and
  // checks the failure: non-zero exit, one line containing `expected`, the CSV untouched and
  // nothing else left in the directory.
  void expect_failure(const std::string& mesh_name, const std::string& contents,
                      const std::string& expected) {
    const fs::path mesh = dir_ / mesh_name;
    write_text(mesh, contents);
    const fs::path csv = dir_ / "curvature.csv";
    write_text(csv, good_csv);
    const test::CommandResult result =
        run_toonwater({"analyze", mesh.string(), "--csv", csv.string()});
    EXPECT_NE(result.exit_code, 0) << result.output;
    EXPECT_EQ(lines_of(result.output).size(), 1u) << result.output;
    EXPECT_NE(result.output.find(expected), std::string::npos)
        << "expected " << expected << "\n got " << result.output;
    EXPECT_EQ(read_text(csv), good_csv);
    EXPECT_EQ(entries(dir_.path()), std::vector<std::string>({"curvature.csv", mesh_name}));
    fs::remove(mesh);
  }

  ScratchDir dir_;
};

const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST_F(AnalyzeCli, BadMeshesFailWithOneLineNamingFileAndLine) {
  expect_failure("malformed.obj", triangle + "v 1 2 three\nf 1 2 3\n",
                 (dir_ / "malformed.obj").string() + ":4: malformed number 'three'");
  expect_failure("index.obj", triangle + "f 1 2 3\nf 1 2 7\n",
                 (dir_ / "index.obj").string() + ":5: face index 7 out of range");
  expect_failure("nan.obj", "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n",
                 (dir_ / "nan.obj").string() + ":2: coordinate 'nan' is NaN or infinite");
  expect_failure("empty.obj", "", (dir_ / "empty.obj").string() + ": contains no faces");
  expect_failure("truncated.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n",
                 (dir_ / "truncated.off").string() + ":4: file ends after 2 of 3 vertices");
}

TEST_F(AnalyzeCli, MissingFileFailsNamingIt) {
  const fs::path csv = dir_ / "curvature.csv";
  write_text(csv, good_csv);
  const fs::path missing = dir_ / "missing.obj";
  const test::CommandResult result =
      run_toonwater({"analyze", missing.string(), "--csv", csv.string()});
  EXPECT_NE(result.exit_code, 0);
  EXPECT_EQ(result.output,
            "toonwater: error: " + missing.string() + ": cannot open: No such file or directory\n");
  EXPECT_EQ(read_text(csv), good_csv);
  EXPECT_EQ(entries(dir_.path()), std::vector<std::string>({"curvature.csv"}));
}

TEST_F(AnalyzeCli, UnknownOptionFailsWithOneLine) {
  const fs::path mesh = dir_ / "mesh.obj";
  write_text(mesh, triangle + "f 1 2 3\n");
  const test::CommandResult result = run_toonwater({"analyze", mesh.string(), "--bogus"});
  EXPECT_NE(result.exit_code, 0);
  EXPECT_EQ(lines_of(result.output).size(), 1u) << result.output;
  EXPECT_NE(result.output.find("--bogus"), std::string::npos) << result.output;
}

TEST_F(AnalyzeCli, UnwritableOutputFailsNamingItAndLeavesNothing) {
  const fs::path mesh = dir_ / "mesh.obj";
  write_text(mesh, triangle + "f 1 2 3\n");
  const fs::path csv = dir_ / "no-such-dir" / "curvature.csv";
  const test::CommandResult result =
      run_toonwater({"analyze", mesh.string(), "--csv", csv.string()});
  EXPECT_NE(result.exit_code, 0);
  EXPECT_EQ(lines_of(result.output).size(), 1u) << result.output;
  EXPECT_NE(result.output.find(csv.string() + ": "), std::string::npos) << result.output;
  EXPECT_EQ(entries(dir_.path()), std::vector<std::string>({"mesh.obj"}));
}

// A closed octahedron as an ASCII STL soup: 8 facets, 24 input vertices, 6 distinct positions.
std::string octahedron_stl() {
  const double p[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                           {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  std::ostringstream stl;
  stl << "solid octahedron\n";
  for (const auto& f : faces) {
    stl << " facet normal 0 0 0\n  outer loop\n";
    for (const int v : f)
      stl << "   vertex " << p[v][0] << ' ' << p[v][1] << ' ' << p[v][2] << '\n';
    stl << "  endloop\n endfacet\n";
  }
  stl << "endsolid octahedron\n";
  return stl.str();
}

TEST_F(AnalyzeCli, SoupGetsOneRowPerInputVertexAndWeldedCopiesAgree) {
  const fs::path mesh = dir_ / "octahedron.stl";
  write_text(mesh, octahedron_stl());
  const fs::path csv = dir_ / "curvature.csv";
  const fs::path ply = dir_ / "curvature.ply";
  write_text(csv, good_csv);
  const test::CommandResult result =
      run_toonwater({"analyze", mesh.string(), "--csv", csv.string(), "--ply", ply.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("24 vertices (18 welded)"), std::string::npos) << result.output;

  const std::vector<std::string> rows = lines_of(read_text(csv));
  ASSERT_EQ(rows.size(), 1u + 24u);
  EXPECT_EQ(rows[0], "x,y,z,gaussian,mean,k1,k2,area,label,flow");
  const InputMesh input = read_mesh(mesh);
  for (std::size_t v = 0; v < 24; ++v) {
    std::istringstream fields(rows[1 + v]);
    std::string field;
    std::vector<double> values;
    while (std::getline(fields, field, ',')) values.push_back(std::strtod(field.c_str(), nullptr));
    ASSERT_EQ(values.size(), 10u) << rows[1 + v];
    for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(values[axis], input.mesh.positions[v][axis]);
    // Welded, every corner is an interior vertex of a closed convex surface: K > 0 and H > 0
    // (unwelded, each copy would sit alone on a boundary).
    EXPECT_GT(values[3], 0.0) << rows[1 + v];
    EXPECT_GT(values[4], 0.0) << rows[1 + v];
    // Copies of the same position carry the same values.
    for (std::size_t u = 0; u < v; ++u)
      if (input.mesh.positions[u] == input.mesh.positions[v]) {
        const std::string& earlier = rows[1 + u];
        EXPECT_EQ(earlier, rows[1 + v]) << "vertices " << u << " and " << v;
      }
  }

  const InputMesh back = read_mesh(ply);
  EXPECT_EQ(back.mesh.positions.size(), 24u);
  EXPECT_EQ(back.mesh.triangles, input.mesh.triangles);
  EXPECT_EQ(entries(dir_.path()),
            std::vector<std::string>({"curvature.csv", "curvature.ply", "octahedron.stl"}));
}

TEST_F(AnalyzeCli, ObjRowsFollowInputOrder) {
  // A square pyramid without a base, listed with its apex last.
  const fs::path mesh = dir_ / "pyramid.obj";
  write_text(mesh,
             "v 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nv 0 0 0.5\n"
             "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n");
  const fs::path csv = dir_ / "curvature.csv";
  const test::CommandResult result =
      run_toonwater({"analyze", mesh.string(), "--csv", csv.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::vector<std::string> rows = lines_of(read_text(csv));
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[1].substr(0, 6), "1,0,0,");
  EXPECT_EQ(rows[3].substr(0, 7), "-1,0,0,");
  EXPECT_EQ(rows[5].substr(0, 8), "0,0,0.5,");
}

}  // namespace
}  // namespace toonwater
