#include "render/video.hpp"

#include "analyzer/mesh_reader.hpp"  // InputError
#include "common/atomic_file.hpp"
#include "common/temporary_name.hpp"
#include "render/supervised_process.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace toonwater {
namespace {

namespace fs = std::filesystem;

// The preview GIF's width at most: a preview to put in a page or a message, not the video.
constexpr int gif_max_width = 320;

constexpr const char* ffmpeg = "ffmpeg";

// Whether `program` is an executable file in a directory of PATH (an empty entry is the
// working directory, as for execvp).
bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path candidate = (dir.empty() ? fs::path(".") : fs::path(dir)) / program;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return true;
  }
  return false;
}

const char* extension(VideoFormat format) { return format == VideoFormat::mp4 ? "mp4" : "gif"; }

// The image2 pattern of the scene's frame images: POV-Ray pads the frame number to the digits of
// the final frame (frame_image_path). "./" keeps a name with a colon from reading as a protocol.
std::string frame_pattern(const SceneFrames& scene) {
  std::string name;
  for (const char c : scene.output_name) name += c == '%' ? std::string("%%") : std::string(1, c);
  return "./" + name + "%0" + std::to_string(std::to_string(scene.last).size()) + "d.png";
}

// ffmpeg's command line: frames first..first+count-1 at the scene's frame rate into `output`.
std::vector<std::string> ffmpeg_arguments(VideoFormat format, const SceneFrames& scene, long first,
                                          std::size_t count, const std::string& output) {
  const std::string fps = std::to_string(scene.frame_rate);
  // image2 reads on from -start_number until an image is missing; -frames:v stops it at `count`.
  std::vector<std::string> args{ffmpeg, "-nostdin", "-hide_banner", "-loglevel", "error"};
  args.insert(args.end(), {"-framerate", fps, "-start_number", std::to_string(first), "-i",
                           frame_pattern(scene), "-frames:v", std::to_string(count)});
  if (format == VideoFormat::mp4) {
    // yuv420p (what players take) needs even sizes: an odd width or height gains a pixel row or
    // column, a copy of the last (pad, fillborders' smear, then crop to even: an even size is
    // cropped back to itself), where pad's black would draw a line along the edge.
    args.insert(
        args.end(),
        {"-vf", "pad=iw+1:ih+1,fillborders=right=1:bottom=1,crop=trunc(iw/2)*2:trunc(ih/2)*2:0:0",
         "-c:v", "libx264", "-pix_fmt", "yuv420p", "-r", fps, "-movflags", "+faststart", "-f",
         "mp4"});
  } else {
    // One palette for the whole animation, made from its frames.
    const std::string scale = "scale='min(" + std::to_string(gif_max_width) + ",iw)':-1";
    args.insert(args.end(), {"-filter_complex",
                             scale + ":flags=lanczos,split[a][b];[a]palettegen[p];[b][p]paletteuse",
                             "-f", "gif"});
  }
  args.push_back("./" + output);
  return args;
}

// The last non-blank line of ffmpeg's log (-loglevel error: its error).
std::string last_line(const fs::path& log) {
  std::ifstream in(log);
  std::string last;
  for (std::string line; std::getline(in, line);)
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  return last;
}

// A video made under its temporary name, not yet in place.
struct PendingVideo {
  fs::path target, temporary;
};

void remove_temporaries(const std::vector<PendingVideo>& videos) {
  for (const PendingVideo& v : videos) {
    std::error_code ec;
    fs::remove(v.temporary, ec);
  }
}

