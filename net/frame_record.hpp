#pragma once
// A frame that crosses from one tile of a partitioned run to another
// (docs/decisions/0012-partitioned-runs.md): what the receiving tile needs to book and deliver
// the frame to its own nodes exactly as the whole radio would have — the sender, its range and
// payload, the event key its delivery takes, and the mobile nodes that heard it at send time
// (the tiles that run them learn of the frame only after the window).
#include <cstdint>
#include <vector>

#include "net/messages.hpp"
#include "net/vec2.hpp"
#include "sim/event_queue.hpp"
#include "sim/time.hpp"

namespace masnet::net {

struct FrameRecord {
  sim::Time sent_at{}, arrival{};
  sim::EventKey key;  ///< the delivery's key, made by the sender's tile
  NodeId source = sim::kNoNode, destination = sim::kNoNode;
  Vec2 source_position{0, 0};  ///< at send time (a mobile sender moves on)
  double range = 0.0, destination_distance = -1.0;
  std::uint64_t frame_number = 0;
  std::uint32_t type_index = 0, bytes = 0;
  bool destination_reached = false;    ///< a unicast's addressee was within range at send time
  std::vector<NodeId> mobile_hearers;  ///< in range at send time, sender and addressee excluded
  Payload payload;
  // With link faults (partitions, degraded areas): the state they were in when it was sent, each
  // mobile hearer's loss then (the ones a partition cut off are not hearers), and the mobile
  // addressee's (negative: cut off). A mobile node may have moved since.
  std::uint32_t link_epoch = 0;
  std::vector<double> mobile_losses;
  double destination_loss = 0.0;
};

}  // namespace masnet::net
