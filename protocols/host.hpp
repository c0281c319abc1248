#pragma once
// The narrow interface through which a protocol state machine touches the world (ARGoS
// controllers see only sensors and actuators). A test drives a protocol with a fake host and no
// radio; the world implements it for real robots and sensors. Ground truth (true cells, readings
// taken without messages) is not here: only the oracle gets it (docs/protocol-api.md).
#include <array>
#include <cstdint>
#include <vector>

#include "net/messages.hpp"
#include "net/vec2.hpp"
#include "protocols/geometry.hpp"
#include "protocols/lloyd.hpp"
#include "sim/simulator.hpp"

namespace masnet::protocols {

using net::NodeId;
using net::Vec2;

/// A protocol's own timer, returned to it through on_timer(kind).
using TimerHandle = sim::EventId;

/// Messages of one kind attributed to one update (sent by the robot or received by it).
struct MessageTally {
  std::uint64_t count = 0, bytes = 0;
};

/// A robot as one update heard it: its position as carried by the NEIGHBOR reply the update used.
struct HeardRobot {
  NodeId robot = sim::kNoNode;
  Vec2 position{0, 0};
};

/// Messages attributed to one update, by type. Built-in types are kept inline; the types
/// protocols register take a slot only once counted.
class MessageTallies {
 public:
  void add(net::MessageType type, std::uint32_t bytes) {
    if (bytes == 0) return;  // refused by the radio
    MessageTally& tally = slot(type);
    ++tally.count;
    tally.bytes += bytes;
  }
  MessageTally operator[](std::size_t type) const {
    if (type < builtin_.size()) return builtin_[type];
    const std::size_t custom = type - builtin_.size();
    return custom < custom_.size() ? custom_[custom] : MessageTally{};
  }
  MessageTally operator[](net::MessageType type) const {
    return (*this)[static_cast<std::size_t>(type)];
  }

 private:
  MessageTally& slot(net::MessageType type) {
    const auto t = static_cast<std::size_t>(type);
    if (t < builtin_.size()) return builtin_[t];
    if (custom_.size() <= t - builtin_.size()) custom_.resize(t - builtin_.size() + 1);
    return custom_[t - builtin_.size()];
  }
  std::array<MessageTally, net::kBuiltinMessageTypeCount> builtin_{};
  std::vector<MessageTally> custom_;
};

/// What one update did (docs/protocols.md): the part recorders keep. Every protocol that
/// computes cells reports them in this form, so cell correctness, costs and figures work for it
/// unchanged (docs/protocol-api.md).
struct UpdateSummary {
  NodeId robot = sim::kNoNode;
  std::uint32_t update = 0;  ///< the robot's update counter, from 1
  sim::Time started{}, finished{};
  std::uint32_t rounds = 0;        ///< DISCOVER rounds (0 for the oracle)
  double radius = 0.0;             ///< R at the end of the update (before range decay)
  bool truncated = false;          ///< R was capped at max_range before the stop rule held
  bool delayed = false;            ///< started late because the previous update was still running
  bool no_mass = false;            ///< no positive reading in the cell: target kept
  Vec2 position{0, 0};             ///< the robot's position the cell was computed for
  ConvexPolygon cell;              ///< the cell the robot computed
  std::vector<NodeId> neighbours;  ///< robots whose bisectors bound the cell, ascending
  Vec2 centroid{0, 0};             ///< the new target (or the kept one)
  std::uint32_t readings = 0;      ///< readings inside the cell used for the centroid
  MessageTallies messages;
  /// Clips and point-in-cell tests of this update (docs/protocols.md, "Computation load"); a
  /// protocol that does not count leaves them zero.
  GeometryWork geometry;
  /// The protocol's own per-update fields, in the order of its definition's update_columns
  /// (extra columns of updates.csv).
  std::vector<double> extra;
};

/// An update as the robot reports it. Recorders judge it (e.g. cell correctness) and keep the
/// summary: the robots heard are judged, not stored.
struct UpdateRecord : UpdateSummary {
  /// Every robot whose reply the update kept, at the position its reply carried (in the order
  /// heard); the oracle protocol leaves it empty.
  std::vector<HeardRobot> heard;
};

/// The world as a robot's protocol sees it.
class RobotHost {
 public:
  virtual ~RobotHost() = default;
  virtual sim::Time now() const = 0;
  virtual NodeId id() const = 0;
  /// Own position now (world units).
  virtual Vec2 position() const = 0;
  /// Sends; returns the frame size in bytes, 0 if the radio refused (battery empty).
  virtual std::uint32_t broadcast(double range, net::Payload payload) = 0;
  virtual std::uint32_t unicast(NodeId to, net::Payload payload) = 0;
  /// Field sizes on the air, to size a message of the protocol's own.
  virtual const net::MessageSizes& message_sizes() const = 0;
  /// Calls the protocol's on_timer(kind) after `delay`.
  virtual TimerHandle set_timer(sim::Duration delay, std::uint32_t kind) = 0;
  virtual void cancel_timer(TimerHandle timer) = 0;
  /// The control target c of p̈ = −k(p − c) − k_v ṗ.
  virtual void set_target(const Vec2& target) = 0;
  virtual void update_finished(const UpdateRecord& record) = 0;
  /// The area A(s) a sensor stands for (deployment knowledge, not a message).
  virtual double sensor_area(NodeId sensor) const = 0;
};

/// The world as a sensor's protocol sees it.
class SensorHost {
 public:
  virtual ~SensorHost() = default;
  virtual sim::Time now() const = 0;
  virtual NodeId id() const = 0;
  /// This sensor's number among the sensors, 0..S−1: the index of its state in a protocol's
  /// per-sensor arrays.
  virtual std::size_t index() const = 0;
  virtual Vec2 position() const = 0;
  /// This sensor's measurement of ρ now.
  virtual double reading() = 0;
  virtual std::uint32_t broadcast(double range, net::Payload payload) = 0;
  virtual std::uint32_t unicast(NodeId to, net::Payload payload) = 0;
  virtual const net::MessageSizes& message_sizes() const = 0;
  /// Calls SensorProtocol::on_timer for this sensor after `delay`.
  virtual void set_timer(sim::Duration delay, std::uint32_t kind) = 0;
};

}  // namespace masnet::protocols
