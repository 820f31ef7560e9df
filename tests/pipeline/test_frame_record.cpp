// A frame's record (pipeline/frame_record.hpp) kept by the frame cache (pipeline/frame_cache.hpp):
// a prepared surface whose every field holds a value of its own comes back equal, field by
// field, whether the cache kept it in memory or spilled it to its file. A field added to
// PreparedSurface, SceneMesh or FlowLine and not to its field list (for_each_field) does not
// compile, so it cannot be silently left out of the record.
#include "pipeline/frame_cache.hpp"
#include "pipeline/frame_record.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

namespace toonwater {
namespace {

namespace fs = std::filesystem;

// Every field set, each to a value no other field and no default has.
PreparedSurface distinct_surface() {
  PreparedSurface s;
  s.mesh.positions = {Vec3(1, 2, 3), Vec3(4, 5, 6), Vec3(7, 8, 9.5)};
  s.mesh.normals = {Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 0, 0)};
  s.mesh.triangles = {Triangle{0, 1, 2}, Triangle{2, 1, 0}};
  s.mesh.closed = true;
  s.mesh.degenerate_faces = 11;
  s.mesh.replaced_normals = 12;
  s.mesh.min = Vec3(-1, -2, -3);
  s.mesh.max = Vec3(13, 14, 15);
  s.flow_field = {0.25, -0.5, 0.75};
  FlowLine ridge;
  ridge.sign = FlowLabel::ridge;
  ridge.closed = true;
  ridge.points = {Vec3(1, 1, 1), Vec3(2, 2, 2)};
  ridge.taper = {0.5, 1.0};
  FlowLine valley;
  valley.sign = FlowLabel::valley;
  valley.closed = false;
  valley.points = {Vec3(3, 3, 3), Vec3(4, 4, 4), Vec3(5, 5, 5)};
  valley.taper = {0.0, 0.125, 0.0};
  s.flow_lines = {ridge, valley};
  s.view_values = {16.5, 17.5};
  s.view_range = 18.25;
  s.ridge_vertices = 19;
  s.valley_vertices = 20;
  s.normal_noise = 21.5;
  s.analysis_seconds = 22.75;
  return s;
}

void expect_equal(const PreparedSurface& a, const PreparedSurface& b) {
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.mesh.normals, b.mesh.normals);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.mesh.closed, b.mesh.closed);
  EXPECT_EQ(a.mesh.degenerate_faces, b.mesh.degenerate_faces);
  EXPECT_EQ(a.mesh.replaced_normals, b.mesh.replaced_normals);
  EXPECT_EQ(a.mesh.min, b.mesh.min);
  EXPECT_EQ(a.mesh.max, b.mesh.max);
  EXPECT_EQ(a.flow_field, b.flow_field);
  ASSERT_EQ(a.flow_lines.size(), b.flow_lines.size());
  for (std::size_t i = 0; i < a.flow_lines.size(); ++i) {
    EXPECT_EQ(a.flow_lines[i].sign, b.flow_lines[i].sign) << i;
    EXPECT_EQ(a.flow_lines[i].closed, b.flow_lines[i].closed) << i;
    EXPECT_EQ(a.flow_lines[i].points, b.flow_lines[i].points) << i;
    EXPECT_EQ(a.flow_lines[i].taper, b.flow_lines[i].taper) << i;
  }
  EXPECT_EQ(a.view_values, b.view_values);
  EXPECT_EQ(a.view_range, b.view_range);
  EXPECT_EQ(a.ridge_vertices, b.ridge_vertices);
  EXPECT_EQ(a.valley_vertices, b.valley_vertices);
  EXPECT_EQ(a.normal_noise, b.normal_noise);
  EXPECT_EQ(a.analysis_seconds, b.analysis_seconds);
}

// The comparison above names every field: the field lists have as many as it compares.
TEST(FrameRecord, FieldListsNameEveryFieldTheTestCompares) {
  PreparedSurface s = distinct_surface();
  int surface_fields = 0, mesh_fields = 0, line_fields = 0;
  for_each_field(s, [&](auto&) { ++surface_fields; });
  for_each_field(s.mesh, [&](auto&) { ++mesh_fields; });
  for_each_field(s.flow_lines[0], [&](auto&) { ++line_fields; });
  EXPECT_EQ(surface_fields, 9);
  EXPECT_EQ(mesh_fields, 8);
  EXPECT_EQ(line_fields, 4);
}

TEST(FrameRecord, APreparedSurfaceComesBackWithEveryFieldFromMemoryAndFromTheSpillFile) {
  const fs::path dir =
      fs::temp_directory_path() / ("toonwater_frame_record_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const PreparedSurface original = distinct_surface();
  RecordWriter writer;
  pack_surface(writer, original);
  const std::string record(writer.bytes());
  {
    // The first record fits the budget and stays in memory; the second goes to the file.
    FrameCache cache(dir / "cache.bin", record.size());
    cache.put(record);
    cache.put(record);
    ASSERT_EQ(cache.spilled(), 1u);
    for (std::size_t i = 0; i < 2; ++i) {
      std::string bytes;
      cache.take(i, bytes);
      RecordReader reader(bytes);
      SCOPED_TRACE(i == 0 ? "in memory" : "spilled");
      expect_equal(unpack_surface(reader), original);
    }
  }
  fs::remove_all(dir);
}

TEST(FrameRecord, ReadingPastTheRecordsEndIsAnError) {
  RecordWriter writer;
  pack_surface(writer, distinct_surface());
  const std::string truncated(writer.bytes().substr(0, writer.bytes().size() - 1));
  RecordReader reader(truncated);
  EXPECT_THROW(unpack_surface(reader), std::logic_error);
}

}  // namespace
}  // namespace toonwater
