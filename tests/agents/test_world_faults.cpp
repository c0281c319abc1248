// Faults in a running world: a robot killed, a partition, batteries by class, the robots'
// travel (docs/faults-and-lifetime.md).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <memory>

#include "agents/locomotion.hpp"
#include "agents/world.hpp"

using namespace masnet;
using agents::World;
using agents::WorldDef;
using net::Vec2;

namespace {

// Static robots (k = 0) on a jittered 3 × 3 grid, a 20 × 20 sensor grid, the radius-doubling
// protocol: every update re-discovers its neighbours, so a dead robot drops out at once.
WorldDef still_robots() {
  WorldDef def;
  def.seed = 5;
  def.domain = protocols::rectangle(0, 0, 1, 1);
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i)
      def.sensors.push_back({Vec2{(i + 0.5) / 20, (j + 0.5) / 20}, 1.0 / 400});
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      def.robots.push_back(Vec2{(i + 0.5) / 3 + 0.03 * (j - 1), (j + 0.5) / 3 + 0.02 * (i - 1)});
  def.motion.k = 0.0;
  def.field.kind = agents::FieldKind::uniform;
  def.radio.max_range = 1.5;
  def.protocol = protocols::choose_protocol("radius_doubling");
  // Cortés' vertex rule certifies each cell: the oracle's cell whenever no frame is lost.
  def.protocol.params.set("criterion", std::string("vertices"));
  return def;
}

struct Updates : agents::WorldObserver {
  World* world = nullptr;
  struct Row {
    std::size_t robot;
    double started_s, finished_s;
    bool correct;
    std::vector<sim::NodeId> neighbours;
  };
  std::vector<Row> rows;
  std::vector<std::pair<sim::NodeId, double>> downs, ups;
  void on_update(std::size_t robot, const protocols::UpdateRecord& r) override {
    rows.push_back({robot, sim::to_seconds(r.started), sim::to_seconds(r.finished),
                    world->oracle_cell(robot).neighbours == r.neighbours, r.neighbours});
  }
  void on_node_down(sim::NodeId node, agents::DownCause) override {
    downs.emplace_back(node, sim::to_seconds(world->simulator().now()));
  }
  void on_node_up(sim::NodeId node) override {
    ups.emplace_back(node, sim::to_seconds(world->simulator().now()));
  }
};

std::uint64_t frames_sent(net::Radio& radio, sim::NodeId node) {
  std::uint64_t n = 0;
  for (std::size_t t = 0; t < net::message_type_count(); ++t)
    n += radio.counters(node, static_cast<net::MessageType>(t)).tx_count;
  return n;
}

}  // namespace

TEST_CASE("A killed robot falls silent, stands still, and drops out of its neighbours' cells",
          "[faults]") {
  for (const bool moving : {true, false}) {
    // Moving robots: standing still is then something. Still ones: the oracle's cells are the
    // protocol's whenever nobody is lost (a moving neighbour may cross a cell edge mid-update).
    WorldDef def = still_robots();
    if (moving) {
      def.motion.k = 3.0;
      def.motion.k_v = 1.0;
    }
    agents::FaultDef fault;
    fault.at_s = 1.0;
    fault.ids = {4};  // the middle robot: a neighbour of all the others
    def.faults.push_back(fault);
    sim::Simulator simulator;
    World world(simulator, def);
    Updates updates;
    updates.world = &world;
    world.set_observer(&updates);
    world.start();
    const sim::NodeId victim = world.robot_node(4);
    simulator.run_until(sim::time_at(1.0));
    REQUIRE(updates.downs.size() == 1);
    CHECK(updates.downs[0] == std::pair{victim, 1.0});
    const std::uint64_t sent = frames_sent(world.radio(), victim);
    const std::uint64_t heard = world.radio().stats(victim).heard_bytes;
    const Vec2 stopped = world.robot_state(4).position;
    CHECK(world.alive_robot_count() == 8);
    simulator.run_until(sim::time_at(3.0));
    CHECK(frames_sent(world.radio(), victim) == sent);
    CHECK(world.radio().stats(victim).heard_bytes == heard);
    CHECK(world.robot_state(4).position == stopped);
    CHECK(world.robot_state(4).velocity.norm() == 0.0);
    // Every survivor's update that starts after the kill (the bound: the first one after it)
    // leaves the victim out; with still robots it is the oracle's cell among the survivors.
    std::size_t after = 0;
    for (const Updates::Row& row : updates.rows) {
      if (row.robot == 4) CHECK(row.started_s < 1.0);
      if (row.started_s <= 1.0) continue;
      ++after;
      if (!moving) CHECK(row.correct);
      CHECK(std::find(row.neighbours.begin(), row.neighbours.end(), victim) ==
            row.neighbours.end());
    }
    CHECK(after > 8 * 20);
  }
}

