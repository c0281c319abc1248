// The radio in the kernel's origin order (docs/time-and-ordering.md): a receiver's handler acts
// as the receiver, and frames due together share one event that hands them over in the order
// of their own keys, letting any other event of the instant keyed between two of them run
// between them.
#include <catch2/catch.hpp>

#include <vector>

#include "net/contended_medium.hpp"
#include "net/radio.hpp"

using namespace masnet;
using net::Vec2;
using sim::NodeId;

namespace {

// Four senders unicast to node 4 at t = 0. Each send acts as `sender_origin(i)`; `marker` >= 0
// schedules a marker at the frames' arrival, acting as `marker_origin`, right after send
// `marker`.
struct Outcome {
  std::uint64_t events = 0;
  std::vector<int> order;
  int foreign = 0;                  // receptions handled while not acting as the receiver
  std::vector<sim::EventKey> keys;  // the running key at each reception
};

template <class SenderOrigin>
Outcome run(SenderOrigin sender_origin, int marker, std::uint32_t marker_origin) {
  Outcome out;
  sim::Simulator sim;
  sim.order_ties_by_origin();
  net::Radio radio(sim, net::RadioParams{}, 1);
  struct : net::RadioListener {
    sim::Simulator* sim;
    Outcome* out;
    void on_frame(NodeId receiver, const net::Frame& f) override {
      out->order.push_back(static_cast<int>(sim::index(f.source)));
      out->foreign += sim->acting_origin() != sim::origin_of(receiver);
      out->keys.push_back(sim->running_key());
    }
  } listener;
  listener.sim = &sim;
  listener.out = &out;
  radio.set_listener(&listener);
  for (std::uint32_t i = 0; i < 4; ++i)
    radio.add_static_node(sim::node_id(i), Vec2{0.1, 0.05 * i}, i);
  radio.add_static_node(sim::node_id(4), Vec2{0, 0}, 4);
  // Every frame has the same size and distance: they all arrive at one instant.
  const sim::Time arrival =
      sim::kTimeZero + sim::seconds(radio.params().latency_s) +
      radio.airtime(net::size_bytes(net::Payload{net::Beacon{}}, radio.params().sizes));
  for (std::uint32_t i = 0; i < 4; ++i) {
    sim.act_as(sender_origin(i));
    radio.unicast(sim::node_id(i), sim::node_id(4), net::Beacon{sim::node_id(i), Vec2{0, 0}});
    if (static_cast<int>(i) == marker) {
      sim.act_as(marker_origin);
      sim.at(arrival, [&out] { out.order.push_back(-1); });
    }
  }
  sim.act_as(sim::kWorldOrigin);
  sim.run();
  out.events = sim.events_run();
  return out;
}

}  // namespace

TEST_CASE("origin order: frames sent acting as one origin share one event, in sending order",
          "[net]") {
  const Outcome o = run([](std::uint32_t) { return sim::kWorldOrigin; }, -1, 0);
  CHECK(o.events == 1);
  CHECK(o.order == std::vector<int>{0, 1, 2, 3});
  CHECK(o.foreign == 0);
}

TEST_CASE("origin order: an event of the same origin between two frames splits their batch",
          "[net]") {
  const Outcome o = run([](std::uint32_t) { return sim::kWorldOrigin; }, 1, sim::kWorldOrigin);
  CHECK(o.events == 3);  // frames 0-1, the marker, frames 2-3
  CHECK(o.order == std::vector<int>{0, 1, -1, 2, 3});
  CHECK(o.foreign == 0);
}

TEST_CASE("origin order: an event of another origin does not split a batch and runs by its origin",
          "[net]") {
  // The marker's origin 9 sorts after the world's batch, wherever it was scheduled.
  const Outcome o = run([](std::uint32_t) { return sim::kWorldOrigin; }, 1, 9);
  CHECK(o.events == 2);
  CHECK(o.order == std::vector<int>{0, 1, 2, 3, -1});
}

TEST_CASE("origin order: frames of several senders share one event, each handed over as its own",
          "[net]") {
  // Sent acting as senders 0, 1, 2, 3 in turn: one event, each frame with its own key.
  const Outcome o = run([](std::uint32_t i) { return sim::origin_of(sim::node_id(i)); }, -1, 0);
  CHECK(o.events == 1);
  CHECK(o.order == std::vector<int>{0, 1, 2, 3});
  CHECK(o.foreign == 0);
  std::vector<sim::EventKey> own;
  for (std::uint32_t i = 0; i < 4; ++i)
    own.push_back(sim::EventKey{0, sim::origin_of(sim::node_id(i)), 0});
  CHECK(o.keys == own);
}

TEST_CASE("origin order: an event keyed between two senders' frames runs between them", "[net]") {
  // The marker is sender 2's second event at the arrival: after its frame, before sender 3's.
  const Outcome o = run([](std::uint32_t i) { return sim::origin_of(sim::node_id(i)); }, 2,
                        sim::origin_of(sim::node_id(2)));
  CHECK(o.events == 3);  // frames 0-2, the marker, frame 3 (the rest of the batch)
  CHECK(o.order == std::vector<int>{0, 1, 2, -1, 3});
  CHECK(o.foreign == 0);
  CHECK(o.keys.back() == sim::EventKey{0, sim::origin_of(sim::node_id(3)), 0});
}

