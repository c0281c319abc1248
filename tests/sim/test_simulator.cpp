#include <catch2/catch.hpp>

#include <vector>

#include "sim/random.hpp"
#include "sim/simulator.hpp"

using namespace masnet::sim;

TEST_CASE("equal-time events run in the order they were scheduled", "[sim]") {
  Simulator sim;
  std::vector<int> order;
  for (int i = 0; i < 100; ++i)
    sim.at(time_at(1.0), [&order, i] { order.push_back(i); });
  sim.run();
  REQUIRE(order.size() == 100);
  for (int i = 0; i < 100; ++i)
    CHECK(order[i] == i);
}

TEST_CASE("events run in time order and the clock shows each event's time", "[sim]") {
  Simulator sim;
  std::vector<std::int64_t> seen;
  const std::int64_t times[] = {50, 10, 30, 20, 40, 10};
  for (std::int64_t t : times)
    sim.at(kTimeZero + Duration{t}, [&sim, &seen] { seen.push_back(to_ns(sim.now())); });
  sim.run();
  CHECK(seen == std::vector<std::int64_t>{10, 10, 20, 30, 40, 50});
  CHECK(sim.events_run() == 6);
}

TEST_CASE("an event scheduled at the current time runs after the other events already due then",
          "[sim]") {
  Simulator sim;
  std::vector<char> order;
  sim.at(time_at(1), [&] {
    order.push_back('a');
    sim.after(Duration{0}, [&] { order.push_back('c'); });
  });
  sim.at(time_at(1), [&] { order.push_back('b'); });
  sim.run();
  CHECK(order == std::vector<char>{'a', 'b', 'c'});
}

TEST_CASE("a cancelled event never runs and cancelling twice reports false", "[sim]") {
  const bool by_origin = GENERATE(false, true);  // both tie orders
  Simulator sim;
  if (by_origin) sim.order_ties_by_origin();
  int ran = 0;
  EventId keep = sim.after(seconds(1), [&] { ran += 1; });
  EventId drop = sim.after(seconds(2), [&] { ran += 10; });
  CHECK(sim.cancel(drop));
  CHECK_FALSE(sim.cancel(drop));
  CHECK(sim.pending() == 1);
  sim.run();
  CHECK(ran == 1);
  CHECK(sim.events_run() == 1);
  CHECK_FALSE(sim.cancel(keep));  // already ran
}

TEST_CASE("a stale handle cannot cancel the event that reuses its slot", "[sim]") {
  Simulator sim;
  int ran = 0;
  EventId first = sim.after(seconds(1), [&] { ++ran; });
  sim.run();
  sim.after(seconds(1), [&] { ++ran; });  // reuses the freed slot
  CHECK_FALSE(sim.cancel(first));
  sim.run();
  CHECK(ran == 2);
}

TEST_CASE("run_until runs events at exactly the limit and leaves later ones pending", "[sim]") {
  Simulator sim;
  std::vector<int> ran;
  sim.at(time_at(1.0), [&] { ran.push_back(1); });
  sim.at(time_at(2.0), [&] { ran.push_back(2); });
  sim.at(time_at(2.0) + Duration{1}, [&] { ran.push_back(3); });
  CHECK(sim.run_until(time_at(2.0)) == 2);
  CHECK(ran == std::vector<int>{1, 2});
  CHECK(sim.now() == time_at(2.0));
  CHECK(sim.pending() == 1);
  sim.run_until(time_at(3.0));
  CHECK(ran == std::vector<int>{1, 2, 3});
  CHECK(sim.now() == time_at(3.0));
}

TEST_CASE("stop ends the run after the current event", "[sim]") {
  Simulator sim;
  int ran = 0;
  sim.at(time_at(1), [&] {
    ++ran;
    sim.stop();
  });
  sim.at(time_at(2), [&] { ++ran; });
  sim.run_until(time_at(10));
  CHECK(ran == 1);
  CHECK(sim.now() == time_at(1));
  sim.run_until(time_at(10));
  CHECK(ran == 2);
}

