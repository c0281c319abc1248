// The loader's faults, batteries and locomotion energy (docs/scenario-reference.md, "faults"):
// each form of a fault read into its FaultDef, every bad one refused with its exact located
// message, batteries by class and per sensor from a CSV column, and the resolved scenario (so
// the run key) changed by a fault.
#include <catch2/catch.hpp>

#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "loader_helpers.hpp"
#include "scenarios/loader/scenario.hpp"

using namespace masnet::scenarios;
using masnet::agents::FaultKind;
using masnet::agents::FaultNodes;
using masnet::net::Region;
using masnet::test::texts;
using TempDir = masnet::test::TempDir;

namespace {

const std::string kMasnet = MASNET_BINARY_DIR "/scenarios/masnet";

// 9 robots (3 × 3) and 100 sensors (10 × 10) by default, over 5 s.
const std::string kBase = "duration: 5\nfaults:\n  - ";

std::vector<std::string> problems(const std::string& text) {
  return texts(load_scenario_text(text, "inline.yaml", {}).diagnostics);
}

// The diagnostics of a scenario whose single fault (on line 3, from column 5) is `entry`.
std::vector<std::string> fault_problems(const std::string& entry) {
  return problems(kBase + entry + "\n");
}

ScenarioDef loaded(const std::string& text, const std::vector<std::string>& sets = {}) {
  const LoadResult result = load_scenario_text(text, "inline.yaml", sets);
  for (const std::string& problem : texts(result.diagnostics))
    UNSCOPED_INFO(problem);
  REQUIRE(result.scenario);
  return *result.scenario;
}

// The scenario `text` loaded as if it were the file `path` (relative files beside it).
ScenarioDef loaded_file(const std::string& text, const std::string& path) {
  const LoadResult result = load_scenario_text(text, path, {});
  for (const std::string& problem : texts(result.diagnostics))
    UNSCOPED_INFO(problem);
  REQUIRE(result.scenario);
  return *result.scenario;
}

}  // namespace

TEST_CASE("each form of a fault is read into its FaultDef, in file order", "[scenarios]") {
  const ScenarioDef def = loaded(
      "duration: 5\n"
      "faults:\n"
      "  - {at: 2.0, kill: robots, ids: [4]}\n"
      "  - {at: 1.0, kill: sensors, region: {center: [0.5, 0.5], radius: 0.2}}\n"
      "  - {at: 1.0, until: 3.0, kill: robots, ids: [1]}\n"
      "  - {at: 1.0, until: 3.0, partition: {line: [[0.5, 0.0], [0.5, 1.0]]}}\n"
      "  - {at: 0.5, until: 2.5, degrade: {loss: 0.3, region: {center: [0.2, 0.8], radius: 0.3}}}\n"
      "  - {at: 0, kill: sensors, fraction: 0.2}\n"
      "  - {at: 4, until: 5, kill: robots, region: {polygon: [[0, 0], [0, 0.5], [0.5, 0]]}}\n"
      "  - {at: 3, kill: sensors, ids: [99, 0, 7]}\n");
  const auto& f = def.world.faults;
  REQUIRE(f.size() == 8);
  const double never = std::numeric_limits<double>::infinity();

  CHECK(f[0].kind == FaultKind::kill);
  CHECK(f[0].at_s == 2.0);
  CHECK(f[0].until_s == never);
  CHECK_FALSE(f[0].restarts());
  CHECK(f[0].nodes == FaultNodes::robots);
  CHECK(f[0].ids == std::vector<std::uint32_t>{4});
  CHECK_FALSE(f[0].fraction);
  CHECK_FALSE(f[0].region);

  CHECK(f[1].kind == FaultKind::kill);
  CHECK(f[1].at_s == 1.0);
  CHECK(f[1].nodes == FaultNodes::sensors);
  CHECK(f[1].ids.empty());
  CHECK_FALSE(f[1].fraction);
  REQUIRE(f[1].region);
  CHECK(f[1].region->shape == Region::Shape::disk);
  CHECK(f[1].region->center == Vec2{0.5, 0.5});
  CHECK(f[1].region->radius == 0.2);

  CHECK(f[2].kind == FaultKind::kill);
  CHECK(f[2].at_s == 1.0);
  CHECK(f[2].until_s == 3.0);
  CHECK(f[2].restarts());
  CHECK(f[2].nodes == FaultNodes::robots);
  CHECK(f[2].ids == std::vector<std::uint32_t>{1});

  CHECK(f[3].kind == FaultKind::partition);
  CHECK(f[3].at_s == 1.0);
  CHECK(f[3].until_s == 3.0);
  CHECK(f[3].line.a == Vec2{0.5, 0.0});
  CHECK(f[3].line.b == Vec2{0.5, 1.0});
  CHECK_FALSE(f[3].region);

  CHECK(f[4].kind == FaultKind::degrade);
  CHECK(f[4].at_s == 0.5);
  CHECK(f[4].until_s == 2.5);
  CHECK(f[4].loss == 0.3);
  REQUIRE(f[4].region);
  CHECK(f[4].region->shape == Region::Shape::disk);
  CHECK(f[4].region->center == Vec2{0.2, 0.8});
  CHECK(f[4].region->radius == 0.3);

  CHECK(f[5].kind == FaultKind::kill);
  CHECK(f[5].at_s == 0.0);
  CHECK(f[5].nodes == FaultNodes::sensors);
  CHECK(f[5].fraction == 0.2);
  CHECK(f[5].ids.empty());
  CHECK_FALSE(f[5].region);

  // A clockwise polygon is kept as written; `until` may be the duration.
  CHECK(f[6].until_s == 5.0);
  REQUIRE(f[6].region);
  CHECK(f[6].region->shape == Region::Shape::polygon);
  CHECK(f[6].region->polygon == std::vector<Vec2>{{0, 0}, {0, 0.5}, {0.5, 0}});
  CHECK(f[6].region->contains(Vec2{0.1, 0.1}));
  CHECK_FALSE(f[6].region->contains(Vec2{0.4, 0.4}));

  // Sensor ids are by class, 0-based: the last of 100 sensors is 99.
  CHECK(f[7].nodes == FaultNodes::sensors);
  CHECK(f[7].ids == std::vector<std::uint32_t>{99, 0, 7});
}

