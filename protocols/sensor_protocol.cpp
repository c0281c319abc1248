#include "protocols/sensor_protocol.hpp"

#include "sim/random.hpp"

namespace masnet::protocols {
namespace {
constexpr std::uint64_t kReplyJitterPurpose = sim::purpose("sensor.reply_jitter");
}  // namespace

sim::Duration PaperSensorProtocol::jitter(std::size_t index, NodeId source,
                                          std::uint64_t number) const {
  return sim::seconds(reply_jitter_s_ * sim::keyed_uniform01(seed_, kReplyJitterPurpose, index,
                                                             sim::index(source), number));
}

void PaperSensorProtocol::on_frame(SensorHost& host, const net::Frame& frame) {
  if (const auto* sense = std::get_if<net::Sense>(&frame.payload)) {
    // Answer only if this sensor lies inside the robot's cell (boundary included).
    if (frame.source != sense_source_ || frame.number != sense_number_) {
      sense_cell_.reset(sense->cell);
      sense_source_ = frame.source;
      sense_number_ = frame.number;
    }
    // Not logged: this runs for every sensor that hears a SENSE, where even a level test
    // costs a measurable share of a run (docs/logging.md).
    ++point_in_cell_tests_;
    if (!sense_cell_.contains(host.position())) return;
    if (reply_jitter_s_ <= 0) {
      host.unicast(sense->robot,
                   net::Reading{host.id(), sense->update, host.reading(), host.position()});
      return;
    }
    pending_[host.index()].push_back(PendingReply{sense->robot, sense->update});
    host.set_timer(jitter(host.index(), frame.source, frame.number), kReply);
  } else if (const auto* position = std::get_if<net::Position>(&frame.payload)) {
    SensorState& state = states_[host.index()];
    // 2: each sensor finds its closest robot (ties: the lower id).
    const double d2 = (position->position - host.position()).squaredNorm();
    const NodeId closest = state.closest_robot();
    if (closest == sim::kNoNode || d2 < state.closest_distance2 ||
        (d2 == state.closest_distance2 && position->robot < closest)) {
      state.closest_distance2 = d2;
      state.closest_robot_plus_one = sim::index(position->robot) + 1;
    }
    if (!state.report_scheduled) {
      state.report_scheduled = true;
      const sim::Duration extra =
          reply_jitter_s_ > 0 ? jitter(host.index(), sim::kNoNode, 0) : sim::Duration{};
      host.set_timer(sim::seconds(report_delay_s_) + extra, kReport);
    }
  }
}

void PaperSensorProtocol::on_timer(SensorHost& host, std::uint32_t kind) {
  if (kind == kReply) {
    // The oldest reply waiting: draws differ, so timers fire out of order, but each sends one.
    std::vector<PendingReply>& waiting = pending_[host.index()];
    const PendingReply reply = waiting.front();
    waiting.erase(waiting.begin());
    host.unicast(reply.robot,
                 net::Reading{host.id(), reply.update, host.reading(), host.position()});
    return;
  }
  const SensorState& state = states_[host.index()];
  // 3: each sensor sends its position and measurement to its closest robot.
  const NodeId closest = state.closest_robot();
  if (kind == kReport && closest != sim::kNoNode) {
    const double reading = host.reading();
    MASNET_LOG(log_, trace, "sensor {}: reports {} to its closest robot {}", sim::index(host.id()),
               reading, sim::index(closest));
    host.unicast(closest, net::Report{host.id(), reading, host.position()});
  }
}

}  // namespace masnet::protocols
