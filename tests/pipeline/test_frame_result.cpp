// Each frame's result (pipeline/frame_result.hpp) and the report summed from them: on a sequence
// with frames of different sizes, a frame without water and a static and an animated object,
// each frame counts its own mesh, the frame without water carries its reason, and the report's
// totals are the sums of its frames (with the static object), with a survey and without one.
#include "corpus/analytic_surfaces.hpp"
#include "pipeline/generate_scene.hpp"
#include "scene/config.hpp"
#include "tests/support/povray_test_util.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

constexpr long sequence_frames = 4;
constexpr long empty_frame = 2;

// Frame f's water: a wavy grid, finer each frame (its vertices are its own).
TriangleMesh water_frame(long f) {
  return make_height_grid(static_cast<int>(7 + 4 * f), 1.0, [&](double x, double z) {
    return 0.08 * std::sin(5 * x + 0.4 * static_cast<double>(f)) * std::cos(4 * z);
  });
}

std::string numbered(const std::string& stem, long f) {
  return stem + "_000" + std::to_string(f) + ".obj";
}

void write_sequence(const fs::path& dir) {
  for (long f = 1; f <= sequence_frames; ++f) {
    if (f == empty_frame)
      write_text(dir / numbered("water", f), "# the liquid has left the domain\n");
    else
      write_obj(dir / numbered("water", f), water_frame(f));
    TriangleMesh buoy = make_icosphere(1, 0.1).mesh;
    for (Vec3& p : buoy.positions) p += Vec3(0.2 * static_cast<double>(f), 0.1, 0.0);
    write_obj(dir / numbered("buoy", f), buoy);
  }
  write_obj(dir / "rock.obj", make_icosphere(1, 0.2).mesh);
}

// The default camera and maps make a survey (the frames wait in the frame cache); a fixed
// camera without maps does not (the frame loop reads each frame).
struct Case {
  std::string name;
  std::vector<std::string> overrides;
  bool maps = false;
};
const std::vector<Case> cases = {
    {"surveyed", {}, true},
    {"fixed", {"camera.location=[0, 3, -3]", "camera.look_at=[0, 0, 0]"}, false},
};

PovgenReport generate(const fs::path& dir, const Case& c) {
  const std::string& out = c.name;
  ConfigSources sources;
  sources.overrides = c.overrides;
  sources.object_patterns = {(dir / "rock.obj").string(), (dir / "buoy_####.obj").string()};
  PovgenRequest request;
  request.water_pattern = (dir / "water_####.obj").string();
  request.base_dir = dir;
  request.out_dir = dir / out;
  if (c.maps) request.maps_dir = dir / (out + "_maps");
  return generate_scene(load_config(sources), request, {}, nullptr);
}

TEST(PovgenFrameResults, EachFrameCountsItsOwnMesh) {
  ScratchDir dir;
  write_sequence(dir.path());
  for (const Case& c : cases) {
    const std::string& name = c.name;
    const PovgenReport r = generate(dir.path(), c);
    ASSERT_EQ(r.per_frame.size(), static_cast<std::size_t>(sequence_frames)) << name;
    for (long f = 1; f <= sequence_frames; ++f) {
      const FrameResult& result = r.per_frame[static_cast<std::size_t>(f - 1)];
      EXPECT_EQ(result.frame, f) << name;
      EXPECT_EQ(result.objects.reads, 1u) << name << " frame " << f << ": its buoy";
      if (f == empty_frame) continue;
      const TriangleMesh mesh = water_frame(f);
      EXPECT_EQ(result.vertices, mesh.positions.size()) << name << " frame " << f;
      EXPECT_EQ(result.faces, mesh.triangles.size()) << name << " frame " << f;
      EXPECT_LE(result.faces_kept, result.faces) << name << " frame " << f;
      EXPECT_TRUE(result.empty.empty()) << name << " frame " << f << ": " << result.empty;
      EXPECT_EQ(result.maps, c.maps) << name << " frame " << f;
      // The outline is on: the water's shell has a face for each face rendered.
      EXPECT_EQ(result.shell_faces, result.faces_kept) << name << " frame " << f;
    }
  }
}

