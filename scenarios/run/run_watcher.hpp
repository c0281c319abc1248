#pragma once
// Something that watches a run while it happens — the live viewer (docs/live-and-replay.md).
// It sees frames between events, never as events: a watched run is the same run.
#include <nlohmann/json.hpp>

namespace masnet::scenarios {

class RunWatcher {
 public:
  virtual ~RunWatcher() = default;
  /// Simulated seconds between two frames.
  virtual double frame_period_s() const = 0;
  /// Once, before the first event: what does not change (SceneCapture::header).
  virtual void on_start(const nlohmann::json& header) = 0;
  /// A frame (SceneCapture::frame). May block the simulation: pause, real-time pacing.
  virtual void on_frame(const nlohmann::json& frame) = 0;
  /// Asked after every protocol update: true stops the run there for a frame (one update at a
  /// time). The run then goes on from the same event, so nothing else changes.
  virtual bool stop_after_update() = 0;
  /// Once, when the simulation has ended (before the run directory is written).
  virtual void on_end(const nlohmann::json& final_frame) = 0;
};

}  // namespace masnet::scenarios