TEST_CASE("negative delays and scheduling in the past are assertion failures", "[sim]") {
  set_assertion_mode(AssertionMode::throw_exception);
  Simulator sim;
  CHECK_THROWS_AS(sim.after(Duration{-1}, [] {}), AssertionFailure);
  sim.at(time_at(5), [] {});
  sim.run();
  CHECK_THROWS_AS(sim.at(time_at(4), [] {}), AssertionFailure);
  CHECK_THROWS_AS(sim.run_until(time_at(1)), AssertionFailure);
  set_assertion_mode(AssertionMode::abort);
}

TEST_CASE("seconds convert to integer nanoseconds by rounding", "[sim]") {
  CHECK(seconds(0.01).count() == 10'000'000);
  CHECK(seconds(1e-9).count() == 1);
  CHECK(seconds(0.4e-9).count() == 0);
  CHECK(to_seconds(seconds(2.5)) == 2.5);
  CHECK(time_at(0.3) - time_at(0.1) == seconds(0.2));
}

TEST_CASE("the fingerprint depends on the times and order of executed events", "[sim]") {
  auto run = [](std::vector<double> times) {
    Simulator sim;
    for (double t : times)
      sim.at(time_at(t), [] {});
    sim.run();
    return sim.fingerprint().value();
  };
  CHECK(run({1, 2, 3}) == run({3, 1, 2}));  // same executed stream
  CHECK(run({1, 2, 3}) != run({1, 2, 4}));
  CHECK(run({1, 2, 3}) != run({1, 2}));
}

TEST_CASE("in the origin order the fingerprint combines one stream per origin", "[sim]") {
  // Origin 1's events and digests, with or without origin 2's around them: origin 1's stream is
  // the same, which lets a part of a partitioned run keep its own nodes' streams alone.
  auto run = [](bool with_second, std::uint64_t digest) {
    Simulator sim;
    sim.order_ties_by_origin();
    sim.act_as(1);
    for (double t : {1.0, 2.0, 2.0})
      sim.at(time_at(t), [&sim, digest] { sim.fingerprint_stream().mix(digest); });
    if (with_second) {
      sim.act_as(2);
      for (double t : {0.5, 2.0})
        sim.at(time_at(t), [&sim] { sim.fingerprint_stream().mix(std::uint64_t{99}); });
    }
    sim.act_as(0);
    sim.run();
    return std::pair{sim.fingerprint().value(), sim.origin_streams()};
  };
  const auto [both, both_streams] = run(true, 5);
  const auto [alone, alone_streams] = run(false, 5);
  REQUIRE(both_streams.size() == 3);
  REQUIRE(alone_streams.size() == 2);
  CHECK(both_streams[1].value() == alone_streams[1].value());
  CHECK(both_streams[0].untouched());  // the world ran nothing
  CHECK(both == combine_origin_streams(both_streams).value());
  CHECK(both != alone);
  // A stream sees its origin's digests and times.
  CHECK(run(false, 6).second[1].value() != alone_streams[1].value());
}

TEST_CASE("many interleaved schedules and cancels keep the heap order", "[sim]") {
  Simulator sim;
  RandomStream rng(7);
  std::vector<EventId> ids;
  std::int64_t last = -1;
  std::uint64_t last_seq_time_violations = 0;
  for (int i = 0; i < 20000; ++i) {
    const Duration d{static_cast<std::int64_t>(rng.below(1000))};
    ids.push_back(sim.after(d, [&] {
      if (to_ns(sim.now()) < last) ++last_seq_time_violations;
      last = to_ns(sim.now());
    }));
  }
  int cancelled = 0;
  for (std::size_t i = 0; i < ids.size(); i += 3)
    cancelled += sim.cancel(ids[i]) ? 1 : 0;
  sim.run();
  CHECK(last_seq_time_violations == 0);
  CHECK(sim.events_run() == 20000 - static_cast<std::uint64_t>(cancelled));
}
