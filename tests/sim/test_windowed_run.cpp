// WindowedRun (sim/windowed_run.hpp): the parts of a run in conservative windows on a pool of
// threads give the run in one piece, event for event, whatever the number of threads.
#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

#include "sim/windowed_run.hpp"
#include "small_network.hpp"

using namespace masnet::sim;
using namespace masnet::test;

namespace {

struct Outcome {
  std::vector<Executed> merged;
  std::uint64_t windows = 0;
  unsigned threads = 0;
  bool clocks_at_end = true;
  int wrong_owner = 0;
  int too_early = 0;  // messages due before the end of the window that sent them
};

Outcome run_in_parts(const std::vector<std::uint32_t>& cuts, unsigned threads, Time end) {
  Parts cut(cuts);
  const std::vector<Part*>& parts = cut.all;
  std::vector<Simulator*> simulators;
  for (Part* p : parts)
    simulators.push_back(&p->sim);
  Outcome out;
  {
    WindowedRun run(simulators, Duration{kLookahead}, threads);
    out.threads = run.threads();
    run.run_until(end, [&](Time window_end) {
      for (const Part* p : parts)
        for (const Message& m : p->outbox)
          out.too_early += m.time_ns <= to_ns(window_end);
      exchange(parts);
    });
    out.windows = run.windows();
  }
  for (const Part* p : parts) {
    out.clocks_at_end = out.clocks_at_end && p->sim.now() == end;
    out.wrong_owner += p->wrong_owner;
  }
  out.merged = cut.merged_log();
  return out;
}

}  // namespace

TEST_CASE("a windowed run on 1, 2 or 3 threads gives the run in one piece, event for event",
          "[sim]") {
  const Time end = time_at(0.01);
  Part whole(0, kNodes);
  whole.start();
  whole.sim.run_until(end);
  REQUIRE(whole.log.size() > 1000);
  for (const std::vector<std::uint32_t>& cuts :
       {std::vector<std::uint32_t>{0, 5, kNodes}, std::vector<std::uint32_t>{0, 3, 7, kNodes},
        std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, kNodes}}) {
    for (unsigned threads : {1u, 2u, 3u}) {
      const Outcome o = run_in_parts(cuts, threads, end);
      INFO("parts: " << cuts.size() - 1 << ", threads: " << threads);
      CHECK(o.threads == std::min<unsigned>(threads, static_cast<unsigned>(cuts.size() - 1)));
      CHECK(o.merged == whole.log);
      CHECK(o.clocks_at_end);
      CHECK(o.wrong_owner == 0);
      CHECK(o.too_early == 0);  // the lookahead holds
      // One window per lookahead at most: 0.01 s in windows of 5 µs.
      CHECK(o.windows >= 1);
      CHECK(o.windows <= static_cast<std::uint64_t>(to_ns(end) / kLookahead) + 1);
    }
  }
}

TEST_CASE("a windowed run starts each window at the earliest pending event", "[sim]") {
  // Two parts, one event each, far apart: two windows, not one per lookahead in between.
  Simulator a, b;
  a.order_ties_by_origin();
  b.order_ties_by_origin();
  int ran = 0;
  a.at(time_at(1.0), [&] { ++ran; });
  b.at(time_at(2.0), [&] { ++ran; });
  WindowedRun run({&a, &b}, Duration{kLookahead}, 2);
  int exchanges = 0;
  run.run_until(time_at(3.0), [&](Time) { ++exchanges; });
  CHECK(ran == 2);
  CHECK(run.windows() == 2);
  CHECK(exchanges == 2);
  CHECK(a.now() == time_at(3.0));
  CHECK(b.now() == time_at(3.0));
}
