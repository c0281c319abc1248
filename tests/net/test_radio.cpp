#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "net/radio.hpp"
#include "sim/random.hpp"

using namespace masnet;
using net::Vec2;
using sim::NodeId;

namespace {

// Records every frame handed over, with the receiver.
struct Recorder : net::RadioListener {
  struct Delivery {
    NodeId receiver, source;
    net::MessageType type;
    double at_s;
  };
  sim::Simulator* sim = nullptr;
  std::vector<Delivery> deliveries;
  std::vector<NodeId> emptied;
  void on_frame(NodeId receiver, const net::Frame& f) override {
    deliveries.push_back({receiver, f.source, f.type, sim::to_seconds(sim->now())});
  }
  void on_battery_empty(NodeId node) override { emptied.push_back(node); }
};

// Mobile nodes moving on straight lines: p(t) = p0 + v·t.
struct LinearMotion : net::MobilePositions {
  const sim::Simulator* sim = nullptr;
  std::map<std::uint32_t, std::pair<Vec2, Vec2>> lines;
  Vec2 position(NodeId id) const override {
    const auto& [p0, v] = lines.at(sim::index(id));
    return p0 + sim::to_seconds(sim->now()) * v;
  }
  double speed_bound() const override {
    double s = 0;
    for (const auto& [id, line] : lines)
      s = std::max(s, line.second.norm());
    return s;
  }
};

// A simulator, a radio, a recorder listening to it and straight-line motion for its mobile nodes.
struct Rig {
  sim::Simulator sim;
  net::Radio radio;
  Recorder rec;
  LinearMotion motion;
  Rig(const net::RadioParams& params, std::uint64_t seed) : radio(sim, params, seed) {
    rec.sim = &sim;
    motion.sim = &sim;
    radio.set_listener(&rec);
    radio.set_mobile_positions(&motion);
  }
};

net::Payload beacon(NodeId from) {
  return net::Beacon{from, Vec2{0, 0}};
}

// A side × side cell-centred sensor grid as nodes 0 … side²−1 (indexed as lines by the radio),
// then `robots` robots at random places moving at up to `speed` per axis.
void add_grid_and_robots(Rig& rig, int side, int robots, double speed, std::uint64_t seed,
                         std::uint32_t sensor_interest) {
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const auto id = static_cast<std::uint32_t>(j * side + i);
      rig.radio.add_static_node(sim::node_id(id), Vec2{(i + 0.5) / side, (j + 0.5) / side}, id);
      rig.radio.set_interest(sim::node_id(id), sensor_interest);
    }
  sim::RandomStream rng(seed);
  for (int r = 0; r < robots; ++r) {
    const auto id = static_cast<std::uint32_t>(side * side + r);
    rig.motion.lines[id] = {Vec2{rng.uniform01(), rng.uniform01()},
                            Vec2{rng.uniform(-speed, speed), rng.uniform(-speed, speed)}};
    rig.radio.add_mobile_node(sim::node_id(id), id);
  }
}

}  // namespace

