#pragma once
// The PHOLD workload of the kernel benchmarks (phold.cpp on masnet's kernel, and
// phold_heap_reference.cpp on a plain heap): N logical processes, M initial events each; every
// event schedules one new event at a uniformly random LP after an exponential delay of mean 1 s.
// Same random stream and draws as the ns-3 peer (tests/bench/peers/phold_ns3.cc), so every
// kernel prints the same checksum for the same arguments.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "bench_args.hpp"
#include "sim/random.hpp"

namespace masnet::bench {

struct PholdWorkload {
  sim::RandomStream rng{42};
  std::uint32_t lps = 100, initial_per_lp = 10;
  std::vector<std::uint64_t> per_lp;
  std::uint64_t processed = 0, warmup = 0, measured = 0;
  double t0 = 0, t1 = 0;

  /// --lps, --m (initial events per LP), --events (measured), --warmup (default: the larger of
  /// the population and 200 000).
  explicit PholdWorkload(const Args& args)
      : lps(static_cast<std::uint32_t>(args.number("lps", 100))),
        initial_per_lp(static_cast<std::uint32_t>(args.number("m", 10))),
        per_lp(lps, 0),
        measured(static_cast<std::uint64_t>(args.number("events", 1e7))) {
    warmup = static_cast<std::uint64_t>(
        args.number("warmup", static_cast<double>(population() < 200000 ? 200000 : population())));
  }
  std::uint64_t population() const { return std::uint64_t{lps} * initial_per_lp; }

  std::int64_t delay_ticks() {
    const auto d = static_cast<std::int64_t>(-std::log(unit_open_closed(rng.next_u64())) * 1e9);
    return d < 1 ? 1 : d;
  }
  std::uint32_t random_lp() {
    return static_cast<std::uint32_t>((static_cast<unsigned __int128>(rng.next_u64()) * lps) >> 64);
  }
  /// Counts one event at `lp`; true when it was the last measured one (the run stops there).
  bool count(std::uint32_t lp) {
    ++per_lp[lp];
    ++processed;
    if (processed == warmup) t0 = wall_seconds();
    if (processed == warmup + measured) {
      t1 = wall_seconds();
      return true;
    }
    return false;
  }

  /// The RESULT line; `kernel` names the kernel ("masnet", "heap4-reference").
  void print_result(const char* kernel) const {
    std::uint64_t checksum = kFnvBasis;
    for (std::uint64_t c : per_lp)
      checksum = fnv_word(checksum, c);
    const double sec = t1 - t0;
    std::printf(
        "RESULT name=phold/%s/pop=%llu metric=%.0f unit=events/s ns_per_event=%.1f sec=%.3f "
        "events=%llu lps=%u m=%u checksum=%016llx\n",
        kernel, static_cast<unsigned long long>(population()), static_cast<double>(measured) / sec,
        sec * 1e9 / static_cast<double>(measured), sec, static_cast<unsigned long long>(measured),
        lps, initial_per_lp, static_cast<unsigned long long>(checksum));
  }
};

}  // namespace masnet::bench