TEST_CASE("every bad fault is refused with its exact located message", "[scenarios]") {
  using Lines = std::vector<std::string>;
  const std::string at = "inline.yaml:3:";
  // Keys and kinds.
  CHECK(fault_problems("{at: 1, kill: robots, ids: [1], util: 3}") ==
        Lines{at + "37: unknown key 'util' in 'faults[0]' (did you mean 'until'?)"});
  CHECK(fault_problems("{at: 1, kill: robot, ids: [1]}") ==
        Lines{at + "19: faults[0].kill: expected one of robots, sensors, got 'robot' (did you "
                   "mean 'robots'?)"});
  CHECK(fault_problems("{at: 1}") ==
        Lines{at + "5: faults[0]: a fault needs one of 'kill', 'partition' or 'degrade' (what "
                   "goes wrong)"});
  CHECK(fault_problems("{at: 1, kill: robots, ids: [1], partition: {line: [[0, 0], [1, 1]]}}") ==
        Lines{at + "48: faults[0].partition: give one of 'kill', 'partition' or 'degrade' per "
                   "fault, not both 'kill' and 'partition'"});
  CHECK(fault_problems("{kill: robots, ids: [1]}") ==
        Lines{at + "5: faults[0].at: missing required key 'at' (when the fault strikes, s)"});
  // Which nodes a kill takes.
  CHECK(fault_problems("{at: 1, kill: robots}") ==
        Lines{at + "19: faults[0].kill: a kill needs 'ids', 'fraction' or 'region' (which nodes "
                   "it takes)"});
  CHECK(fault_problems("{at: 1, kill: robots, ids: [1], fraction: 0.5}") ==
        Lines{at + "47: faults[0].fraction: give one of 'ids', 'fraction' or 'region', not both "
                   "'ids' and 'fraction'"});
  CHECK(fault_problems("{at: 1, kill: robots, ids: [2, 9]}") ==
        Lines{at + "36: faults[0].ids[1]: there is no robot 9 (robots are numbered 0 to 8)"});
  CHECK(fault_problems("{at: 1, kill: sensors, ids: [100]}") ==
        Lines{at + "34: faults[0].ids[0]: there is no sensor 100 (sensors are numbered 0 to 99)"});
  CHECK(fault_problems("{at: 1, kill: robots, ids: [-1]}") ==
        Lines{at + "33: faults[0].ids[0]: there is no robot -1 (robots are numbered 0 to 8)"});
  CHECK(fault_problems("{at: 1, kill: robots, ids: [1, 2, 1]}") ==
        Lines{at + "39: faults[0].ids[2]: robot 1 is listed twice (first as item 0)"});
  CHECK(fault_problems("{at: 1, kill: robots, ids: [1.5]}") ==
        Lines{at + "33: faults[0].ids[0]: expected a whole number, got '1.5'"});
  CHECK(fault_problems("{at: 1, kill: robots, ids: []}") ==
        Lines{at + "32: faults[0].ids: an empty list kills nobody; give at least one robot"});
  CHECK(fault_problems("{at: 1, kill: sensors, fraction: 1.5}") ==
        Lines{at + "38: faults[0].fraction: must be in [0, 1] (got 1.5)"});
  // Times: 0 <= at < duration, at < until <= duration.
  CHECK(fault_problems("{at: -1, kill: robots, ids: [1]}") ==
        Lines{at + "10: faults[0].at: must be in [0, 5) (got -1)"});
  CHECK(fault_problems("{at: 5, kill: robots, ids: [1]}") ==
        Lines{at + "10: faults[0].at: must be in [0, 5) (got 5)"});
  CHECK(fault_problems("{at: 2, until: 2, kill: robots, ids: [1]}") ==
        Lines{at + "20: faults[0].until: must be > at = 2 (got 2)"});
  CHECK(fault_problems("{at: 2, until: 6, kill: robots, ids: [1]}") ==
        Lines{at + "20: faults[0].until: must be in [0, 5] (got 6)"});
  // Regions.
  CHECK(fault_problems("{at: 1, kill: sensors, region: {center: [0.5, 0.5], radius: 0}}") ==
        Lines{at + "65: faults[0].region.radius: must be > 0 (got 0)"});
  CHECK(fault_problems("{at: 1, kill: sensors, region: {center: [0.5, 0.5], radius: .inf}}") ==
        Lines{at + "65: faults[0].region.radius: must be finite and > 0 (got .inf)"});
  CHECK(fault_problems("{at: 1, kill: sensors, region: {center: [.nan, 0.5], radius: 0.2}}") ==
        Lines{at + "45: faults[0].region.center: expected a point [x, y], got [.nan, 0.5]"});
  CHECK(fault_problems("{at: 1, kill: sensors, region: {center: [0.5, 0.5]}}") ==
        Lines{at + "36: faults[0].region.radius: a disk needs 'radius' (world units, > 0)"});
  CHECK(fault_problems("{at: 1, kill: sensors, region: {}}") ==
        Lines{at + "36: faults[0].region: a region needs 'center' and 'radius' (a disk) or "
                   "'polygon: [[x, y], ...]'"});
  CHECK(fault_problems("{at: 1, kill: sensors, region: {radius: 1, polygon: [[0, 0], [1, 0], "
                       "[0, 1]]}}") ==
        Lines{at + "57: faults[0].region.polygon: give either 'center' and 'radius' (a disk) or "
                   "'polygon', not both"});
  CHECK(fault_problems("{at: 1, kill: sensors, region: {polygon: [[0, 0], [1, 1]]}}") ==
        Lines{at + "46: faults[0].region.polygon: needs at least 3 points (got 2)"});
  CHECK(fault_problems("{at: 1, kill: sensors, region: {polygon: [[0, 0], [0.5, 0.5], [1, 1]]}}") ==
        Lines{at + "46: faults[0].region.polygon: the polygon has no area (its vertices lie on "
                   "one line)"});
  CHECK(fault_problems(
            "{at: 1, kill: sensors, region: {polygon: [[0, 0], [1, 1], [1, 0], [0, 1]]}}") ==
        Lines{at + "46: faults[0].region.polygon: the polygon intersects itself"});
  CHECK(fault_problems("{at: 1, kill: sensors, region: {polygon: [[0, 0], [2, 2], [2, 0], [0, "
                       "1]]}}") ==
        Lines{at + "46: faults[0].region.polygon: the polygon intersects itself"});
  CHECK(fault_problems("{at: 1, kill: sensors, region: {polygon: [[1, 1], [1, 1], [1, 1]]}}") ==
        Lines{at + "46: faults[0].region.polygon: the polygon has no area (its vertices lie on "
                   "one line)"});
  // Partitions and degraded areas.
  CHECK(fault_problems("{at: 1, partition: {line: [[0.5, 0.5], [0.5, 0.5]]}}") ==
        Lines{at + "31: faults[0].partition.line: the two ends are the same point (0.5, 0.5)"});
  CHECK(fault_problems("{at: 1, partition: {line: [[0, 0], [1, 0], [1, 1]]}}") ==
        Lines{at + "31: faults[0].partition.line: expected the two ends of a segment [[x1, y1], "
                   "[x2, y2]] (got 3 points)"});
  CHECK(fault_problems("{at: 1, partition: {}}") ==
        Lines{at + "24: faults[0].partition.line: a partition needs 'line: [[x1, y1], [x2, y2]]'"});
  CHECK(fault_problems("{at: 1, partition: {line: [[0, 0], [1, 1]]}, ids: [1]}") ==
        Lines{at + "55: faults[0].ids: 'ids' applies to a kill"});
  CHECK(
      fault_problems("{at: 1, degrade: {loss: 1.5, region: {center: [0.5, 0.5], radius: 0.2}}}") ==
      Lines{at + "29: faults[0].degrade.loss: must be in [0, 1] (got 1.5)"});
  CHECK(fault_problems("{at: 1, degrade: {loss: 0.5}, region: {center: [0.5, 0.5], radius: 1}}") ==
        Lines{at + "22: faults[0].degrade.region: a degraded area needs 'region' (a disk or a "
                   "polygon)",
              at + "43: faults[0].region: 'region' applies to a kill (a degraded area's region "
                   "goes inside 'degrade')"});
  CHECK(fault_problems("{at: 1, degrade: {region: {center: [0.5, 0.5], radius: 1}}}") ==
        Lines{at + "22: faults[0].degrade.loss: missing required key 'loss' (the probability "
                   "that a reception is lost)"});
  // The list itself.
  CHECK(problems("duration: 5\nfaults: {at: 1}\n") ==
        Lines{"inline.yaml:2:9: faults: expected a list, got a mapping"});
  CHECK(problems("duration: 5\nfaults:\n  - 3\n") ==
        Lines{"inline.yaml:3:5: faults[0]: expected a mapping of keys, got '3'"});
}