TEST_CASE("broadcast deliveries equal a brute-force range check, static and moving nodes",
          "[net]") {
  for (int layout = 0; layout < 20; ++layout) {
    net::RadioParams params;
    params.max_range = 0.4;
    Rig rig(params, 1);
    auto& [sim, radio, rec, motion] = rig;
    sim::RandomStream rng(static_cast<std::uint64_t>(layout));
    const int n_static = 50 + 20 * layout, n_mobile = layout % 2 == 0 ? 10 : 60;  // both paths
    for (int i = 0; i < n_static; ++i)
      radio.add_static_node(sim::node_id(i), Vec2{rng.uniform01(), rng.uniform01()}, i);
    for (int i = 0; i < n_mobile; ++i) {
      const auto id = static_cast<std::uint32_t>(n_static + i);
      motion.lines[id] = {Vec2{rng.uniform01(), rng.uniform01()},
                          Vec2{rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)}};
      radio.add_mobile_node(sim::node_id(id), id);
    }
    const int n = n_static + n_mobile;
    // Expected receivers computed by brute force at each send time.
    std::multiset<std::pair<std::uint32_t, std::uint32_t>> expected;
    auto send = [&](std::uint32_t src, double range) {
      const Vec2 p = radio.position(sim::node_id(src));
      const double r = std::min(range, params.max_range);
      for (int j = 0; j < n; ++j) {
        if (static_cast<std::uint32_t>(j) == src) continue;
        if ((radio.position(sim::node_id(j)) - p).norm() <= r) expected.insert({src, j});
      }
      radio.broadcast(sim::node_id(src), range, beacon(sim::node_id(src)));
    };
    for (int k = 0; k < 200; ++k) {
      const double t = rng.uniform(0.0, 2.0);
      const auto src = static_cast<std::uint32_t>(rng.below(static_cast<std::uint64_t>(n)));
      const double range = rng.uniform(0.0, 0.6);  // sometimes above max_range
      sim.at(sim::time_at(t), [&send, src, range] { send(src, range); });
    }
    sim.run();
    std::multiset<std::pair<std::uint32_t, std::uint32_t>> got;
    for (const auto& d : rec.deliveries)
      got.insert({sim::index(d.source), sim::index(d.receiver)});
    REQUIRE(got == expected);
  }
}

TEST_CASE("nothing is delivered beyond the range and the addressee of a unicast gets it", "[net]") {
  net::RadioParams params;
  params.max_range = 0.5;
  Rig rig(params, 1);
  auto& [sim, radio, rec, motion] = rig;
  radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
  radio.add_static_node(sim::node_id(1), Vec2{0.3, 0}, 1);
  radio.add_static_node(sim::node_id(2), Vec2{0.3000001, 0}, 2);
  radio.add_static_node(sim::node_id(3), Vec2{0.6, 0}, 3);  // beyond max_range from node 0
  radio.broadcast(sim::node_id(0), 0.3, beacon(sim::node_id(0)));
  radio.unicast(sim::node_id(0), sim::node_id(2), beacon(sim::node_id(0)));
  radio.unicast(sim::node_id(0), sim::node_id(3), beacon(sim::node_id(0)));
  sim.run();
  REQUIRE(rec.deliveries.size() == 2);
  CHECK(sim::index(rec.deliveries[0].receiver) == 1);  // broadcast reaches exactly range 0.3
  CHECK(sim::index(rec.deliveries[1].receiver) == 2);  // unicast: only the addressee
  // The unicast to node 2 is overheard by node 1; the one to node 3 (capped at 0.5) by 1 and 2.
  CHECK(radio.stats(sim::node_id(1)).overheard_count == 2);
  CHECK(radio.stats(sim::node_id(2)).overheard_count == 1);
  CHECK(radio.stats(sim::node_id(0)).unreachable_count == 1);
  CHECK(radio.counters(sim::node_id(0), net::MessageType::beacon).tx_count == 3);
  CHECK(radio.frames_sent(sim::node_id(0)) == 3);  // all types, as the live frames count them
  CHECK(radio.frames_sent(sim::node_id(1)) == 0);
}

TEST_CASE("the loss rate lies inside the binomial 99.9% interval", "[net]") {
  for (double p : {0.1, 0.3, 0.5}) {
    net::RadioParams params;
    params.loss = p;
    params.level = net::RadioLevel::ideal;
    Rig rig(params, 77);
    auto& [sim, radio, rec, motion] = rig;
    const int n = 101;
    for (int i = 0; i < n; ++i)
      radio.add_static_node(sim::node_id(i), Vec2{0.001 * i, 0}, i);
    const int frames = 200;
    for (int k = 0; k < frames; ++k)
      radio.broadcast(sim::node_id(k % n), 1.0, beacon(sim::node_id(k % n)));
    sim.run();
    const double trials = frames * (n - 1.0);
    const double delivered = static_cast<double>(rec.deliveries.size());
    const double lost_rate = 1.0 - delivered / trials;
    const double sd = std::sqrt(p * (1 - p) / trials);
    INFO("p = " << p << " observed " << lost_rate);
    CHECK(std::fabs(lost_rate - p) <= 3.29 * sd);  // two-sided 99.9 %
    std::uint64_t lost = 0;
    for (int i = 0; i < n; ++i)
      lost += radio.stats(sim::node_id(i)).lost_count;
    CHECK(static_cast<double>(lost) + delivered == trials);
  }
}

