#pragma once
// Identifiers that cross folders: plain integers with a type, never pointers.
#include <cstdint>
#include <functional>

namespace masnet::sim {

/// A node of the simulated network (sensor or robot). Dense from 0 in creation order.
enum class NodeId : std::uint32_t {};

inline constexpr std::uint32_t index(NodeId id) {
  return static_cast<std::uint32_t>(id);
}
inline constexpr NodeId node_id(std::uint32_t i) {
  return static_cast<NodeId>(i);
}

/// "No node": the broadcast destination and "nothing heard yet".
inline constexpr NodeId kNoNode = static_cast<NodeId>(0xFFFFFFFFu);

/// The origin of a node's events in the kernel's origin order (docs/time-and-ordering.md);
/// origin 0 is the world.
inline constexpr std::uint32_t kWorldOrigin = 0;
inline constexpr std::uint32_t origin_of(NodeId id) {
  return index(id) + 1;
}

}  // namespace masnet::sim
