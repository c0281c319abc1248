// Robot groups in whole runs (docs/formations.md): the paper's claim that robots of two groups
// never meet, measured over seeds; formation messages counted like any other; loss degrades
// the formation while followers keep to their leaders' cells.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "scenarios/loader/scenario.hpp"
#include "scenarios/run/run.hpp"

using namespace masnet;
using namespace masnet::scenarios;

namespace {

const std::string kScenario =
    std::string(MASNET_SOURCE_DIR) + "/scenarios/paper/formation_tracking.yaml";

// A formation scenario, shortened and on a coarser sensor grid so that 20 seeds stay quick;
// `extra` overrides more keys.
ScenarioDef formation_scenario(std::uint64_t seed, std::vector<std::string> extra,
                               const std::string& file) {
  std::vector<std::string> overrides = {"duration=2", "sensors.nx=20", "sensors.ny=20",
                                        "output.snapshots=[]", "output.replay=false"};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  LoadResult loaded = load_scenario(file, overrides, seed);
  INFO((loaded.diagnostics.empty() ? std::string() : loaded.diagnostics[0].text()));
  REQUIRE(loaded.scenario);
  return *loaded.scenario;
}

nlohmann::json run_formation(std::uint64_t seed, std::vector<std::string> extra = {},
                             const std::string& file = kScenario) {
  Run run(formation_scenario(seed, std::move(extra), file));
  run.execute();
  REQUIRE(run.formation() != nullptr);
  return run.summary();
}

}  // namespace

TEST_CASE("formation runs: robots of two groups never meet, on 20 seeds") {
  // Groups live in disjoint cells with a margin: the nearest robots of two groups stay apart
  // by more than the margin on every seed (the seed phases every update and message, so each run
  // takes its own course).
  double nearest = 1.0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const nlohmann::json summary = run_formation(seed, {"duration=5"});
    const nlohmann::json& f = summary.at("formation");
    INFO("seed " << seed << ": " << f.dump());
    CHECK(f.at("groups") == 9);
    CHECK(f.at("followers") == 18);
    CHECK(f.at("min_distance_between_groups").get<double>() > 0.01);
    CHECK(f.at("min_distance_within_group").get<double>() > 0.0);
    nearest = std::min(nearest, f.at("min_distance_between_groups").get<double>());
  }
  INFO("nearest robots of two groups over 20 seeds: " << nearest);
  CHECK(nearest > 0.01);
}

TEST_CASE("formation runs: FORMATION messages are counted and charged like any other") {
  const nlohmann::json summary = run_formation(1);
  const nlohmann::json& f = summary.at("formation");
  const nlohmann::json& by_type = summary.at("messages").at("by_type").at("FORMATION");
  CHECK(f.at("messages").at("count") == by_type.at("count"));
  CHECK(f.at("messages").at("bytes") == by_type.at("bytes"));
  // 27 members, one message each per 0.05 s over 2 s (seeded phases: 39 or 40 each).
  const auto count = f.at("messages").at("count").get<std::uint64_t>();
  CHECK(count >= 27 * 39);
  CHECK(count <= 27 * 40);
  const nlohmann::json& energy = summary.at("energy_j").at("by_type").at("FORMATION");
  CHECK(f.at("energy_j").get<double>() ==
        Approx(energy.at("radio_tx").get<double>() + energy.at("radio_rx").get<double>()));
  CHECK(f.at("energy_j").get<double>() > 0.0);
}

TEST_CASE("formation runs: loss degrades the formation, followers keep to their cells") {
  // Oracle leaders: their cells are exact whatever the loss, so what degrades is the formation
  // alone (its messages are lost). A follower learns a smaller cell only from its leader's next
  // message: the margin is the room it has until then, and no follower strays farther out.
  const std::vector<std::string> oracle = {"protocol.kind=oracle"};
  const nlohmann::json clear = run_formation(3, oracle).at("formation");
  const nlohmann::json lossy =
      run_formation(3, {"protocol.kind=oracle", "radio.loss=0.3"}).at("formation");
  INFO("no loss: " << clear.dump() << "\nloss 0.3: " << lossy.dump());
  CHECK(lossy.at("error_mean").get<double>() > 1.2 * clear.at("error_mean").get<double>());
  for (const nlohmann::json* f : {&clear, &lossy}) {
    CHECK(f->at("outside_cell_follower_max").get<double>() < 0.01);  // robots.groups.margin
    CHECK(f->at("outside_cell_share").get<double>() < 0.01);
    CHECK(f->at("outside_cell_leader_max").get<double>() == 0.0);
  }
}

TEST_CASE("formation runs: the replay carries each follower with its leader") {
  Run run(formation_scenario(1, {"duration=0.5", "output.replay=true"}, kScenario));
  run.execute();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("masnet-formation-replay-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  run.write_files(dir.string());
  std::ifstream in(dir / "replay.json");
  const nlohmann::json replay = nlohmann::json::parse(in);
  std::filesystem::remove_all(dir);
  REQUIRE_FALSE(replay.at("frames").empty());
  for (const nlohmann::json& frame : replay.at("frames")) {
    const nlohmann::json& followers = frame.at("followers");
    REQUIRE(followers.size() == 18 * 3);
    for (std::size_t k = 0; k < 18; ++k)
      CHECK(followers[3 * k + 2] == k / 2);  // two followers per group, group by group
  }
}
