// toonwater: cartoon-style rendering of fluid-simulation output with POV-Ray.
#include "cli/commands.hpp"

#include "analyzer/atomic_file.hpp"
#include "analyzer/mesh_reader.hpp"

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
  toonwater::remove_temporaries_on_signals();  // an interrupted run leaves no temporary file
  CLI::App app{"toonwater: cartoon water from fluid-simulation meshes, rendered with POV-Ray"};
  app.require_subcommand(1);
  // Parse errors in one line, like every other error (CLI11 adds a second by default).
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "toonwater: error: " + std::string(e.what()) + " (see --help)\n";
  });
  toonwater::cli::add_analyze_command(app);
  toonwater::cli::add_povgen_command(app);
  toonwater::cli::add_render_command(app);
  toonwater::cli::add_render_task_command(app);
  toonwater::cli::add_simulate_command(app);
  toonwater::cli::add_report_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const toonwater::InputError& e) {
    std::cerr << "toonwater: error: " << e.what() << '\n';
    return 2;
  } catch (const toonwater::OutputError& e) {
    std::cerr << "toonwater: error: " << e.what() << '\n';
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "toonwater: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
