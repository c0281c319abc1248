// A run cut into tiles by space (scenarios/run/run_tiles.hpp, docs/decisions/0012-partitioned-
// runs.md): bands of sensors side by side in conservative windows, every robot in every tile (or,
// when the robots act a window late, in the first tile only).
// Every output file and both fingerprints equal the run in one piece, for 2 and 3 tiles on one
// and two threads (the acoustic and pollution scenarios, robot groups, beacons, kills, link
// faults, the oracle), and over ranks (threads standing in for MPI ranks: every frame, share and
// ledger crosses as bytes); what the tiles cannot run yet is refused with the reason.
#include <catch2/catch.hpp>

#include <algorithm>
#include <barrier>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "../text_files.hpp"
#include "scenarios/loader/scenario.hpp"
#include "scenarios/run/run.hpp"

using namespace masnet;
using namespace masnet::scenarios;
namespace fs = std::filesystem;

namespace {

ScenarioDef load(const std::string& relative, const std::vector<std::string>& overrides) {
  LoadResult loaded = load_scenario(std::string(MASNET_SOURCE_DIR) + "/" + relative, overrides);
  REQUIRE(loaded.scenario);
  return *loaded.scenario;
}

struct Outcome {
  std::string fingerprint, traffic;
  nlohmann::json summary;
  std::vector<std::string> files;
};

// Ranks as threads of this process: the collective calls meet at a barrier.
class ThreadRanks {
 public:
  explicit ThreadRanks(unsigned ranks) : meet_(ranks), earliest_(ranks), outboxes_(ranks) {
    for (unsigned r = 0; r < ranks; ++r)
      links_.push_back(std::make_unique<Link>(*this, r));
  }
  TileLink& link(unsigned rank) { return *links_[rank]; }

 private:
  class Link final : public TileLink {
   public:
    Link(ThreadRanks& all, unsigned rank) : all_(all), rank_(rank) {}
    unsigned rank() const override { return rank_; }
    unsigned size() const override { return static_cast<unsigned>(all_.links_.size()); }
    sim::Time earliest(sim::Time earliest_here) override {
      all_.earliest_[rank_] = earliest_here;
      all_.meet_.arrive_and_wait();
      const sim::Time earliest = *std::min_element(all_.earliest_.begin(), all_.earliest_.end());
      all_.meet_.arrive_and_wait();
      return earliest;
    }
    const std::vector<std::vector<std::byte>>& exchange(
        const std::vector<std::vector<std::byte>>& outbox) override {
      all_.outboxes_[rank_] = &outbox;
      all_.meet_.arrive_and_wait();
      inbox_.assign(size(), {});
      for (unsigned from = 0; from < size(); ++from)
        if (from != rank_) inbox_[from] = (*all_.outboxes_[from])[rank_];
      all_.meet_.arrive_and_wait();
      return inbox_;
    }

   private:
    ThreadRanks& all_;
    unsigned rank_;
    std::vector<std::vector<std::byte>> inbox_;
  };
  std::barrier<> meet_;
  std::vector<sim::Time> earliest_;
  std::vector<const std::vector<std::vector<std::byte>>*> outboxes_;
  std::vector<std::unique_ptr<Link>> links_;
};

Outcome run_in(const ScenarioDef& def, unsigned tiles, unsigned threads, TileLink* link = nullptr) {
  Run run(def, tiles, threads, link);
  run.execute();
  Outcome o{run.fingerprint(), run.traffic_fingerprint(), run.summary(), {}};
  // What says how the run was made (its cost), not what happened in it.
  o.summary.erase("wall_time_s");
  o.summary.erase("events");
  const fs::path dir =
      fs::temp_directory_path() /
      ("masnet-test-tiles-" + std::to_string(::getpid()) + "-" + std::to_string(tiles) + "-" +
       std::to_string(threads) + (link ? "-ranks" : ""));
  fs::remove_all(dir);
  fs::create_directories(dir);
  run.write_files(dir.string());
  // Every file the run writes, by name (name, then content); summary.json is `summary` above.
  std::vector<fs::path> written;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir))
    if (entry.path().filename() != "summary.json") written.push_back(entry.path());
  std::sort(written.begin(), written.end());
  for (const fs::path& file : written) {
    o.files.push_back(file.filename().string());
    o.files.push_back(masnet::test::slurp(file));
  }
  fs::remove_all(dir);
  return o;
}

// The first rank's outcome; the others run their tiles on threads of their own.
Outcome run_over_ranks(const ScenarioDef& def, unsigned ranks) {
  ThreadRanks links(ranks);
  std::vector<std::unique_ptr<Run>> others;
  for (unsigned r = 1; r < ranks; ++r)
    others.push_back(std::make_unique<Run>(def, ranks, 1, &links.link(r)));
  std::vector<std::thread> threads;
  for (auto& run : others)
    threads.emplace_back([&run] { run->execute(); });
  Outcome first = run_in(def, ranks, 1, &links.link(0));
  for (std::thread& t : threads)
    t.join();
  return first;
}

