// toonwater: cartoon-style rendering of fluid-simulation output with POV-Ray.
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/progress.hpp"

#include "common/atomic_file.hpp"
#include "common/large_arrays.hpp"
#include "analyzer/mesh_reader.hpp"
#include "analyzer/readers/vdb/level_set_module.hpp"
#include "images/image_codec.hpp"
#include "povgen/config.hpp"
#include "povgen/render.hpp"

#include <csignal>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include <unistd.h>

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


// OpenMP threads sleep soon after a parallel loop unless OMP_WAIT_POLICY or GOMP_SPINCOUNT says
// otherwise. libgomp's default keeps each idle thread spinning for about a millisecond after
// every loop, and an analysis runs dozens of short loops: on a machine shared with other work
// that spinning took the core from the thread with work to do (a 55k-vertex analyze took 4.5×
// the wall time and 3× the CPU time of OMP_WAIT_POLICY=passive, measured side by side). libgomp
// reads its environment once, as it is loaded, before any of the program's code runs (glibc
// resets the environment after an executable's preinit functions): so the program starts itself
// again with the policy set, at the cost of one more program start (about 3 ms).
void default_to_passive_wait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (::setenv("OMP_WAIT_POLICY", "passive", 0) != 0) return;
  ::execv("/proc/self/exe", argv);  // returns only on failure: then run with libgomp's default
}

std::string subcommand_names(const CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands({}))
    names += (names.empty() ? "" : ", ") + sub->get_name();
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  default_to_passive_wait(argv);
  toonwater::remove_temporaries_on_signals();  // an interrupted run leaves no temporary file
  // A closed standard error or output is a failed write, not an end (cli/stop_signals.hpp).
  std::signal(SIGPIPE, SIG_IGN);
  toonwater::keep_large_arrays_in_the_heap();     // analyze and every povgen frame reuse pages
  CLI::App app{"toonwater: cartoon water from fluid-simulation meshes, rendered with POV-Ray"};
  app.name("toonwater");
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("toonwater ") + TOONWATER_VERSION);
  app.footer("Run `toonwater help SUBCOMMAND` or `toonwater SUBCOMMAND --help` for its options.\n"
             "Exit codes: 0 success, 2 bad input, 3 output failure, 4 interrupted, "
             "5 POV-Ray failed, 6 image module missing, 1 internal error.");
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
      return fail("unknown subcommand '" + printable(topic) + "' (subcommands: " +
                      subcommand_names(app) + ")",
                  exit_code::bad_input);
    }
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) known = known || sub->get_name() == word;
    if (!known)
      return fail("unknown subcommand '" + printable(word) + "' (subcommands: " +
                      subcommand_names(app) + "; see --help)",
                  exit_code::bad_input);
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" that exit 0; every other one is bad input.
    return app.exit(e) == 0 ? exit_code::success : exit_code::bad_input;
  } catch (const toonwater::InputError& e) {
    return fail(e.what(), exit_code::bad_input);
  } catch (const toonwater::povgen::ConfigError& e) {
    return fail(e.what(), exit_code::bad_input);
  } catch (const toonwater::InterruptedError& e) {
    return fail(e.what(), exit_code::interrupted);
  } catch (const toonwater::OutputError& e) {
    return fail(e.what(), exit_code::output_failed);
  } catch (const toonwater::povgen::PovrayError& e) {
    return fail(e.what(), exit_code::povray_failed);
  } catch (const toonwater::LevelSetModuleError& e) {
    return fail(e.what(), exit_code::incomplete_install);
  } catch (const toonwater::ImageModuleError& e) {
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
