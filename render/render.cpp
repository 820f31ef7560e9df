#include "render/render.hpp"

#include "common/atomic_file.hpp"
#include "common/temporary_name.hpp"
#include "analyzer/mesh_reader.hpp"
#include "pipeline/scene_directory.hpp"
#include "render/frame_ranges.hpp"
#include "render/supervised_process.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>
#include <string_view>
#include <thread>

namespace toonwater {
namespace {

namespace fs = std::filesystem;

// More frames than any sequence povgen writes (simulate makes at most 100,000).
constexpr long largest_frame_count = 10'000'000;

// povgen records the scene's frame rate in a comment of scene.ini, which POV-Ray ignores
// (scene_writer.cpp); a scene.ini without it plays at default_frame_rate.
constexpr std::string_view frame_rate_line = "; Frame_Rate=";

SceneFrames read_ini_frames(const fs::path& ini) {
  std::ifstream in(ini);
  if (!in) throw InputError(ini.string() + ": no povgen scene here (scene.ini missing)");
  SceneFrames f;
  bool has_first = false, has_last = false;
  const auto whole_number = [&](const std::string& text, const char* what) {
    long n = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), n);
    if (error != std::errc{} || end != text.data() + text.size())
      throw InputError(ini.string() + ": malformed " + what + " '" + text.substr(0, 20) + "'");
    return n;
  };
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("Initial_Frame=", 0) == 0) {
      f.first = whole_number(line.substr(14), "frame number");
      has_first = true;
    }
    if (line.rfind("Final_Frame=", 0) == 0) {
      f.last = whole_number(line.substr(12), "frame number");
      has_last = true;
    }
    if (line.rfind(frame_rate_line, 0) == 0) {
      const long fps = whole_number(line.substr(frame_rate_line.size()), "frame rate");
      if (fps < 1 || fps > max_frame_rate)
        throw InputError(ini.string() + ": frame rate " + std::to_string(fps) +
                         " is not from 1 to " + std::to_string(max_frame_rate));
      f.frame_rate = static_cast<int>(fps);
    }
    if (line.rfind("Output_File_Name=\"", 0) == 0 && line.size() > 19 && line.back() == '"')
      f.output_name = line.substr(18, line.size() - 19);
  }
  // Images go into the scene directory and nowhere else: an edited scene.ini that names a path
  // ("../x", "/tmp/x", "sub/x") would have render publish, and replace, files outside it.
  const std::string& name = f.output_name;
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos ||
      std::any_of(name.begin(), name.end(), [](unsigned char c) { return c < 32 || c == 127; }))
    throw InputError(ini.string() +
                     ": Output_File_Name must be a file name in the scene directory, "
                     "without a directory or control characters");
  f.animation = has_first && has_last;
  // An edited or foreign scene.ini: a range that renders nothing would be a false success, and
  // one of billions of frames would be planned (and its memory taken) before any is rendered.
  if (f.animation && !(f.first <= f.last &&
                       static_cast<unsigned long>(f.last) - static_cast<unsigned long>(f.first) <
                           largest_frame_count))
    throw InputError(ini.string() + ": frames " + std::to_string(f.first) + "-" +
                     std::to_string(f.last) + " are not a range of 1 to " +
                     std::to_string(largest_frame_count) + " frames");
  return f;
}

bool stop_requested(const std::atomic<bool>* stop) { return stop && stop->load(); }

// Runs one povray process in `dir` with its output in `log`; returns its exit status.
int run_povray(const fs::path& dir, const std::vector<std::string>& args, const fs::path& log,
               const std::atomic<bool>* stop, const std::function<bool()>& tick) {
  ChildSetup setup;
  setup.working_directory = dir.string();
  setup.output_file = log.string();
  return run_supervised(args, setup, stop, tick);
}

