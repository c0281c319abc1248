// The radius-doubling protocol and its variants driven step by step through a fake host:
// no radio, no world; the test decides which replies arrive and fires the timers.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "protocols/heard_cell.hpp"
#include "protocols/voronoi_protocol.hpp"

using namespace masnet;
using namespace masnet::protocols;
using net::Vec2;
using sim::NodeId;

namespace {

struct Sent {
  double range;  // broadcast range; -1 for unicast
  NodeId to;
  net::Payload payload;
};

struct Timer {
  sim::Time at;
  std::uint32_t kind;
  std::uint64_t id;
};

class FakeHost : public RobotHost {
 public:
  sim::Time clock = sim::kTimeZero;
  Vec2 here{0.5, 0.5};
  std::vector<Sent> sent;
  std::vector<Timer> timers;
  std::vector<UpdateRecord> records;
  std::vector<Vec2> targets;
  std::uint64_t next_timer = 1;

  sim::Time now() const override { return clock; }
  NodeId id() const override { return sim::node_id(0); }
  Vec2 position() const override { return here; }
  std::uint32_t broadcast(double range, net::Payload payload) override {
    sent.push_back({range, sim::kNoNode, std::move(payload)});
    return 20;
  }
  std::uint32_t unicast(NodeId to, net::Payload payload) override {
    sent.push_back({-1.0, to, std::move(payload)});
    return 20;
  }
  TimerHandle set_timer(sim::Duration delay, std::uint32_t kind) override {
    timers.push_back({clock + delay, kind, next_timer});
    return TimerHandle{0, next_timer++};
  }
  void cancel_timer(TimerHandle) override {}
  void set_target(const Vec2& target) override { targets.push_back(target); }
  void update_finished(const UpdateRecord& record) override { records.push_back(record); }
  double sensor_area(NodeId) const override { return 1.0; }
  const net::MessageSizes& message_sizes() const override { return sizes; }
  net::MessageSizes sizes;

  /// Fires the earliest timer of `kind` (advancing the clock to it) and returns true.
  bool fire(VoronoiProtocol& p, std::uint32_t kind) {
    auto it = std::min_element(timers.begin(), timers.end(), [&](const Timer& a, const Timer& b) {
      return (a.kind == kind) > (b.kind == kind) ||
             ((a.kind == kind) == (b.kind == kind) && a.at < b.at);
    });
    if (it == timers.end() || it->kind != kind) return false;
    const Timer t = *it;
    timers.erase(it);
    clock = std::max(clock, t.at);
    p.on_timer(kind);
    return true;
  }
  const Sent& last() const { return sent.back(); }
};

net::Frame frame(net::Payload payload) {
  net::Frame f;
  f.type = net::type_of(payload);
  f.size_bytes = 20;
  f.payload = std::move(payload);
  return f;
}

struct World {
  std::map<std::uint32_t, Vec2> robots;   // other robots (id -> position)
  std::map<std::uint32_t, Vec2> sensors;  // sensors (id -> position), reading 1
};

// Plays the radio: robots within the DISCOVER radius reply, sensors inside the SENSE cell
// within its range reply.
void answer_last(FakeHost& host, VoronoiProtocol& p, const World& w) {
  const Sent& s = host.last();
  if (const auto* d = std::get_if<net::Discover>(&s.payload)) {
    for (const auto& [id, pos] : w.robots)
      if ((pos - d->position).norm() <= s.range)
        p.on_frame(frame(net::Neighbor{sim::node_id(id), pos}));
  } else if (const auto* q = std::get_if<net::Sense>(&s.payload)) {
    const ConvexPolygon cell{q->cell};
    for (const auto& [id, pos] : w.sensors)
      if ((pos - host.here).norm() <= s.range && contains(cell, pos))
        p.on_frame(frame(net::Reading{sim::node_id(id), q->update, 1.0, pos}));
  }
}

ProtocolContext unit_square(double max_range = 1.5) {
  return ProtocolContext{rectangle(0, 0, 1, 1), DensityScaling{}, max_range};
}

// Initialises with reports at the given distances east of the robot, then returns.
void initialise(FakeHost& host, VoronoiProtocol& p, std::vector<double> report_distances,
                double max_range = 1.5) {
  p.start();
  REQUIRE(std::holds_alternative<net::Position>(host.last().payload));
  CHECK(host.last().range == max_range);  // POSITION at max range
  for (double d : report_distances)
    p.on_frame(frame(net::Report{sim::node_id(100), 1.0, host.here + Vec2{d, 0.0}}));
  REQUIRE(host.fire(p, VoronoiProtocol::kInitEnd));
}

// Runs one whole update; returns its record.
UpdateRecord run_update(FakeHost& host, VoronoiProtocol& p, const World& w) {
  const std::size_t before = host.records.size();
  REQUIRE(host.fire(p, VoronoiProtocol::kTick));
  for (int guard = 0; guard < 50 && host.records.size() == before; ++guard) {
    answer_last(host, p, w);
    if (!host.fire(p, VoronoiProtocol::kRoundEnd))
      REQUIRE(host.fire(p, VoronoiProtocol::kSenseEnd));
    else if (std::holds_alternative<net::Sense>(host.last().payload)) {
      answer_last(host, p, w);
      REQUIRE(host.fire(p, VoronoiProtocol::kSenseEnd));
    }
  }
  REQUIRE(host.records.size() == before + 1);
  return host.records.back();
}

std::vector<double> discover_ranges(const FakeHost& host) {
  std::vector<double> r;
  for (const Sent& s : host.sent)
    if (std::holds_alternative<net::Discover>(s.payload)) r.push_back(s.range);
  return r;
}

}  // namespace

