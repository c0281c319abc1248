// A radio cut into tiles by space (docs/decisions/0012-partitioned-runs.md): each tile books and
// delivers to its own static nodes and to every mobile node (or the first tile alone runs them),
// ships its static senders' frames to the other tiles after each conservative window, and the
// tiles' ledgers, absorbed into one, read as the whole radio's. A network of sensors on a grid and
// robots on circles exchanges SENSE, READING, REPORT and NEIGHBOR frames; cut into 2 and 3 tiles on
// 1 and 2 threads, every node receives the same frames at the same times and every counter and
// energy is the same — also under partitions and degraded areas that change while frames wait to
// cross.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <tuple>
#include <vector>

#include "net/radio.hpp"
#include "net/tile_ledger.hpp"
#include "sim/windowed_run.hpp"

using namespace masnet;
using net::Vec2;
using sim::NodeId;

namespace {

constexpr std::uint32_t kSide = 24;  // sensors per row and column, 0.25 apart
constexpr std::uint32_t kSensors = kSide * kSide;
constexpr std::uint32_t kRobots = 6;
constexpr double kSpacing = 0.25;
const sim::Time kEnd = sim::kTimeZero + sim::seconds(0.12);

// Robots circle about points of the field: their positions are a function of time.
struct Circles : net::MobilePositions {
  const sim::Simulator* sim = nullptr;
  Vec2 position(NodeId node) const override {
    const double i = sim::index(node) - kSensors;
    const double angle = 25.0 * sim::to_seconds(sim->now()) + i;
    return Vec2{1.0 + 0.8 * i + 0.9 * std::cos(angle), 2.9 + 0.4 * i + 0.9 * std::sin(angle)};
  }
  double speed_bound() const override { return 25.0 * 0.9; }
};

using Reception = std::tuple<std::int64_t, std::uint32_t, std::uint64_t, int>;

// Link faults that come and go every 7 ms (world events, the same in every tile): a partition
// across the grid and a degraded disk that two robots' circles cross.
bool g_link_faults = false;

// The nodes' behaviour: the same code in the whole run and in every tile (a tile runs its own
// sensors and every robot).
struct Network : net::RadioListener {
  sim::Simulator sim;
  Circles circles;
  std::unique_ptr<net::Radio> radio;
  std::vector<std::vector<Reception>> received{kSensors + kRobots};
  std::vector<std::uint32_t> heard_senses = std::vector<std::uint32_t>(kSensors + kRobots, 0);
  std::vector<std::uint32_t> readings = std::vector<std::uint32_t>(kSensors + kRobots, 0);

