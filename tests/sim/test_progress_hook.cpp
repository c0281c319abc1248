#include <catch2/catch.hpp>

#include <cstdint>
#include <functional>
#include <vector>

#include "sim/random.hpp"
#include "sim/simulator.hpp"

using namespace masnet::sim;

namespace {

// A PHOLD-like workload: `processes` chains, each event schedules the next one of a random
// chain after a random delay, cancelling now and then an event it scheduled, until `events`
// have run. Run in chunks of `chunk_s` (as a run advances between sample instants).
struct Workload {
  Simulator sim;
  RandomStream rng{7};
  std::uint64_t events_left;
  std::vector<std::uint32_t> visits;

  Workload(std::uint32_t processes, std::uint64_t events)
      : events_left(events), visits(processes, 0) {
    for (std::uint32_t p = 0; p < processes; ++p)
      sim.after(Duration{1 + rng.below(1000)}, [this, p] { step(p); });
  }
  void step(std::uint32_t p) {
    ++visits[p];
    if (--events_left == 0) {
      sim.stop();
      return;
    }
    const auto next = static_cast<std::uint32_t>(rng.below(visits.size()));
    sim.after(Duration{1 + rng.below(1000)}, [this, next] { step(next); });
    if (rng.below(8) == 0) {  // a decoy that is cancelled before it runs
      const EventId decoy = sim.after(Duration{2000}, [] {});
      sim.cancel(decoy);
    }
  }
  void run_in_chunks(Duration chunk) {
    while (events_left > 0)
      sim.run_until(sim.now() + chunk);
  }
};

}  // namespace

TEST_CASE("The progress hook is called once every N events, across run_until chunks", "[sim]") {
  constexpr std::uint64_t kEvents = 100000, kPeriod = 4096;
  Workload w(64, kEvents);
  std::vector<std::uint64_t> calls;
  std::vector<Time> times;
  w.sim.set_progress_hook(kPeriod, [&](Time now, std::uint64_t events) {
    calls.push_back(events);
    times.push_back(now);
  });
  // Chunks of 50 ns hold only a few events each: the count must carry over between them.
  w.run_in_chunks(Duration{50});
  REQUIRE(w.sim.events_run() == kEvents);
  REQUIRE(calls.size() == kEvents / kPeriod);  // 24 calls, at events 4096, 8192, ...
  for (std::size_t i = 0; i < calls.size(); ++i)
    CHECK(calls[i] == (i + 1) * kPeriod);
  for (std::size_t i = 1; i < times.size(); ++i)
    CHECK(times[i] >= times[i - 1]);
}

TEST_CASE("An observing progress hook leaves the event stream and its fingerprint unchanged",
          "[sim]") {
  constexpr std::uint64_t kEvents = 50000;
  Workload plain(32, kEvents), hooked(32, kEvents);
  int calls = 0;
  hooked.sim.set_progress_hook(1000, [&](Time, std::uint64_t) { ++calls; });
  plain.run_in_chunks(Duration{300});
  hooked.run_in_chunks(Duration{300});
  CHECK(calls == 50);
  CHECK(hooked.sim.events_run() == plain.sim.events_run());
  CHECK(hooked.sim.fingerprint().hex() == plain.sim.fingerprint().hex());
  CHECK(hooked.visits == plain.visits);
  CHECK(hooked.sim.now() == plain.sim.now());
}

TEST_CASE("A removed progress hook is no longer called, and run() calls it too", "[sim]") {
  Simulator sim;
  int calls = 0;
  for (int i = 0; i < 10; ++i)
    sim.at(time_at(i), [] {});
  sim.set_progress_hook(3, [&](Time, std::uint64_t) { ++calls; });
  sim.run_until(time_at(4.5));  // events 1..5: called after the third
  CHECK(calls == 1);
  sim.set_progress_hook(0, nullptr);
  sim.run();
  CHECK(calls == 1);
  CHECK(sim.events_run() == 10);
}
