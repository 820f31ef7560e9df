#include "povgen/render.hpp"

#include "analyzer/atomic_file.hpp"
#include "analyzer/mesh_reader.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

namespace toonwater::povgen {
namespace {

namespace fs = std::filesystem;

SceneFrames read_ini_frames(const fs::path& ini) {
  std::ifstream in(ini);
  if (!in) throw InputError(ini.string() + ": no povgen scene here (scene.ini missing)");
  SceneFrames f;
  bool has_first = false, has_last = false;
  const auto frame_number = [&](const std::string& text) {
    long n = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), n);
    if (error != std::errc{} || end != text.data() + text.size())
      throw InputError(ini.string() + ": malformed frame number '" + text.substr(0, 20) + "'");
    return n;
  };
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("Initial_Frame=", 0) == 0) {
      f.first = frame_number(line.substr(14));
      has_first = true;
    }
    if (line.rfind("Final_Frame=", 0) == 0) {
      f.last = frame_number(line.substr(12));
      has_last = true;
    }
    if (line.rfind("Output_File_Name=\"", 0) == 0 && line.size() > 19 && line.back() == '"')
      f.output_name = line.substr(18, line.size() - 19);
  }
  f.animation = has_first && has_last;
  return f;
}

bool stop_requested(const std::atomic<bool>* stop) { return stop && stop->load(); }

