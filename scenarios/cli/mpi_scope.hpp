#pragma once
// MPI for the commands that can use it (`masnet sweep` spreads runs over ranks, `masnet run`
// spreads one run's tiles): initialised only when the process was started by mpirun, mpiexec
// or srun — a plain command never touches MPI.
#include <memory>

#include "scenarios/run/run_tiles.hpp"

namespace masnet::scenarios {

class MpiScope {
 public:
  /// MPI_Init on entry when `allowed` and launched by MPI; MPI_Finalize on exit.
  explicit MpiScope(bool allowed);
  ~MpiScope();
  MpiScope(const MpiScope&) = delete;
  MpiScope& operator=(const MpiScope&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Whether every rank runs on this host (collective: every rank must call it).
  bool all_on_one_host() const { return this_host().ranks == size_; }
  /// The ranks on this rank's host, and the processors they may run on together (the union of
  /// their affinity masks: mpirun binds each rank to its own). Collective.
  struct Host {
    int ranks = 1, processors = 1;
  };
  Host this_host() const;
  /// Whether `ok_here` holds on every rank (collective).
  bool all(bool ok_here) const;
  /// The first rank's `value`, on every rank (collective).
  bool first_rank_says(bool value) const;
  /// The ranks as the link of a run cut into one tile per rank (size() > 1).
  std::unique_ptr<TileLink> tile_link() const;
  [[noreturn]] void abort(int code);

 private:
  int rank_ = 0, size_ = 1;
  bool owned_ = false;
};

}  // namespace masnet::scenarios
