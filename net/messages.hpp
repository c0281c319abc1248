#pragma once
// Message value types: a std::variant of payload structs, each with an
// explicit size in bytes (docs/radio-and-energy.md). The radio knows these formats, never protocol
// logic. Protocols may define types of their own (docs/protocol-api.md): they travel as a
// CustomMessage whose body the radio never reads, and are counted under their own name.
#include <array>
#include <cstdint>
#include <memory>
#include <string_view>
#include <variant>
#include <vector>

#include "net/vec2.hpp"
#include "sim/ids.hpp"
#include "sim/time.hpp"

namespace masnet::net {

using sim::NodeId;

// Vec2 is 16-byte aligned: it comes last in every payload, so that none exceeds 32 bytes (a
// Payload is then 48 bytes and a Frame 96; every frame in the air waits in such a record).

/// Periodic "I am here" of the demo scenario.
struct Beacon {
  NodeId sender;
  Vec2 position;
};
/// Initialisation step 1 (paper §III-B): a robot announces its position at max range.
struct Position {
  NodeId robot;
  Vec2 position;
};
/// Initialisation step 3: a sensor reports its position and measurement to its closest robot.
struct Report {
  NodeId sensor;
  double reading;  ///< sent as 32 bits (MessageSizes::measurement_bytes); kept exact here
  Vec2 position;
};
/// Radius-doubling round: "who is within radius_m of me?"
struct Discover {
  NodeId robot;
  double radius;  ///< world units; sent as 32 bits
  Vec2 position;
};
/// Reply of a robot to a Discover.
struct Neighbor {
  NodeId robot;
  Vec2 position;
};
/// First round of an update: sensors inside this convex cell, send me your reading.
struct Sense {
  NodeId robot;
  std::uint32_t update;  ///< the robot's update counter, so stale readings can be dropped
  std::vector<Vec2> cell;
};
/// A sensor's answer to Sense.
struct Reading {
  NodeId sensor;
  std::uint32_t update;
  double reading;  ///< sent as 32 bits (MessageSizes::measurement_bytes); kept exact here
  Vec2 position;
};

/// The message types: the built-in ones in variant order, then the types protocols register
/// (register_message_type), numbered from kBuiltinMessageTypeCount. Used as counter indices.
enum class MessageType : std::uint8_t {
  beacon,
  position,
  report,
  discover,
  neighbor,
  sense,
  reading
};
inline constexpr std::size_t kBuiltinMessageTypeCount = 7;
/// Interest masks have one bit per type.
inline constexpr std::size_t kMaxMessageTypes = 32;

inline constexpr std::array<std::string_view, kBuiltinMessageTypeCount> kBuiltinMessageTypeNames = {
    "BEACON", "POSITION", "REPORT", "DISCOVER", "NEIGHBOR", "SENSE", "READING"};

/// A message of a type a protocol registered. The body is shared, never copied: a broadcast's
/// receivers all read the same one. Its size on the air is fixed by the sender.
struct CustomMessage {
  MessageType type = MessageType::beacon;
  std::uint32_t body_bytes = 0;  ///< size on the air without the frame header
  std::shared_ptr<const void> body;
};

using Payload =
    std::variant<Beacon, Position, Report, Discover, Neighbor, Sense, Reading, CustomMessage>;
static_assert(std::variant_size_v<Payload> == kBuiltinMessageTypeCount + 1);

inline MessageType type_of(const Payload& payload) {
  const std::size_t index = payload.index();
  if (index < kBuiltinMessageTypeCount) return static_cast<MessageType>(index);
  return std::get_if<CustomMessage>(&payload)->type;
}

/// Registers a message type under `name` (upper case letters, digits and '_', unique, not a
/// built-in name) and returns it. Types are numbered in registration order; register them before
/// the first run (the radio sizes its counters by message_type_count() when it is built).
/// Throws std::invalid_argument on a bad or taken name, std::length_error past kMaxMessageTypes.
MessageType register_message_type(std::string_view name);
/// Built-in plus registered types.
std::size_t message_type_count();
/// The type's name as outputs spell it ("DISCOVER").
std::string_view name_of(MessageType type);
inline std::string_view name_of(std::size_t type) {
  return name_of(static_cast<MessageType>(type));
}

/// Field sizes on the air (bytes). Defaults: docs/decisions/0004-radio-timing-and-sizes.md; all
/// configurable (`radio.sizes`).
struct MessageSizes {
  std::uint32_t header_bytes = 8;       ///< MAC/PHY header and frame check
  std::uint32_t id_bytes = 2;           ///< a node id
  std::uint32_t position_bytes = 8;     ///< two 32-bit coordinates
  std::uint32_t measurement_bytes = 4;  ///< one 32-bit reading
  std::uint32_t radius_bytes = 4;       ///< one 32-bit radius
  std::uint32_t vertex_bytes = 8;       ///< one polygon vertex
  std::uint32_t counter_bytes = 2;      ///< an update counter
};

/// A frame on the air. Broadcasts share one Frame among all their receivers.
struct Frame {
  NodeId source = sim::kNoNode;
  NodeId destination = sim::kNoNode;  ///< kNoNode for a broadcast
  MessageType type = MessageType::beacon;
  std::uint32_t size_bytes = 0;
  double range = 0.0;  ///< world units, after the max_range cap
  sim::Time sent_at{};
  /// The sender's count of frames before this one: (source, number) names a transmission, so
  /// a receiver-side cache can tell one SENSE from the next.
  std::uint64_t number = 0;
  // May share its tail padding with what a record holding the frame adds (the radio's delivery
  // records: docs/radio-and-energy.md).
  [[no_unique_address]] Payload payload;

  bool is_broadcast() const { return destination == sim::kNoNode; }
};
static_assert(sizeof(Frame) <= 96, "a frame waiting for delivery fits in a line and a half");

/// Size on the air of a frame carrying `payload`.
std::uint32_t size_bytes(const Payload& payload, const MessageSizes& sizes);

}  // namespace masnet::net
