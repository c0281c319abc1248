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
      const sim::Time at = s->rig->sim.now() + sim::seconds(s->random.exponential(s->mean_gap_s));
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
  for (Source& s : sources)
    Arrive::next(&s);
  rig.sim.run();
  const net::ContentionCounters& c = rig.radio.contention()->totals(net::MessageType::beacon);
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

namespace {

// A–B–C on a line, A and C out of each other's range: `pairs` copies far apart, each A and C
// sending one frame to its B at the same instant. Returns the counters of the frames.
net::ContentionCounters hidden_terminals(net::RadioLevel level, std::uint32_t retries, int pairs) {
  net::RadioParams params;
  params.level = level;
  params.max_range = 1.2;
  params.latency_s = 0.0;
  params.bitrate_bps = 250e3;
  params.csma.max_frame_retries = retries;
  Rig rig(params, 5);
  for (int p = 0; p < pairs; ++p)
    for (int k = 0; k < 3; ++k)
      rig.add({10.0 * p + k, 0.0});
  rig.sim.at(sim::Time{} + sim::seconds(1e-3), [&rig, pairs] {
    for (int p = 0; p < pairs; ++p) {
      const auto a = static_cast<std::uint32_t>(3 * p);
      // 40 bytes: 1.28 ms on the air, four backoff periods.
      rig.radio.unicast(sim::node_id(a), sim::node_id(a + 1),
                        frame_of_bytes(40, rig.radio.params().sizes));
      rig.radio.unicast(sim::node_id(a + 2), sim::node_id(a + 1),
                        frame_of_bytes(40, rig.radio.params().sizes));
    }
  });
  rig.sim.run();
  return rig.radio.contention()->totals(net::MessageType::beacon);
}

}  // namespace

TEST_CASE(
    "hidden terminal: simultaneous A→B and C→B both fail, carrier sense cannot help, and "
    "retries recover part of them",
    "[contention]") {
  const net::ContentionCounters aloha = hidden_terminals(net::RadioLevel::collision, 0, 1);
  CHECK(aloha.transmissions == 2);
  CHECK(aloha.collided == 2);
  CHECK(aloha.delivered == 0);

  constexpr int kPairs = 200;
  const net::ContentionCounters once = hidden_terminals(net::RadioLevel::csma, 0, kPairs);
  // A and C never hear each other: only B's acknowledgements (of a frame that got through) can
  // make an assessment find the channel busy.
  CHECK(once.backoffs - once.transmissions <= once.delivered);
  CHECK(once.access_failures == 0);
  CHECK(once.transmissions == 2 * kPairs);
  // Backoffs of 0..7 periods against frames of 4: most pairs still overlap at B.
  CHECK(once.collided > kPairs);
  CHECK(once.delivered + once.collided == once.transmissions);
  CHECK(once.dropped == once.collided);

  const net::ContentionCounters retried = hidden_terminals(net::RadioLevel::csma, 3, kPairs);
  CHECK(retried.retries > 0);
  CHECK(retried.transmissions == 2 * kPairs + retried.retries);
  CHECK(retried.delivered > once.delivered);
  CHECK(retried.delivered < 2 * kPairs);  // some pairs collide on every attempt
  CHECK(retried.delivered + retried.dropped == 2 * kPairs);
}

namespace {

// BER of 2.4 GHz O-QPSK (IEEE 802.15.4 annex E), written out again here: binomials by their
// product formula.
double reference_ber(double snr) {
  double sum = 0.0, binomial = 1.0;  // C(16, 0)
  for (int k = 1; k <= 16; ++k) {
    binomial = binomial * (16 - k + 1) / k;
    if (k >= 2)
      sum += (k % 2 == 0 ? 1.0 : -1.0) * binomial * std::exp(20.0 * snr * (1.0 / k - 1.0));
  }
  return std::min(1.0, std::max(0.0, sum * 8.0 / 15.0 / 16.0));
}

}  // namespace

TEST_CASE("log_distance: reception probability follows the O-QPSK PER at 5 SNR points",
          "[contention]") {
  constexpr std::uint32_t kBytes = 30;
  constexpr int kFrames = 4000;
  for (const double snr_db : {-2.5, -2.0, -1.5, -1.0, -0.5}) {
    net::RadioParams params;
    params.level = net::RadioLevel::collision;
    params.latency_s = 0.0;
    params.meters_per_unit = 1.0;
    params.max_range = 1000.0;
    params.propagation.model = net::PropagationModel::log_distance;
    params.propagation.sensitivity_dbm = -130.0;
    // P_rx = 0 − 40.05 − 30·log10(d) dBm against a −100 dBm floor.
    const double distance_m = std::pow(10.0, (100.0 - 40.05 - snr_db) / 30.0);
    Rig rig(params, 99);
    const NodeId sender = rig.add({0, 0});
    const NodeId receiver = rig.add({distance_m, 0});
    for (int k = 0; k < kFrames; ++k)
      rig.sim.at(sim::Time{} + sim::seconds(1e-2 * k), [&rig, sender] {
        rig.radio.broadcast(sender, 1000.0, frame_of_bytes(kBytes, rig.radio.params().sizes));
      });
    rig.sim.run();
    const double expected =
        std::pow(1.0 - reference_ber(std::pow(10.0, snr_db / 10.0)), 8.0 * kBytes);
    const net::ContentionCounters& c = rig.radio.contention()->totals(net::MessageType::beacon);
    const double measured = static_cast<double>(c.delivered) / kFrames;
    const double sigma = std::sqrt(expected * (1.0 - expected) / kFrames);
    INFO("SNR " << snr_db << " dB: expected " << expected << ", measured " << measured);
    CHECK(std::abs(measured - expected) < 4.0 * sigma);
    CHECK(c.delivered + c.channel_lost == kFrames);
    CHECK(rig.counter.frames_at.size() > sim::index(receiver));
  }
}
