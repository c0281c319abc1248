#pragma once
// What a static sensor does (paper §III-B): keep the closest robot it heard and report to it
// once at the beginning, and answer a robot's SENSE with its reading when it lies inside the
// robot's cell. One shared object serves every sensor; the per-sensor state is a small struct
// in an array (10⁶ sensors must stay cheap), and the prepared cell of the SENSE being answered
// is a cache.
#include <cstdint>
#include <vector>

#include "protocols/geometry.hpp"
#include "protocols/host.hpp"
#include "protocols/protocol.hpp"
#include "sim/log.hpp"
#include "sim/time.hpp"
#include "sim/zeroed_array.hpp"

namespace masnet::protocols {

// All zero bytes: a sensor that has heard no robot yet. The states live in zeroed pages, so a
// tile (or rank) of a run cut by space never makes the other tiles' sensors' states resident.
struct SensorState {
  double closest_distance2 = 0.0;            // once a robot is heard
  std::uint32_t closest_robot_plus_one = 0;  // 0: none heard yet
  bool report_scheduled = false;
  NodeId closest_robot() const {
    return closest_robot_plus_one == 0 ? sim::kNoNode : sim::node_id(closest_robot_plus_one - 1);
  }
};

class PaperSensorProtocol final : public SensorProtocol {
 public:
  enum Timer : std::uint32_t { kReport = 1, kReply = 2 };

  /// `report_delay_s`: how long a sensor listens for POSITIONs before it reports. `log` (may
  /// be null) gets each report at trace level. `reply_jitter_s` > 0: each REPORT and READING
  /// waits a uniform draw in [0, J) more, keyed by `seed`, the sensor and what it answers.
  PaperSensorProtocol(double report_delay_s, std::size_t sensor_count,
                      const sim::Log* log = nullptr, double reply_jitter_s = 0.0,
                      std::uint64_t seed = 0)
      : report_delay_s_(report_delay_s),
        reply_jitter_s_(reply_jitter_s),
        seed_(seed),
        log_(log),
        states_(sensor_count),
        pending_(reply_jitter_s > 0 ? sensor_count : 0) {}

  void on_frame(SensorHost& host, const net::Frame& frame) override;
  void on_timer(SensorHost& host, std::uint32_t kind) override;
  std::uint64_t point_in_cell_tests() const override { return point_in_cell_tests_; }
  const SensorState& state(std::size_t sensor) const { return states_[sensor]; }

 private:
  struct PendingReply {
    NodeId robot;
    std::uint32_t update;
  };
  /// A uniform draw in [0, J) for the sensor `index`'s answer to (source, number).
  sim::Duration jitter(std::size_t index, NodeId source, std::uint64_t number) const;

  double report_delay_s_;
  double reply_jitter_s_;
  std::uint64_t seed_;
  const sim::Log* log_;
  sim::ZeroedArray<SensorState> states_;
  // Jittered READINGs not sent yet, per sensor, oldest first (only with a jitter).
  std::vector<std::vector<PendingReply>> pending_;
  // A SENSE reaches its hearers one after another: its cell is prepared once for all of them
  // (the answers are contains()'s). Keyed by the frame's name, (source, number).
  ConvexMembership sense_cell_;
  NodeId sense_source_ = sim::kNoNode;
  std::uint64_t sense_number_ = 0;
  std::uint64_t point_in_cell_tests_ = 0;  // one per SENSE a sensor heard
};

}  // namespace masnet::protocols
