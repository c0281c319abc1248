// Faults, lifetime and energy in the run's files (docs/outputs.md): the recovery measure on
// synthetic samples, lifetime on a hand-built layout against a hand calculation, the fault-free
// twin, energy by type and by phase, and determinism.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

#include "scenarios/loader/scenario.hpp"
#include "scenarios/report/run_data.hpp"
#include "scenarios/run/energy_outputs.hpp"
#include "scenarios/run/lifetime_outputs.hpp"
#include "scenarios/run/run.hpp"
#include "scenarios/run/run_watcher.hpp"
#include "sim/random.hpp"

using namespace masnet;
using namespace masnet::scenarios;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

ScenarioDef load(const std::string& relative, const std::vector<std::string>& overrides) {
  LoadResult loaded = load_scenario(std::string(MASNET_SOURCE_DIR) + "/" + relative, overrides);
  INFO((loaded.diagnostics.empty() ? std::string() : loaded.diagnostics[0].text()));
  REQUIRE(loaded.scenario);
  return *loaded.scenario;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("masnet-test-lifetime-" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A short acoustic run on a 20 × 20 sensor grid; `kill_robot_0_at_s` > 0 adds a fault that
// takes robot 0 down for good then.
ScenarioDef acoustic(double kill_robot_0_at_s) {
  ScenarioDef def = load("scenarios/paper/acoustic_tracking.yaml",
                         {"duration=1.5", "output.snapshots=[]", "sensors.nx=20", "sensors.ny=20"});
  if (kill_robot_0_at_s > 0) {
    agents::FaultDef fault;
    fault.at_s = kill_robot_0_at_s;
    fault.kind = agents::FaultKind::kill;
    fault.nodes = agents::FaultNodes::robots;
    fault.ids = {0};
    def.world.faults.push_back(fault);
  }
  return def;
}

Sample sample(double t, double cost, double twin_cost, double recent) {
  Sample s;
  s.t_s = t;
  s.coverage_cost = cost;
  s.coverage_cost_twin = twin_cost;
  s.cell_correctness_recent = recent;
  return s;
}

double sum_tx_rx(const json& by) {
  double sum = 0;
  for (const auto& [key, v] : by.items())
    sum += v.at("radio_tx").get<double>() + v.at("radio_rx").get<double>();
  return sum;
}

// A type's or phase's energy; 0 when it cost nothing (left out).
double part(const json& by, const char* name, const char* key) {
  return by.value(name, json::object()).value(key, 0.0);
}

json without_wall_time(json j) {
  j.erase("wall_time_s");
  return j;
}

// The summary but for the wall time, and every file of the two runs, are the same.
void check_same_outputs(const Run& a, const Run& b) {
  CHECK(without_wall_time(a.summary()) == without_wall_time(b.summary()));
  const fs::path da = fresh_dir("a"), db = fresh_dir("b");
  a.write_files(da.string());
  b.write_files(db.string());
  for (const char* file : {"nodes.csv", "timeseries.csv", "trajectories.csv", "updates.csv"})
    CHECK(slurp(da / file) == slurp(db / file));
  fs::remove_all(da.parent_path());
}

// Watches and does nothing: a watched run's twins run after it.
class IdleWatcher final : public RunWatcher {
 public:
  double frame_period_s() const override { return 0.5; }
  void on_start(const json&) override {}
  void on_frame(const json&) override {}
  bool stop_after_update() override { return false; }
  void on_end(const json&) override {}
};

struct ProgressCall {
  double t_s;
  std::uint64_t events;
};

}  // namespace

TEST_CASE("settling time: from the earliest sample after which the condition always holds",
          "[scenarios]") {
  const std::vector<double> t{0, 1, 2, 3, 4, 5};
  // Fails at 3, holds from 4 on: 4 − 1.5.
  CHECK(settling_time_s(t, {true, true, false, false, true, true}, 1.5) == Approx(2.5));
  // Holds from the first sample at or after the strike: 2 − 2.
  CHECK(settling_time_s(t, {false, false, true, true, true, true}, 2.0) == Approx(0.0));
  // A sample before the strike never counts, even when the condition held there.
  CHECK(settling_time_s(t, {true, true, true, true, true, true}, 0.5) == Approx(0.5));
  // Recovered, then lost again at the end: never.
  CHECK_FALSE(settling_time_s(t, {true, true, true, true, true, false}, 1.0).has_value());
  // A strike after the last sample: never.
  CHECK_FALSE(settling_time_s(t, {true, true, true, true, true, true}, 6.0).has_value());
  CHECK_FALSE(settling_time_s({}, {}, 0.0).has_value());
}

TEST_CASE("recovery: coverage within 5 % of the twin's, correctness above 0.95, per fault",
          "[scenarios]") {
  // The twin's cost is 100 throughout. A fault at 1 s raises the cost to 130; it falls to 106
  // (above 105: not yet) at 3 s and to 104 at 4 s, and stays there: recovered 4 − 1 = 3 s after.
  // The windowed correctness drops to 0.5 at 2 s and is 0.96 from 3.5 s: 2.5 s after.
  const std::vector<Sample> samples{
      sample(0.0, 100, 100, 1.0),  sample(0.5, 101, 100, 1.0),  sample(1.0, 130, 100, 1.0),
      sample(1.5, 125, 100, 0.97), sample(2.0, 120, 100, 0.5),  sample(2.5, 110, 100, 0.8),
      sample(3.0, 106, 100, 0.9),  sample(3.5, 106, 100, 0.96), sample(4.0, 104, 100, 0.96),
      sample(4.5, 100, 100, 0.99), sample(5.0, 95, 100, 1.0)};
  std::vector<agents::FaultDef> faults(3);
  faults[0].at_s = 1.0;
  faults[1].at_s = 2.0;  // a partition lifted at 2.5 s
  faults[1].kind = agents::FaultKind::partition;
  faults[1].until_s = 2.5;
  faults[2].at_s = 7.0;  // after the end: never struck
  const json r = recovery_summary(faults, samples);
  REQUIRE(r.size() == 3);
  CHECK(r[0]["index"] == 0);
  CHECK(r[0]["kind"] == "kill");
  CHECK(r[0]["until_s"].is_null());
  CHECK(r[0]["struck"] == true);
  CHECK(r[0]["coverage_recovery_s"].get<double>() == Approx(3.0));
  CHECK(r[0]["correctness_recovery_s"].get<double>() == Approx(2.5));
  CHECK(r[1]["kind"] == "partition");
  CHECK(r[1]["until_s"].get<double>() == 2.5);
  CHECK(r[1]["coverage_recovery_s"].get<double>() == Approx(2.0));
  CHECK(r[1]["correctness_recovery_s"].get<double>() == Approx(1.5));
  CHECK(r[2]["struck"] == false);
  CHECK(r[2]["coverage_recovery_s"].is_null());

  // Never: the cost is still 6 % above the twin's at the end; no robot up (NaN) is never either.
  std::vector<Sample> worse = samples;
  worse.back().coverage_cost = 106;
  CHECK(recovery_summary(faults, worse)[0]["coverage_recovery_s"].is_null());
  worse.back().coverage_cost = std::nan("");
  CHECK(recovery_summary(faults, worse)[0]["coverage_recovery_s"].is_null());
  worse.back().cell_correctness_recent = 0.95;  // "above" 0.95: 0.95 is not
  CHECK(recovery_summary(faults, worse)[0]["correctness_recovery_s"].is_null());
}

TEST_CASE("lifetime of a three-node layout with small batteries equals the hand calculation",
          "[scenarios]") {
  // One robot between two sensors, no protocol traffic and no beacons: each node spends only
  // its idle power P = 0.5 W while it is up, so a battery B lasts B / P of time up.
  //   sensor 0, B = 0.5 J: down at 0.5 / 0.5 = 1 s (battery).
  //   sensor 1, B = 1.5 J: up 0–2 s (1 J spent), taken down by the fault at 2 s, brought up at
  //     2.5 s with 0.5 J left (no drain while down): down at 2.5 + 0.5 / 0.5 = 3.5 s (battery).
  //   robot, B = 2 J: down at 2 / 0.5 = 4 s (battery).
  // Two sensors: one down is already 10 % and 50 % of them, at 1 s.
  ScenarioDef def = load("scenarios/examples/beacons.yaml",
                         {"duration=6", "sensors.nx=2", "sensors.ny=1",
                          "robots.positions=[[0.5, 0.5]]", "beacons.senders=none", "radio.loss=0",
                          "radio.energy.idle_power=0.5", "output.sample_period=0.5"});
  REQUIRE(def.world.sensors.size() == 2);
  def.world.sensors.edit(0).battery_j = 0.5;
  def.world.sensors.edit(1).battery_j = 1.5;
  def.world.robot_battery_j = 2.0;
  agents::FaultDef fault;
  fault.at_s = 2.0;
  fault.until_s = 2.5;
  fault.nodes = agents::FaultNodes::sensors;
  fault.ids = {1};
  def.world.faults.push_back(fault);
  Run run(def);
  run.execute();
  const json s = run.summary();
  const json& l = s.at("lifetime");
  CHECK(l["first_sensor_death_s"].get<double>() == Approx(1.0));
  CHECK(l["sensors_dead_10pct_s"].get<double>() == Approx(1.0));
  CHECK(l["sensors_dead_50pct_s"].get<double>() == Approx(1.0));
  CHECK(l["first_robot_death_s"].get<double>() == Approx(4.0));
  CHECK(l["deaths"]["battery"] == 3);
  CHECK(l["deaths"]["fault"] == 1);
  CHECK(l["deaths"]["sensors"] == 3);  // sensor 1 twice
  CHECK(l["deaths"]["robots"] == 1);
  CHECK(l["restarts"] == 1);
  CHECK(l["sensors_alive_final"] == 0);
  CHECK(l["robots_alive_final"] == 0);
  // Idle energy: every battery emptied, 0.5 + 1.5 + 2 J.
  CHECK(s["energy_j"]["idle"].get<double>() == Approx(4.0));

  const fs::path dir = fresh_dir("three-nodes");
  run.write_files(dir.string());
  const Table ts = Table::read(dir / "timeseries.csv");
  const auto& t = ts.column("t_s");
  const auto& sensors_up = ts.column("alive_sensors");
  const auto& robots_up = ts.column("alive_robots");
  for (std::size_t k = 0; k < t.size(); ++k) {
    INFO("t = " << t[k]);
    const double expected_sensors = t[k] < 1.0   ? 2
                                    : t[k] < 2.0 ? 1
                                    : t[k] < 2.5 ? 0
                                    : t[k] < 3.5 ? 1
                                                 : 0;
    CHECK(sensors_up[k] == expected_sensors);
    CHECK(robots_up[k] == (t[k] < 4.0 ? 1 : 0));
    // No robot up: no coverage cost (NaN), in the run and in its twin (same battery).
    CHECK(std::isnan(ts.column("coverage_cost")[k]) == (t[k] >= 4.0));
  }
  const Table nodes = Table::read(dir / "nodes.csv");
  CHECK(nodes.column("died_at_s") == std::vector<double>{4.0, 1.0, 3.5});
  CHECK(nodes.has("locomotion_j"));
  CHECK(std::isnan(nodes.column("distance_m")[1]));  // sensors have none (an empty cell)
  // The robot dies before the end: coverage never recovers; no update ever fails.
  CHECK(s["recovery"][0]["coverage_recovery_s"].is_null());
  CHECK(s["recovery"][0]["correctness_recovery_s"].get<double>() == 0.0);
  fs::remove_all(dir.parent_path());
}

TEST_CASE("a run with faults has a fault-free twin, lifetime and recovery, one without has none",
          "[scenarios]") {
  Run plain(acoustic(0)), faulty(acoustic(0.5));
  plain.execute();
  faulty.execute();
  const json p = plain.summary(), f = faulty.summary();
  // The twin is the same scenario and seed without the fault: the plain run.
  REQUIRE(f.contains("twin"));
  CHECK(f["twin"]["fingerprint"] == p["fingerprint"]);
  CHECK(f["fingerprint"] != p["fingerprint"]);
  CHECK(f["twin"]["coverage_final_cost"] == p["coverage"]["final_cost"]);
  CHECK(f["twin"]["tracking_mean_error"] == p["tracking"]["mean_error"]);
  CHECK(f["twin"]["energy_total_j"] == p["energy_j"]["total"]);
  CHECK(f["twin"]["updates"] == p["protocol"]["updates"]);
  for (const char* key : {"twin", "recovery", "lifetime"})
    CHECK_FALSE(p.contains(key));
  REQUIRE(f["recovery"].size() == 1);
  CHECK(f["recovery"][0]["at_s"] == 0.5);
  CHECK(f["recovery"][0]["struck"] == true);
  CHECK(f["lifetime"]["first_robot_death_s"].get<double>() == 0.5);
  CHECK(f["lifetime"]["deaths"]["fault"] == 1);
  CHECK(f["lifetime"]["robots_alive_final"] == 8);
  CHECK(f["lifetime"]["first_sensor_death_s"].is_null());

  const fs::path dp = fresh_dir("plain"), df = fresh_dir("faulty");
  plain.write_files(dp.string());
  faulty.write_files(df.string());
  const Table tp = Table::read(dp / "timeseries.csv"), tf = Table::read(df / "timeseries.csv");
  for (const char* column : {"alive_sensors", "alive_robots", "locomotion_j",
                             "cell_correctness_recent", "coverage_cost_twin"})
    CHECK_FALSE(tp.has(column));
  CHECK_FALSE(Table::read(dp / "nodes.csv").has("locomotion_j"));
  CHECK(tf.column("coverage_cost_twin") == tp.column("coverage_cost"));
  CHECK(tf.column("tracking_error_mean_twin") == tp.column("tracking_error_mean"));
  const auto& t = tf.column("t_s");
  for (std::size_t k = 0; k < t.size(); ++k) {
    INFO("t = " << t[k]);
    CHECK(tf.column("alive_robots")[k] == (t[k] < 0.5 ? 9 : 8));
    CHECK(tf.column("alive_sensors")[k] == 400);
    if (t[k] < 0.5) CHECK(tf.column("coverage_cost")[k] == tp.column("coverage_cost")[k]);
    // At the strike the robots stand where the twin's do, but robot 0 covers nothing now.
    if (t[k] == 0.5) CHECK(tf.column("coverage_cost")[k] > tp.column("coverage_cost")[k]);
  }
  // Locomotion: per robot in nodes.csv, the total in summary.json and timeseries.csv's last row.
  const Table nodes = Table::read(df / "nodes.csv");
  const auto& loco = nodes.column("locomotion_j");
  const double robots_j = std::accumulate(loco.begin(), loco.begin() + 9, 0.0);
  CHECK(robots_j == Approx(f["energy_j"]["locomotion"]["total"].get<double>()));
  CHECK(tf.column("locomotion_j").back() == Approx(robots_j));
  CHECK(robots_j > 0);
  CHECK(nodes.column("alive")[0] == 0);
  CHECK(nodes.column("died_at_s")[0] == 0.5);
  fs::remove_all(dp.parent_path());
}

TEST_CASE("the twin runs before the run and the progress counts both, a watched run's after",
          "[scenarios]") {
  Run plain(acoustic(0)), faulty(acoustic(0.5)), watched(acoustic(0.5));
  CHECK(plain.passes() == 1);
  CHECK(faulty.passes() == 2);
  plain.execute();
  std::vector<ProgressCall> calls, watched_calls;
  faulty.execute([&](double t_s, std::uint64_t events) { calls.push_back({t_s, events}); });
  IdleWatcher watcher;
  watched.execute(
      [&](double t_s, std::uint64_t events) {
        watched_calls.push_back({t_s, events});
      },
      &watcher);
  // Unwatched: the twin's pass (the plain run's events) from 0 to 1.5 s, then the run's own.
  REQUIRE(!calls.empty());
  for (std::size_t k = 1; k < calls.size(); ++k) {
    CHECK(calls[k].t_s >= calls[k - 1].t_s);
    CHECK(calls[k].events >= calls[k - 1].events);
  }
  const auto end_of_twin =
      std::find_if(calls.begin(), calls.end(), [](const ProgressCall& c) { return c.t_s == 1.5; });
  REQUIRE(end_of_twin != calls.end());
  CHECK(end_of_twin->events == plain.events());
  CHECK(calls.back().t_s == 3.0);
  CHECK(calls.back().events == plain.events() + faulty.events());
  // Watched: the run first, its progress only.
  REQUIRE(!watched_calls.empty());
  CHECK(watched_calls.back().t_s == 1.5);
  CHECK(watched_calls.back().events == watched.events());
  // Either order, the same run and the same twin.
  check_same_outputs(faulty, watched);
}

TEST_CASE("a diffusion run counts its baseline twin and its fault-free twin as passes",
          "[scenarios]") {
  CHECK(Run(load("scenarios/paper/pollution_control.yaml", {})).passes() == 2);
  CHECK(Run(load("scenarios/paper/pollution_control.yaml", {"control.baseline=false"})).passes() ==
        1);
  CHECK(Run(load("scenarios/paper/pollution_control.yaml",
                 {"faults=[{at: 1.0, kill: robots, ids: [0]}]"}))
            .passes() == 3);
}

TEST_CASE("energy by type and by phase each add up to the radio's transmit and receive energy",
          "[scenarios]") {
  for (const std::string level : {"ideal", "csma"}) {
    INFO(level);
    Run run(load("scenarios/paper/acoustic_tracking.yaml",
                 {"duration=0.5", "output.snapshots=[]", "sensors.nx=20", "sensors.ny=20",
                  "radio.level=" + level}));
    run.execute();
    const json e = run.summary()["energy_j"];
    const double radio_j = e["radio_tx"].get<double>() + e["radio_rx"].get<double>();
    REQUIRE(radio_j > 0);
    CHECK(sum_tx_rx(e["by_type"]) == Approx(radio_j).epsilon(1e-12));
    CHECK(sum_tx_rx(e["by_phase"]) == Approx(radio_j).epsilon(1e-12));
    // Radius doubling: DISCOVER and NEIGHBOR discover, SENSE and READING sense.
    const json& t = e["by_type"];
    const json& ph = e["by_phase"];
    CHECK(part(ph, "discovery", "radio_tx") ==
          Approx(part(t, "DISCOVER", "radio_tx") + part(t, "NEIGHBOR", "radio_tx")));
    CHECK(part(ph, "sensing", "radio_rx") ==
          Approx(part(t, "SENSE", "radio_rx") + part(t, "READING", "radio_rx")));
    CHECK(e["per_update"].get<double>() ==
          Approx(radio_j / run.summary()["protocol"]["updates"].get<double>()));

    // The distribution over nodes against nodes.csv, by nearest rank.
    const fs::path dir = fresh_dir("energy-" + level);
    run.write_files(dir.string());
    const Table nodes = Table::read(dir / "nodes.csv");
    std::vector<double> sensors;
    for (std::size_t i = 0; i < nodes.rows(); ++i)
      if (nodes.text("role")[i] == "sensor") sensors.push_back(nodes.column("energy_j")[i]);
    std::sort(sensors.begin(), sensors.end());
    const json& d = e["distribution"]["sensors"];
    CHECK(d["min"].get<double>() == Approx(sensors.front()));
    CHECK(d["p50"].get<double>() == Approx(sensors[199]));  // rank ⌈0.5 · 400⌉ = 200
    CHECK(d["p90"].get<double>() == Approx(sensors[359]));  // rank 360
    CHECK(d["max"].get<double>() == Approx(sensors.back()));
    CHECK(e["distribution"]["robots"]["max"].get<double>() >=
          e["distribution"]["robots"]["min"].get<double>());
    fs::remove_all(dir.parent_path());
  }
  CHECK(nearest_rank({1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, 0.5) == 5);
  CHECK(nearest_rank({1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, 0.9) == 9);
  CHECK(nearest_rank({7}, 0.9) == 7);
  CHECK(distribution_summary({}).is_null());
  // The selections give exactly what a sorted copy holds at each rank.
  sim::RandomStream rng(7);
  for (std::size_t n : {1u, 2u, 3u, 9u, 10u, 11u, 400u, 1001u}) {
    std::vector<double> values;
    for (std::size_t i = 0; i < n; ++i)
      values.push_back(i % 3 == 0 ? 0.25 : std::floor(rng.uniform(0.0, 50.0)) / 8);  // ties
    std::vector<double> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    const json d = distribution_summary(values);
    INFO("n = " << n);
    CHECK(d["min"].get<double>() == sorted.front());
    CHECK(d["p50"].get<double>() == nearest_rank(sorted, 0.5));
    CHECK(d["p90"].get<double>() == nearest_rank(sorted, 0.9));
    CHECK(d["max"].get<double>() == sorted.back());
  }
}

TEST_CASE("the same faulty scenario and seed give identical outputs apart from wall time",
          "[scenarios]") {
  Run a(acoustic(0.5)), b(acoustic(0.5));
  a.execute();
  b.execute();
  check_same_outputs(a, b);
}
