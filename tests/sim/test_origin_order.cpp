// The origin order of ties (docs/time-and-ordering.md): a run cut into partitions that each
// schedule their own events, exchanging only the messages that cross, executes every event in
// the same total order as the run in one piece.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <tuple>
#include <vector>

#include "sim/simulator.hpp"
#include "small_network.hpp"

using namespace masnet::sim;
using namespace masnet::test;

TEST_CASE("origin order: ties run by origin and count, not by when they were scheduled", "[sim]") {
  Simulator sim;
  sim.order_ties_by_origin();
  std::vector<char> order;
  sim.act_as(5);
  sim.at(time_at(1), [&] { order.push_back('a'); });
  sim.act_as(2);
  sim.at(time_at(1), [&] { order.push_back('b'); });
  sim.at(time_at(1), [&] { order.push_back('c'); });
  sim.act_as(3);
  sim.at(time_at(1), [&] { order.push_back('d'); });
  sim.run();
  CHECK(order == std::vector<char>{'b', 'c', 'd', 'a'});
}

TEST_CASE("origin order: a zero-delay event follows its cause and every event of its depth",
          "[sim]") {
  Simulator sim;
  sim.order_ties_by_origin();
  std::vector<char> order;
  sim.act_as(9);
  sim.at(time_at(1), [&] {  // key (0, 9, 0)
    order.push_back('a');
    CHECK(sim.running_key() == EventKey{0, 9, 0});
    CHECK(sim.acting_origin() == 9);
    sim.act_as(0);  // acting as the world now: the lowest origin, but one level deeper
    sim.after(Duration{0}, [&] {
      order.push_back('d');
      CHECK(sim.running_key() == EventKey{1, 0, 0});
    });
  });
  sim.act_as(1);
  sim.at(time_at(1), [&] {  // (0, 1, 0): first
    order.push_back('b');
    sim.act_as(7);
    sim.after(Duration{0}, [&] { order.push_back('x'); });  // (1, 7, 0)
  });
  sim.act_as(12);
  sim.at(time_at(1), [&] {  // (0, 12, 0): after 'a'
    order.push_back('c');
    sim.act_as(2);
    sim.after(Duration{0}, [&] { order.push_back('y'); });  // (1, 2, 0): before 'x'
  });
  sim.run();
  CHECK(order == std::vector<char>{'b', 'a', 'c', 'd', 'y', 'x'});
}

TEST_CASE("origin order: an event runs as its owner and a key made now can be scheduled later",
          "[sim]") {
  Simulator sim;
  sim.order_ties_by_origin();
  std::vector<std::uint32_t> owners;
  sim.act_as(3);
  sim.at_for(8, time_at(1), [&] { owners.push_back(sim.acting_origin()); });  // (0, 3, 0)
  const EventKey key = sim.next_key(time_at(1));                              // (0, 3, 1)
  sim.at(time_at(1), [&] { owners.push_back(sim.acting_origin()); });         // (0, 3, 2)
  sim.at_keyed(time_at(1), key, 5, [&] { owners.push_back(sim.acting_origin()); });
  sim.run();
  CHECK(owners == std::vector<std::uint32_t>{8, 5, 3});
  CHECK(sim.acting_origin() == 0);  // between runs: the world
}

TEST_CASE(
    "origin order: an event doing the work of several lets events keyed between its parts run",
    "[sim]") {
  // One event stands for parts keyed (0, 2, 0) and (0, 6, 0) — say, two frames of one delivery
  // batch; origin 4's event sorts between them.
  Simulator sim;
  sim.order_ties_by_origin();
  std::vector<char> order;
  sim.act_as(6);
  const EventKey second = sim.next_key(time_at(1));
  sim.act_as(4);
  sim.at(time_at(1), [&] { order.push_back('m'); });
  sim.act_as(2);
  sim.at(time_at(1), [&] {
    order.push_back('a');
    CHECK(sim.nothing_due_before(EventKey{0, 3, 0}));  // origin 4's event is after it
    CHECK_FALSE(sim.nothing_due_before(second));
    sim.at_keyed(time_at(1), second, 6, [&] {  // the rest, as its own event
      CHECK(sim.nothing_due_before(second));
      sim.continue_as(second);
      order.push_back('b');
      sim.after(Duration{0}, [&] { order.push_back('z'); });  // follows the part, one deeper
    });
  });
  sim.run();
  CHECK(order == std::vector<char>{'a', 'm', 'b', 'z'});
}

