#pragma once
// The live viewer's side of a run (docs/live-and-replay.md): hands each frame to the server,
// paces the simulation (× real time, or as fast as possible), pauses it, and runs it one
// protocol update at a time, as the viewers command. The simulation waits only on this
// controller, never on a viewer.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "scenarios/live/live_server.hpp"
#include "scenarios/run/run_watcher.hpp"

namespace masnet::live {

struct WatchOptions {
  bool start_running = false;  ///< false: wait, paused, for the first viewer
  double speed = 1.0;          ///< × real time; 0 = as fast as possible
  double frame_period_s = 0.02;
  /// Metric points and trail positions kept for a viewer who joins late; beyond it every
  /// other point is dropped (the history stays bounded and covers the whole run).
  std::size_t max_history = 4000;
};

class LiveWatch final : public scenarios::RunWatcher {
 public:
  /// Registers itself as `server`'s greeting, command and viewers handler; its destructor stops
  /// the server (whose thread would otherwise call into a destroyed object).
  LiveWatch(Server& server, WatchOptions options);
  ~LiveWatch() override;

  double frame_period_s() const override { return options_.frame_period_s; }
  void on_start(const nlohmann::json& header) override;
  void on_frame(const nlohmann::json& frame) override;
  bool stop_after_update() override;
  void on_end(const nlohmann::json& final_frame) override;

  /// Viewers' commands: pause, play, step, speed (value), end. Empty when accepted.
  std::string command(const nlohmann::json& command);
  void viewers_changed(std::size_t viewers);
  /// What a new viewer is sent: hello (header), history, latest frame, status.
  std::vector<std::string> greeting();
  /// Wall seconds the simulation was held so far: paused, paced to real time, or waiting
  /// for its first viewer (the rest of the run's wall time is the simulation's own).
  double held_s() const;

 private:
  using Clock = std::chrono::steady_clock;
  std::string status_locked() const;
  void remember(const nlohmann::json& frame);
  /// Real-time pacing from the last anchor (reset on every change of speed or pause).
  void reanchor_locked(double t_s);

  Server& server_;
  WatchOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  bool paused_ = true;
  bool waiting_for_viewer_ = true;
  bool step_requested_ = false;
  bool announce_pause_ = false;  // a step ended: say so with the next frame
  bool to_end_ = false;          // "run to the end": no pacing, no pauses
  bool finished_ = false;
  double speed_ = 1.0;
  double t_s_ = 0.0;
  double anchor_t_s_ = 0.0;
  Clock::time_point anchor_wall_;
  std::size_t viewers_ = 0;
  std::string hello_;
  bool greeted_without_hello_ = false;  // a viewer came before the run started
  std::string latest_frame_;
  std::deque<nlohmann::json> history_;  // {t, p, metrics} of frames, thinned when full
  std::size_t history_stride_ = 1, frames_seen_ = 0;
  Clock::duration held_{};
};

}  // namespace masnet::live
