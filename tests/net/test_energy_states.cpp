// The `states` energy model against its closed form, and energy by message type against the
// totals (docs/radio-and-energy.md, "Energy").
#include <catch2/catch.hpp>

#include "net/radio.hpp"

using namespace masnet;
using net::Vec2;

TEST_CASE("states energy: E = V·I·time in each state, idle what is left of the time alive",
          "[energy]") {
  for (const net::RadioLevel level : {net::RadioLevel::airtime, net::RadioLevel::csma}) {
    net::RadioParams params;
    params.level = level;
    params.latency_s = 0.0;
    params.bitrate_bps = 250e3;
    params.energy.model = net::EnergyModel::states;
    sim::Simulator simulator;
    net::Radio radio(simulator, params, 3);
    radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
    radio.add_static_node(sim::node_id(1), Vec2{0.5, 0}, 1);
    constexpr int kFrames = 50;
    constexpr std::uint32_t kBytes = 40;
    for (int k = 0; k < kFrames; ++k)
      simulator.at(sim::Time{} + sim::seconds(0.01 * k), [&radio] {
        radio.broadcast(sim::node_id(0), 1.0,
                        net::CustomMessage{net::MessageType::beacon,
                                           kBytes - radio.params().sizes.header_bytes, nullptr});
      });
    simulator.run_until(sim::Time{} + sim::seconds(1.0));
    const net::EnergyParams& e = params.energy;
    const double frame_s = 8.0 * kBytes / params.bitrate_bps;
    const net::NodeRadioStats sender = radio.stats(sim::node_id(0));
    const net::NodeRadioStats hearer = radio.stats(sim::node_id(1));
    INFO("level " << static_cast<int>(level));
    CHECK(sender.energy_tx_j == Approx(e.voltage_v * e.tx_current_a * kFrames * frame_s));
    CHECK(sender.energy_rx_j == 0.0);
    CHECK(sender.energy_idle_j ==
          Approx(e.voltage_v * e.idle_current_a * (1.0 - kFrames * frame_s)));
    CHECK(hearer.energy_tx_j == 0.0);
    CHECK(hearer.energy_rx_j == Approx(e.voltage_v * e.rx_current_a * kFrames * frame_s));
    CHECK(hearer.energy_idle_j ==
          Approx(e.voltage_v * e.idle_current_a * (1.0 - kFrames * frame_s)));
    // By message type: every joule is a beacon's.
    CHECK(radio.type_tx_energy_j(net::MessageType::beacon) == Approx(radio.total_tx_energy_j()));
    CHECK(radio.type_rx_energy_j(net::MessageType::beacon) == Approx(radio.total_rx_energy_j()));
    CHECK(radio.type_tx_energy_j(net::MessageType::sense) == 0.0);
  }
}

TEST_CASE("energy by message type adds up to the totals, first-order model", "[energy]") {
  net::RadioParams params;
  params.level = net::RadioLevel::airtime;
  sim::Simulator simulator;
  net::Radio radio(simulator, params, 4);
  for (std::uint32_t i = 0; i < 20; ++i)
    radio.add_static_node(sim::node_id(i), Vec2{0.05 * i, 0.0}, i);
  simulator.at(sim::Time{}, [&radio] {
    for (std::uint32_t i = 0; i < 20; ++i) {
      radio.broadcast(sim::node_id(i), 0.3, net::Beacon{sim::node_id(i), Vec2{0.05 * i, 0.0}});
      radio.unicast(sim::node_id(i), sim::node_id((i + 3) % 20),
                    net::Report{sim::node_id(i), 1.0, Vec2{0.05 * i, 0.0}});
    }
  });
  simulator.run();
  double tx = 0, rx = 0;
  for (std::size_t t = 0; t < net::message_type_count(); ++t) {
    tx += radio.type_tx_energy_j(static_cast<net::MessageType>(t));
    rx += radio.type_rx_energy_j(static_cast<net::MessageType>(t));
  }
  CHECK(tx == Approx(radio.total_tx_energy_j()));
  CHECK(rx == Approx(radio.total_rx_energy_j()));
  CHECK(radio.type_tx_energy_j(net::MessageType::beacon) > 0);
  CHECK(radio.type_rx_energy_j(net::MessageType::report) > 0);
}
