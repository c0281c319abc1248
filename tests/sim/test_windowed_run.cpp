// WindowedRun (sim/windowed_run.hpp): the parts of a run in conservative windows on a pool of
// threads give the run in one piece, event for event, whatever the number of threads — also
// when every sender reads one node's state at send time, if every part runs that node.
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
  std::uint64_t fingerprint = 0;  // from each node's stream in its home part
  std::uint64_t windows = 0;
  unsigned threads = 0;
  bool clocks_at_end = true;
  int wrong_owner = 0;
  int too_early = 0;              // messages due before the end of the window that sent them
  std::vector<Executed> watched;  // the first part's record of a node every part runs
  bool replicas_agree = true;     // ... and every other part's is the same
};

std::vector<Executed> events_of(const std::vector<Executed>& log, std::uint32_t node) {
  std::vector<Executed> mine;
  for (const Executed& e : log)
    if (e.node == node) mine.push_back(e);
  return mine;
}

Outcome run_in_parts(const std::vector<std::uint32_t>& cuts, unsigned threads, Time end,
                     Watch watch = {}) {
  Parts cut(cuts, watch);
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
  out.fingerprint = cut.merged_fingerprint();
  // A node run by every part: each part's record of it is the same.
  if (watch.everywhere)
    for (const Part* p : parts) {
      const std::vector<Executed> mine = events_of(p->log, watch.node);
      if (p == parts.front())
        out.watched = mine;
      else
        out.replicas_agree = out.replicas_agree && mine == out.watched;
    }
  return out;
}

struct Whole {
  std::vector<Executed> log;
  std::uint64_t fingerprint = 0;
};

Whole run_whole(Time end, Watch watch = {}) {
  Part whole(0, kNodes, watch);
  whole.start();
  whole.sim.run_until(end);
  return {whole.log, whole.sim.fingerprint().value()};
}

}  // namespace

TEST_CASE("a windowed run on 1, 2 or 3 threads gives the run in one piece, event for event",
          "[sim]") {
  const Time end = time_at(0.01);
  const Whole whole = run_whole(end);
  REQUIRE(whole.log.size() > 1000);
  for (const std::vector<std::uint32_t>& cuts :
       {std::vector<std::uint32_t>{0, 5, kNodes}, std::vector<std::uint32_t>{0, 3, 7, kNodes},
        std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, kNodes}}) {
    for (unsigned threads : {1u, 2u, 3u}) {
      const Outcome o = run_in_parts(cuts, threads, end);
      INFO("parts: " << cuts.size() - 1 << ", threads: " << threads);
      CHECK(o.threads == std::min<unsigned>(threads, static_cast<unsigned>(cuts.size() - 1)));
      CHECK(o.merged == whole.log);
      // The fingerprint too: each node's stream is the same in its home part.
      CHECK(o.fingerprint == whole.fingerprint);
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

TEST_CASE(
    "a node read at send time by every sender, run by every part, keeps the parts equal to the "
    "run in one piece",
    "[sim]") {
  // The radio reads a robot's position when a sensor sends: robots change course at any event,
  // so a part cannot learn where one is a lookahead in advance — it runs every robot itself,
  // each one's messages reaching every part (docs/decisions/0012-partitioned-runs.md).
  const Time end = time_at(0.01);
  for (std::uint32_t watched : {0u, 4u, kNodes - 1}) {
    const Whole whole = run_whole(end, Watch{watched, false});
    REQUIRE(whole.log.size() > 1000);
    const std::vector<Executed> whole_watched = events_of(whole.log, watched);
    REQUIRE(whole_watched.size() > 50);
    for (const std::vector<std::uint32_t>& cuts :
         {std::vector<std::uint32_t>{0, 5, kNodes}, std::vector<std::uint32_t>{0, 3, 7, kNodes}}) {
      for (unsigned threads : {1u, 2u}) {
        const Outcome o = run_in_parts(cuts, threads, end, Watch{watched, true});
        INFO("watched: " << watched << ", parts: " << cuts.size() - 1 << ", threads: " << threads);
        CHECK(o.merged == whole.log);
        CHECK(o.fingerprint == whole.fingerprint);
        CHECK(o.watched == whole_watched);
        CHECK(o.replicas_agree);
        CHECK(o.wrong_owner == 0);
        CHECK(o.too_early == 0);
      }
    }
  }
}

TEST_CASE(
    "a node read at send time but run by one part only leaves the others reading a stale "
    "state",
    "[sim]") {
  // Why the node must run everywhere: the exchange after each window is too late for a read
  // with no lookahead.
  const Time end = time_at(0.01);
  const Watch watch{4, false};
  const Whole whole = run_whole(end, watch);
  const Outcome o = run_in_parts({0, 5, kNodes}, 1, end, watch);
  CHECK(o.merged.size() == whole.log.size());  // the same events ...
  CHECK(o.merged != whole.log);                // ... carrying other values
  CHECK(o.fingerprint != whole.fingerprint);   // which the fingerprint sees
  // Without the read the same cut is exact: the difference is the read's alone.
  const Outcome exact = run_in_parts({0, 5, kNodes}, 1, end);
  CHECK(exact.merged == run_whole(end).log);
  CHECK(exact.fingerprint == run_whole(end).fingerprint);
}