TEST_CASE("origin order: an event at the instant's end keeps its place whoever schedules it",
          "[sim]") {
  // Owner 4's event at t = 1 is scheduled acting as 9, cancelled, and scheduled again acting as
  // 2 while t = 1 runs: it still runs after every other event of t = 1 (the world's, zero-delay
  // chains scheduled after it), as owner 4, before owner 6's; its own zero-delay event follows.
  Simulator sim;
  sim.order_ties_by_origin();
  std::vector<char> order;
  std::vector<EventKey> keys;
  std::vector<std::uint32_t> owners;
  auto record = [&](char name) {
    order.push_back(name);
    keys.push_back(sim.running_key());
    owners.push_back(sim.acting_origin());
    if (name == 'e') sim.after(Duration{0}, [&] { order.push_back('g'); });
  };
  auto at_end = [r = &record](char name) { return [r, name] { (*r)(name); }; };
  sim.act_as(9);
  const EventId first = sim.at_instant_end(4, time_at(1), at_end('x'));
  sim.act_as(6);
  sim.at_instant_end(6, time_at(1), at_end('f'));
  sim.act_as(1);
  sim.at(time_at(1), [&] {  // (0, 1, 0)
    order.push_back('a');
    CHECK(sim.cancel(first));
    sim.act_as(2);
    sim.at_instant_end(4, time_at(1), at_end('e'));
    sim.after(Duration{0}, [&] {  // (1, 2, 0)
      order.push_back('c');
      sim.after(Duration{0}, [&] { order.push_back('d'); });  // (2, 2, 1)
    });
  });
  sim.act_as(0);
  sim.at(time_at(1), [&] { order.push_back('w'); });  // (0, 0, 0): the world's, first
  sim.run();
  CHECK(order == std::vector<char>{'w', 'a', 'c', 'd', 'e', 'f', 'g'});
  CHECK(keys ==
        std::vector<EventKey>{EventKey{Simulator::kInstantEndDepth, 4, Simulator::kReservedCount},
                              EventKey{Simulator::kInstantEndDepth, 6, Simulator::kReservedCount}});
  CHECK(owners == std::vector<std::uint32_t>{4, 6});
}

TEST_CASE(
    "origin order: a run in two or three windowed partitions runs the same events in the "
    "same order as in one piece",
    "[sim]") {
  const Time end = time_at(0.01);
  Part whole(0, kNodes);
  whole.start();
  whole.sim.run_until(end);
  REQUIRE(whole.outbox.empty());
  REQUIRE(whole.log.size() > 1000);
  CHECK(whole.wrong_owner == 0);
  CHECK(std::is_sorted(whole.log.begin(), whole.log.end(), in_total_order));
  // Ties are frequent, or the test would prove little.
  std::size_t ties = 0;
  for (std::size_t i = 1; i < whole.log.size(); ++i)
    ties += whole.log[i].time_ns == whole.log[i - 1].time_ns &&
            whole.log[i].node != whole.log[i - 1].node;
  CHECK(ties > 200);

  for (const std::vector<std::uint32_t>& cuts :
       {std::vector<std::uint32_t>{0, 5, kNodes}, std::vector<std::uint32_t>{0, 3, 7, kNodes}}) {
    Parts cut(cuts);
    const std::vector<Part*>& parts = cut.all;
    // Conservative windows of one lookahead: nothing sent in [t, t + L) arrives before t + L.
    for (Time t = kTimeZero; t <= end;) {
      const Time window_end = std::min(end, t + Duration{kLookahead - 1});
      for (Part* p : parts)
        p->sim.run_until(window_end);
      exchange(parts);
      t = window_end + Duration{1};
    }
    const std::vector<Executed> merged = cut.merged_log();
    // The first difference, if any, tells more than two long lists.
    std::size_t same = 0;
    while (same < merged.size() && same < whole.log.size() && merged[same] == whole.log[same])
      ++same;
    INFO("parts: " << parts.size() << ", events: " << merged.size() << " against "
                   << whole.log.size() << ", equal up to " << same);
    CHECK(merged.size() == whole.log.size());
    CHECK(same == whole.log.size());
    for (Part* p : parts)
      CHECK(p->wrong_owner == 0);
  }
}
