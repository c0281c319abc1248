#pragma once
// `masnet run SCENARIO [--out DIR] [--seed N] [--set KEY=VALUE]... [--force] [--quiet]
// [--baseline] [--log-level LEVEL] [--log-file FILE] [--serve ...]`: one run, its run directory
// published whole (data, figures, report) or not at all (docs/outputs.md), optionally watched
// live (docs/live-and-replay.md).
#include <string>
#include <vector>

#include "scenarios/cli/serve_option.hpp"

namespace CLI {
class App;
}

namespace masnet::cli {

struct RunArgs {
  std::string scenario;
  std::string out;
  std::vector<std::string> sets;
  std::string seed;  ///< parsed here, not by CLI11, which clamps out-of-range numbers
  bool seed_given = false;
  bool force = false;
  bool quiet = false;
  bool baseline = false;
  std::string log_level = "warn";
  std::string log_file;
  ServeArgs serve;
  unsigned tiles = 1;  ///< cut the run into this many tiles by space (docs/performance.md)
};

/// Adds the `run` subcommand to `app`, filling `args`; returns it (test `*sub` after parse).
/// After parsing, set args.seed_given from the subcommand's count("--seed").
CLI::App* add_run_subcommand(CLI::App& app, RunArgs& args);

/// Runs the command. Exit code: 0 success, 2 bad input, 1 internal error or a failed write.
int run_run_command(const RunArgs& args);

}  // namespace masnet::cli
