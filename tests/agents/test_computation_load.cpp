// The oracle's computation-load counts in a real world (docs/protocols.md, "Computation load"):
// the clips of the true cell and the sensors whose membership its sensing pass decided.
#include <catch2/catch.hpp>

#include <vector>

#include "agents/world.hpp"
#include "sim/random.hpp"

using namespace masnet;
using agents::World;
using agents::WorldDef;
using net::Vec2;

namespace {

// Two static robots split the square at x = 0.5; a 10 × 10 sensor grid, none near that line.
WorldDef two_robots() {
  WorldDef def;
  def.seed = 3;
  def.domain = protocols::rectangle(0, 0, 1, 1);
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i)
      def.sensors.push_back({Vec2{(i + 0.5) / 10, (j + 0.5) / 10}, 1.0 / 100});
  def.robots = {Vec2{0.25, 0.5}, Vec2{0.75, 0.5}};
  def.motion.k = 0.0;
  def.field.kind = agents::FieldKind::uniform;
  def.radio.max_range = 1.5;
  def.protocol = protocols::choose_protocol("oracle");
  return def;
}

struct Records : agents::WorldObserver {
  std::vector<protocols::UpdateRecord> records;
  void on_update(std::size_t, const protocols::UpdateRecord& r) override { records.push_back(r); }
};

}  // namespace

TEST_CASE("an oracle update clips once per certifying pass and tests each sensor it settles",
          "[agents]") {
  sim::Simulator simulator;
  World world(simulator, two_robots());
  Records seen;
  world.set_observer(&seen);
  world.start();
  simulator.run_until(sim::time_at(0.05));
  REQUIRE(seen.records.size() >= 8);
  for (const protocols::UpdateRecord& r : seen.records) {
    // The first search radius, 2·√2/√2 = 2, already exceeds the domain's diameter: one pass,
    // one candidate, one clip. Each half holds 5 of the 10 sensor columns, and no sensor is
    // near x = 0.5, so the rows' intervals hold exactly the readings: 50 tests, 50 readings.
    CHECK(r.geometry.half_plane_clips == 1);
    CHECK(r.readings == 50);
    CHECK(r.geometry.point_in_cell_tests == 50);
  }
  CHECK(world.sensor_point_in_cell_tests() == 0);  // the oracle sends no SENSE
}

TEST_CASE("off sensor rows the oracle tests every sensor of the disk around the cell", "[agents]") {
  // Random sensors: no rows, so the pass visits the disk about the cell's bounding box and
  // tests each sensor in it exactly.
  WorldDef def = two_robots();
  def.sensors.clear();
  sim::RandomStream rng(8);
  for (int k = 0; k < 400; ++k)
    def.sensors.push_back({Vec2{rng.uniform01(), rng.uniform01()}, 1.0 / 400});
  sim::Simulator simulator;
  World world(simulator, def);
  const protocols::ConvexPolygon cell = protocols::rectangle(0.2, 0.3, 0.6, 0.5);
  const Vec2 centre{0.4, 0.4};
  const double radius = 0.5 * Vec2{0.4, 0.2}.norm();
  std::uint64_t in_disk = 0, in_cell = 0;
  for (const agents::SensorDef& s : def.sensors) {
    in_disk += (s.position - centre).norm() <= radius ? 1 : 0;
    in_cell += protocols::contains(cell, s.position) ? 1 : 0;
  }
  protocols::CentroidAccumulator accumulator{protocols::DensityScaling{}};
  protocols::GeometryWork work;
  CHECK(world.read_sensors_in(cell, accumulator, &work) == in_cell);
  CHECK(work.point_in_cell_tests == in_disk);
  CHECK(work.half_plane_clips == 0);
}