TEST_CASE("origin order: frames sent in descending key order are separate events, in key order",
          "[net]") {
  // Sent acting as senders 3, 2, 1, 0 in turn, they arrive by origin: sender 3 first.
  const Outcome o = run([](std::uint32_t i) { return sim::origin_of(sim::node_id(3 - i)); }, -1, 0);
  CHECK(o.events == 4);
  CHECK(o.order == std::vector<int>{3, 2, 1, 0});
  CHECK(o.foreign == 0);
}

namespace {

struct Emptied {
  NodeId node;
  std::uint32_t acting;
  sim::EventKey key;
};
struct Drain {
  sim::Time node1_died_at = sim::kTimeMax;
  std::vector<Emptied> emptied;
  int node1_alive_at_marker = -1;
};

// Nodes 0 and 1 drain 0.5 W from 2 J; node 0 broadcasts 1000 frames at t = 1 (as node 0), which
// moves node 1's emptying earlier. A marker scheduled at t = 3 (after the emptying was) for
// `marker`, if given, looks whether node 1 is still alive.
Drain drain(bool by_origin, sim::Time marker) {
  Drain out;
  sim::Simulator sim;
  if (by_origin) sim.order_ties_by_origin();
  net::RadioParams params;
  params.energy.idle_power_w = 0.5;
  params.energy.battery_j = 2.0;
  net::Radio radio(sim, params, 1);
  struct : net::RadioListener {
    sim::Simulator* sim;
    Drain* out;
    void on_frame(NodeId, const net::Frame&) override {}
    void on_battery_empty(NodeId node) override {
      out->emptied.push_back(Emptied{node, sim->acting_origin(), sim->running_key()});
    }
  } listener;
  listener.sim = &sim;
  listener.out = &out;
  radio.set_listener(&listener);
  radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
  radio.add_static_node(sim::node_id(1), Vec2{0.01, 0}, 1);
  sim.after_as(sim::origin_of(sim::node_id(0)), sim::seconds(1.0), [&radio] {
    for (int k = 0; k < 1000; ++k)
      radio.broadcast(sim::node_id(0), 0.02, net::Beacon{sim::node_id(0), Vec2{0, 0}});
  });
  if (marker != sim::kTimeMax)
    sim.at(sim::time_at(3.0), [&] {
      sim.at(marker, [&] { out.node1_alive_at_marker = radio.alive(sim::node_id(1)); });
    });
  sim.run_until(sim::time_at(10.0));
  out.node1_died_at = radio.stats(sim::node_id(1)).died_at;
  return out;
}

}  // namespace

TEST_CASE("origin order: a battery runs empty as its node, after every other event of its instant",
          "[net]") {
  const Drain first = drain(true, sim::kTimeMax);
  REQUIRE(first.emptied.size() == 2);
  for (const Emptied& e : first.emptied) {
    CHECK(e.acting == sim::origin_of(e.node));
    CHECK(e.key == sim::EventKey{sim::Simulator::kInstantEndDepth, sim::origin_of(e.node),
                                 sim::Simulator::kReservedCount});
  }
  // The moment is the scheduling order's; only its place among ties differs: a marker
  // scheduled later for that very instant runs before the emptying in the origin order, after
  // it in the scheduling order.
  const sim::Time died = first.node1_died_at;
  REQUIRE(died < sim::time_at(10.0));
  CHECK(drain(false, sim::kTimeMax).node1_died_at == died);
  CHECK(drain(true, died).node1_alive_at_marker == 1);
  CHECK(drain(false, died).node1_alive_at_marker == 0);
}

TEST_CASE("origin order: under csma the addressee acknowledges as itself", "[net]") {
  // The ACK is the addressee's transmission: its events must count as the addressee's own,
  // though the frame's end (the sender's event) decides that it is due.
  sim::Simulator sim;
  sim.order_ties_by_origin();
  net::RadioParams params;
  params.level = net::RadioLevel::csma;
  net::Radio radio(sim, params, 1);
  radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
  radio.add_static_node(sim::node_id(1), Vec2{0.05, 0}, 1);
  sim.after_as(sim::origin_of(sim::node_id(0)), sim::seconds(1e-3), [&radio] {
    radio.unicast(sim::node_id(0), sim::node_id(1), net::Beacon{sim::node_id(0), Vec2{0, 0}});
  });
  sim.run();
  const net::ContentionCounters totals = radio.contention()->totals(net::MessageType::beacon);
  CHECK(totals.delivered == 1);
  CHECK(radio.contention()->node_counters(sim::node_id(1)).acks == 1);
  CHECK(totals.retries == 0);  // the ACK reached the sender
  // The addressee scheduled its turnaround and its ACK's end: counted as its own events.
  sim.act_as(sim::origin_of(sim::node_id(1)));
  CHECK(sim.peek_key(sim.now() + sim::seconds(1)).count >= 2);
}
