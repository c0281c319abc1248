#pragma once
// `masnet validate SCENARIO [--set KEY=VALUE]...`: the checks of `run` without running, every
// problem reported.
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace masnet::cli {

struct ValidateArgs {
  std::string scenario;
  std::vector<std::string> sets;
};

/// Adds the `validate` subcommand to `app`, filling `args`; returns it.
CLI::App* add_validate_subcommand(CLI::App& app, ValidateArgs& args);

/// Runs the command. Exit code: 0 a valid scenario, 2 bad input.
int run_validate_command(const ValidateArgs& args);

}  // namespace masnet::cli
