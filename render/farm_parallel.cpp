#include "render/farm_parallel.hpp"

#include "common/atomic_file.hpp"
#include "common/child_process.hpp"
#include "analyzer/mesh_reader.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

namespace toonwater {

namespace fs = std::filesystem;

namespace {

// Frames missing because GNU parallel could not log in to a host (ssh exits 255: an unknown
// or unreachable host, refused keys) are an output failure of the farm (exit 3), not POV-Ray's
// (5): the hosts named, from the job log's Host and Exitval columns.
void throw_if_hosts_unreachable(const fs::path& joblog, const fs::path& dir,
                                const SceneFrames& scene, const std::vector<long>& frames) {
  if (count_images(dir, scene, frames) == frames.size()) return;
  std::ifstream in(joblog);
  std::string line, unreachable;
  std::getline(in, line);  // the header
  while (std::getline(in, line)) {
    std::vector<std::string> columns;
    std::istringstream fields(line);
    for (std::string column; std::getline(fields, column, '\t');) columns.push_back(column);
    if (columns.size() < 7 || columns[6] != "255") continue;
    if (unreachable.find(" " + columns[1] + ",") == std::string::npos)
      unreachable += " " + columns[1] + ",";
  }
  if (unreachable.empty()) return;
  unreachable.pop_back();
  throw OutputError(dir.string() + ": GNU parallel could not run tasks on" + unreachable +
                    " (ssh exit status 255: unknown or unreachable host, or login refused); see " +
                    joblog.string());
}

}  // namespace

FarmReport render_on_parallel(const FarmRequest& request, const ParallelOptions& options,
                              const FarmProgressFn& progress) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = fs::absolute(request.scene_dir);
  const SceneFrames scene = read_scene_frames(dir);
  if (!fs::is_regular_file(options.hosts_file))
    throw InputError(options.hosts_file + ": no such hosts file (--hosts)");
  const auto [frames, skipped] = farm_work(request, scene);
  FarmReport report;
  report.skipped = skipped;
  if (!frames.empty()) {
    const fs::path farm = dir / ".farm";
    std::error_code ec;
    fs::create_directories(farm, ec);
    if (ec) throw OutputError("cannot create " + farm.string() + ": " + ec.message());
    const fs::path log = farm / "parallel.log";
    // GNU parallel hands the command to a shell (on the remote host over ssh): quoted here.
    const std::string task =
        shell_command({request.toonwater, "render-task", dir.string(), "--frames"}) + " {}";
    std::vector<std::string> argv{"parallel",
                                  "--will-cite",
                                  "--sshloginfile",
                                  fs::absolute(options.hosts_file).string(),
                                  "--retries",
                                  "2",
                                  "--joblog",
                                  (farm / "parallel.joblog").string(),
                                  "--results",
                                  (farm / "parallel").string() + "/",
                                  task,
                                  ":::"};
    const std::vector<FrameRange> tasks = ranges_of_at_most(frames, request.frames_per_task);
    for (const auto& t : tasks) argv.push_back(format_range(t));

    ChildSetup setup;
    setup.output_file = log.string();
    const pid_t pid = start_child_process(argv, setup);
    if (pid < 0) throw OutputError("cannot start '" + shell_command(argv) + "': fork failed");
    if (progress)
      progress("GNU parallel: " + std::to_string(tasks.size()) + " task(s) over " +
               std::to_string(frames.size()) + " frame(s) started");
    std::string last_line;
    int status = 0;
    // A stop: GNU parallel takes a first SIGTERM as "start no new job" and a second as "stop
    // the running ones" (its --termseq); SIGKILL if it is still there 30 s on.
    int terms_sent = 0;
    auto kill_deadline = std::chrono::steady_clock::time_point::max();
    for (;;) {
      if (request.stop && request.stop->load()) {
        if (terms_sent < 2) {
          ::kill(pid, SIGTERM);
          if (++terms_sent == 2)
            kill_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
        } else if (std::chrono::steady_clock::now() > kill_deadline) {
          ::kill(pid, SIGKILL);
        }
      }
      const pid_t r = ::waitpid(pid, &status, WNOHANG);
      if (r < 0 && errno != EINTR)
        throw OutputError("lost GNU parallel: " + std::string(strerror(errno)));
      if (r == pid && terms_sent > 0)
        throw InterruptedError(dir.string() +
                               ": interrupted: GNU parallel and its tasks were "
                               "stopped; the frames rendered so far are kept");
      const std::string line = "GNU parallel: " + std::to_string(count_images(dir, scene, frames)) +
                               "/" + std::to_string(frames.size()) + " frames";
      if (progress && line != last_line) progress(line);
      last_line = line;
      if (r == pid) break;
      // Polled more often while stopping, so that the second SIGTERM follows the first.
      std::this_thread::sleep_for(terms_sent ? std::chrono::duration<double>(0.1)
                                             : std::chrono::duration<double>(options.poll_seconds));
    }
    const int code = exit_status(status);
    std::ifstream log_in(log);
    std::ostringstream log_text;
    log_text << log_in.rdbuf();
    std::string message = log_text.str();
    while (!message.empty() && message.back() == '\n') message.pop_back();
    if (code == child_cannot_execute && message.empty())
      throw OutputError("cannot run '" + shell_command(argv) + "' (is GNU parallel installed?)");
    // Below 101 the exit status counts the failed jobs: their frames are reported below.
    if (code > 100)
      throw OutputError("'" + shell_command(argv) + "' failed (exit status " +
                        std::to_string(code) + "): " + message);
    remove_task_leftovers(dir);
    throw_if_hosts_unreachable(farm / "parallel.joblog", dir, scene, frames);
  }
  report.failures = missing_frames(
      dir, scene, frames,
      "the task ended without its image (task output: .farm/parallel/1/RANGE/stderr)");
  report.rendered = frames.size() - report.failures.size();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace toonwater