TEST_CASE("delay is latency plus airtime, and a transmitter sends one frame at a time", "[net]") {
  net::RadioParams params;
  params.latency_s = 1e-4;
  params.bitrate_bps = 1e5;
  Rig rig(params, 1);
  auto& [sim, radio, rec, motion] = rig;
  radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
  radio.add_static_node(sim::node_id(1), Vec2{0.1, 0}, 1);
  radio.broadcast(sim::node_id(0), 0.2, beacon(sim::node_id(0)));
  radio.broadcast(sim::node_id(0), 0.2, beacon(sim::node_id(0)));
  sim.run();
  const double bytes =
      params.sizes.header_bytes + params.sizes.id_bytes + params.sizes.position_bytes;
  const double air = bytes * 8 / params.bitrate_bps;
  REQUIRE(rec.deliveries.size() == 2);
  CHECK(rec.deliveries[0].at_s == Approx(air + 1e-4).epsilon(1e-9));
  CHECK(rec.deliveries[1].at_s == Approx(2 * air + 1e-4).epsilon(1e-9));
}

TEST_CASE("frames due together share one event unless something was scheduled between them",
          "[net]") {
  // Four senders broadcast at t = 0 to one listener; their frames arrive at the same instant.
  // `marker_after` >= 0 schedules a marker event at that instant between two transmissions:
  // it must run between those frames, exactly where a separate event per frame would put it.
  const auto run = [](int marker_after, sim::Time at, std::vector<int>& order, sim::Time& arrival) {
    sim::Simulator sim;
    net::Radio radio(sim, net::RadioParams{}, 1);
    struct : net::RadioListener {
      sim::Simulator* sim;
      std::vector<int>* order;
      sim::Time* arrival;
      void on_frame(NodeId, const net::Frame& f) override {
        order->push_back(static_cast<int>(sim::index(f.source)));
        *arrival = sim->now();
      }
    } listener;
    listener.sim = &sim;
    listener.order = &order;
    listener.arrival = &arrival;
    radio.set_listener(&listener);
    for (std::uint32_t i = 0; i < 4; ++i)
      radio.add_static_node(sim::node_id(i), Vec2{0.1, 0.05 * i}, i);
    radio.add_static_node(sim::node_id(4), Vec2{0, 0}, 4);
    for (std::uint32_t i = 0; i < 4; ++i) {
      radio.unicast(sim::node_id(i), sim::node_id(4), beacon(sim::node_id(i)));
      if (static_cast<int>(i) == marker_after) sim.at(at, [&order] { order.push_back(-1); });
    }
    sim.run();
    return sim.events_run();
  };
  std::vector<int> order;
  sim::Time arrival{};
  CHECK(run(-1, sim::Time{}, order, arrival) == 1);
  CHECK(order == std::vector<int>{0, 1, 2, 3});
  order.clear();
  sim::Time unused{};
  CHECK(run(1, arrival, order, unused) == 3);  // frames 0-1, the marker, frames 2-3
  CHECK(order == std::vector<int>{0, 1, -1, 2, 3});
}

