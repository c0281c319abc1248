#pragma once
// What a protocol is to the world: a robot protocol is one object per robot, a sensor protocol
// one object for all sensors (10⁶ sensors must stay cheap: per-sensor state lives in its arrays,
// indexed by SensorHost::index()). Both are written against the hosts of protocols/host.hpp and
// registered by name (protocols/registry.hpp; docs/protocol-api.md).
#include <cstdint>
#include <vector>

#include "net/messages.hpp"
#include "protocols/geometry.hpp"
#include "protocols/host.hpp"

namespace masnet::protocols {

/// A reading the robot holds from its last update, inside its cell.
struct CellReading {
  Vec2 position;
  double value;
};

class RobotProtocol {
 public:
  virtual ~RobotProtocol() = default;
  /// Called once at the start of the run.
  virtual void start() = 0;
  /// A frame of a type the protocol's definition says robots hear.
  virtual void on_frame(const net::Frame& frame) = 0;
  /// A timer set through RobotHost::set_timer has fired.
  virtual void on_timer(std::uint32_t kind) = 0;

  // What recorders and the dispenser read between updates.
  /// The robot's communication radius now (world units; 0 if the protocol has none).
  virtual double radius() const { return 0.0; }
  /// The cell of the last finished update (empty before the first).
  virtual const ConvexPolygon& cell() const = 0;
  /// The readings of the last finished update that lie inside its cell.
  virtual const std::vector<CellReading>& cell_readings() const = 0;
};

/// The end of a Lloyd update: the robot heads for the centroid of the mass gathered, or keeps
/// `target` when there was none (record.no_mass). Sets record.centroid and record.finished and
/// returns the target the robot now holds.
inline Vec2 head_for_centroid(RobotHost& host, const CentroidAccumulator& accumulator,
                              UpdateRecord& record, Vec2 target) {
  if (accumulator.has_mass()) {
    target = accumulator.centroid();
    host.set_target(target);
  } else {
    record.no_mass = true;  // keep the previous target
  }
  record.centroid = target;
  record.finished = host.now();
  return target;
}

class SensorProtocol {
 public:
  virtual ~SensorProtocol() = default;
  virtual void on_frame(SensorHost& host, const net::Frame& frame) = 0;
  virtual void on_timer(SensorHost& host, std::uint32_t kind) = 0;
  /// Point-in-cell tests the sensors made so far in this run (deciding whether to answer a
  /// robot's cell): 0 for a protocol that does not count (docs/protocols.md, "Computation
  /// load").
  virtual std::uint64_t point_in_cell_tests() const { return 0; }
};

}  // namespace masnet::protocols
