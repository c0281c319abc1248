// The report draws target and source paths with its own code (it never links the agents):
// it must put every entity exactly where the simulation did.
#include <catch2/catch.hpp>

#include <vector>

#include <nlohmann/json.hpp>

#include "agents/targets.hpp"
#include "scenarios/report/target_paths.hpp"

using namespace masnet;
using nlohmann::json;

TEST_CASE("The report's target paths agree with agents::position_on", "[scenarios]") {
  // Straight lines, waypoints with and without loop, a standing waypoint, a path nested under
  // "path" (a Gaussian bump), repeated and zero-length segments.
  const std::vector<json> items = {
      json::parse(R"({"start": [0.1, 0.2], "velocity": [0.013, -0.007]})"),
      json::parse(R"({"position": [0.5, 0.5]})"),
      json::parse(R"({"waypoints": [[0.1, 0.1], [0.9, 0.1], [0.9, 0.9]], "speed": 0.03})"),
      json::parse(
          R"({"waypoints": [[0.1, 0.1], [0.9, 0.1], [0.9, 0.9], [0.2, 0.7]], "speed": 0.07,
              "loop": true})"),
      json::parse(R"({"waypoints": [[0.3, 0.3]], "speed": 0.1})"),
      json::parse(R"({"waypoints": [[0.2, 0.2], [0.2, 0.2], [0.6, 0.35]], "speed": 0.011})"),
      json::parse(R"({"path": {"start": [0.7, 0.3], "velocity": [-0.01, 0.02]}, "amplitude": 1})"),
  };
  for (const json& item : items) {
    INFO(item.dump());
    const std::optional<scenarios::TargetPath> ours = scenarios::target_path_from_json(item);
    REQUIRE(ours);
    agents::PathDef theirs;
    theirs.start = {ours->start.x, ours->start.y};
    theirs.velocity = {ours->velocity.x, ours->velocity.y};
    for (const auto& w : ours->waypoints)
      theirs.waypoints.push_back({w.x, w.y});
    theirs.speed = ours->speed;
    theirs.loop = ours->loop;
    for (int k = 0; k <= 400; ++k) {
      const double t = 0.37 * k;
      const scenarios::plot::Point p = scenarios::position_on(*ours, t);
      const net::Vec2 q = agents::position_on(theirs, t);
      CHECK(p.x == q.x());
      CHECK(p.y == q.y());
    }
  }
  CHECK_FALSE(scenarios::target_path_from_json(json::parse(R"({"amplitude": 1})")));
  CHECK_FALSE(scenarios::target_path_from_json(json::parse(R"({"start": "here"})")));
}
