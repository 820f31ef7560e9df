// toonwater report [--out DIR] [--quick | --full] [--data DIR]
#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "cli/validators.hpp"

#include "images/image_codec.hpp"
#include "report/report.hpp"

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

namespace toonwater::cli {
namespace {

struct ReportArgs {
  std::string out = "report";
  std::string data = "../shared/data";
  bool quick = false;
  bool full = false;
};

void run_report(const ReportArgs& args) {
  image_codec();  // the report reads renders back: a missing image module fails before any work
  report::ReportOptions options;
  options.out_dir = args.out;
  options.data_dir = args.data;
  options.size = args.quick  ? report::ReportSize::quick
                 : args.full ? report::ReportSize::full
                             : report::ReportSize::standard;
  const auto start = std::chrono::steady_clock::now();
  options.progress = [start](const std::string& line) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "report: %6.1f s  %s\n", elapsed, line.c_str());
  };
  report::write_report(options);
  std::fprintf(stderr, "report: written to %s/report.md\n", printable(args.out).c_str());
}

}  // namespace

void add_report_command(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Measure curvature error against run time and the pipeline's time per frame; "
      "write a Markdown report with plots and CSV");
  cmd->add_option("--out", args->out, "Directory for report.md, the CSV files and the plots")
      ->capture_default_str()
      ->check(NonEmptyPath);
  cmd->add_option("--data", args->data,
                  "Directory holding the sample simulations (mantaflow-wake/, blender-ocean/)")
      ->capture_default_str()
      ->check(NonEmptyPath);
  auto* quick = cmd->add_flag("--quick", args->quick, "Reduced run (up to 16k vertices), for CI");
  cmd->add_flag("--full", args->full, "Also 1M-vertex meshes")->excludes(quick);
  cmd->callback([args] { run_report(*args); });
}

}  // namespace toonwater::cli