TEST_CASE("A restarted robot runs its protocol again from where it stood", "[faults]") {
  WorldDef def = still_robots();
  agents::FaultDef fault;
  fault.at_s = 0.5;
  fault.until_s = 1.5;
  fault.ids = {2};
  def.faults.push_back(fault);
  sim::Simulator simulator;
  World world(simulator, def);
  Updates updates;
  updates.world = &world;
  world.set_observer(&updates);
  world.start();
  simulator.run_until(sim::time_at(3.0));
  REQUIRE(updates.ups.size() == 1);
  CHECK(updates.ups[0] == std::pair{world.robot_node(2), 1.5});
  std::size_t during = 0, later = 0;
  for (const Updates::Row& row : updates.rows) {
    if (row.robot != 2) continue;
    if (row.finished_s > 0.5 && row.started_s < 1.5) ++during;
    if (row.started_s >= 1.5) {
      ++later;
      CHECK(row.correct);
    }
  }
  CHECK(during == 0);
  CHECK(later > 10);
  CHECK(world.alive_robot_count() == 9);
}

TEST_CASE("While a partition stands no robot hears across it, and after it cells are right again",
          "[faults]") {
  WorldDef def = still_robots();
  agents::FaultDef fault;
  fault.kind = agents::FaultKind::partition;
  fault.at_s = 1.0;
  fault.until_s = 2.0;
  fault.line = net::LineCut{Vec2{0.5, -0.1}, Vec2{0.5, 1.1}};
  def.faults.push_back(fault);
  sim::Simulator simulator;
  World world(simulator, def);
  Updates updates;
  updates.world = &world;
  world.set_observer(&updates);
  world.start();
  simulator.run_until(sim::time_at(4.0));
  std::size_t during = 0, after = 0, after_correct = 0;
  for (const Updates::Row& row : updates.rows) {
    const double x = def.robots[row.robot].x();
    if (row.started_s >= 1.0 && row.finished_s <= 2.0) {
      ++during;
      for (sim::NodeId n : row.neighbours)
        CHECK((def.robots[sim::index(n)].x() < 0.5) == (x < 0.5));
    }
    if (row.started_s >= 2.0) {
      ++after;
      after_correct += row.correct ? 1 : 0;
    }
  }
  CHECK(during > 50);
  REQUIRE(after > 50);
  CHECK(static_cast<double>(after_correct) / static_cast<double>(after) > 0.95);
}

TEST_CASE("The same faults and seed give the same run, and faults are in the fingerprint",
          "[faults]") {
  auto fingerprint = [](const WorldDef& def) {
    sim::Simulator simulator;
    World world(simulator, def);
    world.start();
    simulator.run_until(sim::time_at(2.0));
    return simulator.fingerprint().hex() + world.radio().traffic_fingerprint().hex();
  };
  WorldDef def = still_robots();
  agents::FaultDef fault;
  fault.at_s = 0.7;
  fault.fraction = 0.25;
  fault.nodes = agents::FaultNodes::sensors;
  def.faults.push_back(fault);
  const std::string once = fingerprint(def);
  CHECK(fingerprint(def) == once);
  WorldDef later = def;
  later.faults[0].at_s = 0.8;
  CHECK(fingerprint(later) != once);
  WorldDef none = def;
  none.faults.clear();
  CHECK(fingerprint(none) != once);
}