// Why a run that exited with `status` failed: its exit status (a signal above 128, as
// run_supervised reports it), then the log's error lines when it has any.
std::string povray_failure(int status, const std::string& log) {
  std::string reason = status > 128 ? "POV-Ray was killed by signal " + std::to_string(status - 128)
                                    : "POV-Ray exited with status " + std::to_string(status);
  const std::string message = povray_error_message(log);
  return message.empty() ? reason : reason + ": " + message;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path checked_scene_dir(const fs::path& scene_dir) {
  const fs::path dir = fs::absolute(scene_dir);
  if (!fs::is_regular_file(dir / "scene.pov"))
    throw InputError(dir.string() + ": no povgen scene here (scene.pov missing)");
  // render writes images and logs into the directory: only into one povgen wrote.
  if (!fs::is_regular_file(dir / scene_marker))
    throw InputError(dir.string() + ": not a scene directory povgen wrote (no " +
                     std::string(scene_marker) + "); run toonwater povgen --out there first");
  return dir;
}

// Render writes images and logs into the scene directory: one it cannot write (read-only, a
// read-only mount, another user's) is an output failure found before any POV-Ray starts, not
// a failure of every frame.
void check_writable(const fs::path& dir) {
  const fs::path probe = dir / temporary_name("render-probe");
  std::error_code ec;
  if (!fs::create_directory(probe, ec) && !ec) ec = std::make_error_code(std::errc::file_exists);
  if (ec)
    throw OutputError(dir.string() + ": cannot write into the scene directory: " + ec.message());
  fs::remove(probe, ec);
}

// Whether `image` is a whole PNG file: it ends with the IEND chunk, which a PNG writer writes
// last (an empty chunk: length 0, type IEND, its CRC). A file still being written ends elsewhere.
bool is_whole_png(const fs::path& image) {
  static constexpr unsigned char iend[12] = {0,   0,   0,    0,    'I',  'E',
                                             'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  const int fd = ::open(image.c_str(), O_RDONLY);
  if (fd < 0) return false;
  unsigned char tail[sizeof iend];
  const off_t size = ::lseek(fd, 0, SEEK_END);
  const bool whole = size >= static_cast<off_t>(8 + sizeof iend) &&
                     ::pread(fd, tail, sizeof tail, size - static_cast<off_t>(sizeof tail)) ==
                         static_cast<ssize_t>(sizeof tail) &&
                     std::equal(std::begin(tail), std::end(tail), std::begin(iend));
  ::close(fd);
  return whole;
}

std::string povray_threads(int jobs) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  return "+WT" + std::to_string(std::max(1u, cores / static_cast<unsigned>(jobs)));
}

}  // namespace

SceneFrames read_scene_frames(const fs::path& scene_dir) {
  return read_ini_frames(checked_scene_dir(scene_dir) / "scene.ini");
}

std::vector<long> requested_frames(const fs::path& dir, const SceneFrames& ini,
                                   const std::optional<FrameRange>& range) {
  if (!ini.animation) return {0};
  long first = ini.first, last = ini.last;
  if (range) {
    if (range->first < ini.first || range->last > ini.last)
      throw InputError(dir.string() + ": frames " + std::to_string(range->first) + "-" +
                       std::to_string(range->last) + " are outside the scene's " +
                       std::to_string(ini.first) + "-" + std::to_string(ini.last));
    first = range->first;
    last = range->last;
  }
  std::vector<long> frames;
  for (long f = first; f <= last; ++f) frames.push_back(f);
  return frames;
}

fs::path frame_image_path(const fs::path& scene_dir, const SceneFrames& frames, long frame) {
  if (!frames.animation) return scene_dir / frames.output_name;
  // POV-Ray pads the frame number to the digits of the final frame.
  std::string number = std::to_string(frame);
  const std::size_t digits = std::to_string(frames.last).size();
  if (number.size() < digits) number.insert(0, digits - number.size(), '0');
  return scene_dir / (frames.output_name + number + ".png");
}

std::string povray_error_message(const std::string& log) {
  std::istringstream in(log);
  std::string message, last;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    last = line;
    if (line.find("rror") != std::string::npos) message += (message.empty() ? "" : " | ") + line;
  }
  return message.empty() ? last : message;
}

