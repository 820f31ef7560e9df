#include "render/farm.hpp"

#include "common/temporary_name.hpp"

#include "common/atomic_file.hpp"
#include "common/child_process.hpp"
#include "analyzer/mesh_reader.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <sstream>

namespace toonwater {

namespace fs = std::filesystem;

std::vector<long> frames_to_render(const FarmRequest& request, const SceneFrames& scene) {
  const fs::path dir = fs::absolute(request.scene_dir);
  const std::vector<long> frames = requested_frames(dir, scene, request.frames);
  return request.force ? frames : frames_without_image(dir, scene, frames);
}

FarmWork farm_work(const FarmRequest& request, const SceneFrames& scene) {
  FarmRequest all = request;
  all.force = true;
  FarmWork work;
  work.frames = frames_to_render(request, scene);
  work.skipped = frames_to_render(all, scene).size() - work.frames.size();
  return work;
}

std::size_t count_images(const fs::path& dir, const SceneFrames& scene,
                         const std::vector<long>& frames) {
  std::size_t n = 0;
  std::error_code ec;
  for (const long f : frames) n += fs::is_regular_file(frame_image_path(dir, scene, f), ec);
  return n;
}

std::vector<FrameFailure> missing_frames(const fs::path& dir, const SceneFrames& scene,
                                         const std::vector<long>& frames,
                                         const std::string& no_log_reason) {
  std::vector<FrameFailure> missing;
  std::error_code ec;
  for (const long f : frames) {
    if (fs::is_regular_file(frame_image_path(dir, scene, f), ec)) continue;
    const std::string log_name = "render_" + std::to_string(f) + ".log";
    std::ifstream log(dir / log_name);
    if (log) {
      std::ostringstream text;
      text << log.rdbuf();
      missing.push_back({f, povray_error_message(text.str()) + " (log: " + log_name + ")"});
    } else {
      missing.push_back({f, no_log_reason});
    }
  }
  return missing;
}

void remove_task_leftovers(const fs::path& dir) {
  std::error_code ec;
  std::vector<fs::path> leftovers;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    std::string made_for;
    if (is_own_temporary(name, &made_for) && made_for.starts_with("render-") &&
        entry.is_directory(ec))
      leftovers.push_back(entry.path());
  }
  for (const auto& p : leftovers) fs::remove_all(p, ec);
}

CommandOutput run_command(const std::vector<std::string>& argv) {
  CommandOutput result;
  int out_pipe[2], err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0) return {127, "", "cannot create a pipe"};
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
    ::close(out_pipe[0]);
    ::close(out_pipe[1]);
    return {127, "", "cannot create a pipe"};
  }
  ChildSetup setup;
  setup.out_fd = out_pipe[1];
  setup.err_fd = err_pipe[1];
  const pid_t pid = start_child_process(argv, setup);
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  if (pid < 0) {
    ::close(out_pipe[0]);
    ::close(err_pipe[0]);
    return {127, "", "cannot fork"};
  }
  pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
  std::string* sinks[2] = {&result.out, &result.err};
  int open_fds = 2;
  char buffer[4096];
  while (open_fds > 0) {
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t n = ::read(fds[i].fd, buffer, sizeof buffer);
      if (n > 0) {
        sinks[i]->append(buffer, static_cast<std::size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        ::close(fds[i].fd);
        fds[i].fd = -1;
        --open_fds;
      }
    }
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.status = exit_status(status);
  return result;
}

std::string shell_quote(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                              "0123456789_-+=/.,:%@") == std::string::npos)
    return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string shell_command(const std::vector<std::string>& argv) {
  std::string line;
  for (const auto& a : argv) {
    if (!line.empty()) line += ' ';
    line += shell_quote(a);
  }
  return line;
}

void write_farm_state(const fs::path& dir, const FarmState& state) {
  std::string text = "scheduler ";
  text.append(state.scheduler).append("\njob ").append(state.job_id).append("\nframes");
  for (const long f : state.frames) text.append(" ").append(std::to_string(f));
  write_file_atomically(dir / ".farm" / "job", text + "\n");
}

std::optional<FarmState> read_farm_state(const fs::path& dir) {
  std::ifstream in(dir / ".farm" / "job");
  if (!in) return std::nullopt;
  FarmState state;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "scheduler")
      words >> state.scheduler;
    else if (key == "job")
      words >> state.job_id;
    else if (key == "frames")
      for (long f; words >> f;) state.frames.push_back(f);
  }
  if (state.scheduler.empty() || state.job_id.empty())
    throw InputError((dir / ".farm" / "job").string() + ": not a farm state file");
  return state;
}

}  // namespace toonwater
