// IEEE 802.15.4 CSMA-CA saturation on a star, through the real net::Radio at level csma: one
// coordinator, n leaves on a circle of 1 m around it, every leaf always has an acknowledged
// frame for the coordinator. The same topology, PHY and MAC parameters as the ns-3 peer
// (tests/bench/peers/csma_star_ns3.cc): 250 kbit/s, 20-byte payload (37 bytes on the air),
// log-distance loss with ns-3's defaults, frames counted over 20 s after 1 s of warm-up.
//   masnet_bench_csma_star --n=10 --seconds=20 --seed=1
#include <cstdio>
#include <vector>

#include "bench_args.hpp"
#include "net/contended_medium.hpp"
#include "net/radio.hpp"

using namespace masnet;
using net::Vec2;

namespace {

struct Coordinator : net::RadioListener {
  const sim::Simulator* sim = nullptr;
  sim::Time count_from{};
  std::uint64_t received = 0;
  void on_frame(sim::NodeId receiver, const net::Frame&) override {
    if (sim::index(receiver) == 0 && sim->now() >= count_from) ++received;
  }
};

constexpr std::uint32_t kPpduBytes = 37;  // 6 PHY + 9 MAC header + 20 payload + 2 FCS

}  // namespace

int main(int argc, char** argv) {
  const bench::Args args{argc, argv};
  const int leaves = static_cast<int>(args.number("n", 10));
  const double seconds = args.number("seconds", 20);
  const auto seed = static_cast<std::uint64_t>(args.number("seed", 1));
  net::RadioParams params;
  params.level = net::RadioLevel::csma;
  params.max_range = 100.0;
  params.meters_per_unit = 1.0;
  params.latency_s = 0.0;
  params.bitrate_bps = 250e3;
  params.propagation.model = net::PropagationModel::log_distance;
  params.propagation.exponent = 3.0;
  params.propagation.reference_loss_db = 46.6777;  // ns-3's LogDistancePropagationLossModel
  params.propagation.tx_power_dbm = 0.0;
  params.propagation.noise_floor_dbm = -106.98;  // the peer's SNR at 1 m: 60.3 dB
  params.propagation.sensitivity_dbm = -106.58;
  params.csma.cca_threshold_dbm = -96.58;  // 10 dB above the sensitivity
  params.capture_threshold_db = -5.0;      // a receiver synchronises on a frame above -5 dB
  params.csma.queue_frames = 1u << 20;

  sim::Simulator simulator;
  net::Radio radio(simulator, params, seed);
  Coordinator coordinator;
  coordinator.sim = &simulator;
  coordinator.count_from = sim::Time{} + sim::seconds(1.0);
  radio.set_listener(&coordinator);
  radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
  for (int i = 1; i <= leaves; ++i) {
    const double angle = 2.0 * M_PI * (i - 1) / leaves;
    radio.add_static_node(sim::node_id(static_cast<std::uint32_t>(i)),
                          Vec2{std::cos(angle), std::sin(angle)}, static_cast<std::uint64_t>(i));
  }
  // Saturation: each leaf's queue holds more frames than it can send in the run (one frame
  // takes at least 3.8 ms); leaf i starts at i µs, as the peer's.
  const auto per_leaf = static_cast<std::uint32_t>((seconds + 1.0) / 3.5e-3) + 16;
  const net::Payload frame = net::CustomMessage{net::MessageType::reading,
                                                kPpduBytes - params.sizes.header_bytes, nullptr};
  for (int i = 1; i <= leaves; ++i)
    simulator.at(sim::Time{} + sim::seconds(i * 1e-6), [&radio, &frame, i, per_leaf] {
      for (std::uint32_t k = 0; k < per_leaf; ++k)
        radio.unicast(sim::node_id(static_cast<std::uint32_t>(i)), sim::node_id(0), frame);
    });
  simulator.run_until(sim::Time{} + sim::seconds(seconds + 1.0));
  const net::ContentionCounters& c = radio.contention()->totals(net::MessageType::reading);
  std::printf(
      "RESULT n=%d payload=20 seconds=%g seed=%llu unique_per_s=%.1f transmissions=%llu "
      "collided=%llu channel_lost=%llu retries=%llu access_failures=%llu dropped=%llu\n",
      leaves, seconds, static_cast<unsigned long long>(seed),
      static_cast<double>(coordinator.received) / seconds,
      static_cast<unsigned long long>(c.transmissions), static_cast<unsigned long long>(c.collided),
      static_cast<unsigned long long>(c.channel_lost), static_cast<unsigned long long>(c.retries),
      static_cast<unsigned long long>(c.access_failures),
      static_cast<unsigned long long>(c.dropped));
  return 0;
}
