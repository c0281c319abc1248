// The `masnet` command line (docs/scenario-reference.md, docs/outputs.md, docs/sweeps.md): one
// subcommand per file (run_command.cpp, validate_command.cpp, render_command.cpp,
// sweep_command.cpp, protocols_command.cpp).
#include "scenarios/cli/command_line.hpp"

#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "scenarios/cli/command_output.hpp"
#include "scenarios/cli/logging_setup.hpp"
#include "scenarios/cli/protocols_command.hpp"
#include "scenarios/cli/render_command.hpp"
#include "scenarios/cli/run_command.hpp"
#include "scenarios/cli/sweep_command.hpp"
#include "scenarios/cli/validate_command.hpp"

namespace masnet::cli {

int main(int argc, char** argv) {
  CLI::App app{"masnet — discrete-event simulator of mobile actuator/sensor networks"};
  app.require_subcommand(1);
  app.set_version_flag("--version", MASNET_VERSION);

  RunArgs run_args;
  CLI::App* run = add_run_subcommand(app, run_args);
  ValidateArgs validate_args;
  CLI::App* validate = add_validate_subcommand(app, validate_args);
  RenderArgs render_args;
  CLI::App* render = add_render_subcommand(app, render_args);
  scenarios::SweepArgs sweep_args;
  CLI::App* sweep = scenarios::add_sweep_subcommand(app, sweep_args);
  ProtocolsArgs protocols_args;
  CLI::App* protocols = add_protocols_subcommand(app, protocols_args);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kBadInput;
  }
  run_args.seed_given = run->count("--seed") > 0;
  log_to_stderr();
  try {
    if (*run) return run_run_command(run_args);
    if (*validate) return run_validate_command(validate_args);
    if (*render) return run_render_command(render_args);
    if (*sweep) return scenarios::run_sweep_command(sweep_args);
    if (*protocols) return run_protocols_command(protocols_args);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "masnet: internal error: %s\n", e.what());
    return kInternalError;
  }
  return kInternalError;
}

}  // namespace masnet::cli
