// What a window of a partitioned run costs in synchronisation (sim/windowed_run.hpp): parts
// that each run one event per lookahead, so that every window has work and none is skipped.
//   masnet_bench_windows --threads=2 --parts=2 --windows=1e6
#include <cstdio>
#include <memory>
#include <vector>

#include "bench_args.hpp"
#include "sim/windowed_run.hpp"
#include "ticker.hpp"

using namespace masnet;

using bench::Ticker;

int main(int argc, char** argv) {
  const bench::Args args{argc, argv};
  const auto threads = static_cast<unsigned>(args.number("threads", 2));
  const auto part_count = static_cast<std::size_t>(args.number("parts", 2));
  const auto windows = static_cast<std::int64_t>(args.number("windows", 1e6));
  std::vector<std::unique_ptr<Ticker>> parts;
  std::vector<sim::Simulator*> simulators;
  for (std::size_t p = 0; p < part_count; ++p) {
    parts.push_back(std::make_unique<Ticker>());
    Ticker& t = *parts.back();
    t.sim.order_ties_by_origin();
    t.sim.at(sim::kTimeZero, [&t] { t.tick(); });
    simulators.push_back(&t.sim);
  }
  sim::WindowedRun run(simulators, sim::Duration{1000}, threads);
  const double t0 = bench::wall_seconds();
  run.run_until(sim::kTimeZero + sim::Duration{1000 * (windows - 1)}, [](sim::Time) {});
  const double sec = bench::wall_seconds() - t0;
  std::printf("RESULT name=windows/threads=%u/parts=%zu windows=%llu us_per_window=%.3f sec=%.3f\n",
              run.threads(), part_count, static_cast<unsigned long long>(run.windows()),
              sec * 1e6 / static_cast<double>(run.windows()), sec);
  return 0;
}
