// Curvature export: one row per input vertex in input order, values that round-trip exactly in
// CSV, a binary PLY our own reader reads back, and never a NaN or Inf.
#include "analyzer/curvature_export.hpp"

#include "common/atomic_file.hpp"
#include "analyzer/mesh_reader.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace toonwater {
namespace {

namespace fs = std::filesystem;
using test::read_text;
using test::ScratchDir;

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

// A soup of two triangles (6 input vertices) welded into 4 analysis rows, with values that are
// hard to round-trip, and a NaN and an Inf that must come out as 0.
struct Fixture {
  TriangleMesh input;
  Analysis analysis;

  Fixture() {
    input.positions = {Vec3(0.1, -0.0, 1e-300), Vec3(1.0 / 3.0, 2, 3),   Vec3(5e-324, 1e300, -7),
                       Vec3(1.0 / 3.0, 2, 3),   Vec3(0.1, -0.0, 1e-300), Vec3(123456.789, 0, 1)};
    input.triangles = {{0, 1, 2}, {3, 4, 5}};
    analysis.input_to_surface = {0, 1, 2, 1, 0, 3};
    analysis.surface.positions = {input.positions[0], input.positions[1], input.positions[2],
                                  input.positions[5]};
    analysis.surface.triangles = {{0, 1, 2}, {1, 0, 3}};
    CurvatureField& c = analysis.curvature;
    c.gaussian = {0.1, -2.5e-17, nan, 1.7976931348623157e308};
    c.mean = {-1.0 / 3.0, 4.9406564584124654e-324, inf, 2.0};
    c.area = {0.5, 0.25, 0.125, 6.02214076e23};
    analysis.flow.label = {1, 0, -1, 1};
    analysis.flow.field = {1.5, 0.25, -3.0, nan};
  }

  // The ten values of input vertex v as the export must write them.
  std::vector<double> expected_row(std::size_t v) const {
    const std::size_t s = analysis.input_to_surface[v];
    const CurvatureField& c = analysis.curvature;
    const auto [k1, k2] = principal_curvatures(c.gaussian[s], c.mean[s]);
    std::vector<double> row{input.positions[v].x(),
                            input.positions[v].y(),
                            input.positions[v].z(),
                            c.gaussian[s],
                            c.mean[s],
                            k1,
                            k2,
                            c.area[s],
                            static_cast<double>(analysis.flow.label[s]),
                            analysis.flow.field[s]};
    for (double& value : row)
      if (!std::isfinite(value)) value = 0.0;
    return row;
  }
};

// What a PLY float of `value` must hold: doubles beyond the float range are clamped to it, not
// turned into infinity.
float as_ply_float(double value) {
  return static_cast<float>(std::clamp(value, -double{FLT_MAX}, double{FLT_MAX}));
}

std::string csv_of(const Analysis& analysis) {
  ScratchDir dir;
  write_curvature_csv(dir / "c.csv", analysis);
  return read_text(dir / "c.csv");
}

std::string ply_of(const std::vector<Triangle>& triangles, const Analysis& analysis) {
  ScratchDir dir;
  write_curvature_ply(dir / "c.ply", triangles, analysis);
  return read_text(dir / "c.ply");
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, separator);) parts.push_back(part);
  return parts;
}

TEST(CurvatureExport, CsvRowsRoundTripBitForBit) {
  const Fixture f;
  const std::string csv = csv_of(f.analysis);
  ASSERT_FALSE(csv.empty());
  EXPECT_EQ(csv.back(), '\n');
  const std::vector<std::string> lines = split(csv, '\n');
  ASSERT_EQ(lines.size(), 1 + f.input.positions.size());
  EXPECT_EQ(lines[0], "x,y,z,gaussian,mean,k1,k2,area,label,flow");
  for (std::size_t v = 0; v < f.input.positions.size(); ++v) {
    const std::vector<std::string> fields = split(lines[1 + v], ',');
    const std::vector<double> expected = f.expected_row(v);
    ASSERT_EQ(fields.size(), expected.size()) << lines[1 + v];
    for (std::size_t k = 0; k < fields.size(); ++k) {
      char* end = nullptr;
      const double parsed = std::strtod(fields[k].c_str(), &end);
      EXPECT_EQ(*end, '\0') << fields[k];
      EXPECT_EQ(std::bit_cast<std::uint64_t>(parsed), std::bit_cast<std::uint64_t>(expected[k]))
          << "row " << v << " field " << k << ": " << fields[k];
    }
  }
  EXPECT_EQ(csv.find("nan"), std::string::npos);
  EXPECT_EQ(csv.find("inf"), std::string::npos);
  // The label column is an integer.
  EXPECT_EQ(split(lines[3], ',')[8], "-1");
}