TEST_CASE("energy equals the first-order radio model, continuous at d0", "[net]") {
  net::EnergyParams e;
  const double d0 = e.crossover_m();
  CHECK(d0 == Approx(std::sqrt(10.0 / 0.0013)));
  const double k = 8.0 * 100;  // a 100-byte frame
  // Hand-computed: 50 nJ/bit electronics; 10 pJ/bit/m² below d0; 0.0013 pJ/bit/m⁴ above.
  CHECK(net::tx_energy_j(e, k, 50.0) == Approx(k * 50e-9 + k * 10e-12 * 2500.0).epsilon(1e-12));
  CHECK(net::tx_energy_j(e, k, 100.0) == Approx(k * 50e-9 + k * 0.0013e-12 * 1e8).epsilon(1e-12));
  CHECK(net::rx_energy_j(e, k) == Approx(k * 50e-9).epsilon(1e-12));
  const double below = net::tx_energy_j(e, k, d0 * (1 - 1e-9));
  const double at = net::tx_energy_j(e, k, d0);
  CHECK(at == Approx(below).epsilon(1e-7));

  // The radio books exactly these amounts: the sender pays E_tx at its range in metres, and
  // every node in range pays E_rx, addressed or not.
  sim::Simulator sim;
  net::RadioParams params;
  params.meters_per_unit = 100;
  net::Radio radio(sim, params, 1);
  radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
  radio.add_static_node(sim::node_id(1), Vec2{0.5, 0}, 1);  // 50 m
  radio.add_static_node(sim::node_id(2), Vec2{0.2, 0}, 2);  // overhears the unicast to node 1
  radio.add_static_node(sim::node_id(3), Vec2{0.9, 0}, 3);  // out of range
  radio.unicast(sim::node_id(0), sim::node_id(1), beacon(sim::node_id(0)));
  sim.run();
  const double bits =
      8.0 * (params.sizes.header_bytes + params.sizes.id_bytes + params.sizes.position_bytes);
  CHECK(radio.stats(sim::node_id(0)).energy_tx_j ==
        Approx(bits * 50e-9 + bits * 10e-12 * 2500).epsilon(1e-12));
  CHECK(radio.stats(sim::node_id(1)).energy_rx_j == Approx(bits * 50e-9).epsilon(1e-12));
  CHECK(radio.stats(sim::node_id(2)).energy_rx_j == Approx(bits * 50e-9).epsilon(1e-12));
  CHECK(radio.stats(sim::node_id(3)).energy_rx_j == 0.0);
}

TEST_CASE("a node whose battery empties stops sending and receiving", "[net]") {
  net::RadioParams params;
  const double bits =
      8.0 * (params.sizes.header_bytes + params.sizes.id_bytes + params.sizes.position_bytes);
  const double tx = net::tx_energy_j(params.energy, bits, 0.1 * params.meters_per_unit);
  params.energy.battery_j = 2.5 * tx;  // enough for two frames, not three
  Rig rig(params, 1);
  auto& [sim, radio, rec, motion] = rig;
  radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
  radio.add_static_node(sim::node_id(1), Vec2{0.1, 0}, 1);
  CHECK(radio.broadcast(sim::node_id(0), 0.1, beacon(sim::node_id(0))));
  CHECK(radio.broadcast(sim::node_id(0), 0.1, beacon(sim::node_id(0))));
  CHECK_FALSE(radio.broadcast(sim::node_id(0), 0.1, beacon(sim::node_id(0))));
  sim.run();
  CHECK_FALSE(radio.alive(sim::node_id(0)));
  REQUIRE(rec.emptied.size() == 1);
  CHECK(rec.emptied[0] == sim::node_id(0));
  CHECK(rec.deliveries.size() == 2);
  CHECK(radio.energy_j(sim::node_id(0)) <= params.energy.battery_j);
  // The dead node no longer hears anything, nor pays for it.
  const double before = radio.energy_j(sim::node_id(0));
  radio.broadcast(sim::node_id(1), 0.1, beacon(sim::node_id(1)));
  sim.run();
  CHECK(rec.deliveries.size() == 2);
  CHECK(radio.energy_j(sim::node_id(0)) == before);
}

TEST_CASE("idle power empties a battery at the predicted time", "[net]") {
  net::RadioParams params;
  params.energy.idle_power_w = 0.5;
  params.energy.battery_j = 2.0;
  Rig rig(params, 1);
  auto& [sim, radio, rec, motion] = rig;
  radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
  sim.run_until(sim::time_at(10.0));
  REQUIRE(rec.emptied.size() == 1);
  CHECK(sim::to_seconds(radio.stats(sim::node_id(0)).died_at) == Approx(4.0));
  CHECK(radio.energy_j(sim::node_id(0)) == Approx(2.0));
}