namespace {

// What every POV-Ray process of a run shares.
struct RangeRun {
  const RenderRequest* request = nullptr;
  fs::path dir;
  SceneFrames ini;
  std::string threads;  // +WTn
};

// POV-Ray's front end gives up when its worker thread has not started within three seconds, as
// on a loaded machine (vfeSession::Initialize's vfeInitializeTimedOut): nothing was rendered,
// and the same command run again works. Such a start is tried again, after a pause that grows,
// this many times before its frame counts as failed.
constexpr int kPovrayStartRetries = 3;
constexpr std::string_view kPovrayStartTimedOut = "Timed out waiting for worker thread startup";

// Called once per frame: when its image is in place (failure empty) or it failed.
using FrameDoneFn = std::function<void(long frame, const std::string& failure)>;

// Renders `frames` (consecutive) with one POV-Ray process over the range (+SF/+EF), into a
// hidden temporary directory of DIR. A frame's image is complete once POV-Ray has written the
// next frame's image (it renders and writes the frames in order), once it is a whole PNG, or
// once POV-Ray has exited with status 0; then it is renamed into DIR, so DIR only ever holds
// complete images, and `done` is called. Once every image is published POV-Ray is killed rather
// than waited for through its shut-down. When POV-Ray fails, the frame after the last complete
// image failed (after a signal, or when every image is there but the last is not a whole PNG,
// the last image is not trusted and that frame failed); its log is kept
// as render_N.log and a new process takes the frames after it. A process whose threads did not
// start is run again (kPovrayStartRetries). Stops when the request's stop flag is set: the
// running process is terminated and its unpublished images are removed.
void render_range(const RangeRun& run, const std::vector<long>& frames, const FrameDoneFn& done) {
  const RenderRequest& request = *run.request;
  std::size_t next = 0;
  int start_retries = 0;
  while (next < frames.size() && !stop_requested(request.stop)) {
    const long first = frames[next], last = frames.back();
    const std::string work_name =
        temporary_name("render-" + std::to_string(first) + "-" + std::to_string(last));
    const fs::path work = run.dir / work_name, log = work / "render.log";
    std::error_code ec;
    if (!fs::create_directory(work, ec) && !ec) ec = std::make_error_code(std::errc::file_exists);
    if (ec) {
      for (std::size_t i = next; i < frames.size(); ++i)
        done(frames[i], "cannot create " + work.string() + ": " + ec.message());
      return;
    }
    // Frames [next, published) are in DIR.
    std::size_t published = next;
    auto publish = [&](std::size_t i) {
      const fs::path image = frame_image_path(work, run.ini, frames[i]);
      std::error_code e;
      std::string failure;
      // A full disk can leave an empty file behind a zero exit status.
      if (fs::file_size(image, e) == 0 || e)
        failure = "POV-Ray wrote an empty image";
      else
        fs::rename(image, frame_image_path(run.dir, run.ini, frames[i]), e);
      if (failure.empty() && e)
        failure = "cannot move " + image.string() + " into place: " + e.message();
      if (failure.empty())
        fs::remove(run.dir / ("render_" + std::to_string(frames[i]) + ".log"), e);
      done(frames[i], failure);
    };
    auto has_image = [&](std::size_t i) {
      std::error_code e;
      return fs::is_regular_file(frame_image_path(work, run.ini, frames[i]), e);
    };
    // Frame i's image is complete once the next frame's image is there, or once it is a whole
    // PNG: then POV-Ray is done with it (it writes an image only when its frame is finished,
    // never on a cancel).
    auto is_complete = [&](std::size_t i) {
      return (i + 1 < frames.size() && has_image(i + 1)) ||
             is_whole_png(frame_image_path(work, run.ini, frames[i]));
    };
    // Publishes the complete images; true once every frame's image is published, when POV-Ray
    // has nothing left to do but shut down (about 0.4 s of idle wall time, which would be the
    // tail of a run): it is killed instead.
    auto publish_finished = [&] {
      while (published < frames.size() && is_complete(published)) publish(published++);
      return published == frames.size();
    };
    std::vector<std::string> args{request.povray, "scene.ini", run.threads,
                                  "+O" + work_name + "/" + run.ini.output_name};
    if (run.ini.animation) {
      args.push_back("+SF" + std::to_string(first));
      args.push_back("+EF" + std::to_string(last));
    }
    args.insert(args.end(), request.extra_arguments.begin(), request.extra_arguments.end());
    const int status = run_povray(run.dir, args, log, request.stop, publish_finished);
    if (stop_requested(request.stop)) {
      fs::remove_all(work, ec);  // interrupted: nothing unpublished of this run stays
      return;
    }
    if (status > 0 && status < 128 && published == next && !has_image(next) &&
        start_retries < kPovrayStartRetries &&
        read_all(log).find(kPovrayStartTimedOut) != std::string::npos) {
      ++start_retries;
      fs::remove_all(work, ec);
      std::this_thread::sleep_for(std::chrono::milliseconds(250 * start_retries));
      continue;
    }
    publish_finished();
    std::size_t end = published;  // the first frame without an image
    while (end < frames.size() && has_image(end)) ++end;
    if (status != 0 && (status >= 128 || end == frames.size()) && end > published) --end;
    while (published < end) publish(published++);
    if (end < frames.size()) {  // frames[end] failed
      std::string failure;
      if (status == child_cannot_execute)
        failure = "cannot run '" + request.povray + "' (is POV-Ray installed?)";
      else if (status == child_cannot_write_output)
        failure = "cannot write " + log.string();
      else if (status == child_cannot_enter_directory)
        failure = "cannot enter " + run.dir.string();
      else if (status != 0)
        failure = povray_failure(status, read_all(log));
      else
        failure = "POV-Ray wrote no image";
      const fs::path kept_log = run.dir / ("render_" + std::to_string(frames[end]) + ".log");
      fs::rename(log, kept_log, ec);
      done(frames[end], ec ? failure : failure + " (log: " + kept_log.filename().string() + ")");
      ++end;
    }
    fs::remove_all(work, ec);
    next = end;
  }
}

// Frames done and failed, shared by the processes of a run.
class RunReport {
 public:
  RunReport(std::size_t total, const RenderProgressFn& progress)
      : total_(total), progress_(progress), start_(std::chrono::steady_clock::now()) {}
  void done(long frame, const std::string& failure) {
    std::lock_guard lock(mutex_);
    if (failure.empty())
      ++report_.rendered;
    else
      report_.failures.push_back({frame, failure});
    ++done_;
    if (progress_) progress_(done_, total_, elapsed());
  }
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  RenderReport finish() {
    std::sort(report_.failures.begin(), report_.failures.end(),
              [](const FrameFailure& a, const FrameFailure& b) { return a.frame < b.frame; });
    report_.seconds = elapsed();
    return report_;
  }
  std::size_t rendered() const { return report_.rendered; }

