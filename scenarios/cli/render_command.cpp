#include "scenarios/cli/render_command.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>

#include <CLI/CLI.hpp>

#include "scenarios/cli/command_output.hpp"
#include "scenarios/output/output_file.hpp"
#include "scenarios/report/report.hpp"

namespace masnet::cli {
using namespace masnet::scenarios;

CLI::App* add_render_subcommand(CLI::App& app, RenderArgs& args) {
  CLI::App* render = app.add_subcommand(
      "render", "redraw a run directory's figures and report from its data files");
  render->add_option("run_dir", args.dir, "run directory written by masnet run")->required();
  render->add_flag("--no-oracle-cells", args.no_oracle_cells,
                   "leave out the oracle's cells (dashed)");
  render->add_flag("--radius-circles", args.radius_circles,
                   "draw each robot's radius R_i as a circle");
  render->add_flag("--quiet", args.quiet, "print nothing");

  return render;
}

int run_render_command(const RenderArgs& args) {
  RenderOptions options;
  options.figure.oracle_cells = !args.no_oracle_cells;
  options.figure.radius_circles = args.radius_circles;
  std::optional<RunData> data;
  try {
    data = load_run_data(args.dir);
  } catch (const std::exception& e) {
    // Missing or unreadable data files: the directory given is not a (complete) run.
    std::fprintf(stderr, "masnet render: %s\n", e.what());
    return kBadInput;
  }
  std::filesystem::path report;
  try {
    report = render_run(*data, options);
  } catch (const OutputError& e) {
    std::fprintf(stderr, "masnet render: %s\n", e.what());
    return kInternalError;
  } catch (const std::filesystem::filesystem_error& e) {
    std::fprintf(stderr, "masnet render: %s\n", e.what());
    return kInternalError;
  }
  if (!args.quiet) std::printf("report: %s\n", report.string().c_str());
  return 0;
}

}  // namespace masnet::cli
