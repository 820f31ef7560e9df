// One frame source for the scene and its maps (analyzer/frame_source.hpp): povgen reads and
// analyses each water frame once. Where the sequence shares something (the default camera's
// box, a curvature view's colour range, the maps' view and ranges) the survey reads them and
// keeps each frame (pipeline/frame_cache.hpp) for the frame loop, in memory or spilled to a file,
// with the same output either way. The maps written from the scene's analyses equal those of
// the sequence's maps planned and written from the library alone.
#include "analyzer/frame_source.hpp"
#include "analyzer/maps/map_writer.hpp"
#include "corpus/analytic_surfaces.hpp"
#include "scene/config.hpp"
#include "pipeline/generate_scene.hpp"
#include "tests/support/povray_test_util.hpp"
#include "tests/support/test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t frame_count = 3;

// Every channel of an image file as floats, with its channel names and text metadata (the
// files' bytes differ: OpenEXR stamps the time of writing).
std::string image_content(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) return "unreadable: " + path.string();
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  std::string content = std::to_string(spec.width) + "x" + std::to_string(spec.height);
  for (const std::string& name : spec.channelnames) content += " " + name;
  for (const char* key :
       {"toonwater:K_range", "toonwater:H_range", "toonwater:box_uv", "toonwater:pixel_size"})
    content += std::string(" ") + key + "=" + std::string(spec.get_string_attribute(key));
  content.append(reinterpret_cast<const char*>(pixels.data()), pixels.size() * sizeof(float));
  return content;
}

void write_frames(const fs::path& dir) {
  for (std::size_t f = 0; f < frame_count; ++f) {
    const double phase = 0.4 * static_cast<double>(f);
    write_obj(dir / ("water_000" + std::to_string(f + 1) + ".obj"),
              make_height_grid(25, 1.0, [&](double x, double z) {
                return 0.08 * std::sin(5 * x + phase) * std::cos(4 * z);
              }));
  }
}

PovgenReport generate(const fs::path& dir, const std::string& out,
                      const std::vector<std::string>& overrides, bool maps,
                      std::size_t cache_bytes = PovgenRequest{}.frame_cache_bytes,
                      const ProgressFn& progress = {}) {
  ConfigSources sources;
  sources.overrides = overrides;
  const SceneConfig config = load_config(sources);
  PovgenRequest request;
  request.water_pattern = (dir / "water_####.obj").string();
  request.base_dir = dir;
  request.out_dir = dir / out;
  if (maps) request.maps_dir = dir / (out + "_maps");
  request.frame_cache_bytes = cache_bytes;
  return generate_scene(config, request, progress, nullptr);
}

TEST(PovgenFrameReads, MapsAndACurvatureViewReadEachFrameOnce) {
  ScratchDir dir;
  write_frames(dir.path());
  const PovgenReport r = generate(dir.path(), "mean", {"water.shading=mean"}, true);
  EXPECT_EQ(r.frames, frame_count);
  EXPECT_EQ(r.map_frames, frame_count);
  // One read a frame, not two (a survey and the frame loop) or five.
  EXPECT_EQ(r.water_reads, frame_count);
  EXPECT_EQ(r.cached_frames, frame_count);
  EXPECT_EQ(r.spilled_frames, 0u);
  for (const char* stem : {"water_0001", "water_0002", "water_0003"}) {
    EXPECT_TRUE(fs::exists(dir / "mean_maps" / (std::string(stem) + ".exr"))) << stem;
    EXPECT_TRUE(fs::exists(dir / "mean_maps" / (std::string(stem) + "_label.png"))) << stem;
  }
}