// Runs ffmpeg for one video into its temporary name. Throws as make_videos says, after removing
// the temporary.
void assemble(const VideoRequest& request, const fs::path& dir, const SceneFrames& scene,
              const std::vector<long>& frames, VideoFormat format, const PendingVideo& video) {
  const fs::path log = dir / temporary_name(video.target.filename().string() + ".log");
  ChildSetup setup;
  setup.working_directory = dir.string();
  setup.output_file = log.string();
  const int status = run_supervised(ffmpeg_arguments(format, scene, frames.front(), frames.size(),
                                                     video.temporary.filename().string()),
                                    setup, request.stop);
  std::error_code ec;
  // Stopped: ffmpeg ends a file it was writing on SIGTERM and may exit 0, but the run was
  // interrupted, and an interrupted run makes no video.
  if (request.stop && request.stop->load()) {
    fs::remove(video.temporary, ec);
    fs::remove(log, ec);
    throw InterruptedError(video.target.string() + ": interrupted while ffmpeg was making it");
  }
  if (status == 0) {
    fs::remove(log, ec);
    return;
  }
  fs::remove(video.temporary, ec);
  std::string reason;
  if (status == child_cannot_execute)
    reason = "cannot run ffmpeg (is it installed?)";
  else if (status == child_cannot_write_output)
    reason = "cannot write " + log.string();
  else if (status < 0)
    reason = "cannot start ffmpeg";
  else
    reason = (status > 128 ? "ffmpeg was killed by signal " + std::to_string(status - 128)
                           : "ffmpeg exited with status " + std::to_string(status));
  const std::string message = last_line(log);
  if (!message.empty()) reason += ": " + message;
  const fs::path kept_log = video.target.string() + ".log";
  fs::rename(log, kept_log, ec);
  if (ec)
    fs::remove(log, ec);
  else
    reason += " (log: " + kept_log.filename().string() + ")";
  throw OutputError(video.target.string() + ": " + reason);
}

}  // namespace

fs::path video_path(const fs::path& scene_dir, VideoFormat format) {
  return scene_dir / (std::string("video.") + extension(format));
}

void check_video_request(const VideoRequest& request) {
  if (request.formats.empty()) return;
  if (!read_scene_frames(request.scene_dir).animation)
    throw InputError(request.scene_dir.string() +
                     ": --video needs an animation; this scene is a single image");
  if (!on_path(ffmpeg))
    throw MissingProgramError(
        "--video needs ffmpeg, which is not on PATH (Debian: apt-get install ffmpeg)");
}

std::vector<fs::path> make_videos(const VideoRequest& request) {
  std::vector<VideoFormat> formats;
  for (const VideoFormat f : request.formats)
    if (std::find(formats.begin(), formats.end(), f) == formats.end()) formats.push_back(f);
  if (formats.empty()) return {};
  const fs::path dir = fs::absolute(request.scene_dir);
  const SceneFrames scene = read_scene_frames(dir);
  const std::vector<long> frames = requested_frames(dir, scene, request.frames);
  std::vector<PendingVideo> videos;
  for (const VideoFormat f : formats) {
    const fs::path target = video_path(dir, f);
    videos.push_back({target, dir / temporary_name(target.filename().string())});
  }
  // Every frame of the range, rendered for this scene: else the video would show another
  // scene's frames, or skip some.
  const std::vector<long> missing = frames_without_image(dir, scene, frames);
  if (!missing.empty())
    throw OutputError(videos.front().target.string() + ": frame " +
                      std::to_string(missing.front()) + " has no image of this scene (" +
                      frame_image_path(dir, scene, missing.front()).filename().string() +
                      "); no video was made");
  // All the videos or none: each is made under its temporary name, then all are put in place.
  try {
    for (std::size_t i = 0; i < formats.size(); ++i)
      assemble(request, dir, scene, frames, formats[i], videos[i]);
  } catch (...) {
    remove_temporaries(videos);
    throw;
  }
  std::vector<fs::path> written;
  for (const PendingVideo& v : videos) {
    std::error_code ec;
    fs::rename(v.temporary, v.target, ec);
    if (ec) {
      remove_temporaries(videos);
      throw OutputError(v.target.string() +
                        ": cannot move ffmpeg's output into place: " + ec.message());
    }
    fs::remove(v.target.string() + ".log", ec);  // of an earlier run that failed
    written.push_back(v.target);
  }
  return written;
}

}  // namespace toonwater