TEST(PovgenFrameResults, AFrameWithoutWaterCarriesItsReason) {
  ScratchDir dir;
  write_sequence(dir.path());
  for (const Case& c : cases) {
    const std::string& name = c.name;
    const PovgenReport r = generate(dir.path(), c);
    ASSERT_EQ(r.per_frame.size(), static_cast<std::size_t>(sequence_frames)) << name;
    const FrameResult& empty = r.per_frame[empty_frame - 1];
    EXPECT_NE(empty.empty.find(numbered("water", empty_frame) + ": contains no faces"),
              std::string::npos)
        << name << ": " << empty.empty;
    EXPECT_EQ(empty.vertices, 0u) << name;
    EXPECT_EQ(empty.faces, 0u) << name;
    EXPECT_EQ(empty.shell_faces, 0u) << name;
    EXPECT_FALSE(empty.maps) << name;
    EXPECT_EQ(r.empty_frames, std::vector<std::string>{empty.empty}) << name;
  }
}

TEST(PovgenFrameResults, TheReportIsTheSumOfItsFrames) {
  ScratchDir dir;
  write_sequence(dir.path());
  for (const Case& c : cases) {
    const std::string& name = c.name;
    const PovgenReport r = generate(dir.path(), c);
    FrameResult sum;
    std::size_t map_frames = 0;
    for (const FrameResult& f : r.per_frame) {
      sum.vertices += f.vertices;
      sum.faces += f.faces;
      sum.faces_kept += f.faces_kept;
      sum.degenerate_faces += f.degenerate_faces;
      sum.replaced_normals += f.replaced_normals;
      sum.ridge_vertices += f.ridge_vertices;
      sum.valley_vertices += f.valley_vertices;
      sum.shell_faces += f.shell_faces;
      sum.shell_faces_kept += f.shell_faces_kept;
      sum.simplify_seconds += f.simplify_seconds;
      sum.maps_seconds += f.maps_seconds;
      sum.objects += f.objects;
      map_frames += f.maps ? 1 : 0;
    }
    EXPECT_EQ(r.frames, r.per_frame.size()) << name;
    EXPECT_EQ(r.vertices, sum.vertices) << name;
    EXPECT_EQ(r.faces, sum.faces) << name;
    EXPECT_EQ(r.faces_kept, sum.faces_kept) << name;
    EXPECT_EQ(r.degenerate_faces, sum.degenerate_faces) << name;
    EXPECT_EQ(r.replaced_normals, sum.replaced_normals) << name;
    EXPECT_EQ(r.ridge_vertices, sum.ridge_vertices) << name;
    EXPECT_EQ(r.valley_vertices, sum.valley_vertices) << name;
    EXPECT_EQ(r.map_frames, map_frames) << name;
    EXPECT_EQ(r.map_frames, c.maps ? static_cast<std::size_t>(sequence_frames - 1) : 0) << name;
    EXPECT_EQ(r.cached_frames, c.maps ? static_cast<std::size_t>(sequence_frames) : 0) << name;
    EXPECT_DOUBLE_EQ(r.simplify_seconds, sum.simplify_seconds) << name;
    EXPECT_DOUBLE_EQ(r.maps_seconds, sum.maps_seconds) << name;
    // The static rock's include adds its one read and its whole shell to the frames'.
    const std::size_t rock_faces = make_icosphere(1, 0.2).mesh.triangles.size();
    EXPECT_EQ(r.object_reads, 1 + sum.objects.reads) << name;
    EXPECT_EQ(r.shell_faces, sum.shell_faces + sum.objects.shell_faces + rock_faces) << name;
    EXPECT_EQ(r.shell_faces_kept, sum.shell_faces_kept + sum.objects.shell_faces + rock_faces)
        << name;
    EXPECT_EQ(r.water_reads, static_cast<std::size_t>(sequence_frames)) << name;
  }
}

}  // namespace
}  // namespace toonwater::test
