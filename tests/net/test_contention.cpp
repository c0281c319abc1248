// The contended radio levels against their analytic models: pure and slotted ALOHA throughput,
// the hidden terminal, the O-QPSK packet error rate, and CSMA-CA's bookkeeping
// (docs/radio-and-energy.md).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "net/contended_medium.hpp"
#include "net/radio.hpp"
#include "sim/random.hpp"

using namespace masnet;
using net::Vec2;
using sim::NodeId;

namespace {

struct Counter : net::RadioListener {
  std::vector<std::uint64_t> frames_at;  // by receiver id
  void on_frame(NodeId receiver, const net::Frame&) override {
    if (frames_at.size() <= sim::index(receiver)) frames_at.resize(sim::index(receiver) + 1);
    ++frames_at[sim::index(receiver)];
  }
};

struct Rig {
  sim::Simulator sim;
  net::Radio radio;
  Counter counter;
  Rig(const net::RadioParams& params, std::uint64_t seed) : radio(sim, params, seed) {
    radio.set_listener(&counter);
  }
  NodeId add(const Vec2& at) {
    const NodeId id{static_cast<std::uint32_t>(radio.node_count())};
    radio.add_static_node(id, at, sim::index(id));
    return id;
  }
};

net::Payload frame_of_bytes(std::uint32_t bytes, const net::MessageSizes& sizes) {
  return net::CustomMessage{net::MessageType::beacon, bytes - sizes.header_bytes, nullptr};
}

constexpr std::uint32_t kAlohaFrameBytes = 100;
constexpr double kAlohaBitrate = 1e6;
constexpr double kFrameTime_s = kAlohaFrameBytes * 8.0 / kAlohaBitrate;  // 0.8 ms, whole ns

// Senders on a circle around one sink, all in one collision domain; Poisson arrivals of total
// offered load G frames per frame time. Slotted: a frame waits for the next slot boundary.
// Returns {measured G, measured S}.
std::pair<double, double> aloha(double offered_load, bool slotted, std::uint64_t seed) {
  net::RadioParams params;
  params.level = net::RadioLevel::collision;
  params.max_range = 10.0;
  params.latency_s = 0.0;
  params.bitrate_bps = kAlohaBitrate;
  Rig rig(params, seed);
  const NodeId sink = rig.add({0, 0});
  constexpr int kSenders = 100;
  for (int i = 0; i < kSenders; ++i) {
    const double angle = 2.0 * M_PI * i / kSenders;
    rig.add({std::cos(angle), std::sin(angle)});
  }
  // Enough frame times for ~12 000 successes: a relative spread under 1 % at every load.
  const double expected_s =
      slotted ? offered_load * std::exp(-offered_load) : offered_load * std::exp(-2 * offered_load);
  const double frame_times = std::max(40000.0, 12000.0 / expected_s);
  const sim::Time end = sim::Time{} + sim::seconds(frame_times * kFrameTime_s);
  const double mean_gap_s = kSenders * kFrameTime_s / offered_load;
  struct Source {
    Rig* rig;
    sim::RandomStream random{0};
    NodeId id, sink;
    double mean_gap_s;
    bool slotted;
    sim::Time end;
  };
  std::vector<Source> sources;
  sources.reserve(kSenders);
  for (int i = 0; i < kSenders; ++i)
    sources.push_back(Source{&rig, sim::RandomStream::keyed(seed, std::uint64_t(i), 7),
                             NodeId{static_cast<std::uint32_t>(i + 1)}, sink, mean_gap_s, slotted,
                             end});
  struct Arrive {
    static void next(Source* s) {
      const sim::Time at =
          s->rig->sim.now() + sim::seconds(s->random.exponential(s->mean_gap_s));
      if (at >= s->end) return;
      s->rig->sim.at(at, [s] {
        Source* const source = s;
        auto send = [source] {
          source->rig->radio.unicast(
              source->id, source->sink,
              frame_of_bytes(kAlohaFrameBytes, source->rig->radio.params().sizes));
        };
        if (source->slotted) {
          const std::int64_t slot_ns = sim::seconds(kFrameTime_s).count();
          const std::int64_t now_ns = sim::to_ns(source->rig->sim.now());
          const std::int64_t boundary = (now_ns + slot_ns - 1) / slot_ns * slot_ns;
          source->rig->sim.at(sim::Time{} + sim::Duration{boundary}, send);
        } else {
          send();
        }
        next(source);
      });
    }
  };
  for (Source& s : sources) Arrive::next(&s);
  rig.sim.run();
  const net::ContentionCounters& c =
      rig.radio.contention()->totals(net::MessageType::beacon);
  const double elapsed = sim::to_seconds(rig.sim.now()) / kFrameTime_s;
  const double span = std::max(elapsed, frame_times);
  return {c.transmissions / span, c.delivered / span};
}

}  // namespace

TEST_CASE("pure ALOHA on one collision domain: S = G·exp(-2G) within 3 %", "[contention]") {
  for (const double g : {0.1, 0.5, 1.0, 2.0}) {
    const auto [measured_g, s] = aloha(g, false, 11);
    INFO("G = " << g << ", measured G = " << measured_g << ", S = " << s);
    REQUIRE(measured_g == Approx(g).epsilon(0.05));
    CHECK(s == Approx(measured_g * std::exp(-2.0 * measured_g)).epsilon(0.03));
  }
}

TEST_CASE("slotted ALOHA: S = G·exp(-G) within 3 %", "[contention]") {
  for (const double g : {0.1, 0.5, 1.0, 2.0}) {
    const auto [measured_g, s] = aloha(g, true, 12);
    INFO("G = " << g << ", measured G = " << measured_g << ", S = " << s);
    REQUIRE(measured_g == Approx(g).epsilon(0.05));
    CHECK(s == Approx(measured_g * std::exp(-measured_g)).epsilon(0.03));
  }
}
