// toonwater render --video: the MP4 and the GIF preview ffmpeg makes of the rendered frames,
// checked with ffprobe (codec, pixel format, size, frame count, duration) and by decoding frames
// back; and the cases that must make no video: ffmpeg missing (exit 6), a failed frame, ffmpeg
// failing, a single image. ffmpeg and ffprobe are required: scripts/test.sh installs them
// (scripts/setup.sh --tests), and a test that cannot find them fails saying so.
#include "tests/render/farm_test_util.hpp"

#include "common/atomic_file.hpp"
#include "common/child_process.hpp"
#include "render/video.hpp"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

// The scene: the wake example, odd sizes (the MP4 pads them to even ones) and wider than the
// GIF's 320 pixels, at 12 frames per second.
constexpr int kFrames = 6, kWidth = 333, kHeight = 61, kFps = 12;

// `program` on PATH, or an empty path (and a test failure saying how to install it).
fs::path on_path(const std::string& program) {
  std::istringstream dirs(std::getenv("PATH") ? std::getenv("PATH") : "");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && ::access((fs::path(dir) / program).c_str(), X_OK) == 0)
      return fs::path(dir) / program;
  ADD_FAILURE() << program << " is not on PATH: scripts/setup.sh --tests installs ffmpeg";
  return {};
}

// ffprobe's fields of the first video stream of `video`, frames counted by decoding.
std::map<std::string, std::string> probe(const fs::path& video) {
  const CommandResult r = run_program(
      on_path("ffprobe"),
      {"-v", "error", "-select_streams", "v:0", "-count_frames", "-show_entries",
       "stream=codec_name,pix_fmt,width,height,nb_frames,nb_read_frames,r_frame_rate,duration",
       "-of", "default=noprint_wrappers=1", video.string()});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::map<std::string, std::string> fields;
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);)
    if (const auto eq = line.find('='); eq != std::string::npos)
      fields[line.substr(0, eq)] = line.substr(eq + 1);
  return fields;
}

// Frame `index` (from 0) of `video`, decoded into a PNG in `dir`.
Image decoded_frame(const fs::path& video, int index, const fs::path& dir) {
  const fs::path png = dir / ("decoded_" + std::to_string(index) + ".png");
  const CommandResult r =
      run_program(on_path("ffmpeg"),
                  {"-nostdin", "-v", "error", "-y", "-i", video.string(), "-vf",
                   "select=eq(n\\," + std::to_string(index) + ")", "-frames:v", "1", png.string()});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return read_image(png);
}

// The mean absolute difference of the channels of `a` and `b` over b's size (a is at least as
// large: the video's padding is left out).
double mean_difference(const Image& a, const Image& b) {
  if (a.width < b.width || a.height < b.height) return 255;
  double sum = 0;
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x)
      for (int c = 0; c < 3; ++c) sum += std::abs(a.at(x, y)[c] - b.at(x, y)[c]);
  return sum / (3.0 * b.width * b.height);
}

// The frame (1 to kFrames) whose image in `scene` `decoded` is nearest to.
int nearest_frame(const Image& decoded, const fs::path& scene) {
  int nearest = 0;
  double smallest = 255;
  for (int f = 1; f <= kFrames; ++f) {
    const double difference = mean_difference(decoded, read_image(scene / frame_name(f)));
    if (difference < smallest) {
      smallest = difference;
      nearest = f;
    }
  }
  // H.264 and yuv420p change a few levels (3.5 here); other frames differ by 20 or more.
  EXPECT_LT(smallest, 8.0);
  return nearest;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The entries of `dir` that ffmpeg's temporaries or a video would leave.
std::vector<std::string> video_files(const fs::path& dir) {
  std::vector<std::string> found;
  for (const std::string& name : entries(dir))
    if (name.starts_with(".video") || name.starts_with("video")) found.push_back(name);
  return found;
}

class Video : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir;
    const CommandResult sim =
        run_toonwater({"simulate", "wake", "--frames", std::to_string(kFrames), "--out",
                       (*dir_ / "sim").string()});
    ASSERT_EQ(sim.exit_code, 0) << sim.output;
    fs::copy_file(fs::path(TOONWATER_SOURCE_DIR) / "examples/wake/scene.toml",
                  *dir_ / "scene.toml");
    const CommandResult pov = run_toonwater(
        {"povgen", "--config", (*dir_ / "scene.toml").string(), "--water",
         (*dir_ / "sim/water_####.obj").string(), "--set", "render.width=" + std::to_string(kWidth),
         "--set", "render.height=" + std::to_string(kHeight), "--set",
         "render.fps=" + std::to_string(kFps), "--out", (*dir_ / "scene").string()});
    ASSERT_EQ(pov.exit_code, 0) << pov.output;
  }
  static void TearDownTestSuite() { delete dir_; }
  // A fresh copy of the unrendered scene.
  fs::path copy_scene(const std::string& name) const {
    const fs::path copy = work_ / name;
    fs::copy(*dir_ / "scene", copy, fs::copy_options::recursive);
    return copy;
  }
  static ScratchDir* dir_;
  ScratchDir work_;
};
ScratchDir* Video::dir_ = nullptr;