  explicit Network(const net::RadioParams& params) {
    sim.order_ties_by_origin();
    radio = std::make_unique<net::Radio>(sim, params, 7);
    circles.sim = &sim;
    radio->set_mobile_positions(&circles);
    radio->set_listener(this);
    for (std::uint32_t k = 0; k < kSensors; ++k)
      radio->add_static_node(sim::node_id(k), Vec2{kSpacing * (k % kSide), kSpacing * (k / kSide)},
                             k);
    for (std::uint32_t r = 0; r < kRobots; ++r)
      radio->add_mobile_node(sim::node_id(kSensors + r), kSensors + r);
  }
  // Robots ask the sensors around them every 10 ms, each at its own phase (`robots`: this
  // network runs them).
  void start(bool robots = true) {
    if (g_link_faults) sim.after(sim::seconds(0.007), [this] { toggle_link_faults(1); });
    for (std::uint32_t r = 0; r < kRobots && robots; ++r) {
      const NodeId robot = sim::node_id(kSensors + r);
      sim.after_as(sim::origin_of(robot), sim::seconds(0.001 * (r + 1)),
                   [this, robot] { sense(robot); });
    }
  }
  void toggle_link_faults(std::uint32_t step) {
    net::LinkFaults& faults = radio->link_faults();
    if (step % 2 == 1) faults.add_cut(step, net::LineCut{Vec2{2.9, -1.0}, Vec2{3.1, 7.0}});
    if (step % 3 == 1) {
      net::DegradedArea area;
      area.region.center = Vec2{2.6, 3.7};
      area.region.radius = 0.8;
      area.loss = 0.9;
      faults.add_degraded(step, area);
    }
    if (step > 1) faults.remove(step - 1);
    radio->link_faults_changed();
    sim.after(sim::seconds(0.007), [this, step] { toggle_link_faults(step + 1); });
  }
  void sense(NodeId robot) {
    radio->broadcast(robot, 1.1, net::Sense{robot, 0, {}});
    sim.after(sim::seconds(0.01), [this, robot] { sense(robot); });
  }
  void on_frame(NodeId receiver, const net::Frame& frame) override {
    received[sim::index(receiver)].emplace_back(sim::to_ns(sim.now()), sim::index(frame.source),
                                                frame.number, static_cast<int>(frame.type));
    const std::uint32_t me = sim::index(receiver);
    if (me < kSensors && frame.type == net::MessageType::sense) {
      // Answer the robot; every other SENSE, tell the sensors around too.
      radio->unicast(receiver, frame.source, net::Reading{receiver, 0, 1.0, Vec2{0, 0}});
      if (++heard_senses[me] % 2 == 0)
        radio->broadcast(receiver, 0.6, net::Report{receiver, 1.0, Vec2{0, 0}});
    } else if (me >= kSensors && frame.type == net::MessageType::reading) {
      // Every fifth reading is acknowledged: a robot's unicast to a sensor of any tile.
      if (++readings[me] % 5 == 0)
        radio->unicast(receiver, frame.source, net::Neighbor{receiver, Vec2{0, 0}});
    }
  }
};

struct Tiled {
  std::vector<std::unique_ptr<Network>> tiles;
};

// The whole network cut into `count` tiles of contiguous slots, run in windows of the radio's
// latency on `threads` threads, the frames that crossed shipped after each window. With
// `robots_in_first`, only the first tile runs the robots (whose course no decision changes).
Tiled run_tiled(const net::RadioParams& params, std::uint32_t count, unsigned threads,
                bool robots_in_first) {
  Tiled t;
  std::vector<sim::Simulator*> parts;
  for (std::uint32_t i = 0; i < count; ++i) {
    t.tiles.push_back(std::make_unique<Network>(params));
    net::Radio& radio = *t.tiles.back()->radio;
    const auto slots = static_cast<std::uint32_t>(radio.static_slots().size());
    radio.own_static_slots(slots * i / count, slots * (i + 1) / count);
    if (robots_in_first) radio.home_mobiles(i == 0);
    t.tiles.back()->start(!robots_in_first || i == 0);
    parts.push_back(&t.tiles.back()->sim);
  }
  sim::WindowedRun run(parts, sim::seconds(params.latency_s), threads);
  run.run_until(kEnd, [&](sim::Time) {
    for (std::uint32_t from = 0; from < count; ++from) {
      std::vector<net::FrameRecord>& outbox = t.tiles[from]->radio->outbox();
      for (const net::FrameRecord& record : outbox)
        for (std::uint32_t to = 0; to < count; ++to)
          if (to != from) t.tiles[to]->radio->inject(record);
      outbox.clear();
    }
  });
  return t;
}

void check_same_ledger(net::Radio& whole, net::Radio& merged) {
  for (std::uint32_t n = 0; n < kSensors + kRobots; ++n) {
    INFO("node " << n);
    const net::NodeRadioStats a = whole.stats(sim::node_id(n)), b = merged.stats(sim::node_id(n));
    CHECK(a.heard_bytes == b.heard_bytes);
    CHECK(a.overheard_count == b.overheard_count);
    CHECK(a.lost_count == b.lost_count);
    CHECK(a.unreachable_count == b.unreachable_count);
    CHECK(a.energy_tx_j == b.energy_tx_j);
    CHECK(a.energy_rx_j == b.energy_rx_j);
    for (std::size_t t = 0; t < net::kBuiltinMessageTypeCount; ++t) {
      const auto type = static_cast<net::MessageType>(t);
      const net::TypeCounters x = whole.counters(sim::node_id(n), type),
                              y = merged.counters(sim::node_id(n), type);
      CHECK(std::tie(x.tx_count, x.tx_bytes, x.rx_count, x.rx_bytes) ==
            std::tie(y.tx_count, y.tx_bytes, y.rx_count, y.rx_bytes));
    }
  }
  for (std::size_t t = 0; t < net::kBuiltinMessageTypeCount; ++t) {
    const auto type = static_cast<net::MessageType>(t);
    const net::TypeCounters& x = whole.totals(type);
    const net::TypeCounters& y = merged.totals(type);
    CHECK(std::tie(x.tx_count, x.tx_bytes, x.rx_count, x.rx_bytes) ==
          std::tie(y.tx_count, y.tx_bytes, y.rx_count, y.rx_bytes));
    CHECK(whole.type_tx_energy_j(type) == merged.type_tx_energy_j(type));
    CHECK(whole.type_rx_energy_j(type) == merged.type_rx_energy_j(type));
  }
  CHECK(whole.total_tx_energy_j() == merged.total_tx_energy_j());
  CHECK(whole.total_rx_energy_j() == merged.total_rx_energy_j());
  CHECK(whole.traffic_fingerprint().value() == merged.traffic_fingerprint().value());
}

void check_tiles_equal_whole(const net::RadioParams& params, bool robots_in_first = false) {
  Network whole(params);
  whole.start();
  whole.sim.run_until(kEnd);
  std::uint64_t readings = 0;
  for (std::uint32_t r = 0; r < kRobots; ++r)
    readings += whole.readings[kSensors + r];
  REQUIRE(readings > 1000);  // the robots met many sensors of every tile
  for (const std::uint32_t count : {2u, 3u}) {
    for (const unsigned threads : {1u, 2u}) {
      INFO(count << " tiles on " << threads << " threads");
      Tiled tiled = run_tiled(params, count, threads, robots_in_first);
      std::uint64_t crossed_reports = 0;
      for (std::uint32_t n = 0; n < kSensors + kRobots; ++n) {
        INFO("node " << n);
        for (const auto& tile : tiled.tiles) {
          if (!tile->radio->owns(sim::node_id(n))) continue;
          CHECK(tile->received[n] == whole.received[n]);
        }
      }
      // Sensors of one tile heard REPORTs from sensors of another.
      for (const auto& tile : tiled.tiles)
        for (std::uint32_t n = 0; n < kSensors; ++n)
          if (tile->radio->owns(sim::node_id(n)))
            for (const Reception& r : tile->received[n])
              crossed_reports += std::get<3>(r) == static_cast<int>(net::MessageType::report) &&
                                 !tile->radio->owns(sim::node_id(std::get<1>(r)));
      CHECK(crossed_reports > 0);
      // The kernel's fingerprint: each origin's stream from a tile that holds it (the world's
      // and the robots' are the same in every tile).
      std::vector<sim::Fingerprint> streams(1 + kSensors + kRobots);
      for (std::uint32_t origin = 0; origin < streams.size(); ++origin)
        for (const auto& tile : tiled.tiles) {
          const std::vector<sim::Fingerprint> held = tile->sim.origin_streams();
          if (origin == 0 || tile->radio->owns(sim::node_id(origin - 1))) {
            if (origin < held.size()) streams[origin] = held[origin];
            break;
          }
        }
      CHECK(sim::combine_origin_streams(streams).value() == whole.sim.fingerprint().value());
      net::Radio& merged = *tiled.tiles[0]->radio;
      for (std::uint32_t i = 1; i < count; ++i)
        merged.absorb_tile(tiled.tiles[i]->radio->tile_ledger());
      check_same_ledger(*whole.radio, merged);
    }
  }
}

}  // namespace

