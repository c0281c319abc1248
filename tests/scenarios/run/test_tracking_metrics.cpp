// The tracking metrics (docs/outputs.md, "Tracking"): exact values on hand-made positions, and
// the acoustic paper scenario, where robots that track must score better than the same robots
// kept still.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "scenarios/loader/scenario.hpp"
#include "scenarios/run/run.hpp"
#include "scenarios/run/tracking_metrics.hpp"

using namespace masnet;
using namespace masnet::scenarios;
using net::Vec2;
namespace fs = std::filesystem;

namespace {

// One target moving along the x axis at 1 world unit/s, sampled at t = 0 … 4 s; robots given
// by their position at time t.
template <class Robots>
TrackingMetrics one_target_run(double radius, Robots robots_at) {
  TrackingMetrics metrics(radius);
  for (int step = 0; step <= 4; ++step) {
    const double t = step;
    metrics.sample(t, robots_at(t), {Vec2{t, 0.0}});
  }
  return metrics;
}

ScenarioDef acoustic(const std::vector<std::string>& overrides) {
  std::vector<std::string> sets = {"output.snapshots=[]", "output.updates=false"};
  sets.insert(sets.end(), overrides.begin(), overrides.end());
  LoadResult loaded = load_scenario(
      std::string(MASNET_SOURCE_DIR) + "/scenarios/paper/acoustic_tracking.yaml", sets);
  INFO((loaded.diagnostics.empty() ? std::string() : loaded.diagnostics[0].text()));
  REQUIRE(loaded.scenario);
  return *loaded.scenario;
}

double sum(const nlohmann::json& values) {
  double s = 0;
  for (const auto& v : values)
    s += v.get<double>();
  return s;
}

}  // namespace

TEST_CASE("a robot that moves with its target stays in its group, a fixed one joins and leaves",
          "[scenarios]") {
  // The follower keeps 0.25 beside the target; the fixed robot at x = 2 is within the radius
  // 0.5 only at t = 2 (|t − 2| ≥ 1 at the other samples).
  const auto follower = [](double t) { return std::vector<Vec2>{{t, 0.25}}; };
  const auto fixed = [](double) { return std::vector<Vec2>{{2.0, 0.0}}; };
  const auto both = [](double t) { return std::vector<Vec2>{{t, 0.25}, {2.0, 0.0}}; };

  const nlohmann::json f = one_target_run(0.5, follower).summary();
  CHECK(f["robots_per_target"] == nlohmann::json::array({1.0}));
  CHECK(f["robots_per_target_final"] == nlohmann::json::array({1}));
  CHECK(f["tracking_share"].get<double>() == 1.0);
  CHECK(f["group_changes"].get<int>() == 0);
  CHECK(f["group_changes_per_member_s"].get<double>() == 0.0);
  CHECK(f["mean_error"].get<double>() == 0.25);
  CHECK(f["max_error_after_1s"].get<double>() == 0.25);
  CHECK(f["tracking_radius"].get<double>() == 0.5);

  // Group sizes 0, 0, 1, 0, 0: ∫ = 1 robot·s over 4 s; joined at t = 2, left at t = 3.
  const nlohmann::json x = one_target_run(0.5, fixed).summary();
  CHECK(x["robots_per_target"] == nlohmann::json::array({0.25}));
  CHECK(x["robots_per_target_final"] == nlohmann::json::array({0}));
  CHECK(x["tracking_share"].get<double>() == 0.25);
  CHECK(x["group_changes"].get<int>() == 2);
  CHECK(x["group_changes_per_member_s"].get<double>() == 2.0);
  CHECK(x["max_error_after_1s"].get<double>() == 2.0);  // at t = 4 s (t = 0 s does not count)
  CHECK(x["mean_error"].get<double>() == (2.0 + 1.0 + 0.0 + 1.0 + 2.0) / 5.0);

  // Together: sizes 1, 1, 2, 1, 1 (∫ = 5 robot·s), the fixed robot's two changes.
  const TrackingMetrics together = one_target_run(0.5, both);
  const nlohmann::json b = together.summary();
  CHECK(b["robots_per_target"] == nlohmann::json::array({1.25}));
  CHECK(b["robots_per_target_final"] == nlohmann::json::array({1}));
  CHECK(b["tracking_share"].get<double>() == 0.625);
  CHECK(b["group_changes"].get<int>() == 2);
  CHECK(b["group_changes_per_member_s"].get<double>() == 0.4);
  CHECK(b["mean_error"].get<double>() == (0.25 + 0.25 + 0.0 + 0.25 + 0.25) / 5.0);
  CHECK(together.groups() == std::vector<int>{0, TrackingMetrics::kNoGroup});
}

