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
  /// A run with twins (faults; `baseline` with dispensers) builds its world in execute(),
  /// after them; the accessors below are for after execute().
  explicit Run(ScenarioDef def, unsigned tiles = 1, unsigned threads = 0, TileLink* link = nullptr);
  ~Run();
  /// The scenario it runs (moved in: hold on to this rather than a copy).
  const ScenarioDef& def() const { return def_; }

  /// Simulates the whole duration; `watcher` (may be null) sees it as it happens. The twins run
  /// first, each for the whole duration too, and `progress` counts their simulated time and
  /// events with the run's (from 0 to passes() × the duration); a watched run starts at once
  /// and its twins run after it.
  void execute(const ProgressFn& progress = {}, RunWatcher* watcher = nullptr);
  /// 1 + the number of twins this process runs (the first rank's, over ranks).
  unsigned passes() const;

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
  struct TwinTag {};
  /// A twin: the scenario as given, in one piece, without twins of its own.
  Run(ScenarioDef def, TwinTag);
  /// Builds the simulator's world, the recorder and the tiles.
  void build();
  /// The run itself, from its start to its end; `progress` offset by the passes done.
  void simulate(const ProgressFn& progress, RunWatcher* watcher);
  /// Runs the twins, keeping only their samples and figures.
  void run_twins(const ProgressFn& progress);
  /// Gives the recorder the twins' curves (same sample times).
  void attach_twins();
  void write_replay(const std::string& path) const;

  ScenarioDef def_;  // a copy: the world and recorder refer to it for the whole run
  unsigned tiles_wanted_ = 1, threads_ = 0;
  TileLink* link_ = nullptr;
  bool runs_twins_ = false;  // the whole run's process, with faults or a baseline to compare
  bool twins_done_ = false;
  // Progress of earlier passes (the twins run first): simulated seconds and events.
  struct Done {
    double t_s = 0;
    std::uint64_t events = 0;
  } done_;
  std::unique_ptr<sim::Simulator> simulator_;
  std::unique_ptr<agents::World> world_;
  std::unique_ptr<Recorder> recorder_;
  std::unique_ptr<RunTiles> tiles_;  // a run cut into tiles; null in one piece
  std::unique_ptr<FormationRecorder> formation_;
  std::unique_ptr<SceneCapture> scene_;
  std::vector<std::string> replay_frames_;  // serialised: a run may hold thousands
  double wall_time_s_ = 0.0;
  std::string baseline_fingerprint_;
  std::vector<Sample> baseline_samples_, twin_samples_;  // the twins' curves, kept till attached
  nlohmann::json twin_;  // runs with faults: the fault-free twin's figures
  std::string traffic_fingerprint_;
};

/// A key that names the run: the same resolved scenario (seed included) and version give
/// the same key. A run directory holding another key is "a different run".
std::string run_key(const ScenarioDef& def);

}  // namespace masnet::scenarios
