// toonwater render: runs POV-Ray on the frames of a povgen scene directory, several frames at
// once (frames are independent), each as `povray scene.ini +SFn +EFn` in the directory.
// A frame fails when POV-Ray exits non-zero (whatever its log says), is killed, or writes no
// image or an empty one; the failure gives the reason and POV-Ray's own error lines. Each frame
// renders into a hidden temporary directory in DIR and its image is renamed into DIR once
// POV-Ray has finished, so DIR never holds a partial image.
#pragma once

#include "povgen/config.hpp"

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace toonwater::povgen {

// Some frames failed to render (the CLI's exit code "POV-Ray failed").
class PovrayError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RenderRequest {
  std::filesystem::path scene_dir;
  int jobs = 1;                              // frames rendered at the same time
  std::optional<FrameRange> frames;          // default: all frames in scene.ini
  std::string povray = "povray";             // the executable, looked up on PATH
  std::vector<std::string> extra_arguments;  // passed to every povray run
  // When it becomes true (a signal handler sets it), running povray processes are terminated,
  // no further frame starts, and render_frames throws InterruptedError; images
  // already renamed into DIR stay, nothing partial or temporary is left.
  const std::atomic<bool>* stop = nullptr;
};

struct FrameFailure {
  long frame = 0;
  std::string message;  // the reason, with POV-Ray's error line(s) and the kept log's name
};

struct RenderReport {
  std::size_t rendered = 0;
  std::vector<FrameFailure> failures;  // by frame number
  double seconds = 0;
};

// Called after each frame: frames done, total, seconds since the start.
using RenderProgressFn = std::function<void(std::size_t, std::size_t, double)>;

// Throws InputError when the directory holds no povgen scene or the range is outside it.
// Throws InterruptedError when `request.stop` interrupted the run.
RenderReport render_frames(const RenderRequest& request, const RenderProgressFn& progress);

// The error lines of a POV-Ray log: lines mentioning an error, else its last line.
std::string povray_error_message(const std::string& log);

}  // namespace toonwater::povgen