TEST_CASE("group changes: a switch between targets is one change, ties go to the lower target",
          "[scenarios]") {
  // Targets still at x = 0 and x = 2, radius 1.5. The first robot goes 0.5 → 1 (a tie: target
  // 0) → 1.5 (target 1) → (1.5, 2) (2.06 from target 1: no group): two changes. The second
  // robot is never within the radius.
  const std::vector<Vec2> targets = {{0.0, 0.0}, {2.0, 0.0}};
  const std::vector<Vec2> path = {{0.5, 0.0}, {1.0, 0.0}, {1.5, 0.0}, {1.5, 2.0}};
  const std::vector<int> expected_group = {0, 0, 1, TrackingMetrics::kNoGroup};
  const std::vector<std::vector<std::uint32_t>> expected_sizes = {{1, 0}, {1, 0}, {0, 1}, {0, 0}};
  TrackingMetrics metrics(1.5), far_only(1.5);
  for (std::size_t k = 0; k < path.size(); ++k) {
    const TrackingSample s =
        metrics.sample(static_cast<double>(k), {path[k], Vec2{10.0, 10.0}}, targets);
    CHECK(s.group_sizes == expected_sizes[k]);
    CHECK(metrics.groups() == std::vector<int>{expected_group[k], TrackingMetrics::kNoGroup});
    far_only.sample(static_cast<double>(k), {Vec2{10.0, 10.0}}, targets);
  }
  const nlohmann::json m = metrics.summary();
  CHECK(m["group_changes"].get<int>() == 2);
  // Target 0: sizes 1, 1, 0, 0 → 1.5 robot·s; target 1: 0, 0, 1, 0 → 1 robot·s; over 3 s.
  CHECK(m["robots_per_target"] == nlohmann::json::array({0.5, 1.0 / 3.0}));
  CHECK(m["tracking_share"].get<double>() == 2.5 / 3.0 / 2.0);
  CHECK(m["group_changes_per_member_s"].get<double>() == 2.0 / 2.5);

  // Never in a group: no rate of changes per member-second.
  const nlohmann::json none = far_only.summary();
  CHECK(none["tracking_share"].get<double>() == 0.0);
  CHECK(none["group_changes"].get<int>() == 0);
  CHECK(none["group_changes_per_member_s"].is_null());

  // One sample: its own values.
  TrackingMetrics once(1.5);
  once.sample(0.0, {Vec2{0.5, 0.0}, Vec2{10.0, 10.0}}, targets);
  CHECK(once.summary()["robots_per_target"] == nlohmann::json::array({1.0, 0.0}));
  CHECK(once.summary()["tracking_share"].get<double>() == 0.5);
}

TEST_CASE("the default tracking radius puts one evenly spread robot near a point on average",
          "[scenarios]") {
  CHECK(default_tracking_radius(1.0, 9) == Approx(1.0 / std::sqrt(9.0 * std::numbers::pi)));
  CHECK(default_tracking_radius(4.0, 1) == Approx(2.0 / std::sqrt(std::numbers::pi)));
  // π r² · robots = area.
  const double r = default_tracking_radius(12.5, 7);
  CHECK(std::numbers::pi * r * r * 7.0 == Approx(12.5));
}

