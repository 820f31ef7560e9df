// toonwater render --video: an MP4 (H.264, yuv420p) and a small animated GIF preview of the
// frames a render has just completed, assembled by ffmpeg (run as a child process, found on
// PATH), at the frame rate the scene records (SceneFrames::frame_rate, render.fps).
//
// A video is made only from a whole set: every frame of the requested range has its image, at
// least as new as the scene (frames_without_image), and ffmpeg reads exactly those frames, first
// to last, never an image of another range left by an earlier run. ffmpeg writes into a hidden
// temporary name beside the video, which is renamed over DIR/video.EXT once ffmpeg has succeeded:
// a failed or interrupted run leaves the earlier video, or none, never a partial one.
#pragma once

#include "common/frame_range.hpp"
#include "render/render.hpp"

#include <atomic>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace toonwater {

enum class VideoFormat { mp4, gif };

// ffmpeg is not on PATH (the CLI's exit code "incomplete installation").
class MissingProgramError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct VideoRequest {
  std::filesystem::path scene_dir;
  std::optional<FrameRange> frames;  // default: all frames in scene.ini
  std::vector<VideoFormat> formats;  // each made once, in this order
  // When it becomes true (a signal handler sets it), ffmpeg is stopped, its partial output
  // removed, and make_videos throws InterruptedError.
  const std::atomic<bool>* stop = nullptr;
};

// Checks, before anything is rendered, that the request can make its videos: the scene is an
// animation (InputError) and ffmpeg is on PATH (MissingProgramError).
void check_video_request(const VideoRequest& request);

// Where the video of `format` goes: DIR/video.mp4, DIR/video.gif.
std::filesystem::path video_path(const std::filesystem::path& scene_dir, VideoFormat format);

// Makes the request's videos from its frames, once they are all rendered, and returns the paths
// written. Throws OutputError naming the video when a frame has no current image (nothing is
// made) or ffmpeg fails (with ffmpeg's error line; its log stays as DIR/video.EXT.log), and
// InterruptedError when stopped; either way no partial video is left.
std::vector<std::filesystem::path> make_videos(const VideoRequest& request);

}  // namespace toonwater
