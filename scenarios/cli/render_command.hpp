#pragma once
// `masnet render RUN_DIR [--no-oracle-cells] [--radius-circles] [--quiet]`: a run directory's
// figures and report redrawn from its data files.
#include <string>

namespace CLI {
class App;
}

namespace masnet::cli {

struct RenderArgs {
  std::string dir;
  bool no_oracle_cells = false;
  bool radius_circles = false;
  bool quiet = false;
};

/// Adds the `render` subcommand to `app`, filling `args`; returns it.
CLI::App* add_render_subcommand(CLI::App& app, RenderArgs& args);

/// Runs the command. Exit code: 0 success, 2 not a (complete) run directory, 1 a failed write.
int run_render_command(const RenderArgs& args);

}  // namespace masnet::cli
