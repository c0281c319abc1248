#pragma once
// What a static sensor does (paper §III-B): keep the closest robot it heard and report to it
// once at the beginning, and answer a robot's SENSE with its reading when it lies inside the
// robot's cell. One shared object serves every sensor (its only state is the prepared cell of
// the SENSE being answered, a cache); the per-sensor state is a small struct the world stores
// in an array (10⁶ sensors must stay cheap).
#include <cstdint>
#include <limits>

#include "protocols/geometry.hpp"
#include "protocols/host.hpp"
#include "sim/log.hpp"

namespace masnet::protocols {

struct SensorState {
  NodeId closest_robot = sim::kNoNode;
  double closest_distance2 = std::numeric_limits<double>::infinity();
  bool report_scheduled = false;
};

class SensorProtocol {
 public:
  enum Timer : std::uint32_t { kReport = 1 };

  /// `report_delay_s`: how long a sensor listens for POSITIONs before it reports. `log` (may
  /// be null) gets each report at trace level.
  explicit SensorProtocol(double report_delay_s, const sim::Log* log = nullptr)
      : report_delay_s_(report_delay_s), log_(log) {}

  void on_frame(SensorHost& host, SensorState& state, const net::Frame& frame) const;
  void on_timer(SensorHost& host, SensorState& state, std::uint32_t kind) const;

 private:
  double report_delay_s_;
  const sim::Log* log_;
  // A SENSE reaches its hearers one after another: its cell is prepared once for all of them
  // (the answers are contains()'s). Keyed by the frame's name, (source, number).
  mutable ConvexMembership sense_cell_;
  mutable NodeId sense_source_ = sim::kNoNode;
  mutable std::uint64_t sense_number_ = 0;
};

}  // namespace masnet::protocols
