// `tie_order: origin` runs a scenario with the kernel's origin order of simultaneous events
// (docs/time-and-ordering.md): another order of ties between nodes, the same outcome.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "../loader_helpers.hpp"
#include "scenarios/loader/scenario.hpp"
#include "scenarios/run/run.hpp"

using namespace masnet;
using namespace masnet::scenarios;

namespace {

ScenarioDef acoustic(std::vector<std::string> overrides) {
  overrides.insert(overrides.begin(), {"duration=0.5", "output.snapshots=[]"});
  LoadResult loaded = load_scenario(
      std::string(MASNET_SOURCE_DIR) + "/scenarios/paper/acoustic_tracking.yaml", overrides);
  REQUIRE(loaded.scenario);
  return *loaded.scenario;
}

nlohmann::json outcome(const ScenarioDef& def, std::string* fingerprint = nullptr) {
  Run run(def);
  run.execute();
  if (fingerprint) *fingerprint = run.fingerprint();
  nlohmann::json summary = run.summary();
  // What says which run it was, and how long it took, not what happened in it.
  for (const char* key : {"events", "fingerprint", "run_key", "scenario", "wall_time_s"})
    summary.erase(key);
  return summary;
}

}  // namespace

TEST_CASE("tie_order origin gives the acoustic scenario the same outcome in another event order",
          "[scenarios]") {
  const ScenarioDef by_origin = acoustic({"tie_order=origin"});
  CHECK(by_origin.ties_by_origin);
  CHECK(by_origin.resolved["tie_order"] == "origin");
  std::string first, again, scheduling;
  const nlohmann::json origin_outcome = outcome(by_origin, &first);
  CHECK(outcome(by_origin, &again) == origin_outcome);
  CHECK(again == first);  // deterministic
  const ScenarioDef by_schedule = acoustic({});
  CHECK_FALSE(by_schedule.ties_by_origin);
  CHECK_FALSE(by_schedule.resolved.contains("tie_order"));  // summary.json as without the key
  const nlohmann::json schedule_outcome = outcome(by_schedule, &scheduling);
  CHECK(scheduling != first);  // simultaneous events of different nodes ran in another order
  CHECK(schedule_outcome == origin_outcome);  // every message, energy, cell and tracking figure
  CHECK(schedule_outcome.at("traffic_fingerprint") == origin_outcome.at("traffic_fingerprint"));
}

TEST_CASE("tie_order accepts scheduling and origin only", "[scenarios]") {
  const LoadResult bad = load_scenario_text("duration: 1\ntie_order: random\n", "s.yaml", {});
  CHECK(test::texts(bad.diagnostics) ==
        std::vector<std::string>{
            "s.yaml:2:12: tie_order: expected one of scheduling, origin, got 'random'"});
  const LoadResult explicit_default =
      load_scenario_text("duration: 1\ntie_order: scheduling\n", "s.yaml", {});
  REQUIRE(explicit_default.scenario);
  CHECK_FALSE(explicit_default.scenario->ties_by_origin);
}