TEST_CASE("A fraction kills round(fraction × count) of the class, the same ones every time",
          "[faults]") {
  WorldDef def = still_robots();
  agents::FaultDef fault;
  fault.at_s = 0.1;
  fault.fraction = 0.1;
  fault.nodes = agents::FaultNodes::sensors;
  def.faults.push_back(fault);
  for (int repeat = 0; repeat < 2; ++repeat) {
    sim::Simulator simulator;
    World world(simulator, def);
    world.start();
    simulator.run_until(sim::time_at(0.5));
    CHECK(world.alive_sensor_count() == 400 - 40);
    CHECK(world.alive_robot_count() == 9);
  }
}

TEST_CASE("A robot whose battery empties stops where it is, as a killed one", "[faults]") {
  WorldDef def = still_robots();
  def.motion.k = 3.0;
  def.motion.k_v = 1.0;
  def.radio.energy.idle_power_w = 1.0;
  def.robot_battery_j = 0.75;  // idle alone empties it at 0.75 s; frames a little sooner
  sim::Simulator simulator;
  World world(simulator, def);
  world.start();
  simulator.run_until(sim::time_at(0.75));
  CHECK(world.alive_robot_count() == 0);
  CHECK(world.alive_sensor_count() == 400);  // the sensors' class has no battery
  std::vector<Vec2> stopped;
  for (std::size_t r = 0; r < 9; ++r)
    stopped.push_back(world.robot_state(r).position);
  simulator.run_until(sim::time_at(2.0));
  for (std::size_t r = 0; r < 9; ++r) {
    CHECK(world.robot_state(r).position == stopped[r]);
    CHECK(world.radio().stats(world.robot_node(r)).died_at <= sim::time_at(0.75));
  }
}

TEST_CASE("Travel integrals match the damped spring's closed form", "[faults]") {
  // Overdamped on one axis (k_v² > 4k): from rest at x0 the robot creeps to the target without
  // overshoot, so the distance is x0 − x(T); its speed falls to a minimum and rises back to 0,
  // so ∫|a| dt is the total variation of v: v(T) − 2·v_min.
  agents::MotionParams params;
  params.k = 1.0;
  params.k_v = 3.0;
  const double x0 = 0.4, T = 2.5;
  const agents::MotionSegment segment(params, 1.0, {Vec2{x0, 0.2}, Vec2{0, 0}}, Vec2{0, 0.2});
  const agents::TravelIntegrals travel = agents::travel_between(segment, params, 1.0, 1.0 + T);
  const auto end = agents::damped_spring(params.k, params.k_v, x0, 0.0, T);
  CHECK(travel.distance == Approx(x0 - end.x).epsilon(1e-9));
  double v_min = 0.0;
  for (int i = 0; i <= 200000; ++i)
    v_min = std::min(v_min, agents::damped_spring(params.k, params.k_v, x0, 0.0, T * i / 2e5).v);
  CHECK(travel.accel == Approx(end.v - 2.0 * v_min).epsilon(1e-4));  // a kink where a = 0
}

TEST_CASE("Locomotion energy is booked per metre and per unit of acceleration", "[faults]") {
  WorldDef def = still_robots();
  def.robots = {Vec2{0.2, 0.5}};
  def.motion.k = 3.0;
  def.motion.k_v = 1.0;
  def.locomotion.per_metre_j = 2.0;
  def.locomotion.per_accel_j = 0.5;
  def.radio.meters_per_unit = 100.0;
  sim::Simulator simulator;
  World world(simulator, def);
  world.start();
  simulator.run_until(sim::time_at(3.0));
  const double metres = world.distance_travelled_m(0);
  CHECK(metres > 10.0);  // it went toward the centroid of a uniform square: (0.5, 0.5)
  // The distance is at least the displacement, and the energy its linear combination.
  CHECK(metres >= 100.0 * (world.robot_state(0).position - Vec2{0.2, 0.5}).norm() - 1e-9);
  CHECK(world.locomotion_energy_j(0) > 2.0 * metres);
}