TEST_F(Video, Mp4AndGifOfEveryFrameAtTheScenesFrameRate) {
  const fs::path scene = copy_scene("scene");
  EXPECT_TRUE(has(read_text(scene / "scene.ini"), "; Frame_Rate=12\n"));
  CommandResult r = run_toonwater({"render", "--video", "mp4", scene.string(), "--video", "gif"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(has(r.output, (scene / "video.mp4").string() + "\n")) << r.output;
  EXPECT_TRUE(has(r.output, (scene / "video.gif").string() + "\n")) << r.output;
  EXPECT_EQ(video_files(scene), (std::vector<std::string>{"video.gif", "video.mp4"}));

  auto mp4 = probe(scene / "video.mp4");
  EXPECT_EQ(mp4["codec_name"], "h264");
  EXPECT_EQ(mp4["pix_fmt"], "yuv420p");
  EXPECT_EQ(mp4["width"], std::to_string(kWidth + 1));  // padded to even sizes
  EXPECT_EQ(mp4["height"], std::to_string(kHeight + 1));
  EXPECT_EQ(mp4["nb_frames"], std::to_string(kFrames));
  EXPECT_EQ(mp4["nb_read_frames"], std::to_string(kFrames));
  EXPECT_EQ(mp4["r_frame_rate"], "12/1");
  EXPECT_NEAR(std::stod(mp4["duration"]), double(kFrames) / kFps, 1e-3);
  // The frames in order: each frame of the video, decoded, is nearest the image of its frame.
  for (int i = 0; i < kFrames; ++i)
    EXPECT_EQ(nearest_frame(decoded_frame(scene / "video.mp4", i, work_.path()), scene), i + 1);
  // The added column and row repeat the last ones (the background here), not a black line.
  const Image decoded = decoded_frame(scene / "video.mp4", 0, work_.path());
  double edge = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int c = 0; c < 3; ++c)
      edge += std::abs(decoded.at(kWidth, y)[c] - decoded.at(kWidth - 1, y)[c]);
  for (int x = 0; x < kWidth; ++x)
    for (int c = 0; c < 3; ++c)
      edge += std::abs(decoded.at(x, kHeight)[c] - decoded.at(x, kHeight - 1)[c]);
  EXPECT_LT(edge / (3.0 * (kWidth + kHeight)), 4.0);

  auto gif = probe(scene / "video.gif");
  EXPECT_EQ(gif["codec_name"], "gif");
  EXPECT_EQ(gif["width"], "320");  // the preview's width cap
  EXPECT_EQ(gif["height"], std::to_string(std::lround(kHeight * 320.0 / kWidth)));
  EXPECT_EQ(gif["nb_read_frames"], std::to_string(kFrames));

  // A range: every frame has its image already (skipped), and the video is of frames 2-4 only,
  // not of the other frames beside them.
  r = run_toonwater({"render", scene.string(), "--frames", "2-4", "--video", "mp4"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(has(r.output, "0 frame(s) rendered, 3 skipped")) << r.output;
  mp4 = probe(scene / "video.mp4");
  EXPECT_EQ(mp4["nb_read_frames"], "3");
  EXPECT_NEAR(std::stod(mp4["duration"]), 3.0 / kFps, 1e-3);
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(nearest_frame(decoded_frame(scene / "video.mp4", i, work_.path()), scene), i + 2);
}

TEST_F(Video, WithoutFfmpegAVideoIsExitSixBeforeAnyFrameAndARenderNeedsNoFfmpeg) {
  const fs::path scene = copy_scene("scene");
  // PATH with POV-Ray and nothing else.
  const fs::path bin = work_ / "bin";
  fs::create_directories(bin);
  fs::create_symlink(on_path("povray"), bin / "povray");
  const ScopedEnvironmentVariable path_variable("PATH", bin.string());
  CommandResult r = run_toonwater({"render", scene.string(), "--video", "mp4"});
  EXPECT_EQ(r.exit_code, 6) << r.output;  // incomplete installation (README, "Exit codes")
  EXPECT_EQ(r.output,
            "toonwater: error: --video needs ffmpeg, which is not on PATH (Debian: apt-get "
            "install ffmpeg)\n");
  EXPECT_FALSE(fs::exists(scene / frame_name(1)));
  EXPECT_TRUE(video_files(scene).empty());

  r = run_toonwater({"render", scene.string()});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (int f = 1; f <= kFrames; ++f) EXPECT_TRUE(fs::exists(scene / frame_name(f))) << f;
  EXPECT_TRUE(video_files(scene).empty());
}

TEST_F(Video, AFailedFrameMakesNoVideo) {
  const fs::path scene = copy_scene("scene");
  fs::remove(scene / "water_0003.inc");
  const CommandResult r = run_toonwater({"render", scene.string(), "--video", "mp4,gif"});
  EXPECT_EQ(r.exit_code, 5) << r.output;  // POV-Ray failed
  EXPECT_TRUE(has(r.output, "frame 3 failed")) << r.output;
  EXPECT_TRUE(fs::exists(scene / frame_name(4)));
  EXPECT_TRUE(video_files(scene).empty()) << r.output;
}

// make_videos on its own: a frame without its image, or with an image older than the scene (of
// an earlier scene that povgen carried over), is an error naming it, and no video is made.
TEST_F(Video, AMissingOrStaleFrameMakesNoVideo) {
  const fs::path scene = copy_scene("scene");
  const CommandResult r = run_toonwater({"render", scene.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  VideoRequest request;
  request.scene_dir = scene;
  request.formats = {VideoFormat::mp4, VideoFormat::gif};
  const auto error_of = [&] {
    try {
      make_videos(request);
    } catch (const OutputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  fs::rename(scene / frame_name(3), work_ / frame_name(3));
  EXPECT_EQ(error_of(),
            (scene / "video.mp4").string() +
                ": frame 3 has no image of this scene (frame_3.png); no video was made");
  EXPECT_TRUE(video_files(scene).empty());

  fs::rename(work_ / frame_name(3), scene / frame_name(3));
  request.frames = FrameRange{2, 4};
  EXPECT_EQ(make_videos(request).size(), 2u);  // every frame there: both videos
  fs::last_write_time(scene / "scene.ini",
                      fs::last_write_time(scene / frame_name(2)) + std::chrono::seconds(1));
  EXPECT_TRUE(has(error_of(), ": frame 2 has no image of this scene")) << error_of();
  EXPECT_EQ(probe(scene / "video.mp4")["nb_read_frames"], "3");  // the earlier video stays
}

// An ffmpeg that writes part of its output, then fails on the GIF: neither video is put in
// place, the earlier one stays, and the error names the video with ffmpeg's own message.
TEST_F(Video, FfmpegFailingLeavesNoPartialOrMixedVideos) {
  const fs::path scene = copy_scene("scene");
  const fs::path bin = work_ / "bin";
  fs::create_directories(bin);
  write_text(bin / "ffmpeg",
             "#!/bin/sh\n"
             "for a; do out=$a; done\n"
             "echo partial > \"$out\"\n"
             "case \" $* \" in *\" -f gif \"*) echo 'gif: encoder exploded' >&2; exit 1;; esac\n"
             "exit 0\n");
  fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
  const ScopedEnvironmentVariable path_variable = path_with_first(bin);
  write_text(scene / "video.mp4", "earlier");
  const CommandResult r = run_toonwater({"render", scene.string(), "--video", "mp4,gif"});
  EXPECT_EQ(r.exit_code, 3) << r.output;  // output failure: nothing was replaced
  EXPECT_TRUE(has(r.output, "toonwater: error: " + (scene / "video.gif").string() +
                                ": ffmpeg exited with status 1: gif: encoder exploded (log: "
                                "video.gif.log)\n"))
      << r.output;
  for (int f = 1; f <= kFrames; ++f) EXPECT_TRUE(fs::exists(scene / frame_name(f))) << f;
  EXPECT_EQ(read_text(scene / "video.mp4"), "earlier");
  EXPECT_EQ(video_files(scene), (std::vector<std::string>{"video.gif.log", "video.mp4"}));
}

// SIGTERM while ffmpeg runs: ffmpeg is stopped, its partial output removed, the frames kept.
TEST_F(Video, AStopWhileFfmpegRunsLeavesNoVideoAndNoFfmpeg) {
  const fs::path scene = copy_scene("scene");
  const fs::path bin = work_ / "bin", started = work_ / "ffmpeg.pid";
  fs::create_directories(bin);
  write_text(bin / "ffmpeg",
             "#!/bin/sh\nfor a; do out=$a; done\necho partial > \"$out\"\necho $$ > '" +
                 started.string() + ".new'\nmv '" + started.string() + ".new' '" +
                 started.string() + "'\nexec sleep 60\n");
  fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
  const ScopedEnvironmentVariable path_variable = path_with_first(bin);
  ChildSetup setup;
  setup.output_file = (work_ / "render.log").string();
  const pid_t render = start_child_process(
      {TOONWATER_EXECUTABLE, "render", scene.string(), "--video", "mp4"}, setup);
  ASSERT_GT(render, 0);
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(300);
  while (!fs::exists(started) && std::chrono::steady_clock::now() < deadline &&
         ::waitpid(render, &status, WNOHANG) == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(fs::exists(started)) << read_text(work_ / "render.log");
  const pid_t ffmpeg = std::stoi(read_text(started));
  const auto partial = [](const std::string& name) { return name.starts_with(".video.mp4.tmp-"); };
  const std::vector<std::string> before = entries(scene);
  EXPECT_TRUE(std::any_of(before.begin(), before.end(), partial));  // what ffmpeg has written
  ::kill(render, SIGTERM);
  ASSERT_EQ(::waitpid(render, &status, 0), render);
  const std::string log = read_text(work_ / "render.log");
  EXPECT_EQ(exit_status(status), 4) << log;  // interrupted
  EXPECT_TRUE(has(log, "video.mp4: interrupted while ffmpeg was making it")) << log;
  EXPECT_NE(::kill(ffmpeg, 0), 0) << "ffmpeg still runs";
  EXPECT_TRUE(video_files(scene).empty()) << log;
  for (int f = 1; f <= kFrames; ++f) EXPECT_TRUE(fs::exists(scene / frame_name(f))) << f;
}

TEST_F(Video, RendersOnGnuParallelThenMakesTheVideo) {
  const fs::path scene = copy_scene("scene");
  write_text(work_ / "hosts", ":\n");
  const CommandResult r =
      run_toonwater({"render", scene.string(), "--on", "parallel", "--hosts",
                     (work_ / "hosts").string(), "--frames-per-task", "3", "--video", "mp4"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(has(r.output, (scene / "video.mp4").string() + "\n")) << r.output;
  EXPECT_EQ(probe(scene / "video.mp4")["nb_read_frames"], std::to_string(kFrames));
}

TEST_F(Video, AskedForWhereNoneCanBeMadeIsBadInput) {
  const fs::path scene = copy_scene("scene");
  CommandResult r = run_toonwater({"render", scene.string(), "--video", "webm"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r.output, "'webm' is not one of mp4, gif")) << r.output;
  r = run_toonwater({"render", scene.string(), "--on", "slurm", "--no-wait", "--video", "mp4"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r.output, "--video is made once every frame is rendered")) << r.output;
  // A frame rate that is not one in scene.ini (an edited one).
  std::string ini = read_text(scene / "scene.ini");
  ini.replace(ini.find("; Frame_Rate=12"), 15, "; Frame_Rate=0");
  write_text(scene / "scene.ini", ini);
  r = run_toonwater({"render", scene.string(), "--video", "mp4"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r.output, "scene.ini: frame rate 0 is not from 1 to 240")) << r.output;
  // A single image.
  const CommandResult pov = run_toonwater(
      {"povgen", "--water", (*dir_ / "sim/water_0001.obj").string(), "--set", "render.width=32",
       "--set", "render.height=24", "--out", (work_ / "single").string()});
  ASSERT_EQ(pov.exit_code, 0) << pov.output;
  r = run_toonwater({"render", (work_ / "single").string(), "--video", "gif"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r.output, "--video needs an animation; this scene is a single image"))
      << r.output;
  EXPECT_FALSE(fs::exists(work_ / "single/frame.png"));
  for (const fs::path& dir : {scene, work_ / "single"}) EXPECT_TRUE(video_files(dir).empty());
}

}  // namespace
}  // namespace toonwater::test