void check_tiles_equal_whole(const ScenarioDef& def) {
  const Outcome whole = run_in(def, 1, 1);
  for (const auto& [tiles, threads] : {std::pair{2u, 1u}, std::pair{3u, 2u}, std::pair{2u, 0u}}) {
    // threads 0: over 2 ranks
    INFO(tiles << " tiles on " << threads << " threads (0: ranks)");
    const Outcome cut = threads > 0 ? run_in(def, tiles, threads) : run_over_ranks(def, tiles);
    CHECK(cut.fingerprint == whole.fingerprint);
    CHECK(cut.traffic == whole.traffic);
    CHECK(cut.summary == whole.summary);
    REQUIRE(cut.files.size() == whole.files.size());
    for (std::size_t f = 0; f < whole.files.size(); f += 2) {
      INFO(whole.files[f]);
      CHECK(cut.files[f] == whole.files[f]);
      CHECK(cut.files[f + 1] == whole.files[f + 1]);
    }
  }
}

// The scenario at `relative` with `overrides`, which the tiles must run, in tiles and whole.
void check_in_tiles(const std::string& relative, const std::vector<std::string>& overrides) {
  const ScenarioDef def = load(relative, overrides);
  REQUIRE(tiles_problem(def, 3).empty());
  check_tiles_equal_whole(def);
}

}  // namespace

TEST_CASE("tiles: the scaling benchmark cut into 2 and 3 bands gives every output of the whole run",
          "[scenarios][tiles]") {
  // 10⁴ sensors, 100 robots, samples every 10 ms: the samples between windows read every
  // tile's share of the messages and energy.
  check_in_tiles("scenarios/bench/scaling_1e4.yaml",
                 {"tie_order=origin", "duration=0.06", "output.sample_period=0.01",
                  "output.trajectory_period=0.01"});
}

TEST_CASE("tiles: the 10^5 benchmark, briefly, cut into bands gives every output of the whole run",
          "[scenarios][tiles]") {
  // 10⁵ sensors and 1 024 robots for 15 ms: the first reports, discoveries and updates.
  check_in_tiles("scenarios/bench/scaling_1e5.yaml",
                 {"tie_order=origin", "duration=0.015", "output.sample_period=0.005"});
}

TEST_CASE("tiles: the acoustic scenario cut into bands gives every output of the whole run",
          "[scenarios][tiles]") {
  check_in_tiles("scenarios/paper/acoustic_tracking.yaml",
                 {"tie_order=origin", "duration=0.5", "output.snapshots=[0.25]"});
}

TEST_CASE("tiles: robots that act one window after choosing a target, in bands",
          "[scenarios][tiles]") {
  // With an actuation delay of at least the window the first tile runs every robot and the
  // others move ghosts of them by the courses it publishes (docs/decisions/0012-partitioned-
  // runs.md, "Robots in the first tile"), also over ranks (threads standing in). A ghost
  // that missed a course would answer the wrong robot, a tile that delivered to its ghosts would
  // run their protocol: either changes the outputs.
  check_in_tiles("scenarios/paper/acoustic_tracking.yaml",
                 {"tie_order=origin", "duration=0.3", "output.snapshots=[0.25]",
                  "robots.actuation_delay=0.000114"});
  check_in_tiles("scenarios/bench/scaling_1e4.yaml",
                 {"tie_order=origin", "duration=0.06", "output.sample_period=0.01",
                  "output.trajectory_period=0.01", "robots.actuation_delay=0.00005"});
  check_in_tiles("scenarios/bench/scaling_1e5.yaml",
                 {"tie_order=origin", "duration=0.015", "output.sample_period=0.005",
                  "robots.actuation_delay=0.00005"});
}

TEST_CASE("tiles: robots in the first tile, killed and restarted, with beacons and link faults",
          "[scenarios][tiles]") {
  // A robot killed with a course pending (the ghosts must drop it too) and restarted; robots'
  // beacons (sent by the first tile only); a partition and a degraded area across the bands.
  check_in_tiles(
      "scenarios/paper/acoustic_tracking.yaml",
      {"tie_order=origin", "duration=3", "output.snapshots=[1.5]", "robots.actuation_delay=0.002",
       "faults=[{at: 1.0, until: 2.0, kill: sensors, fraction: 0.1}, {at: 0.5, until: 2.5, kill: "
       "robots, ids: [1, 3]}]"});
  check_in_tiles("scenarios/examples/beacons.yaml",
                 {"tie_order=origin", "duration=3", "robots.actuation_delay=0.001"});
  check_in_tiles(
      "scenarios/paper/acoustic_tracking.yaml",
      {"tie_order=origin", "duration=3", "output.snapshots=[1.5]", "radio.loss=0.05",
       "robots.actuation_delay=0.0002",
       "faults=[{at: 0.6, until: 2.2, partition: {line: [[0.5, 0.0], [0.5, 1.0]]}}, {at: 1.0, "
       "until: 2.5, degrade: {region: {center: [0.5, 0.5], radius: 0.3}, loss: 0.4}}]"});
}