namespace {

// The first update's end and target of robot 0.
struct FirstUpdate : agents::WorldObserver {
  double finished_s = -1.0;
  Vec2 target{0, 0};
  void on_update(std::size_t, const protocols::UpdateRecord& r) override {
    if (finished_s >= 0.0) return;
    finished_s = sim::to_seconds(r.finished);
    target = r.centroid;
  }
};

// One robot at rest at `start`, k = 3, k_v = 1, run until its first update has ended (its
// updates end every 10 ms): that update sends it towards the centroid of the uniform square.
struct OneRobotAfterFirstUpdate {
  static constexpr double kK = 3.0, kKv = 1.0;
  const Vec2 start{0.2, 0.5};
  sim::Simulator simulator;
  std::unique_ptr<World> world;
  FirstUpdate first;
  explicit OneRobotAfterFirstUpdate(double actuation_delay_s) {
    WorldDef def = still_robots();
    def.robots = {start};
    def.motion.k = kK;
    def.motion.k_v = kKv;
    def.actuation_delay_s = actuation_delay_s;
    world = std::make_unique<World>(simulator, def);
    world->set_observer(&first);
    world->start();
    while (first.finished_s < 0.0)
      simulator.run_until(simulator.now() + sim::seconds(1e-4));
  }
  // The damped spring's position on `axis`, `tau` after leaving `start` at rest.
  double law(int axis, double tau) const {
    const double x0 = start[axis] - first.target[axis];
    return first.target[axis] + agents::damped_spring(kK, kKv, x0, 0.0, tau).x;
  }
};

}  // namespace

TEST_CASE("A robot keeps its course for the actuation delay, then follows the law from there",
          "[motion]") {
  const double delay_s = 0.004;
  OneRobotAfterFirstUpdate run(delay_s);
  const double t_f = run.first.finished_s;
  REQUIRE((run.first.target - run.start).norm() > 0.1);

  // Until the delay has passed it stands where it was, at rest.
  run.simulator.run_until(sim::time_at(t_f + 0.5 * delay_s));
  CHECK(run.world->robot_state(0).position == run.start);
  CHECK(run.world->robot_state(0).velocity.norm() == 0.0);

  // Then the damped spring from rest, started at t_f + delay.
  const double tau = 0.003;
  run.simulator.run_until(sim::time_at(t_f + delay_s + tau));
  const Vec2 p = run.world->robot_state(0).position;
  for (int axis = 0; axis < 2; ++axis)
    CHECK(p[axis] == Approx(run.law(axis, tau)).epsilon(1e-9).margin(1e-12));
  CHECK((p - run.start).norm() > 1e-6);  // it did start (the check above is not vacuous)
}

TEST_CASE("A robot taken down during its actuation delay never starts", "[motion]") {
  OneRobotAfterFirstUpdate run(0.004);
  run.world->kill(run.world->robot_node(0));
  run.simulator.run_until(sim::time_at(run.first.finished_s + 0.1));
  CHECK(run.world->robot_state(0).position == run.start);
}

TEST_CASE("Without an actuation delay a robot starts at once", "[motion]") {
  OneRobotAfterFirstUpdate run(0.0);
  const double tau = 0.003;
  run.simulator.run_until(sim::time_at(run.first.finished_s + tau));
  for (int axis = 0; axis < 2; ++axis)
    CHECK(run.world->robot_state(0).position[axis] ==
          Approx(run.law(axis, tau)).epsilon(1e-9).margin(1e-12));
}