TEST_CASE("loss draws of one link do not depend on other nodes", "[net]") {
  // Adding a node elsewhere must not change which receptions of an existing link are lost.
  auto lost_pattern = [](int extra_nodes) {
    net::RadioParams params;
    params.loss = 0.5;
    Rig rig(params, 5);
    auto& [sim, radio, rec, motion] = rig;
    radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
    radio.add_static_node(sim::node_id(1), Vec2{0.05, 0}, 1);
    for (int i = 0; i < extra_nodes; ++i)
      radio.add_static_node(sim::node_id(2 + i), Vec2{0.01 * i, 0.02}, 2 + i);
    std::vector<double> got;
    for (int k = 0; k < 64; ++k)
      radio.broadcast(sim::node_id(0), 0.1, beacon(sim::node_id(0)));
    sim.run();
    for (const auto& d : rec.deliveries)
      if (d.receiver == sim::node_id(1)) got.push_back(d.at_s);
    return got;
  };
  CHECK(lost_pattern(0) == lost_pattern(7));
}

TEST_CASE("receptions bring forward the moment an idle drain empties a battery", "[net]") {
  net::RadioParams params;
  params.energy.idle_power_w = 0.5;
  params.energy.battery_j = 2.0;
  Rig rig(params, 1);
  auto& [sim, radio, rec, motion] = rig;
  radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
  radio.add_static_node(sim::node_id(1), Vec2{0.01, 0}, 1);
  sim.at(sim::time_at(1.0), [&radio] {
    for (int k = 0; k < 1000; ++k)
      radio.broadcast(sim::node_id(0), 0.02, beacon(sim::node_id(0)));
  });
  sim.run_until(sim::time_at(10.0));
  const double bits =
      8.0 * (params.sizes.header_bytes + params.sizes.id_bytes + params.sizes.position_bytes);
  const double heard_j = 1000 * bits * params.energy.electronics_j_per_bit;
  // Node 1 drains 0.5 W and paid for 1000 receptions: empty at (2 J − heard) / 0.5 W.
  CHECK(sim::to_seconds(radio.stats(sim::node_id(1)).died_at) ==
        Approx((2.0 - heard_j) / 0.5).epsilon(1e-9));
  CHECK(radio.energy_j(sim::node_id(1)) == Approx(2.0).epsilon(1e-9));
}

TEST_CASE("looking at idle energy does not change it", "[net]") {
  auto idle_after = [](int looks) {
    sim::Simulator sim;
    net::RadioParams params;
    params.energy.idle_power_w = 0.3;
    net::Radio radio(sim, params, 1);
    radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
    for (int k = 1; k <= looks; ++k) {
      sim.run_until(sim::time_at(7.0 * k / looks));
      (void)radio.stats(sim::node_id(0));
    }
    sim.run_until(sim::time_at(7.0));
    return radio.stats(sim::node_id(0)).energy_idle_j;
  };
  CHECK(idle_after(1) == idle_after(1000));
}

TEST_CASE("idle time counts from a late start and skips the time a node was down", "[net]") {
  // The radio keeps when a node started and went down apart from its hot record, written only
  // for the nodes they concern: node 1 starts at 2 s, node 0 is down from 1 s to 3 s.
  sim::Simulator sim;
  net::RadioParams params;
  params.energy.idle_power_w = 0.25;
  net::Radio radio(sim, params, 1);
  radio.enable_failures();
  radio.add_static_node(sim::node_id(0), Vec2{0, 0}, 0);
  sim.at(sim::time_at(1.0), [&radio] { radio.take_down(sim::node_id(0)); });
  sim.at(sim::time_at(2.0), [&radio] { radio.add_static_node(sim::node_id(1), Vec2{0.5, 0}, 1); });
  sim.run_until(sim::time_at(2.5));
  CHECK_FALSE(radio.stats(sim::node_id(0)).alive);
  CHECK(radio.stats(sim::node_id(0)).died_at == sim::time_at(1.0));
  CHECK(radio.stats(sim::node_id(0)).energy_idle_j == Approx(0.25 * 1.0));
  CHECK(radio.stats(sim::node_id(1)).energy_idle_j == Approx(0.25 * 0.5));
  sim.at(sim::time_at(3.0), [&radio] { CHECK(radio.bring_up(sim::node_id(0))); });
  sim.run_until(sim::time_at(5.0));
  const net::NodeRadioStats restarted = radio.stats(sim::node_id(0));
  CHECK(restarted.alive);
  CHECK(restarted.died_at == sim::kTimeMax);
  CHECK(restarted.energy_idle_j == Approx(0.25 * (1.0 + 2.0)));
  CHECK(radio.stats(sim::node_id(1)).energy_idle_j == Approx(0.25 * 3.0));
  CHECK(radio.stats(sim::node_id(1)).died_at == sim::kTimeMax);
}

