// PHOLD on the masnet kernel: N logical processes, M initial events each; every event
// schedules one new event at a uniformly random LP after an exponential delay of mean 1 s.
// Same workload, random stream and tie-break as the ns-3 peer (tests/bench/peers/phold_ns3.cc),
// so the checksum printed must equal the peer's for the same arguments.
//   masnet_bench_phold --lps=100 --m=10 --events=1e7 [--warmup=N]
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench_args.hpp"
#include "sim/random.hpp"
#include "sim/simulator.hpp"

using namespace masnet;

namespace {

struct Phold {
  sim::Simulator sim;
  sim::RandomStream rng{42};
  std::uint32_t lps;
  std::vector<std::uint64_t> per_lp;
  std::uint64_t processed = 0, warmup = 0, measured = 0;
  double t0 = 0, t1 = 0;

  std::int64_t delay_ticks() {
    const auto d =
        static_cast<std::int64_t>(-std::log(bench::unit_open_closed(rng.next_u64())) * 1e9);
    return d < 1 ? 1 : d;
  }
  std::uint32_t random_lp() {
    return static_cast<std::uint32_t>((static_cast<unsigned __int128>(rng.next_u64()) * lps) >> 64);
  }
  void handle(std::uint32_t lp) {
    ++per_lp[lp];
    ++processed;
    if (processed == warmup) t0 = bench::wall_seconds();
    if (processed == warmup + measured) {
      t1 = bench::wall_seconds();
      sim.stop();
      return;
    }
    const std::uint32_t dst = random_lp();
    sim.after(sim::Duration{delay_ticks()}, [this, dst] { handle(dst); });
  }
};

}  // namespace

int main(int argc, char** argv) {
  bench::Args args{argc, argv};
  Phold p;
  p.lps = static_cast<std::uint32_t>(args.number("lps", 100));
  const auto per_lp = static_cast<std::uint32_t>(args.number("m", 10));
  p.measured = static_cast<std::uint64_t>(args.number("events", 1e7));
  const std::uint64_t population = std::uint64_t{p.lps} * per_lp;
  p.warmup = static_cast<std::uint64_t>(
      args.number("warmup", static_cast<double>(population < 200000 ? 200000 : population)));
  p.per_lp.assign(p.lps, 0);
  p.sim.reserve(population + 16);
  for (std::uint32_t lp = 0; lp < p.lps; ++lp)
    for (std::uint32_t j = 0; j < per_lp; ++j)
      p.sim.after(sim::Duration{p.delay_ticks()}, [&p, lp] { p.handle(lp); });
  p.sim.run();
  std::uint64_t checksum = bench::kFnvBasis;
  for (std::uint64_t c : p.per_lp)
    checksum = bench::fnv_word(checksum, c);
  const double sec = p.t1 - p.t0;
  std::printf(
      "RESULT name=phold/masnet/pop=%llu metric=%.0f unit=events/s ns_per_event=%.1f sec=%.3f "
      "events=%llu lps=%u m=%u checksum=%016llx\n",
      static_cast<unsigned long long>(population), static_cast<double>(p.measured) / sec,
      sec * 1e9 / static_cast<double>(p.measured), sec, static_cast<unsigned long long>(p.measured),
      p.lps, per_lp, static_cast<unsigned long long>(checksum));
  return 0;
}