TEST(PovgenFrameReads, AToonSceneThatSharesNothingReadsEachFrameOnce) {
  ScratchDir dir;
  write_frames(dir.path());
  const PovgenReport r = generate(
      dir.path(), "toon", {"camera.location=[0, 3, -3]", "camera.look_at=[0, 0, 0]"}, false);
  EXPECT_EQ(r.frames, frame_count);
  EXPECT_EQ(r.water_reads, frame_count);
  EXPECT_EQ(r.cached_frames, 0u);
  // The default camera frames the sequence's box: the survey reads each frame, the loop none.
  EXPECT_EQ(generate(dir.path(), "framed", {}, false).water_reads, frame_count);
}

// The survey, now the longer of the two passes, reports its frames before the frame loop does.
TEST(PovgenFrameReads, TheSurveyReportsItsFramesBeforeTheFrameLoop) {
  ScratchDir dir;
  write_frames(dir.path());
  using Call = std::tuple<PovgenPass, std::size_t, std::size_t>;
  const auto calls_of = [&](const std::string& out, const std::vector<std::string>& overrides) {
    std::vector<Call> calls;
    generate(dir.path(), out, overrides, false, PovgenRequest{}.frame_cache_bytes,
             [&](PovgenPass pass, std::size_t done, std::size_t total) {
               calls.emplace_back(pass, done, total);
             });
    return calls;
  };
  std::vector<Call> loop;
  for (std::size_t f = 1; f <= frame_count; ++f)
    loop.emplace_back(PovgenPass::frames, f, frame_count);
  std::vector<Call> survey_then_loop;
  for (std::size_t f = 1; f <= frame_count; ++f)
    survey_then_loop.emplace_back(PovgenPass::survey, f, frame_count);
  survey_then_loop.insert(survey_then_loop.end(), loop.begin(), loop.end());
  EXPECT_EQ(calls_of("framed", {}), survey_then_loop) << "the default camera surveys";
  EXPECT_EQ(calls_of("fixed", {"camera.location=[0, 3, -3]", "camera.look_at=[0, 0, 0]"}), loop)
      << "a fixed camera and toon shading share nothing: no survey";
}

// Every file of a directory with its bytes (maps by their content, image_content).
std::map<std::string, std::string> directory_content(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const fs::path& p = entry.path();
    files[p.filename().string()] =
        p.extension() == ".exr" || p.extension() == ".png" ? image_content(p) : read_text(p);
  }
  return files;
}

// With the default camera the survey reads the objects for the camera's box and keeps them for
// their includes: each object file is read once (a static object once, an animated one once a
// frame), and the scene is the same whether the frames wait in memory or in the cache's file.
TEST(PovgenFrameReads, TheDefaultCameraReadsEachObjectFileOnce) {
  ScratchDir dir;
  write_frames(dir.path());
  write_obj(dir / "rock.obj", make_icosphere(1, 0.2).mesh);
  for (std::size_t f = 0; f < frame_count; ++f) {
    TriangleMesh buoy = make_icosphere(1, 0.1).mesh;
    for (Vec3& p : buoy.positions) p += Vec3(0.2 * static_cast<double>(f), 0.1, 0.0);
    write_obj(dir / ("buoy_000" + std::to_string(f + 1) + ".obj"), buoy);
  }
  const auto scene = [&](const std::string& out, std::size_t cache_bytes,
                         const std::vector<std::string>& overrides = {}) {
    ConfigSources sources;
    sources.overrides = overrides;
    sources.object_patterns = {(dir / "rock.obj").string(), (dir / "buoy_####.obj").string()};
    PovgenRequest request;
    request.water_pattern = (dir / "water_####.obj").string();
    request.base_dir = dir.path();
    request.out_dir = dir / out;
    request.frame_cache_bytes = cache_bytes;
    return generate_scene(load_config(sources), request, {}, nullptr);
  };
  const PovgenReport memory = scene("memory", PovgenRequest{}.frame_cache_bytes);
  const PovgenReport file = scene("file", 0);
  EXPECT_EQ(memory.object_reads, 1 + frame_count);
  EXPECT_EQ(file.object_reads, 1 + frame_count);
  EXPECT_EQ(file.spilled_frames, frame_count);
  const auto memory_scene = directory_content(dir / "memory");
  EXPECT_TRUE(memory_scene == directory_content(dir / "file"));
  // Each frame's include holds that frame's buoy.
  ASSERT_TRUE(memory_scene.count("obj_buoy.0001.inc") && memory_scene.count("obj_buoy.0002.inc"))
      << memory_scene.size() << " files";
  EXPECT_NE(memory_scene.at("obj_buoy.0001.inc"), memory_scene.at("obj_buoy.0002.inc"));
  // A fixed camera needs no survey: the frame loop reads each file, once too.
  EXPECT_EQ(
      scene("fixed", 0, {"camera.location=[0, 3, -3]", "camera.look_at=[0, 0, 0]"}).object_reads,
      1 + frame_count);
}

