#include "tests/support/run_toonwater.hpp"

#include <cstdio>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <stdexcept>

namespace toonwater::test {

CommandResult run_toonwater(const std::vector<std::string>& args) {
  return run_program(TOONWATER_EXECUTABLE, args);
}

CommandResult run_program(const std::filesystem::path& executable,
                          const std::vector<std::string>& args) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    ::dup2(pipe_fds[1], STDOUT_FILENO);
    ::dup2(pipe_fds[1], STDERR_FILENO);
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    std::vector<char*> argv;
    std::string exe = executable.string();
    argv.push_back(exe.data());
    std::vector<std::string> copies = args;
    for (auto& a : copies) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(pipe_fds[1]);
  CommandResult result;
  std::array<char, 4096> buffer;
  ssize_t n;
  while ((n = ::read(pipe_fds[0], buffer.data(), buffer.size())) > 0)
    result.output.append(buffer.data(), static_cast<std::size_t>(n));
  ::close(pipe_fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

std::string libraries_the_program_loads() {
  const std::string command =
      std::string("LD_TRACE_LOADED_OBJECTS=1 '") + TOONWATER_EXECUTABLE + "' 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return "";
  std::string listed;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) listed += buffer;
  ::pclose(pipe);
  return listed;
}

}  // namespace toonwater::test