// Waits for `pid`; once `stop` is set, terminates it (SIGTERM, then SIGKILL if it lingers).
int wait_for(pid_t pid, const std::atomic<bool>* stop) {
  using namespace std::chrono_literals;
  int status = 0;
  auto deadline = std::chrono::steady_clock::time_point::max();
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, stop ? WNOHANG : 0);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) return -1;
    if (r == 0) {
      const auto now = std::chrono::steady_clock::now();
      if (stop_requested(stop) && deadline == std::chrono::steady_clock::time_point::max()) {
        ::kill(pid, SIGTERM);
        deadline = now + 10s;
      } else if (now > deadline) {
        ::kill(pid, SIGKILL);
      }
      std::this_thread::sleep_for(20ms);
    }
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Exit statuses of the forked child before it becomes POV-Ray (the shell's conventions).
constexpr int cannot_write_log = 125, cannot_enter_directory = 126, cannot_execute = 127;

// Runs one povray process in `dir` with its output in `log`; returns its exit status.
int run_povray(const fs::path& dir, const std::vector<std::string>& args, const fs::path& log,
               const std::atomic<bool>* stop) {
  std::vector<std::string> copies = args;
  std::vector<char*> argv;
  for (auto& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string dir_s = dir.string(), log_s = log.string();
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    const int fd = ::open(log_s.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) ::_exit(cannot_write_log);
    if (::chdir(dir_s.c_str()) != 0) ::_exit(cannot_enter_directory);
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
    ::execvp(argv[0], argv.data());
    ::_exit(cannot_execute);
  }
  return wait_for(pid, stop);
}

// Renames the images POV-Ray wrote into `work` to `dir`; an error message, or "" on success.
std::string publish_images(const fs::path& work, const fs::path& dir, const fs::path& log) {
  std::error_code ec;
  std::size_t images = 0;
  for (const auto& entry : fs::directory_iterator(work, ec)) {
    if (entry.path() == log || !entry.is_regular_file()) continue;
    // A full disk can leave an empty file behind a zero exit status.
    if (entry.file_size(ec) == 0 || ec) return "POV-Ray wrote an empty image";
    fs::rename(entry.path(), dir / entry.path().filename(), ec);
    if (ec) return "cannot move " + entry.path().string() + " into place: " + ec.message();
    ++images;
  }
  if (ec) return "cannot list " + work.string() + ": " + ec.message();
  return images == 0 ? "POV-Ray wrote no image" : "";
}

// Why a run that exited with `status` failed: its exit status (a signal above 128, as
// wait_for reports it), then the log's error lines when it has any.
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
  return dir;
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

RenderReport render_frames(const RenderRequest& request, const RenderProgressFn& progress) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = checked_scene_dir(request.scene_dir);
  const SceneFrames ini = read_ini_frames(dir / "scene.ini");
  remove_stale_temporaries(dir);  // frames of runs that were killed
  const std::vector<long> frames = requested_frames(dir, ini, request.frames);

  const int jobs = std::clamp<int>(request.jobs, 1, static_cast<int>(frames.size()));
  const std::string threads = povray_threads(jobs);

  RenderReport report;
  std::mutex mutex;
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;
  auto worker = [&] {
    for (std::size_t i; !stop_requested(request.stop) && (i = next++) < frames.size();) {
      const long frame = frames[i];
      // The frame's image and log go to a temporary directory first (see render.hpp).
      const std::string work_name =
          ".render-" + std::to_string(frame) + ".tmp-" + std::to_string(::getpid());
      const fs::path work = dir / work_name, log = work / "render.log";
      const fs::path kept_log = dir / ("render_" + std::to_string(frame) + ".log");
      std::error_code ec;
      fs::remove_all(work, ec);
      fs::create_directory(work, ec);
      std::vector<std::string> args{request.povray, "scene.ini", threads,
                                    "+O" + work_name + "/" + ini.output_name};
      if (ini.animation) {
        args.push_back("+SF" + std::to_string(frame));
        args.push_back("+EF" + std::to_string(frame));
      }
      args.insert(args.end(), request.extra_arguments.begin(), request.extra_arguments.end());
      std::string failure;
      const int status = ec ? -1 : run_povray(dir, args, log, request.stop);
      if (stop_requested(request.stop)) {
        fs::remove_all(work, ec);  // interrupted: nothing of this frame stays
        break;
      }
      if (ec) failure = "cannot create " + work.string() + ": " + ec.message();
      else if (status == cannot_execute)
        failure = "cannot run '" + request.povray + "' (is POV-Ray installed?)";
      else if (status == cannot_write_log) failure = "cannot write " + log.string();
      else if (status == cannot_enter_directory) failure = "cannot enter " + dir.string();
      else if (status != 0) failure = povray_failure(status, read_all(log));
      else failure = publish_images(work, dir, log);
      bool log_kept = false;
      if (failure.empty()) {
        fs::remove(kept_log, ec);
      } else if (fs::exists(log, ec)) {
        fs::rename(log, kept_log, ec);
        log_kept = !ec;
      }
      fs::remove_all(work, ec);
      std::lock_guard lock(mutex);
      if (failure.empty()) ++report.rendered;
      else report.failures.push_back(
          {frame, log_kept ? failure + " (log: " + kept_log.filename().string() + ")" : failure});
      ++done;
      if (progress)
        progress(done, frames.size(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
  };
  {
    std::vector<std::jthread> pool;
    for (int j = 1; j < jobs; ++j) pool.emplace_back(worker);
    worker();
  }
  if (stop_requested(request.stop))
    throw InterruptedError(dir.string() + ": interrupted after " + std::to_string(report.rendered) +
                      " of " + std::to_string(frames.size()) + " frame(s)");
  std::sort(report.failures.begin(), report.failures.end(),
            [](const FrameFailure& a, const FrameFailure& b) { return a.frame < b.frame; });
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

RenderReport render_frames_in_one_process(const RenderRequest& request,
                                          const RenderProgressFn& progress) {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const fs::path dir = checked_scene_dir(request.scene_dir);
  const SceneFrames ini = read_ini_frames(dir / "scene.ini");
  const std::vector<long> frames = requested_frames(dir, ini, request.frames);

  RenderReport report;
  std::size_t next = 0;
  while (next < frames.size() && !stop_requested(request.stop)) {
    const long first = frames[next], last = frames.back();
    const std::string work_name = ".render-" + std::to_string(first) + "-" + std::to_string(last) +
                                  ".tmp-" + std::to_string(::getpid());
    const fs::path work = dir / work_name, log = work / "render.log";
    std::error_code ec;
    fs::remove_all(work, ec);
    fs::create_directory(work, ec);
    if (ec) throw OutputError("cannot create " + work.string() + ": " + ec.message());
    std::vector<std::string> args{request.povray, "scene.ini", povray_threads(1),
                                  "+O" + work_name + "/" + ini.output_name};
    if (ini.animation) {
      args.push_back("+SF" + std::to_string(first));
      args.push_back("+EF" + std::to_string(last));
    }
    args.insert(args.end(), request.extra_arguments.begin(), request.extra_arguments.end());
    const int status = run_povray(dir, args, log, request.stop);
    if (stop_requested(request.stop)) {
      fs::remove_all(work, ec);  // interrupted: nothing of this run stays
      break;
    }
    // The frames whose images are kept: all when POV-Ray succeeded, else those before the
    // first frame without an image, less the last one after a signal (it may be cut short) or
    // when every image is there (the failure belongs to the last frame).
    std::size_t end = next;
    while (end < frames.size() && fs::is_regular_file(frame_image_path(work, ini, frames[end])))
      ++end;
    if (status != 0 && (status >= 128 || end == frames.size()) && end > next) --end;
    for (std::size_t i = next; i < end; ++i) {
      const fs::path image = frame_image_path(work, ini, frames[i]);
      fs::rename(image, dir / image.filename(), ec);
      if (ec) throw OutputError("cannot move " + image.string() + " into place: " + ec.message());
      fs::remove(dir / ("render_" + std::to_string(frames[i]) + ".log"), ec);
      ++report.rendered;
    }
    if (end < frames.size()) {  // frames[end] failed
      std::string failure;
      if (status == 127) failure = "cannot run '" + request.povray + "' (is POV-Ray installed?)";
      else if (status != 0) failure = povray_error_message(read_all(log));
      else failure = "POV-Ray wrote no image";
      const long frame = frames[end];
      const fs::path kept_log = dir / ("render_" + std::to_string(frame) + ".log");
      fs::rename(log, kept_log, ec);
      report.failures.push_back({frame, failure + " (log: " + kept_log.filename().string() + ")"});
      ++end;
    }
    fs::remove_all(work, ec);
    next = end;
    if (progress) progress(next, frames.size(), elapsed());
  }
  if (stop_requested(request.stop))
    throw OutputError(dir.string() + ": interrupted after " + std::to_string(report.rendered) +
                      " of " + std::to_string(frames.size()) + " frame(s)");
  report.seconds = elapsed();
  return report;
}

}  // namespace toonwater::povgen