 private:
  std::size_t total_, done_ = 0;
  const RenderProgressFn& progress_;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  RenderReport report_;
};

// When the scene in `scene_dir` was last written: the newest of the files povgen writes for
// every scene (a hand edit of scene.pov or scene.ini counts too).
fs::file_time_type scene_written(const fs::path& scene_dir) {
  fs::file_time_type newest = fs::file_time_type::min();
  for (const char* name : {scene_marker, "scene.pov", "scene.ini"}) {
    std::error_code ec;
    const fs::file_time_type written = fs::last_write_time(scene_dir / name, ec);
    if (!ec) newest = std::max(newest, written);
  }
  return newest;
}

}  // namespace

std::vector<long> frames_without_image(const fs::path& scene_dir, const SceneFrames& scene,
                                       const std::vector<long>& frames) {
  const fs::file_time_type scene_time = scene_written(scene_dir);
  std::vector<long> missing;
  for (const long f : frames) {
    std::error_code ec;
    const fs::path image = frame_image_path(scene_dir, scene, f);
    const bool finished = fs::is_regular_file(image, ec) && fs::file_size(image, ec) > 0 &&
                          fs::last_write_time(image, ec) >= scene_time && !ec;
    if (!finished) missing.push_back(f);
  }
  return missing;
}

int default_render_processes() {
  return 4 * static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

RenderReport render_frames(const RenderRequest& request, const RenderProgressFn& progress) {
  RangeRun run;
  run.request = &request;
  run.dir = checked_scene_dir(request.scene_dir);
  run.ini = read_ini_frames(run.dir / "scene.ini");
  remove_stale_temporaries(run.dir);  // frames of runs that were killed
  const std::vector<long> requested = requested_frames(run.dir, run.ini, request.frames);
  const std::vector<long> frames =
      request.skip_rendered ? frames_without_image(run.dir, run.ini, requested) : requested;
  if (!frames.empty()) check_writable(run.dir);
  const std::vector<FrameRange> ranges = ranges_for_processes(frames, request.jobs);
  // With gaps (frames that have their image) there can be more ranges than processes: each
  // process takes the next range when it is done.
  const std::size_t processes =
      std::clamp<std::size_t>(static_cast<std::size_t>(std::max(request.jobs, 1)), 1,
                              std::max<std::size_t>(ranges.size(), 1));
  run.threads = povray_threads(static_cast<int>(processes));

  RunReport report(frames.size(), progress);
  const FrameDoneFn done = [&](long frame, const std::string& failure) {
    report.done(frame, failure);
  };
  std::atomic<std::size_t> next_range{0};
  auto work = [&] {
    for (std::size_t r = next_range++; r < ranges.size(); r = next_range++)
      render_range(run, frames_in(ranges[r]), done);
  };
  {
    std::vector<std::jthread> pool;
    for (std::size_t p = 1; p < processes; ++p) pool.emplace_back(work);
    work();
  }
  if (stop_requested(request.stop))
    throw InterruptedError(run.dir.string() + ": interrupted after " +
                           std::to_string(report.rendered()) + " of " +
                           std::to_string(frames.size()) + " frame(s)");
  RenderReport done_report = report.finish();
  done_report.skipped = requested.size() - frames.size();
  return done_report;
}

RenderReport render_frames_in_one_process(const RenderRequest& request,
                                          const RenderProgressFn& progress) {
  RangeRun run;
  run.request = &request;
  run.dir = checked_scene_dir(request.scene_dir);
  run.ini = read_ini_frames(run.dir / "scene.ini");
  run.threads = povray_threads(1);
  const std::vector<long> frames = requested_frames(run.dir, run.ini, request.frames);
  if (!frames.empty()) check_writable(run.dir);
  RunReport report(frames.size(), progress);
  render_range(run, frames,
               [&](long frame, const std::string& failure) { report.done(frame, failure); });
  if (stop_requested(request.stop))
    throw OutputError(run.dir.string() + ": interrupted after " +
                      std::to_string(report.rendered()) + " of " + std::to_string(frames.size()) +
                      " frame(s)");
  return report.finish();
}

}  // namespace toonwater
