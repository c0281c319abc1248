// The radio's traffic fingerprint: it tells apart runs whose event streams agree but whose
// radio outcomes differ, and it does not depend on which thread booked the overhearing.
#include <catch2/catch.hpp>

#include <utility>

#include "net/radio.hpp"
#include "sim/random.hpp"

using namespace masnet;
using net::Vec2;

namespace {

struct Fingerprints {
  std::uint64_t events = 0;  // the simulator's: the ordered event stream
  std::uint64_t traffic = 0;
};

// A 30 × 30 sensor grid that listens to nothing, so no frame reaches a handler and the event
// stream is the same whatever the radio decides; 3 000 random unicasts (booked in bulk when
// nothing can fail) and 300 broadcasts over 3 s.
Fingerprints run_traffic(const net::RadioParams& params) {
  sim::Simulator simulator;
  net::Radio radio(simulator, params, 7);
  const int side = 30, n = side * side;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const auto id = static_cast<std::uint32_t>(j * side + i);
      radio.add_static_node(sim::node_id(id), Vec2{(i + 0.5) / side, (j + 0.5) / side}, id);
      radio.set_interest(sim::node_id(id), 0);
    }
  sim::RandomStream rng(8);
  for (int k = 0; k < 3300; ++k) {
    const double t = rng.uniform(0.0, 3.0);
    const auto src = static_cast<std::uint32_t>(rng.below(n));
    const auto dst = static_cast<std::uint32_t>((src + 1 + rng.below(n - 1)) % n);
    const bool broadcast = k % 11 == 0;
    const double range = rng.uniform(0.05, 0.4);
    simulator.at(sim::time_at(t), [&radio, src, dst, broadcast, range] {
      const Vec2 p = radio.position(sim::node_id(src));
      net::Payload payload = net::Position{sim::node_id(src), p};
      if (broadcast)
        radio.broadcast(sim::node_id(src), range, std::move(payload));
      else
        radio.unicast(sim::node_id(src), sim::node_id(dst), std::move(payload));
    });
  }
  simulator.run();
  return {simulator.fingerprint().value(), radio.traffic_fingerprint().value()};
}

net::RadioParams grid_params() {
  net::RadioParams params;
  params.max_range = 0.3;
  params.overhearing_thread_min_nodes = 0;
  return params;
}

}  // namespace

TEST_CASE(
    "the same traffic gives the same traffic fingerprint, with or without the overhearing thread",
    "[net]") {
  net::RadioParams inline_params = grid_params(), threaded_params = grid_params();
  threaded_params.overhearing_thread = true;
  const Fingerprints inline_run = run_traffic(inline_params);
  const Fingerprints again = run_traffic(inline_params);
  const Fingerprints threaded = run_traffic(threaded_params);
  CHECK(again.traffic == inline_run.traffic);
  CHECK(threaded.traffic == inline_run.traffic);
  CHECK(threaded.events == inline_run.events);
}

TEST_CASE("the traffic fingerprint tells apart radio outcomes that the event stream does not show",
          "[net]") {
  const net::RadioParams normal = grid_params();
  const Fingerprints reference = run_traffic(normal);

  net::RadioParams lossy = normal;
  lossy.loss = 0.1;
  net::RadioParams flat_batteries = normal;  // every send refused: nothing is heard
  flat_batteries.energy.battery_j = 1e-12;
  net::RadioParams longer_frames = normal;  // the same frames, more bytes each
  longer_frames.sizes.header_bytes += 1;
  for (const auto& [what, params] :
       {std::pair{"loss 0.1", lossy}, std::pair{"batteries empty", flat_batteries},
        std::pair{"one more header byte", longer_frames}}) {
    INFO(what);
    const Fingerprints other = run_traffic(params);
    // Nobody listens: the simulator executes the same events either way.
    REQUIRE(other.events == reference.events);
    CHECK(other.traffic != reference.traffic);
  }
}
