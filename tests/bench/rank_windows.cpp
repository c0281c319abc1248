// What a window of a partitioned run costs when its parts are MPI ranks (ranks/rank_exchange.hpp):
// each rank runs one part that has one event per lookahead, so every window has work; between
// windows the ranks agree on the next window's start (one all-reduce) and swap `--bytes` bytes
// with every other rank (the counts, then the bytes: two all-to-all calls), as the tiles of a
// run would swap their frame records.
//   mpirun -np 2 masnet_bench_rank_windows --windows=1e5 --bytes=0
#include <mpi.h>

#include <cstdio>
#include <vector>

#include "bench_args.hpp"
#include "ranks/rank_exchange.hpp"
#include "sim/windowed_run.hpp"
#include "ticker.hpp"

using namespace masnet;

using bench::Ticker;

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  {
    const bench::Args args{argc, argv};
    const auto windows = static_cast<std::int64_t>(args.number("windows", 1e5));
    const auto bytes = static_cast<std::size_t>(args.number("bytes", 0));
    ranks::RankExchange ex;
    Ticker part;
    part.sim.order_ties_by_origin();
    part.sim.at(sim::kTimeZero, [&part] { part.tick(); });
    std::vector<std::vector<std::byte>> outbox(static_cast<std::size_t>(ex.size()),
                                               std::vector<std::byte>(bytes, std::byte{1}));
    std::size_t received = 0;
    sim::WindowedRun run({&part.sim}, sim::Duration{1000}, 1);
    MPI_Barrier(MPI_COMM_WORLD);
    const double t0 = bench::wall_seconds();
    run.run_until(
        sim::kTimeZero + sim::Duration{1000 * (windows - 1)},
        [&](sim::Time) {
          for (const std::vector<std::byte>& from : ex.exchange(outbox))
            received += from.size();
        },
        [&](sim::Time earliest_here) { return ex.earliest(earliest_here); });
    const double sec = bench::wall_seconds() - t0;
    if (ex.rank() == 0)
      std::printf(
          "RESULT name=rank_windows/ranks=%d windows=%llu bytes_per_pair=%zu us_per_window=%.3f "
          "sec=%.3f received=%zu\n",
          ex.size(), static_cast<unsigned long long>(run.windows()), bytes,
          sec * 1e6 / static_cast<double>(run.windows()), sec, received);
  }
  MPI_Finalize();
  return 0;
}