TEST_CASE("frames booked in bulk on a sensor grid give every node exactly the brute-force counts",
          "[net]") {
  // A 30 × 30 grid (indexed as lines and booked run by run) plus moving robots; random
  // broadcasts of a type the sensors ignore (bulk), of a type they listen to (one by one), and
  // unicasts with their overhearers (bulk).
  net::RadioParams params;
  params.max_range = 0.5;
  params.overhearing_thread = GENERATE(false, true);  // booked inline, or by the second thread
  params.overhearing_thread_min_nodes = 0;
  Rig rig(params, 3);
  auto& [sim, radio, rec, motion] = rig;
  const int side = 30, robots = 40, sensors = side * side;
  const std::uint32_t sensor_interest = 1u << static_cast<unsigned>(net::MessageType::position);
  add_grid_and_robots(rig, side, robots, 0.2, 11, sensor_interest);
  sim::RandomStream rng(12);
  const int n = sensors + robots;
  std::vector<std::uint64_t> heard(n, 0), overheard(n, 0), delivered(n, 0);
  auto send = [&](std::uint32_t src, std::uint32_t dst, double range, int kind) {
    const Vec2 p = radio.position(sim::node_id(src));
    net::Payload payload = kind == 0 ? net::Payload{net::Discover{sim::node_id(src), range, p}}
                                     : net::Payload{net::Position{sim::node_id(src), p}};
    const auto bytes = net::size_bytes(payload, params.sizes);
    const bool unicast = dst != src;
    const double r = std::min(unicast ? (radio.position(sim::node_id(dst)) - p).norm() : range,
                              params.max_range);
    for (int j = 0; j < n; ++j) {
      if (static_cast<std::uint32_t>(j) == src) continue;
      const Vec2 q = radio.position(sim::node_id(j));
      const double dx = q.x() - p.x(), dy = q.y() - p.y();
      const bool in = unicast && static_cast<std::uint32_t>(j) == dst ? (q - p).norm() <= r
                                                                      : dx * dx + dy * dy <= r * r;
      if (!in) continue;
      heard[j] += bytes;
      if (unicast && static_cast<std::uint32_t>(j) != dst) ++overheard[j];
    }
    if (unicast)
      radio.unicast(sim::node_id(src), sim::node_id(dst), std::move(payload));
    else
      radio.broadcast(sim::node_id(src), range, std::move(payload));
  };
  for (int k = 0; k < 600; ++k) {
    const double t = rng.uniform(0.0, 3.0);
    const auto src = static_cast<std::uint32_t>(rng.below(n));
    auto dst = static_cast<std::uint32_t>(rng.below(n));
    const int kind = static_cast<int>(rng.below(3));  // 0 DISCOVER (bulk), 1 POSITION, 2 unicast
    if (kind != 2) dst = src;
    if (kind == 2 && dst == src) dst = (src + 1) % n;
    const double range = rng.uniform(0.0, 0.6);
    sim.at(sim::time_at(t),
           [&send, src, dst, range, kind] { send(src, dst, range, kind == 2 ? 1 : kind); });
  }
  sim.run();
  for (int j = 0; j < n; ++j) {
    const net::NodeRadioStats s = radio.stats(sim::node_id(j));
    INFO("node " << j);
    REQUIRE(s.heard_bytes == heard[j]);
    REQUIRE(s.overheard_count == overheard[j]);
  }
}

