// toonwater render: runs POV-Ray on the frames of a povgen scene directory, several POV-Ray
// processes at once, each over a range of consecutive frames (`povray scene.ini +SFa +EFb` in
// the directory). One process per frame would pay POV-Ray's start-up every frame, about 0.7 s
// of mostly idle wall time; and POV-Ray parses on one thread, which is most of a big frame's
// time. So the frames are split into as many ranges as processes, four processes a core by
// default (POV-Ray's front end also idles about 0.25 s per frame within a range: on the demo's
// frames, 0.56 s of CPU each, a one-thread process is busy about 0.56 s of every 0.8 s, and four
// a core keep the cores busy on lighter frames too), each with an equal share of the cores'
// threads (+WTn, at least 1).
// A frame fails when POV-Ray exits non-zero (whatever its log says), is killed, or writes no
// image or an empty one; the failure gives the reason and POV-Ray's own error lines. Each
// process renders into a hidden temporary directory in DIR, and a frame's image is renamed into
// DIR once it is complete (a whole PNG, ending with its IEND chunk: POV-Ray writes an image only
// when its frame is finished, never on a cancel; or POV-Ray has written the next frame's image,
// or has exited), so DIR never holds a partial image. A process whose images are all published
// is killed: POV-Ray's shut-down idles about 0.4 s, which would otherwise end the run.
#pragma once

#include "common/frame_range.hpp"

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace toonwater {

// Some frames failed to render (the CLI's exit code "POV-Ray failed").
class PovrayError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RenderRequest {
  std::filesystem::path scene_dir;
  int jobs = 1;                              // POV-Ray processes at the same time
  std::optional<FrameRange> frames;          // default: all frames in scene.ini
  std::string povray = "povray";             // the executable, looked up on PATH
  std::vector<std::string> extra_arguments;  // passed to every povray run
  // render_frames: skip the frames that already have their image (frames_without_image), as
  // `toonwater render` does unless --force. Off for callers that render a scene they just wrote.
  bool skip_rendered = false;
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
  std::size_t skipped = 0;             // frames that had their image before (not forced)
  std::vector<FrameFailure> failures;  // by frame number
  double seconds = 0;
};

// The frames of a scene directory, from its scene.ini.
struct SceneFrames {
  bool animation = false;               // false: a single image, Output_File_Name itself
  long first = 0, last = 0;             // Initial_Frame, Final_Frame
  std::string output_name = "frame";    // Output_File_Name, without its quotes
  int frame_rate = default_frame_rate;  // frames per second: the "; Frame_Rate=N" line
};

// Throws InputError when the directory holds no povgen scene.
SceneFrames read_scene_frames(const std::filesystem::path& scene_dir);

// The frames of `range` (default: every frame; 0 for a single image). Throws InputError naming
// `scene_dir` when the range is outside the scene's.
std::vector<long> requested_frames(const std::filesystem::path& scene_dir,
                                   const SceneFrames& frames,
                                   const std::optional<FrameRange>& range);

// Where POV-Ray writes the image of `frame` (ignored for a single image) in `scene_dir`.
std::filesystem::path frame_image_path(const std::filesystem::path& scene_dir,
                                       const SceneFrames& frames, long frame);

// The frames of `frames` that still need rendering, in order: those without a non-empty image
// in `scene_dir` that is at least as new as the scene (its marker file, scene.pov and
// scene.ini). Images are renamed into place complete, so such an image is a finished frame,
// whichever run, task or machine made it; this is what makes a local render and a farm run
// resumable. An image older than the scene is one of an earlier scene, which povgen carries
// over when it rewrites the directory: its frame is rendered again, as make would.
std::vector<long> frames_without_image(const std::filesystem::path& scene_dir,
                                       const SceneFrames& scene, const std::vector<long>& frames);

// Called after each frame: frames done, total, seconds since the start.
using RenderProgressFn = std::function<void(std::size_t, std::size_t, double)>;

// POV-Ray processes a local render runs by default: four a core, as each idles much of the time
// and parses on one thread. Each holds a parsed frame: fewer (--jobs) where memory is short.
int default_render_processes();

// Frames that already have their image are skipped with `request.skip_rendered`.
// Throws InputError when the directory holds no povgen scene or the range is outside it.
// Throws InterruptedError when `request.stop` interrupted the run.
RenderReport render_frames(const RenderRequest& request, const RenderProgressFn& progress);

// Renders the request's frames in one POV-Ray process over the range (+SF/+EF): POV-Ray's start-up
// is paid once, not per frame. This is what a render-farm task runs. `request.jobs` is ignored
// (POV-Ray gets every core), and so is `request.skip_rendered`: every frame of the request is
// rendered (the farm chose them with frames_without_image). Images are published as in
// render_frames. When POV-Ray fails, the images of the frames before the failed one are kept
// (POV-Ray had moved on from them; after a signal the last image is not trusted), the failed frame
// is reported with POV-Ray's message and its log, and a new process takes the frames after it;
// render_frames does the same per range.
RenderReport render_frames_in_one_process(const RenderRequest& request,
                                          const RenderProgressFn& progress);

// The error lines of a POV-Ray log: lines mentioning an error, else its last line.
std::string povray_error_message(const std::string& log);

}  // namespace toonwater