TEST_CASE("initialisation sets R_i to the farthest reporting sensor, or R_min", "[protocols]") {
  ProtocolParams params;
  params.decay.min = 0.05;
  {
    FakeHost host;
    VoronoiProtocol p(host, params, unit_square(), 0.003);
    initialise(host, p, {0.1, 0.23, 0.05});
    CHECK(p.radius() == Approx(0.23));
  }
  {
    FakeHost host;
    VoronoiProtocol p(host, params, unit_square(), 0.003);
    initialise(host, p, {});
    CHECK(p.radius() == 0.05);
  }
}

TEST_CASE("the paper's rule: R grows to 2d and stops on R >= 2d, where a strict test would loop",
          "[protocols]") {
  // Robot at the centre, a neighbour 0.4375 east, sensors 0.1875 east and 0.125 south
  // (binary fractions: every distance below is exact).
  World w;
  w.robots[1] = Vec2{0.9375, 0.5};
  w.sensors[10] = Vec2{0.6875, 0.5};
  w.sensors[11] = Vec2{0.5, 0.375};
  ProtocolParams params;  // growth to_2d, criterion sensors, no shrink
  params.decay.patience = 0;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.001);
  initialise(host, p, {0.25});
  const UpdateRecord r = run_update(host, p, w);
  // Round 1 at R = 0.25 finds nobody; d = 0.1875 so R ← 0.375; round 2 finds nobody new and
  // stops because 0.375 >= 2·0.1875 (the paper's strict '>' would repeat forever).
  CHECK(discover_ranges(host) == std::vector<double>{0.25, 0.375});
  CHECK(r.rounds == 2);
  CHECK(r.radius == 0.375);
  CHECK(r.neighbours.empty());
  CHECK(r.readings == 2);
  CHECK_FALSE(r.truncated);
  // The SENSE of the first round reached exactly R (the cell was the whole square).
  const auto sense = std::find_if(host.sent.begin(), host.sent.end(), [](const Sent& s) {
    return std::holds_alternative<net::Sense>(s.payload);
  });
  REQUIRE(sense != host.sent.end());
  CHECK(sense->range == 0.25);
  // Centroid of the two equally weighted readings.
  CHECK(r.centroid.x() == Approx((0.6875 + 0.5) / 2));
  CHECK(r.centroid.y() == Approx((0.5 + 0.375) / 2));
}

TEST_CASE("Cortés' doubling finds the neighbour that 2d misses", "[protocols]") {
  World w;
  w.robots[1] = Vec2{0.9375, 0.5};
  w.sensors[10] = Vec2{0.6875, 0.5};
  w.sensors[11] = Vec2{0.5, 0.375};
  ProtocolParams params;
  params.growth = Growth::doubling;
  params.decay.patience = 0;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.001);
  initialise(host, p, {0.25});
  const UpdateRecord r = run_update(host, p, w);
  CHECK(discover_ranges(host) == std::vector<double>{0.25, 0.5});  // 2R, not 2d
  CHECK(r.neighbours == std::vector<NodeId>{sim::node_id(1)});
  CHECK(r.rounds == 2);
}