TEST_CASE("tiles: robots stay in every tile unless they act at least one window late",
          "[scenarios][tiles]") {
  const std::string acoustic = "scenarios/paper/acoustic_tracking.yaml";
  const std::vector<std::string> origin{"tie_order=origin"};
  auto in_first = [](const ScenarioDef& def) { return robots_in_first_tile(def.world); };
  // The acoustic scenario's window is its radio latency, 50 µs.
  CHECK(in_first(load(acoustic, {"tie_order=origin", "robots.actuation_delay=0.00005"})));
  CHECK_FALSE(in_first(load(acoustic, {"tie_order=origin", "robots.actuation_delay=0.00004"})));
  CHECK_FALSE(in_first(load(acoustic, origin)));
  // Dispensers, formations and the oracle read what the robots decide outside the radio.
  CHECK_FALSE(in_first(load("scenarios/paper/pollution_control.yaml",
                            {"tie_order=origin", "robots.actuation_delay=0.001"})));
  CHECK_FALSE(in_first(load("scenarios/paper/formation_tracking.yaml",
                            {"tie_order=origin", "robots.actuation_delay=0.001"})));
  CHECK_FALSE(in_first(load(
      acoustic, {"tie_order=origin", "robots.actuation_delay=0.001", "protocol.kind=oracle"})));
}

TEST_CASE("tiles: the pollution scenario (diffusion, dispensers, its baseline) in bands",
          "[scenarios][tiles]") {
  check_in_tiles("scenarios/paper/pollution_control.yaml",
                 {"tie_order=origin", "duration=2", "output.snapshots=[1]"});
}

TEST_CASE("tiles: robot groups in formation, and beacons of sensors and robots, in bands",
          "[scenarios][tiles]") {
  check_in_tiles("scenarios/paper/formation_tracking.yaml",
                 {"tie_order=origin", "duration=1", "output.snapshots=[0.5]"});
  check_in_tiles("scenarios/examples/beacons.yaml", {"tie_order=origin", "duration=3"});
}

TEST_CASE("tiles: sensors and robots killed and restarted, in bands", "[scenarios][tiles]") {
  // A tenth of the sensors for a second, a disk of them for good, a robot for two seconds.
  check_in_tiles(
      "scenarios/paper/acoustic_tracking.yaml",
      {"tie_order=origin", "duration=3", "output.snapshots=[1.5]",
       "faults=[{at: 1.0, until: 2.0, kill: sensors, fraction: 0.1}, {at: 1.5, kill: sensors, "
       "region: {center: [0.3, 0.3], radius: 0.2}}, {at: 0.5, until: 2.5, kill: robots, ids: "
       "[1]}]"});
}

TEST_CASE("tiles: a partition and a degraded area that come and go, in bands",
          "[scenarios][tiles]") {
  // The partition crosses the bands (x = 0.5) and the degraded disk straddles them: frames cross
  // tiles under both, and robots move while those frames wait for the window's end.
  check_in_tiles(
      "scenarios/paper/acoustic_tracking.yaml",
      {"tie_order=origin", "duration=3", "output.snapshots=[1.5]", "radio.loss=0.05",
       "faults=[{at: 0.6, until: 2.2, partition: {line: [[0.5, 0.0], [0.5, 1.0]]}}, {at: 1.0, "
       "until: 2.5, degrade: {region: {center: [0.5, 0.5], radius: 0.3}, loss: 0.4}}]"});
}

TEST_CASE("tiles: the oracle, whose robots read the sensors themselves, in bands",
          "[scenarios][tiles]") {
  // Every tile runs every robot, so every tile makes the robots' reads: counted once.
  check_in_tiles(
      "scenarios/paper/acoustic_tracking.yaml",
      {"tie_order=origin", "duration=2", "output.snapshots=[1]", "protocol.kind=oracle"});
}

TEST_CASE("tiles: what they cannot run yet is refused with the reason", "[scenarios][tiles]") {
  const std::string bench = "scenarios/bench/scaling_1e4.yaml";
  CHECK(tiles_problem(load(bench, {}), 1).empty());
  CHECK(tiles_problem(load(bench, {}), 2) ==
        "tiles need `tie_order: origin`, the order each tile computes alone "
        "(docs/time-and-ordering.md)");
  CHECK(tiles_problem(load(bench, {"tie_order=origin", "radio.level=csma"}), 2) ==
        "tiles need radio.level ideal or airtime");
  CHECK(tiles_problem(load(bench, {"tie_order=origin", "sensors.battery=1"}), 2) ==
        "tiles do not run batteries yet");
  CHECK(tiles_problem(load(bench, {"tie_order=origin", "radio.jitter=0.001"}), 2) ==
        "tiles need radio.jitter 0");
  CHECK(tiles_problem(load(bench, {"tie_order=origin"}), 0) == "expected at least 1 tile");
}