TEST_CASE("radio tiles: 2 and 3 tiles on 1 and 2 threads deliver and book as the whole radio",
          "[net][tiles]") {
  net::RadioParams params;
  params.level = net::RadioLevel::ideal;
  check_tiles_equal_whole(params);
}

TEST_CASE("radio tiles: robots run by the first tile alone, which ships their frames",
          "[net][tiles]") {
  // The other tiles neither book nor deliver a frame to a robot: they ship it to the first,
  // which books and delivers it there, and ships the robots' frames to them.
  net::RadioParams params;
  params.level = net::RadioLevel::ideal;
  check_tiles_equal_whole(params, true);
  params.level = net::RadioLevel::airtime;
  params.loss = 0.2;
  check_tiles_equal_whole(params, true);
  params.level = net::RadioLevel::ideal;
  params.latency_s = 0.01;
  params.loss = 0.1;
  g_link_faults = true;
  check_tiles_equal_whole(params, true);
  g_link_faults = false;
}

TEST_CASE("radio tiles: under partitions and degraded areas that change while frames cross",
          "[net][tiles]") {
  // Windows of 10 ms: the faults change and the robots move up to 22 cm (most of a sensor
  // spacing) between a frame's send and its injection into the other tiles, which must judge it
  // as it was when sent: judged there and then instead, the test fails.
  net::RadioParams params;
  params.level = net::RadioLevel::ideal;
  params.latency_s = 0.01;
  params.loss = 0.1;
  g_link_faults = true;
  check_tiles_equal_whole(params);
  g_link_faults = false;
}

TEST_CASE("radio tiles: with airtime queues and losses too", "[net][tiles]") {
  net::RadioParams params;
  params.level = net::RadioLevel::airtime;
  params.loss = 0.2;
  check_tiles_equal_whole(params);
}