TEST_CASE("fault ids are checked against the class's count only when it is known", "[scenarios]") {
  CHECK(problems("duration: 5\nsensors: {layout: random, count: 0}\nfaults:\n"
                 "  - {at: 1, kill: sensors, ids: [0]}\n") ==
        std::vector<std::string>{"inline.yaml:4:33: faults[0].ids: the scenario has no sensors"});
  // A bad robots section reports itself, not a cascade of ids against a count it never had.
  CHECK(problems("duration: 5\nrobots: {layout: random, count: 0}\nfaults:\n"
                 "  - {at: 1, kill: robots, ids: [3]}\n") ==
        std::vector<std::string>{
            "inline.yaml:2:33: robots.count: must be between 1 and 10000000 (got 0)"});
  // Without a valid duration, times are only bounded by the clock.
  CHECK(problems("duration: 0\nfaults:\n  - {at: 7, kill: robots, ids: [1]}\n") ==
        std::vector<std::string>{"inline.yaml:1:11: duration: must be > 0 (got 0)"});
}

TEST_CASE("a fault is in the resolved scenario, so it changes the run key", "[scenarios]") {
  const std::string base = "duration: 5\n";
  const ScenarioDef none = loaded(base);
  // No list: no key in the resolved scenario.
  CHECK_FALSE(none.resolved.contains("faults"));
  CHECK(none.world.faults.empty());
  const ScenarioDef one = loaded(base + "faults:\n  - {at: 1, kill: robots, ids: [1]}\n");
  const ScenarioDef other = loaded(base + "faults:\n  - {at: 1, kill: robots, ids: [2]}\n");
  const ScenarioDef same = loaded(base + "faults: [{at: 1.0, kill: robots, ids: [1]}]\n");
  // The run key hashes the version and resolved.dump() (scenarios/run/run.cpp, run_key).
  CHECK(one.resolved.dump() != none.resolved.dump());
  CHECK(one.resolved.dump() != other.resolved.dump());
  CHECK(one.resolved.dump() == same.resolved.dump());
  CHECK(one.resolved["faults"] ==
        nlohmann::json::parse(R"([{"at": 1.0, "kill": "robots", "ids": [1]}])"));
  const ScenarioDef mixed =
      loaded(base +
             "faults:\n"
             "  - {at: 1, until: 2, partition: {line: [[0.5, 0], [0.5, 1]]}}\n"
             "  - {at: 0.5, degrade: {loss: 0.3, region: {polygon: [[0, 0], [1, 0], [0, 1]]}}}\n");
  CHECK(mixed.resolved["faults"] == nlohmann::json::parse(R"([
      {"at": 1.0, "until": 2.0, "partition": {"line": [[0.5, 0.0], [0.5, 1.0]]}},
      {"at": 0.5, "degrade": {"loss": 0.3, "region": {"polygon": [[0, 0], [1, 0], [0, 1]]}}}])"));
  // An empty list is a list: resolved, with no fault.
  const ScenarioDef empty = loaded(base + "faults: []\n");
  CHECK(empty.resolved["faults"] == nlohmann::json::array());
  CHECK(empty.world.faults.empty());
  // From the command line too.
  const ScenarioDef set = loaded(base, {"faults=[{at: 1, kill: robots, ids: [1]}]"});
  CHECK(set.resolved.dump() == one.resolved.dump());
  CHECK(texts(load_scenario_text(base, "inline.yaml", {"faults=[{at: 9, kill: robots, ids: [1]}]"})
                  .diagnostics) ==
        std::vector<std::string>{"--set faults=[{at: 9, kill: robots, ids: [1]}]: faults[0].at: "
                                 "must be in [0, 5) (got 9)"});
}