TEST_CASE("in the acoustic scenario robots that track score better than the same robots kept still",
          "[scenarios]") {
  Run tracking(acoustic({}));
  Run still(acoustic({"robots.k=0"}));  // the same protocol and messages, no motion
  Run idle(acoustic({"protocol.kind=none"}));
  for (Run* run : {&tracking, &still, &idle})
    run->execute();
  const nlohmann::json t = tracking.summary()["tracking"], s = still.summary()["tracking"],
                       i = idle.summary()["tracking"];
  // The still robots really stayed where they were placed (nodes.csv: robots first).
  const fs::path nodes =
      fs::temp_directory_path() / ("masnet-test-tracking-nodes-" + std::to_string(::getpid()));
  still.recorder().write_nodes(nodes.string());
  std::ifstream in(nodes);
  std::string line;
  std::getline(in, line);
  const std::vector<Vec2> placed = acoustic({}).world.robots;
  REQUIRE(placed.size() == 9);
  for (const Vec2& p : placed) {
    REQUIRE(std::getline(in, line));
    std::stringstream row(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(row, cell, ','))
      cells.push_back(cell);
    REQUIRE(cells.size() > 4);
    CHECK(cells[1] == "robot");
    CHECK(std::strtod(cells[3].c_str(), nullptr) == p.x());
    CHECK(std::strtod(cells[4].c_str(), nullptr) == p.y());
  }
  in.close();
  fs::remove(nodes);
  // Without a protocol the robots stay as still: the same groups.
  for (const char* key :
       {"robots_per_target", "tracking_share", "group_changes", "group_changes_per_member_s"})
    CHECK(i[key] == s[key]);

  const double radius = default_tracking_radius(1.0, 9);
  CHECK(t["tracking_radius"].get<double>() == radius);
  INFO("tracking " << t.dump() << "\nstill " << s.dump());
  REQUIRE(t["robots_per_target"].size() == 2);
  REQUIRE(s["robots_per_target"].size() == 2);
  // More robots gather at the targets, over the run and target by target.
  CHECK(sum(t["robots_per_target"]) > 1.5 * sum(s["robots_per_target"]));
  for (std::size_t k = 0; k < 2; ++k)
    CHECK(t["robots_per_target"][k].get<double>() > s["robots_per_target"][k].get<double>());
  CHECK(t["tracking_share"].get<double>() > 1.5 * s["tracking_share"].get<double>());
  // Still robots spread on a grid: about one robot per target, as the radius is chosen for.
  CHECK(sum(s["robots_per_target"]) / 2.0 == Approx(1.0).margin(0.25));
  // Members of the still robots' groups come and go more often per second in a group.
  CHECK(t["group_changes_per_member_s"].get<double>() <
        0.8 * s["group_changes_per_member_s"].get<double>());
  // The tracking error agrees.
  CHECK(t["mean_error"].get<double>() < s["mean_error"].get<double>());
  WARN("acoustic tracking: robots per target "
       << t["robots_per_target"] << ", share " << t["tracking_share"] << ", changes per member-s "
       << t["group_changes_per_member_s"] << "; kept still: " << s["robots_per_target"] << ", "
       << s["tracking_share"] << ", " << s["group_changes_per_member_s"]);
}

TEST_CASE("output.tracking_radius sets the radius, and without it the run key is unchanged",
          "[scenarios]") {
  const ScenarioDef by_default = acoustic({"duration=0.5"});
  CHECK(by_default.output.tracking_radius == 0.0);
  CHECK_FALSE(by_default.resolved["output"].contains("tracking_radius"));
  const ScenarioDef wide = acoustic({"duration=0.5", "output.tracking_radius=2"});
  CHECK(wide.resolved["output"]["tracking_radius"] == 2.0);
  CHECK(run_key(wide) != run_key(by_default));
  Run run(wide);
  run.execute();
  const nlohmann::json t = run.summary()["tracking"];
  CHECK(t["tracking_radius"].get<double>() == 2.0);
  // A radius beyond the domain's diameter puts every robot in its nearest target's group.
  CHECK(t["tracking_share"].get<double>() == 1.0);
  CHECK(sum(t["robots_per_target_final"]) == 9.0);

  const LoadResult gaussian =
      load_scenario(std::string(MASNET_SOURCE_DIR) + "/scenarios/examples/static_coverage.yaml",
                    {"output.tracking_radius=0.2"});
  REQUIRE(gaussian.diagnostics.size() == 1);
  CHECK(gaussian.diagnostics[0].text().find("'tracking_radius' applies to field kind acoustic") !=
        std::string::npos);
}
