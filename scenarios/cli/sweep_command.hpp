#pragma once
// `masnet sweep SWEEP.yaml [--jobs N] [--out DIR] [--force] [--list] [--quiet] [--no-mpi]`
// (docs/sweeps.md). Runs spread over --jobs threads; launched under mpirun or srun
// (and built with MPI), also over the ranks, rank 0 writing every output.
#include <string>

namespace CLI {
class App;
}

namespace masnet::scenarios {

struct SweepArgs {
  std::string file;     ///< the sweep file
  int jobs = 0;         ///< worker threads per process; 0: all cores, or 1 per MPI rank
  std::string out;      ///< results folder; empty: the file's output.dir
  bool force = false;   ///< discard earlier results in the folder and run everything
  bool list = false;    ///< print the runs (index, id, parameters) and run nothing
  bool quiet = false;   ///< no progress line and no closing summary
  bool no_mpi = false;  ///< run locally even under mpirun
};

/// Adds the `sweep` subcommand to `app`, filling `args`; returns it (test `*sub` after parse).
CLI::App* add_sweep_subcommand(CLI::App& app, SweepArgs& args);

/// Runs the command. Exit code: 0 when every run is ok; 2 for a bad sweep file or an unusable
/// output folder (nothing written); 1 for an internal error; otherwise the number of failed
/// runs, capped at 125.
int run_sweep_command(const SweepArgs& args);

/// True when this build can spread a sweep over MPI ranks.
bool sweep_has_mpi();

}  // namespace masnet::scenarios