TEST_CASE("batteries by class, and locomotion energy with its defaults", "[scenarios]") {
  const ScenarioDef defaults = loaded("duration: 1\n");
  CHECK(defaults.world.sensor_battery_j == 0.0);
  CHECK(defaults.world.robot_battery_j == 0.0);
  const masnet::agents::LocomotionEnergy model_defaults;
  CHECK(defaults.world.locomotion.per_metre_j == model_defaults.per_metre_j);
  CHECK(defaults.world.locomotion.per_accel_j == model_defaults.per_accel_j);
  CHECK(defaults.resolved["robots"]["energy"]["per_metre"] == model_defaults.per_metre_j);
  CHECK(defaults.resolved["robots"]["energy"]["per_accel"] == model_defaults.per_accel_j);
  CHECK(defaults.resolved["sensors"]["battery"] == 0.0);
  CHECK(defaults.resolved["robots"]["battery"] == 0.0);
  for (const auto& sensor : defaults.world.sensors)
    CHECK(sensor.battery_j == 0.0);

  const ScenarioDef set = loaded(
      "duration: 1\nsensors: {battery: 2.5}\n"
      "robots: {battery: 300, energy: {per_metre: 3, per_accel: 0}}\n");
  CHECK(set.world.sensor_battery_j == 2.5);
  CHECK(set.world.robot_battery_j == 300.0);
  CHECK(set.world.locomotion.per_metre_j == 3.0);
  CHECK(set.world.locomotion.per_accel_j == 0.0);
  CHECK(set.resolved["robots"]["energy"]["per_metre"] == 3.0);
  CHECK(set.resolved["sensors"]["battery"] == 2.5);
  // The class's battery does not become a node's own.
  CHECK(set.world.sensors.front().battery_j == 0.0);

  CHECK(problems("duration: 1\nsensors: {battery: -1}\nrobots: {battery: .nan, energy: "
                 "{per_metre: -2, per_accel: .inf, per_step: 1}}\n") ==
        std::vector<std::string>{
            "inline.yaml:2:20: sensors.battery: must be >= 0 (got -1)",
            "inline.yaml:3:19: robots.battery: must be finite and >= 0 (got .nan)",
            "inline.yaml:3:45: robots.energy.per_metre: must be >= 0 (got -2)",
            "inline.yaml:3:60: robots.energy.per_accel: must be finite and >= 0 (got .inf)",
            "inline.yaml:3:66: unknown key 'per_step' in 'robots.energy'"});
}