// Frames spilled to the cache's file give the same scene and maps as frames kept in memory,
// and the file is gone from the scene.
TEST(PovgenFrameReads, FramesSpilledToAFileGiveTheSameSceneAndMaps) {
  ScratchDir dir;
  write_frames(dir.path());
  const std::vector<std::string> view = {"water.shading=mean"};
  const PovgenReport memory = generate(dir.path(), "memory", view, true);
  const PovgenReport file = generate(dir.path(), "file", view, true, 0);
  EXPECT_EQ(memory.spilled_frames, 0u);
  EXPECT_EQ(file.spilled_frames, frame_count);
  EXPECT_EQ(file.water_reads, frame_count);
  const auto memory_scene = directory_content(dir / "memory");
  const auto file_scene = directory_content(dir / "file");
  EXPECT_EQ(memory_scene.size(), file_scene.size());
  EXPECT_TRUE(memory_scene == file_scene);
  EXPECT_FALSE(fs::exists(dir / "file" / ".frame_cache.bin"));
  EXPECT_TRUE(directory_content(dir / "memory_maps") == directory_content(dir / "file_maps"));
  // Each frame's include holds its own frame, not another's.
  EXPECT_NE(file_scene.at("water_0001.inc"), file_scene.at("water_0002.inc"));
}

// The maps from povgen's own frames and coherence run are the maps of the sequence alone: each
// frame analysed in order with coherence, planned together (MapPlanner), then written.
TEST(PovgenFrameReads, SceneMapsEqualTheSequenceMaps) {
  ScratchDir dir;
  write_frames(dir.path());
  const PovgenReport r = generate(dir.path(), "toon", {}, true);
  FrameSourceOptions options;
  options.analysis = analysis_options(FlowConfig{}, Axis::y, WaterShading::toon);
  options.coherent = true;
  FrameSource source(options);
  std::vector<Analysis> analyses;
  MapPlanner planner(Axis::y);
  for (std::size_t f = 0; f < frame_count; ++f) {
    SourceFrame frame = source.read(dir / ("water_000" + std::to_string(f + 1) + ".obj"));
    ASSERT_TRUE(frame.analysis);
    planner.add(*frame.analysis);
    analyses.push_back(std::move(*frame.analysis));
  }
  const MapView view = planner.view(MapOptions{});
  const MapRanges ranges = planner.ranges(MapOptions{}.percentile);
  EXPECT_EQ(r.map_ranges.gaussian, ranges.gaussian);
  EXPECT_EQ(r.map_ranges.mean, ranges.mean);
  for (std::size_t f = 0; f < frame_count; ++f) {
    const std::string stem = "water_000" + std::to_string(f + 1);
    write_maps(dir / "alone", stem, analyses[f], view, ranges);
    for (const char* suffix : {".exr", "_K.png", "_H.png", "_label.png"}) {
      const std::string name = stem + suffix;
      EXPECT_TRUE(image_content(dir / "toon_maps" / name) == image_content(dir / "alone" / name))
          << name;
    }
  }
}

}  // namespace
}  // namespace toonwater::test
