// The radio in the kernel's origin order (docs/time-and-ordering.md): a receiver's handler acts
// as the receiver, and frames due together share one event only when a separate event per
// frame would have run right after the batch — the same sender, nothing else scheduled by it.
#include <catch2/catch.hpp>

#include <vector>

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
  int foreign = 0;  // receptions handled while not acting as the receiver
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

TEST_CASE("origin order: frames of different senders are separate events, in origin order",
          "[net]") {
  // Sent acting as senders 3, 2, 1, 0 in turn, they arrive by origin: sender 3 first.
  const Outcome o = run([](std::uint32_t i) { return sim::origin_of(sim::node_id(3 - i)); }, -1, 0);
  CHECK(o.events == 4);
  CHECK(o.order == std::vector<int>{3, 2, 1, 0});
  CHECK(o.foreign == 0);
}