TEST(CurvatureExport, CsvOfManyVerticesKeepsInputOrder) {
  // Enough rows for the formatting to be split over threads and written in several blocks.
  TriangleMesh input;
  Analysis analysis;
  constexpr std::size_t n = 100000;
  for (std::size_t v = 0; v < n; ++v) {
    input.positions.emplace_back(static_cast<double>(v), 0.5, -1.0);
    analysis.input_to_surface.push_back(static_cast<std::int32_t>(n - 1 - v));
  }
  input.triangles = {{0, 1, 2}};
  for (std::size_t s = 0; s < n; ++s)
    analysis.surface.positions.emplace_back(static_cast<double>(n - 1 - s), 0.5, -1.0);
  CurvatureField& c = analysis.curvature;
  for (std::size_t s = 0; s < n; ++s) c.gaussian.push_back(static_cast<double>(s) + 0.25);
  c.mean = c.area = std::vector<double>(n, 1.0);
  analysis.flow.label.assign(n, 0);
  analysis.flow.field.assign(n, 0.0);
  const std::vector<std::string> lines = split(csv_of(analysis), '\n');
  ASSERT_EQ(lines.size(), n + 1);
  for (std::size_t v = 0; v < n; v += 997) {
    const std::vector<std::string> fields = split(lines[1 + v], ',');
    EXPECT_EQ(std::strtod(fields[0].c_str(), nullptr), static_cast<double>(v));
    EXPECT_EQ(std::strtod(fields[3].c_str(), nullptr), static_cast<double>(n - 1 - v) + 0.25);
  }
}

TEST(CurvatureExport, PlyReadsBackWithOurReader) {
  const Fixture f;
  ScratchDir dir;
  const fs::path path = dir / "curvature.ply";
  write_curvature_ply(path, f.input.triangles, f.analysis);
  const InputMesh back = read_mesh(path);
  ASSERT_EQ(back.mesh.positions.size(), f.input.positions.size());
  for (std::size_t v = 0; v < f.input.positions.size(); ++v)
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_EQ(back.mesh.positions[v][axis],
                static_cast<double>(as_ply_float(f.input.positions[v][axis])))
          << v;
  EXPECT_EQ(back.mesh.triangles, f.input.triangles);
}

TEST(CurvatureExport, PlyHeaderAndFloatValues) {
  const Fixture f;
  const std::string ply = ply_of(f.input.triangles, f.analysis);
  const std::string header =
      "ply\nformat binary_little_endian 1.0\n"
      "comment toonwater curvature per vertex; label: 1 ridge, -1 valley, 0 none; flow: the "
      "signed flow field, regions where |flow| >= 1\n"
      "element vertex 6\n"
      "property float x\nproperty float y\nproperty float z\nproperty float gaussian\n"
      "property float mean\nproperty float k1\nproperty float k2\nproperty float area\n"
      "property float label\nproperty float flow\n"
      "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
  ASSERT_EQ(ply.substr(0, header.size()), header);
  ASSERT_EQ(ply.size(), header.size() + 6 * 10 * 4 + 2 * 13);
  for (std::size_t v = 0; v < 6; ++v) {
    const std::vector<double> expected = f.expected_row(v);
    for (std::size_t k = 0; k < 10; ++k) {
      std::uint32_t bits = 0;
      for (int byte = 3; byte >= 0; --byte)
        bits = bits << 8 | static_cast<unsigned char>(ply[header.size() + (v * 10 + k) * 4 + byte]);
      const float value = std::bit_cast<float>(bits);
      ASSERT_TRUE(std::isfinite(value)) << v << " " << k;
      EXPECT_EQ(value, as_ply_float(expected[k])) << "vertex " << v << " value " << k;
    }
  }
}

TEST(CurvatureExport, WritesFilesAtomically) {
  const Fixture f;
  ScratchDir dir;
  write_file_atomically(dir / "c.csv", "an earlier good file\n");
  write_curvature_csv(dir / "c.csv", f.analysis);
  EXPECT_EQ(read_text(dir / "c.csv").rfind("x,y,z,gaussian,mean,k1,k2,area,label,flow\n", 0), 0u);
  EXPECT_THROW(write_curvature_csv(dir / "no" / "c.csv", f.analysis), OutputError);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(CurvatureExport, RejectsAnAnalysisOfAnotherMesh) {
  Fixture f;
  Fixture g;
  g.analysis.input_to_surface[0] = 4;  // there are 4 rows: 0..3
  EXPECT_THROW(csv_of(g.analysis), std::invalid_argument);
  f.analysis.input_to_surface.pop_back();  // input vertex 5 is gone, a triangle still uses it
  EXPECT_THROW(ply_of(f.input.triangles, f.analysis), std::invalid_argument);
  ScratchDir dir;
  EXPECT_THROW(write_curvature_csv(dir / "c.csv", g.analysis), std::invalid_argument);
  EXPECT_TRUE(fs::is_empty(dir.path())) << "no temporary file left behind";
}

}  // namespace
}  // namespace toonwater
