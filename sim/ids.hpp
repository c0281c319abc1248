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

}  // namespace masnet::sim