TEST_CASE(
    "bursts of unicasts to one moving robot at one instant are overheard exactly as brute force "
    "says",
    "[net]") {
  // Replies to one robot at one instant reuse the robots near it (Radio::NearAddressee): senders
  // near and far in either order (the neighbourhood grows), and bursts to two robots interleaved
  // at one instant (it is rebuilt), must give the counts a per-frame range check gives.
  net::RadioParams params;
  params.max_range = 0.6;
  params.overhearing_thread = GENERATE(false, true);
  params.overhearing_thread_min_nodes = 0;
  Rig rig(params, 5);
  auto& [sim, radio, rec, motion] = rig;
  const int side = 32, robots = 300, sensors = side * side;  // robots above the linear-scan limit
  static_assert(300 > net::Radio::kMobileScanLimit);
  add_grid_and_robots(rig, side, robots, 0.3, 21, 0xFFFFFFFFu);
  sim::RandomStream rng(22);
  const int n = sensors + robots;
  std::vector<std::uint64_t> overheard(n, 0);
  auto send = [&](std::uint32_t src, std::uint32_t dst) {
    const Vec2 p = radio.position(sim::node_id(src));
    const double r = std::min((radio.position(sim::node_id(dst)) - p).norm(), params.max_range);
    for (int j = 0; j < n; ++j) {
      if (static_cast<std::uint32_t>(j) == src || static_cast<std::uint32_t>(j) == dst) continue;
      const Vec2 q = radio.position(sim::node_id(j));
      const double dx = q.x() - p.x(), dy = q.y() - p.y();
      if (dx * dx + dy * dy <= r * r) ++overheard[j];
    }
    radio.unicast(sim::node_id(src), sim::node_id(dst),
                  net::Payload{net::Position{sim::node_id(src), p}});
  };
  // Each burst: the 60 sensors nearest to robot `a` send to it, nearest first (its neighbourhood
  // must grow) or farthest first, and every 7th sends to the robot nearest to `a` instead.
  std::vector<std::uint32_t> addressees;
  for (int k = 0; k < 40; ++k)
    addressees.push_back(static_cast<std::uint32_t>(sensors + rng.below(robots)));
  auto run_burst = [&](std::size_t index) {
    const std::uint32_t a = addressees[index];
    const Vec2 pa = radio.position(sim::node_id(a));
    auto distance_to_a = [&](std::uint32_t x) {
      return (radio.position(sim::node_id(x)) - pa).norm();
    };
    std::uint32_t b =
        a == static_cast<std::uint32_t>(sensors) ? a + 1 : static_cast<std::uint32_t>(sensors);
    for (int r = 0; r < robots; ++r) {
      const auto id = static_cast<std::uint32_t>(sensors + r);
      if (id != a && distance_to_a(id) < distance_to_a(b)) b = id;
    }
    std::vector<std::uint32_t> order(static_cast<std::size_t>(sensors));
    for (int k = 0; k < sensors; ++k)
      order[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(k);
    std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
      return distance_to_a(x) < distance_to_a(y);
    });
    order.resize(60);
    if (index % 2 == 1) std::reverse(order.begin(), order.end());
    for (std::size_t k = 0; k < order.size(); ++k) {
      if (k == 30) {
        // A third robot jumps next to the next sender (the mobile index is rebuilt mid-burst).
        const auto c = static_cast<std::uint32_t>(sensors + (index * 7) % robots);
        if (c != a && c != b) {
          auto& [p0, v] = motion.lines[c];
          p0 = radio.position(sim::node_id(order[k])) + Vec2{1e-4, 0} -
               sim::to_seconds(sim.now()) * v;
          radio.mobile_node_jumped();
        }
      }
      send(order[k], k % 7 == 3 ? b : a);
    }
  };
  for (std::size_t k = 0; k < addressees.size(); ++k)
    sim.at(sim::time_at(0.05 * static_cast<double>(k)), [&run_burst, k] { run_burst(k); });
  sim.run();
  for (int j = 0; j < n; ++j) {
    INFO("node " << j);
    REQUIRE(radio.stats(sim::node_id(j)).overheard_count == overheard[j]);
  }
}