TEST_CASE("a sensor file's header may name a battery column, in any place", "[scenarios]") {
  TempDir dir;
  REQUIRE(!dir.path.empty());
  const std::string scenario = (dir.path / "s.yaml").string();
  const std::string csv = (dir.path / "sensors.csv").string();
  const std::string text = "duration: 1\nsensors: {layout: file, file: sensors.csv}\n";
  auto write = [&](const std::string& lines) { std::ofstream(csv) << lines; };

  write("x,y,battery\n0.25,0.25,1.5\n0.75,0.75,0\n");
  ScenarioDef def = loaded_file(text, scenario);
  REQUIRE(def.world.sensors.size() == 2);
  CHECK(def.world.sensors[0].position == Vec2{0.25, 0.25});
  CHECK(def.world.sensors[0].battery_j == 1.5);
  CHECK(def.world.sensors[0].area == 0.5);  // no area column: an equal share of Ω
  CHECK(def.world.sensors[1].battery_j == 0.0);

  write("battery , x,y,area\r\n2,0.25,0.25,0.1\r\n# a comment\r\n3,0.75,0.75,0.2\r\n");
  def = loaded_file(text, scenario);
  REQUIRE(def.world.sensors.size() == 2);
  CHECK(def.world.sensors[0].battery_j == 2.0);
  CHECK(def.world.sensors[0].area == 0.1);
  CHECK(def.world.sensors[1].position == Vec2{0.75, 0.75});
  CHECK(def.world.sensors[1].battery_j == 3.0);
  CHECK(def.world.sensors[1].area == 0.2);

  // Without a battery column, a header is skipped as before and batteries stay 0.
  write("px,py,weight\n0.25,0.25,0.1\n");
  def = loaded_file(text, scenario);
  REQUIRE(def.world.sensors.size() == 1);
  CHECK(def.world.sensors[0].area == 0.1);
  CHECK(def.world.sensors[0].battery_j == 0.0);

  write(
      "x,y,area,battery\n0.25,0.25,0.1,-1\n0.5,0.5,0.1,nan\n0.5,0.5,0.1\n0.5,0.5,0.1,1,2\n"
      "0.5,0.5,0.1,many\n");
  CHECK(texts(load_scenario_text(text, scenario, {}).diagnostics) ==
        std::vector<std::string>{
            csv + ":2:15: the battery (column 4) must be in [0, 1e+12] J (got '-1')",
            csv + ":3:13: the battery (column 4) must be in [0, 1e+12] J (got 'nan')",
            csv + ":4:1: expected 4 columns (x,y,area,battery, as the header says), got 3",
            csv + ":5:1: expected 4 columns (x,y,area,battery, as the header says), got 5",
            csv + ":6:13: expected a number, got 'many' (lines are 'x,y,area,battery')"});
  write("x,battery,y,battery\n0.5,1,0.5,1\n");
  CHECK(texts(load_scenario_text(text, scenario, {}).diagnostics) ==
        std::vector<std::string>{csv + ":1:13: the header names 'battery' twice",
                                 // A refused header names no column: lines are read as x,y[,area].
                                 csv + ":2:1: expected 2 or 3 columns (x,y[,area]), got 4"});
  write("battery,x\n0.5,0.5\n");
  CHECK(texts(load_scenario_text(text, scenario, {}).diagnostics) ==
        std::vector<std::string>{csv + ":1:1: a header with a 'battery' column has 3 or 4 "
                                       "columns (x,y[,area] and battery), got 2"});
}

TEST_CASE("masnet validate refuses a bad fault with exit code 2", "[scenarios]") {
  TempDir dir;
  REQUIRE(!dir.path.empty());
  const std::string file = (dir.path / "bad_fault.yaml").string();
  std::ofstream(file) << "duration: 5\nfaults:\n  - {at: 1, kill: drones, ids: [0]}\n";
  const masnet::test::Outcome outcome =
      masnet::test::shell("'" + kMasnet + "' validate '" + file + "' 2>&1 >/dev/null");
  CHECK(outcome.exit_code == 2);
  CHECK(outcome.output == file +
                              ":3:19: faults[0].kill: expected one of robots, sensors, got "
                              "'drones'\n");
}
