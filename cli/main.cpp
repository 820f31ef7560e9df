// toonwater: cartoon-style rendering of fluid-simulation output with POV-Ray.
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/progress.hpp"

#include "common/atomic_file.hpp"
#include "common/large_arrays.hpp"
#include "analyzer/mesh_reader.hpp"
#include "analyzer/readers/vdb/vdb_module.hpp"
#include "images/image_codec.hpp"
#include "scene/config.hpp"
#include "render/render.hpp"
#include "render/video.hpp"

#include <csignal>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include <tbb/global_control.h>

namespace {

namespace exit_code = toonwater::cli::exit_code;
using toonwater::cli::printable;

// The message on one line whatever the file names in it hold: a newline or a terminal escape in
// a name shows as '?' (other bytes, such as UTF-8 names, as they are).
int fail(std::string message, int code) {
  for (char& c : message)
    if (static_cast<unsigned char>(c) < ' ' || c == '\x7f') c = '?';
  std::cerr << "toonwater: error: " << message << '\n';
  return code;
}

// Most threads the program may use, from TOONWATER_THREADS: the analysis gives the same bits
// with any number (common/parallel.hpp), so the variable only shares the cores with other work.
constexpr unsigned long most_threads = 1024;

// The limit TOONWATER_THREADS sets (0 when unset), or a one-line reason it is not a count.
struct ThreadLimit {
  std::size_t threads = 0;
  std::string error;
};

ThreadLimit thread_limit_from_environment() {
  const char* text = std::getenv("TOONWATER_THREADS");
  if (!text) return {};
  const std::string value = text;
  const bool digits = !value.empty() && value.size() <= 4 &&
                      value.find_first_not_of("0123456789") == std::string::npos;
  const unsigned long threads = digits ? std::stoul(value) : 0;
  if (threads < 1 || threads > most_threads)
    return {0, "TOONWATER_THREADS: '" + printable(value) + "' is not a thread count from 1 to " +
                   std::to_string(most_threads)};
  return {threads, {}};
}

std::string subcommand_names(const CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands({}))
    names += (names.empty() ? "" : ", ") + sub->get_name();
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  const ThreadLimit limit = thread_limit_from_environment();
  if (!limit.error.empty()) return fail(limit.error, exit_code::bad_input);
  // Held for the whole run: every parallel loop of the process stays within the limit.
  std::optional<tbb::global_control> thread_control;
  if (limit.threads > 0)
    thread_control.emplace(tbb::global_control::max_allowed_parallelism, limit.threads);
  toonwater::remove_temporaries_on_signals();  // an interrupted run leaves no temporary file
  // A closed standard error or output is a failed write, not an end (cli/stop_signals.hpp).
  std::signal(SIGPIPE, SIG_IGN);
  toonwater::set_up_heap_for_large_arrays();  // analyze and every povgen frame reuse pages
  CLI::App app{"toonwater: cartoon water from fluid-simulation meshes, rendered with POV-Ray"};
  app.name("toonwater");
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("toonwater ") + TOONWATER_VERSION);
  app.footer(
      "Run `toonwater help SUBCOMMAND` or `toonwater SUBCOMMAND --help` for its options.\n"
      "Exit codes: 0 success, 2 bad input, 3 output failure, 4 interrupted, "
      "5 POV-Ray failed, 6 incomplete installation, 1 internal error.\n"
      "TOONWATER_THREADS=N uses at most N threads (1-1024; default: every core).");
  // Parse errors in one line, like every other error (CLI11 adds a second by default).
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "toonwater: error: " + printable(e.what()) + " (see --help)\n";
  });
  toonwater::cli::add_analyze_command(app);
  toonwater::cli::add_povgen_command(app);
  toonwater::cli::add_render_command(app);
  toonwater::cli::add_render_task_command(app);
  toonwater::cli::add_simulate_command(app);
  toonwater::cli::add_report_command(app);

  // `help [SUBCOMMAND]`, and a first word that is neither an option nor a subcommand.
  if (argc >= 2 && argv[1][0] != '-') {
    const std::string word = argv[1];
    if (word == "help") {
      if (argc == 2) {
        std::cout << app.help();
        return exit_code::success;
      }
      const std::string topic = argv[2];
      for (const CLI::App* sub : app.get_subcommands({}))
        if (sub->get_name() == topic) {
          std::cout << sub->help();
          return exit_code::success;
        }
      return fail("unknown subcommand '" + printable(topic) +
                      "' (subcommands: " + subcommand_names(app) + ")",
                  exit_code::bad_input);
    }
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) known = known || sub->get_name() == word;
    if (!known)
      return fail("unknown subcommand '" + printable(word) +
                      "' (subcommands: " + subcommand_names(app) + "; see --help)",
                  exit_code::bad_input);
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" that exit 0; every other one is bad input.
    return app.exit(e) == 0 ? exit_code::success : exit_code::bad_input;
  } catch (const toonwater::InputError& e) {
    return fail(e.what(), exit_code::bad_input);
  } catch (const toonwater::ConfigError& e) {
    return fail(e.what(), exit_code::bad_input);
  } catch (const toonwater::InterruptedError& e) {
    return fail(e.what(), exit_code::interrupted);
  } catch (const toonwater::OutputError& e) {
    return fail(e.what(), exit_code::output_failed);
  } catch (const toonwater::PovrayError& e) {
    return fail(e.what(), exit_code::povray_failed);
  } catch (const toonwater::VdbModuleError& e) {
    return fail(e.what(), exit_code::incomplete_install);
  } catch (const toonwater::ImageModuleError& e) {
    return fail(e.what(), exit_code::incomplete_install);
  } catch (const toonwater::MissingProgramError& e) {
    return fail(e.what(), exit_code::incomplete_install);
  } catch (const std::filesystem::filesystem_error& e) {
    // A file operation without its own message: name the file and the reason only.
    const std::string path = e.path1().empty() ? "" : e.path1().string() + ": ";
    return fail(path + e.code().message(), exit_code::output_failed);
  } catch (const std::exception& e) {
    return fail(e.what(), exit_code::internal_error);
  }
  return exit_code::success;
}
