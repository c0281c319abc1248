#include "scenarios/run/run.hpp"

#include <chrono>
#include <filesystem>
#include <optional>

#include "scenarios/output/output_file.hpp"
#include "scenarios/run/run_warnings.hpp"
#include "sim/cpus.hpp"
#include "sim/fingerprint.hpp"
#include "sim/log.hpp"

namespace masnet::scenarios {
namespace fs = std::filesystem;

namespace {
std::unique_ptr<sim::Simulator> make_simulator(const ScenarioDef& def) {
  auto simulator = std::make_unique<sim::Simulator>();
  if (def.ties_by_origin) simulator->order_ties_by_origin();  // before the world schedules
  return simulator;
}

bool has_baseline_twin(const ScenarioDef& def) {
  return def.baseline && def.world.dispenser.enabled;
}
bool has_fault_free_twin(const ScenarioDef& def) {
  return !def.world.faults.empty();
}
// What every twin drops: its own baseline, snapshots and replay (a twin runs no twins).
ScenarioDef twin_base(const ScenarioDef& def) {
  ScenarioDef twin = def;
  twin.baseline = false;
  twin.output.snapshots.clear();
  twin.output.replay = false;
  return twin;
}
}  // namespace

Run::Run(ScenarioDef def, unsigned tiles, unsigned threads, TileLink* link)
    : def_(std::move(def)),
      tiles_wanted_(tiles),
      threads_(threads),
      link_(link),
      // Only the process that writes the outputs needs the twins (over ranks, the first).
      runs_twins_((has_baseline_twin(def_) || has_fault_free_twin(def_)) &&
                  (!link || link->rank() == 0)),
      simulator_(make_simulator(def_)) {
  // A run with twins builds its world after them (execute), so that a twin and the run's own
  // world never take memory together.
  if (!runs_twins_) build();
}

Run::Run(ScenarioDef def, TwinTag) : def_(std::move(def)), simulator_(make_simulator(def_)) {
  build();
}

void Run::build() {
  unsigned threads = threads_;
  if (threads == 0) threads = static_cast<unsigned>(sim::allowed_cpu_count());
  RunTiles::Building others;
  if (tiles_wanted_ > 1) {
    MASNET_ASSERT(tiles_problem(def_, tiles_wanted_).empty(), "a scenario the tiles run");
    if (!link_) others = RunTiles::build_others(def_.world, tiles_wanted_, threads);
  }
  world_ = std::make_unique<agents::World>(*simulator_, def_.world);
  recorder_ = std::make_unique<Recorder>(*world_, def_);
  world_->set_observer(recorder_.get());
  if (tiles_wanted_ > 1)
    tiles_ = std::make_unique<RunTiles>(*simulator_, *world_, def_.world, tiles_wanted_, threads,
                                        link_, std::move(others));
  if (world_->group_count() > 0) formation_ = std::make_unique<FormationRecorder>(*world_);
}

Run::~Run() = default;

std::uint64_t Run::events() const {
  return tiles_ ? tiles_->events() : simulator_->events_run();
}
std::string Run::fingerprint() const {
  return tiles_ ? tiles_->fingerprint().hex() : simulator_->fingerprint().hex();
}
std::string Run::traffic_fingerprint() const {
  return traffic_fingerprint_;
}

namespace {
// Events between two progress calls while a chunk runs: a few microseconds of wall time each,
// so the bar hears from the run many times a second at a negligible cost per event.
constexpr std::uint64_t kProgressEveryEvents = 4096;
// SceneCapture::sent_since_last streams: the replay's frames and a watcher's count apart.
constexpr std::size_t kReplayStream = 0, kWatcherStream = 1;
}  // namespace

unsigned Run::passes() const {
  if (!runs_twins_) return 1;
  return 1 + unsigned{has_baseline_twin(def_)} + unsigned{has_fault_free_twin(def_)};
}

void Run::execute(const ProgressFn& progress, RunWatcher* watcher) {
  const auto wall_start = std::chrono::steady_clock::now();
  // Twins first, unless someone watches: the viewer shows the run itself at once.
  if (runs_twins_ && !watcher) run_twins(progress);
  if (!world_) {
    if (twins_done_)
      sim::Log(*simulator_).info("the run itself starts now; its clock starts again at 0");
    build();
  }
  simulate(progress, watcher);
  if (runs_twins_ && !twins_done_) run_twins({});
  attach_twins();
  wall_time_s_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
}

void Run::simulate(const ProgressFn& progress, RunWatcher* watcher) {
  world_->start();
  if (tiles_) tiles_->start();
  // Checkpoints on integer grids of each period (no accumulated rounding): the recorder, the
  // replay and a watcher observe between run_until chunks, never as an event.
  const sim::Time end = sim::time_at(def_.duration_s);
  const sim::Duration sample = sim::seconds(def_.output.sample_period_s);
  const sim::Duration trajectory = sim::seconds(def_.output.trajectory_period_s);
  const bool replay = def_.output.replay;
  const sim::Duration replay_period = sim::seconds(def_.output.replay_period_s);
  const sim::Duration frame_period =
      watcher ? sim::seconds(watcher->frame_period_s()) : sim::Duration{};
  if (replay || watcher) scene_ = std::make_unique<SceneCapture>(*world_, def_);
  std::vector<sim::Time> snapshots;
  for (double t : def_.output.snapshots)
    snapshots.push_back(sim::time_at(t));
  std::sort(snapshots.begin(), snapshots.end());
  std::int64_t next_sample = 0, next_trajectory = 0, next_replay = 0, next_frame = 0;
  std::size_t next_snapshot = 0;
  // Between checkpoints too (a large run may spend seconds of wall time in one chunk): the
  // kernel calls back every few thousand events, and the callee decides from the wall clock
  // whether to draw.
  const Done done = done_;  // the twins' passes, when they ran first
  if (progress)
    simulator_->set_progress_hook(kProgressEveryEvents,
                                  [&progress, done](sim::Time now, std::uint64_t events) {
                                    progress(done.t_s + sim::to_seconds(now), done.events + events);
                                  });
  bool stopped_after_update = false;
  if (watcher) {
    watcher->on_start(scene_->header());
    recorder_->set_update_listener([&] {
      if (watcher->stop_after_update()) {
        stopped_after_update = true;
        simulator_->stop();
      }
    });
  }
  // A frame for one stream (the replay or the watcher): the capture `now` (made here if it is
  // empty, so that streams at the same instant share it) with that stream's transmission counts.
  const auto frame_for = [this](std::size_t stream, std::optional<nlohmann::json>& now) {
    if (!now)
      now = scene_->frame(recorder_->samples().empty() ? nullptr : &recorder_->samples().back());
    nlohmann::json frame = *now;
    frame["sent"] = scene_->sent_since_last(stream);
    return frame;
  };
  for (;;) {
    const sim::Time t_sample = sim::kTimeZero + next_sample * sample;
    const sim::Time t_trajectory = sim::kTimeZero + next_trajectory * trajectory;
    const sim::Time t_replay = replay ? sim::kTimeZero + next_replay * replay_period : end;
    const sim::Time t_frame = watcher ? sim::kTimeZero + next_frame * frame_period : end;
    sim::Time next = std::min({t_sample, t_trajectory, t_replay, t_frame, end});
    if (next_snapshot < snapshots.size()) next = std::min(next, snapshots[next_snapshot]);
    if (tiles_) {
      tiles_->run_until(next);
      // The other tiles' sensors join the first tile's world before the end is sampled.
      if (next == end) tiles_->absorb();
    } else {
      simulator_->run_until(next);
    }
    if (stopped_after_update) {
      // Stopped inside the chunk, possibly with more events at this very time: show the frame,
      // then finish the chunk as if nothing had happened.
      stopped_after_update = false;
      std::optional<nlohmann::json> now;
      watcher->on_frame(frame_for(kWatcherStream, now));
      continue;
    }
    if (t_sample == next) {
      recorder_->sample();
      if (formation_) formation_->sample();
      ++next_sample;
    }
    if (t_trajectory == next) {
      recorder_->sample_trajectories();
      if (formation_) formation_->sample_positions();
      ++next_trajectory;
    }
    while (next_snapshot < snapshots.size() && snapshots[next_snapshot] == next) {
      recorder_->snapshot();
      ++next_snapshot;
    }
    // The replay and a watcher usually share their instants: one capture serves both.
    std::optional<nlohmann::json> now;
    if (replay && t_replay == next) {
      replay_frames_.push_back(frame_for(kReplayStream, now).dump());
      ++next_replay;
    }
    if (watcher && t_frame == next) {
      watcher->on_frame(frame_for(kWatcherStream, now));
      ++next_frame;
    }
    if (progress)
      progress(done.t_s + sim::to_seconds(next), done.events + simulator_->events_run());
    if (next == end) break;
  }
  simulator_->set_progress_hook(0, nullptr);
  // The final state is always sampled, whatever the period.
  if (recorder_->samples().empty() || recorder_->samples().back().t_s != def_.duration_s) {
    recorder_->sample();
    if (formation_) formation_->sample();
  }
  if (watcher) {
    recorder_->set_update_listener(nullptr);
    std::optional<nlohmann::json> now;
    watcher->on_end(frame_for(kWatcherStream, now));
  }
  traffic_fingerprint_ =
      world_->radio().traffic_fingerprint().hex();  // a pass over every node: once
}

void Run::run_twins(const ProgressFn& progress) {
  // One twin: announced on the run's own log (before the run, its simulator is still at 0),
  // its progress continuing the passes before it; `keep` takes what the run needs of it.
  const auto run_twin = [&](ScenarioDef def, const char* name, const auto& keep) {
    Run twin(std::move(def), TwinTag{});
    sim::Log(*simulator_)
        .info("the {} runs {}; its clock starts {}at 0", name, world_ ? "now" : "first",
              world_ || done_.t_s > 0 ? "again " : "");
    twin.execute([&](double t_s, std::uint64_t events) {
      if (progress) progress(done_.t_s + t_s, done_.events + events);
    });
    keep(twin);
    done_.t_s += def_.duration_s;
    done_.events += twin.events();
  };
  if (has_baseline_twin(def_)) {
    // The uncontrolled twin: same scenario and seed, dispensers off, so that with/without
    // control always sit side by side (docs/field-models.md).
    ScenarioDef def = twin_base(def_);
    def.world.dispenser.enabled = false;
    run_twin(std::move(def), "baseline twin (no dispensers)", [&](const Run& baseline) {
      baseline_samples_ = baseline.recorder().samples();
      baseline_fingerprint_ = baseline.fingerprint();
    });
  }
  if (has_fault_free_twin(def_)) {
    // The same scenario and seed without its faults: what the faults cost is the difference
    // (docs/outputs.md, `twin` and `recovery`).
    ScenarioDef def = twin_base(def_);
    def.world.faults.clear();
    run_twin(std::move(def), "fault-free twin", [&](const Run& fault_free) {
      twin_samples_ = fault_free.recorder().samples();
      const nlohmann::json metrics = fault_free.recorder().summary_metrics();
      twin_ = {
          {"fingerprint", fault_free.fingerprint()},
          {"coverage_final_cost", metrics.at("coverage").at("final_cost")},
          {"tracking_mean_error", metrics.contains("tracking")
                                      ? metrics["tracking"].value("mean_error", nlohmann::json())
                                      : nlohmann::json()},
          {"energy_total_j", metrics.at("energy_j").at("total")},
          {"updates", metrics.at("protocol").at("updates")}};
    });
  }
  twins_done_ = true;
}

void Run::attach_twins() {
  if (!twins_done_) return;
  if (has_baseline_twin(def_)) recorder_->attach_baseline(baseline_samples_);
  if (has_fault_free_twin(def_)) recorder_->attach_twin(twin_samples_);
  baseline_samples_ = {};
  twin_samples_ = {};
}

nlohmann::json Run::summary() const {
  nlohmann::json j;
  j["masnet_version"] = MASNET_VERSION;
  j["seed"] = def_.seed;
  j["sim_time_s"] = def_.duration_s;
  j["wall_time_s"] = wall_time_s_;
  j["events"] = events();
  j["fingerprint"] = fingerprint();
  j["traffic_fingerprint"] = traffic_fingerprint();
  j["run_key"] = run_key(def_);
  if (!baseline_fingerprint_.empty()) j["baseline_fingerprint"] = baseline_fingerprint_;
  if (!twin_.is_null()) j["twin"] = twin_;
  j["scenario"] = {{"name", def_.name},
                   {"source", def_.source_path},
                   {"sensors", world_->sensor_count()},
                   {"robots", world_->robot_count()},
                   {"sensor_layout", def_.sensor_layout},
                   {"resolved", def_.resolved}};
  j.update(recorder_->summary_metrics());
  if (formation_) j["formation"] = formation_->summary();
  j["warnings"] = run_warnings(j, def_.world.radio.loss);
  return j;
}

void Run::write_files(const std::string& dir) const {
  const fs::path d(dir);
  write_file(d / "summary.json", summary().dump(2) + "\n");
  recorder_->write_nodes((d / "nodes.csv").string());
  recorder_->write_timeseries((d / "timeseries.csv").string());
  recorder_->write_trajectories((d / "trajectories.csv").string());
  if (def_.output.updates) recorder_->write_updates((d / "updates.csv").string());
  recorder_->write_snapshots((d / "snapshots.json").string());
  if (formation_) {
    formation_->write_formation((d / "formation.csv").string());
    formation_->write_followers((d / "followers.csv").string());
  }
  if (def_.output.replay && scene_) write_replay((d / "replay.json").string());
}

void Run::write_replay(const std::string& path) const {
  // One frame a line: the file stays readable and a reader can stream it.
  OutputFile out(path);
  out.write("{\"header\": " + scene_->header().dump() + ",\n\"frames\": [\n");
  for (std::size_t i = 0; i < replay_frames_.size(); ++i)
    out.write(replay_frames_[i] + (i + 1 < replay_frames_.size() ? ",\n" : "\n"));
  out.write("]}\n");
  out.close();
}

std::string run_key(const ScenarioDef& def) {
  sim::Fingerprint h;
  const std::string text = std::string(MASNET_VERSION) + "\n" + def.resolved.dump();
  for (unsigned char c : text)
    h.mix(std::uint64_t{c});
  return h.hex();
}

}  // namespace masnet::scenarios