TEST_CASE("the vertex criterion grows R until the whole cell is certified", "[protocols]") {
  World w;
  w.robots[1] = Vec2{0.9375, 0.5};
  ProtocolParams params;
  params.criterion = StopCriterion::vertices;
  params.decay.patience = 0;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.001);
  initialise(host, p, {0.25});
  const UpdateRecord r = run_update(host, p, w);
  // d = min(R, farthest vertex): 0.25 → R 0.5 (neighbour found, cell [0, 0.71875] × [0, 1],
  // farthest vertex √0.5) → d = 0.5 → R 1 → d = √0.5 → R = 2√0.5, which satisfies R >= 2d.
  const std::vector<double> ranges = discover_ranges(host);
  REQUIRE(ranges.size() == 4);
  CHECK(ranges[1] == 0.5);
  CHECK(ranges[2] == 1.0);
  CHECK(ranges[3] == Approx(2 * std::sqrt(0.5)));
  CHECK(r.neighbours == std::vector<NodeId>{sim::node_id(1)});
  CHECK_FALSE(r.truncated);
  CHECK(r.cell.vertices.size() == 4);
  CHECK(area(r.cell) == Approx(0.71875));
}

TEST_CASE("a radius capped at max range ends the update with a truncated cell", "[protocols]") {
  World w;
  ProtocolParams params;
  params.criterion = StopCriterion::vertices;
  params.decay.patience = 0;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(0.3), 0.001);
  initialise(host, p, {0.2}, 0.3);
  const UpdateRecord r = run_update(host, p, w);
  CHECK(r.truncated);
  CHECK(r.radius == 0.3);
  CHECK(discover_ranges(host).back() == 0.3);
  // The reported cell is the square cut by the disk of radius 0.3 (circumscribed polygon).
  CHECK(max_vertex_distance(r.cell, host.here) <= 0.3 * 1.0013);
}

TEST_CASE("shrink_on_stop sets R to exactly 2d when the update stops", "[protocols]") {
  World w;
  w.sensors[10] = Vec2{0.6, 0.5};
  ProtocolParams params;
  params.shrink_on_stop = true;
  params.decay.patience = 0;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.001);
  initialise(host, p, {0.4});
  const UpdateRecord r = run_update(host, p, w);
  CHECK(r.rounds == 1);  // 0.4 >= 2·0.1 at once
  CHECK(r.radius == Approx(0.2));
  CHECK(p.radius() == Approx(0.2));
}

TEST_CASE("range decay shrinks R by step after patience unchanged updates, never below min",
          "[protocols]") {
  World w;  // nobody answers: d = 0 and R never grows
  ProtocolParams params;
  params.decay = RangeDecay{3, 0.05, 0.12};
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.001);
  initialise(host, p, {0.25});
  std::vector<double> radii;
  for (int u = 0; u < 12; ++u) {
    run_update(host, p, w);
    radii.push_back(p.radius());
  }
  // Updates 1-3 end with R = 0.25, then it decays; 0.20 three times, 0.15 three times, then the
  // floor 0.12 (not 0.10).
  const std::vector<double> expected = {0.25, 0.25, 0.20, 0.20, 0.20, 0.15,
                                        0.15, 0.15, 0.12, 0.12, 0.12, 0.12};
  REQUIRE(radii.size() == expected.size());
  for (std::size_t i = 0; i < radii.size(); ++i)
    CHECK(radii[i] == Approx(expected[i]));
}

TEST_CASE("a tick that finds the previous update still running is delayed and counted",
          "[protocols]") {
  World w;
  ProtocolParams params;
  params.period_s = 0.001;  // shorter than one round
  params.reply_timeout_s = 0.002;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.0);
  initialise(host, p, {0.2});
  REQUIRE(host.fire(p, VoronoiProtocol::kTick));  // update 1 starts
  REQUIRE(host.fire(p, VoronoiProtocol::kTick));  // due while busy
  CHECK(p.delayed_updates() == 1);
  // Finish update 1 (SENSE, then decide); update 2 starts at once, flagged delayed.
  REQUIRE(host.fire(p, VoronoiProtocol::kRoundEnd));
  REQUIRE(host.fire(p, VoronoiProtocol::kSenseEnd));
  REQUIRE(host.records.size() == 1);
  CHECK_FALSE(host.records[0].delayed);
  CHECK(p.busy());
  REQUIRE(host.fire(p, VoronoiProtocol::kRoundEnd));
  REQUIRE(host.fire(p, VoronoiProtocol::kSenseEnd));
  REQUIRE(host.records.size() == 2);
  CHECK(host.records[1].delayed);
}

