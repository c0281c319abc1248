#include "protocols/sensor_protocol.hpp"

namespace masnet::protocols {

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
    if (sense_cell_.contains(host.position()))
      host.unicast(sense->robot,
                   net::Reading{host.id(), sense->update, host.position(), host.reading()});
  } else if (const auto* position = std::get_if<net::Position>(&frame.payload)) {
    SensorState& state = states_[host.index()];
    // 2: each sensor finds its closest robot (ties: the lower id).
    const double d2 = (position->position - host.position()).squaredNorm();
    if (d2 < state.closest_distance2 ||
        (d2 == state.closest_distance2 && position->robot < state.closest_robot)) {
      state.closest_distance2 = d2;
      state.closest_robot = position->robot;
    }
    if (!state.report_scheduled) {
      state.report_scheduled = true;
      host.set_timer(sim::seconds(report_delay_s_), kReport);
    }
  }
}

void PaperSensorProtocol::on_timer(SensorHost& host, std::uint32_t kind) {
  const SensorState& state = states_[host.index()];
  // 3: each sensor sends its position and measurement to its closest robot.
  if (kind == kReport && state.closest_robot != sim::kNoNode) {
    const double reading = host.reading();
    MASNET_LOG(log_, trace, "sensor {}: reports {} to its closest robot {}", sim::index(host.id()),
               reading, sim::index(state.closest_robot));
    host.unicast(state.closest_robot, net::Report{host.id(), host.position(), reading});
  }
}

}  // namespace masnet::protocols
