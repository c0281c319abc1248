#include "scenarios/cli/validate_command.hpp"

#include <cstdio>
#include <optional>

#include <CLI/CLI.hpp>

#include "scenarios/cli/command_output.hpp"
#include "scenarios/loader/scenario.hpp"

namespace masnet::cli {
using namespace masnet::scenarios;

CLI::App* add_validate_subcommand(CLI::App& app, ValidateArgs& args) {
  CLI::App* validate =
      app.add_subcommand("validate", "check a scenario file and report every problem");
  validate->add_option("scenario", args.scenario, "scenario file (YAML)")->required();
  validate->add_option("--set", args.sets, "override a key before checking (repeatable)");

  return validate;
}

int run_validate_command(const ValidateArgs& args) {
  const std::string& scenario = args.scenario;
  // The same checks as `run`, but the sensors are only counted, not built.
  LoadOptions options;
  options.build_sensors = false;
  LoadResult loaded = load_scenario(scenario, args.sets, std::nullopt, options);
  if (!loaded.scenario) return print_diagnostics(loaded.diagnostics);
  print_warnings(loaded.warnings);
  const ScenarioDef& def = *loaded.scenario;
  std::printf("%s: ok (%zu sensors, %zu robots, %.3f s)\n", scenario.c_str(), def.sensor_count,
              def.world.robots.size(), def.duration_s);
  return 0;
}

}  // namespace masnet::cli
