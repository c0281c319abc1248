#pragma once
// One run of a scenario: the simulator, the world and the recorder together, advanced in
// chunks between sample times, and the run directory it writes (docs/outputs.md).
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "scenarios/loader/scenario.hpp"
#include "scenarios/run/formation_outputs.hpp"
#include "scenarios/run/recorder.hpp"
#include "scenarios/run/run_tiles.hpp"
#include "scenarios/run/run_watcher.hpp"
#include "scenarios/run/scene_capture.hpp"

namespace masnet::scenarios {

/// Called now and then during a run with (simulated seconds done, events so far).
using ProgressFn = std::function<void(double t_s, std::uint64_t events)>;

class Run {
 public:
  /// `tiles` > 1 cuts the run into that many tiles by space (run_tiles.hpp; `tiles_problem`
  /// must be empty) on `threads` threads (0: one per allowed processor, at most one per tile);
  /// with a `link`, over its ranks instead, one tile each (the first rank's run is the whole).
  explicit Run(ScenarioDef def, unsigned tiles = 1, unsigned threads = 0, TileLink* link = nullptr);
  ~Run();
  /// The scenario it runs (moved in: hold on to this rather than a copy).
  const ScenarioDef& def() const { return def_; }

  /// Simulates the whole duration; `watcher` (may be null) sees it as it happens.
  void execute(const ProgressFn& progress = {}, RunWatcher* watcher = nullptr);

  /// summary.json: the keys of docs/outputs.md.
  nlohmann::json summary() const;
  /// Writes summary.json, nodes.csv, timeseries.csv, trajectories.csv, updates.csv and
  /// snapshots.json (and replay.json unless output.replay is off) into the existing directory
  /// `dir`.
  void write_files(const std::string& dir) const;

  const Recorder& recorder() const { return *recorder_; }
  /// What the robot groups did; null in a run without groups.
  const FormationRecorder* formation() const { return formation_.get(); }
  std::uint64_t events() const;
  std::string fingerprint() const;
  /// The radio's outcomes (net::Radio::traffic_fingerprint) at the end of the run: with
  /// `fingerprint`, "same run".
  std::string traffic_fingerprint() const;
  double wall_time_s() const { return wall_time_s_; }

 private:
  void write_replay(const std::string& path) const;
  /// Runs the scenario again without its faults and attaches that twin's curves.
  void run_fault_free_twin();

  ScenarioDef def_;  // a copy: the world and recorder refer to it for the whole run
  std::unique_ptr<sim::Simulator> simulator_;
  std::unique_ptr<agents::World> world_;
  std::unique_ptr<Recorder> recorder_;
  std::unique_ptr<RunTiles> tiles_;  // a run cut into tiles; null in one piece
  std::unique_ptr<FormationRecorder> formation_;
  std::unique_ptr<SceneCapture> scene_;
  std::vector<std::string> replay_frames_;  // serialised: a run may hold thousands
  double wall_time_s_ = 0.0;
  std::string baseline_fingerprint_;
  nlohmann::json twin_;  // runs with faults: the fault-free twin's figures
  std::string traffic_fingerprint_;
};

/// A key that names the run: the same resolved scenario (seed included) and version give
/// the same key. A run directory holding another key is "a different run".
std::string run_key(const ScenarioDef& def);

}  // namespace masnet::scenarios