TEST_CASE("the gabriel variant bounds the cell by Gabriel neighbours only, in one round",
          "[protocols]") {
  World w;
  w.robots[1] = Vec2{0.7, 0.5};   // Gabriel neighbour
  w.robots[2] = Vec2{0.9, 0.52};  // hidden behind robot 1: inside the circle on (p, robot 2)
  ProtocolParams params;
  params.variant = VoronoiVariant::gabriel;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.001);
  p.start();  // no initialisation round for gabriel
  const UpdateRecord r = run_update(host, p, w);
  CHECK(discover_ranges(host) == std::vector<double>{1.5});
  CHECK(r.rounds == 1);
  CHECK(r.neighbours == std::vector<NodeId>{sim::node_id(1)});
}

TEST_CASE("fixed_radius runs one round at its radius and flags a cell reaching past it",
          "[protocols]") {
  World w;
  w.robots[1] = Vec2{0.9375, 0.5};
  ProtocolParams params;
  params.variant = VoronoiVariant::fixed_radius;
  params.fixed_radius = 0.3;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.001);
  p.start();
  const UpdateRecord r = run_update(host, p, w);
  CHECK(discover_ranges(host) == std::vector<double>{0.3});
  CHECK(r.neighbours.empty());  // 0.4375 away: not heard
  CHECK(r.truncated);
}

TEST_CASE("stale readings of an earlier update and late replies are ignored", "[protocols]") {
  World w;
  w.sensors[10] = Vec2{0.6, 0.5};
  ProtocolParams params;
  params.decay.patience = 0;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.001);
  initialise(host, p, {0.3});
  run_update(host, p, w);
  // A reading tagged with update 1 arriving during update 2 does not count.
  REQUIRE(host.fire(p, VoronoiProtocol::kTick));
  REQUIRE(host.fire(p, VoronoiProtocol::kRoundEnd));
  p.on_frame(frame(net::Reading{sim::node_id(10), 1, 1.0, Vec2{0.6, 0.5}}));
  REQUIRE(host.fire(p, VoronoiProtocol::kSenseEnd));
  CHECK(host.records.back().readings == 0);
  CHECK(host.records.back().no_mass);
}

TEST_CASE("an update records every reply it used, at the position the reply carried",
          "[protocols]") {
  World w;
  w.robots[1] = Vec2{0.9375, 0.5};
  w.robots[2] = Vec2{0.5, 0.125};
  w.robots[3] = Vec2{0.95, 0.05};  // heard, but its bisector x − y = 0.45 misses the cell
  ProtocolParams params;
  params.criterion = StopCriterion::vertices;
  params.decay.patience = 0;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.001);
  initialise(host, p, {1.5});
  const UpdateRecord r = run_update(host, p, w);
  REQUIRE(r.heard.size() == 3);
  for (const HeardRobot& h : r.heard)
    CHECK(h.position == w.robots.at(sim::index(h.robot)));
  CHECK(r.neighbours == std::vector<NodeId>{sim::node_id(1), sim::node_id(2)});
  CHECK(heard_neighbours(r.position, r.heard, rectangle(0, 0, 1, 1)) == r.neighbours);
}