TEST_CASE("radio tiles: a frame is shipped only when another tile has a node it can reach",
          "[net][tiles]") {
  // Tile 1 of 3 owns rows 8 to 15 (y from 2.0 to 3.75). A sensor's frame goes into its outbox
  // when its disk reaches a row of another tile, any mobile node, or a mobile addressee.
  net::RadioParams params;
  params.level = net::RadioLevel::ideal;
  Network tile(params);
  net::Radio& radio = *tile.radio;
  const auto slots = static_cast<std::uint32_t>(radio.static_slots().size());
  radio.own_static_slots(slots / 3, slots * 2 / 3);
  auto sensor = [](std::uint32_t column, std::uint32_t row) {
    return sim::node_id(row * kSide + column);
  };
  auto shipped_after = [&](auto send) {
    radio.outbox().clear();
    send();
    return radio.outbox().size();
  };
  const double range = 0.3;  // the rows next to the sender's, not the ones after
  for (const std::uint32_t row : {8u, 12u, 15u})
    for (std::uint32_t r = 0; r < kRobots; ++r)  // no robot hears these frames
      REQUIRE(
          (tile.circles.position(sim::node_id(kSensors + r)) - Vec2{kSpacing * 22, kSpacing * row})
              .norm() > range);
  const net::Report report{sim::node_id(0), 1.0, Vec2{0, 0}};
  CHECK(shipped_after([&] { radio.broadcast(sensor(22, 12), range, report); }) == 0);
  CHECK(shipped_after([&] { radio.broadcast(sensor(22, 8), range, report); }) == 1);   // row 7
  CHECK(shipped_after([&] { radio.broadcast(sensor(22, 15), range, report); }) == 1);  // row 16
  const net::Neighbor hello{sim::node_id(0), Vec2{0, 0}};
  CHECK(shipped_after([&] { radio.unicast(sensor(22, 12), sensor(22, 13), hello); }) == 0);
  CHECK(shipped_after([&] { radio.unicast(sensor(22, 15), sensor(22, 16), hello); }) == 1);
  // A robot's copy lives in every tile: a frame to it, or one it hears, is every tile's.
  const NodeId robot = sim::node_id(kSensors);
  const Vec2 robot_at = tile.circles.position(robot);
  // The sensor 0.9 from the robot: its disk holds rows 9 to 15 and no other robot.
  REQUIRE((radio.position(sensor(4, 12)) - robot_at).norm() < 0.91);
  CHECK(shipped_after([&] { radio.unicast(sensor(4, 12), robot, hello); }) == 1);
  std::uint32_t beside = 0;  // the sensor of this tile closest to the robot
  for (std::uint32_t k = slots / 3; k < slots * 2 / 3; ++k)
    if ((radio.position(sim::node_id(k)) - robot_at).norm() <
        (radio.position(sim::node_id(beside)) - robot_at).norm())
      beside = k;
  REQUIRE((radio.position(sim::node_id(beside)) - robot_at).norm() < range);
  CHECK(shipped_after([&] { radio.broadcast(sim::node_id(beside), range, report); }) == 1);
}

TEST_CASE("radio tiles: a frame crosses to the tile that runs the robots only if they need it",
          "[net][tiles]") {
  // Tile 2 of 3 owns rows 16 to 23 (y from 4.0). Robot 5 stands at y ≈ 4.04, just inside it.
  net::RadioParams params;
  params.level = net::RadioLevel::ideal;
  const NodeId robot = sim::node_id(kSensors + 5);
  const net::Neighbor hello{sim::node_id(0), Vec2{0, 0}};
  const net::Sense sense{robot, 0, {}};
  for (const bool robots_here : {false, true}) {
    INFO("this tile runs the robots: " << robots_here);
    Network tile(params);
    net::Radio& radio = *tile.radio;
    const auto slots = static_cast<std::uint32_t>(radio.static_slots().size());
    radio.own_static_slots(slots * 2 / 3, slots);
    radio.home_mobiles(robots_here);
    auto shipped_after = [&](auto send) {
      radio.outbox().clear();
      send();
      return radio.outbox().size();
    };
    const Vec2 robot_at = tile.circles.position(robot);
    const NodeId sensor = sim::node_id(17 * kSide + 21);  // (5.25, 4.25)
    const double distance = (radio.position(sensor) - robot_at).norm();
    // The sensor's disk to the robot holds no row of another tile and no other robot.
    REQUIRE(radio.position(sensor).y() - distance > 4.0);
    for (std::uint32_t r = 0; r < kRobots; ++r)
      if (r != 5)
        REQUIRE(
            (tile.circles.position(sim::node_id(kSensors + r)) - radio.position(sensor)).norm() >
            distance);
    // To the robot: another tile's business unless this one runs it.
    CHECK(shipped_after([&] { radio.unicast(sensor, robot, hello); }) == (robots_here ? 0 : 1));
    if (!robots_here) continue;
    // The robot's own frames cross when they reach another tile's rows (row 15, y = 3.75).
    REQUIRE(robot_at.y() - 0.3 < 3.75);
    REQUIRE(robot_at.y() - 0.02 > 3.75);
    CHECK(shipped_after([&] { radio.broadcast(robot, 0.3, sense); }) == 1);
    CHECK(shipped_after([&] { radio.broadcast(robot, 0.02, sense); }) == 0);
  }
}
