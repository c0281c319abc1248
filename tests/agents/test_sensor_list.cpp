// The sensors' definitions are shared by the copies of a world's definition and written on
// copy: a world reads its scenario's list instead of a copy (a million sensors are 32 MB).
#include <catch2/catch.hpp>

#include "agents/sensor_list.hpp"
#include "agents/world.hpp"

using namespace masnet;
using agents::SensorList;
using net::Vec2;

TEST_CASE("sensor list: copies share one list, a write detaches only the writer") {
  SensorList a(
      std::vector<agents::SensorDef>{{Vec2{0.1, 0.2}, 0.5, 0.0}, {Vec2{0.3, 0.4}, 0.5, 0.0}});
  const SensorList b = a;
  CHECK(a.shares_with(b));
  CHECK(b.data() == a.data());

  a.edit(1).battery_j = 2.0;
  CHECK_FALSE(a.shares_with(b));
  CHECK(a[1].battery_j == 2.0);
  CHECK(b[1].battery_j == 0.0);  // the other copy kept its value
  CHECK(a[0].position == b[0].position);

  SensorList c = b;
  c.push_back({Vec2{0.5, 0.5}, 0.25, 0.0});
  CHECK(c.size() == 3);
  CHECK(b.size() == 2);

  SensorList empty;
  CHECK(empty.empty());
  CHECK(empty.begin() == empty.end());
  empty.push_back({Vec2{0.5, 0.5}, 1.0, 0.0});  // the first write makes the list
  CHECK(empty.size() == 1);
  int seen = 0;
  for (const agents::SensorDef& s : empty)
    seen += s.area == 1.0 ? 1 : 0;
  CHECK(seen == 1);
  empty.clear();
  CHECK(empty.empty());
}

TEST_CASE("sensor list: a world reads its definition's sensors without copying them") {
  agents::WorldDef def;
  def.domain = protocols::rectangle(0, 0, 1, 1);
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i)
      def.sensors.push_back({Vec2{(i + 0.5) / 10, (j + 0.5) / 10}, 1.0 / 100});
  def.robots = {Vec2{0.3, 0.3}, Vec2{0.7, 0.6}};
  sim::Simulator simulator;
  agents::World world(simulator, def);
  CHECK(world.def().sensors.shares_with(def.sensors));
  // The oracle's pass reads the radio's index of the sensor rows (the world keeps none of its
  // own): a triangle holds exactly the sensors an independent test puts inside it.
  protocols::ConvexPolygon cell;
  cell.vertices = {Vec2{0.12, 0.08}, Vec2{0.93, 0.31}, Vec2{0.41, 0.88}};
  std::uint32_t inside = 0;
  for (const agents::SensorDef& s : def.sensors)
    inside += protocols::contains(cell, s.position) ? 1 : 0;
  REQUIRE(inside > 20);
  protocols::CentroidAccumulator accumulator{protocols::DensityScaling{}};
  CHECK(world.read_sensors_in(cell, accumulator) == inside);
}