TEST_CASE(
    "a reply that comes after its round's deadline still bounds the cell the update stops with",
    "[protocols]") {
  // R = 1.5 certifies the whole square at once (farthest vertex √0.5); the neighbour's reply is
  // queued behind other frames and arrives while the sensors answer the SENSE. Its bisector
  // x = 0.6 cuts the cell, and R >= 2d still holds for the cut cell.
  World w;
  w.sensors[10] = Vec2{0.25, 0.5};
  w.sensors[11] = Vec2{0.75, 0.5};  // beyond the late neighbour's bisector
  ProtocolParams params;
  params.criterion = StopCriterion::vertices;
  params.decay.patience = 0;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.001);
  initialise(host, p, {1.5});
  REQUIRE(host.fire(p, VoronoiProtocol::kTick));
  REQUIRE(host.fire(p, VoronoiProtocol::kRoundEnd));  // nobody replied in time
  REQUIRE(std::holds_alternative<net::Sense>(host.last().payload));
  p.on_frame(frame(net::Neighbor{sim::node_id(1), Vec2{0.7, 0.5}}));
  answer_last(host, p, w);
  REQUIRE(host.fire(p, VoronoiProtocol::kSenseEnd));
  REQUIRE(host.records.size() == 1);
  const UpdateRecord& r = host.records[0];
  CHECK(r.rounds == 1);
  CHECK(r.neighbours == std::vector<NodeId>{sim::node_id(1)});
  CHECK(heard_neighbours(r.position, r.heard, rectangle(0, 0, 1, 1)) == r.neighbours);
  CHECK(area(r.cell) == Approx(0.6));
  CHECK(r.readings == 1);  // the reading east of the bisector is no longer in the cell
  CHECK(r.centroid == Vec2{0.25, 0.5});
}

TEST_CASE("an update counts a clip per bisector it builds and a point test per reading re-checked",
          "[protocols]") {
  // Four robots 0.2 away bound the cell [0.4, 0.6]²; three sensors lie inside it.
  World w;
  w.robots[1] = Vec2{0.7, 0.5};
  w.robots[2] = Vec2{0.5, 0.7};
  w.robots[3] = Vec2{0.3, 0.5};
  w.robots[4] = Vec2{0.5, 0.3};
  w.sensors[10] = Vec2{0.45, 0.45};
  w.sensors[11] = Vec2{0.55, 0.45};
  w.sensors[12] = Vec2{0.58, 0.58};
  w.sensors[13] = Vec2{0.9, 0.9};  // outside the cell and the SENSE range
  ProtocolParams params;
  params.variant = VoronoiVariant::fixed_radius;
  params.fixed_radius = 0.3;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.001);
  p.start();

  // The cell the readings come back for is the one sent: the sensors decided, the robot tests
  // nothing. Four bisectors, four clips.
  const UpdateRecord first = run_update(host, p, w);
  CHECK(first.readings == 3);
  CHECK_FALSE(first.truncated);
  CHECK(first.geometry.half_plane_clips == 4);
  CHECK(first.geometry.point_in_cell_tests == 0);

  // A fifth robot's reply comes while the sensors answer: the cell is built again from five
  // sites (all within twice its farthest vertex: 0.15² · 2 < 4 · 0.02), and each of the three
  // readings is tested against it; its bisector x + y = 1.15 leaves (0.58, 0.58) out.
  REQUIRE(host.fire(p, VoronoiProtocol::kTick));
  answer_last(host, p, w);
  REQUIRE(host.fire(p, VoronoiProtocol::kRoundEnd));
  REQUIRE(std::holds_alternative<net::Sense>(host.last().payload));
  answer_last(host, p, w);
  p.on_frame(frame(net::Neighbor{sim::node_id(5), Vec2{0.65, 0.65}}));
  REQUIRE(host.fire(p, VoronoiProtocol::kSenseEnd));
  const UpdateRecord& second = host.records.back();
  CHECK(second.update == 2);
  CHECK(second.readings == 2);
  CHECK(second.geometry.half_plane_clips == 4 + 5);
  CHECK(second.geometry.point_in_cell_tests == 3);
}

TEST_CASE("a cell truncated by the radius costs the disk's sides in clips", "[protocols]") {
  // Nobody within R = 0.3: the cell is the square (no bisector), and the disk polygon cuts it
  // side by side (every vertex of the square is farther than 0.3).
  World w;
  w.robots[1] = Vec2{0.9375, 0.5};
  ProtocolParams params;
  params.variant = VoronoiVariant::fixed_radius;
  params.fixed_radius = 0.3;
  FakeHost host;
  VoronoiProtocol p(host, params, unit_square(), 0.001);
  p.start();
  const UpdateRecord r = run_update(host, p, w);
  REQUIRE(r.truncated);
  CHECK(r.geometry.half_plane_clips == static_cast<std::uint64_t>(kDiskSides));
  CHECK(r.geometry.point_in_cell_tests == 0);
}
