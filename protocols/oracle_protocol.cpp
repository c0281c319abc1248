#include "protocols/oracle_protocol.hpp"

namespace masnet::protocols {

OracleProtocol::OracleProtocol(RobotHost& host, GroundTruth& truth, std::size_t robot,
                               const ProtocolContext& context, double period_s, double phase_s,
                               const sim::Log* log)
    : host_(host),
      truth_(truth),
      robot_(robot),
      context_(context),
      period_s_(period_s),
      phase_s_(phase_s),
      log_(log) {}

void OracleProtocol::start() {
  last_target_ = host_.position();
  host_.set_timer(sim::seconds(phase_s_), kTick);
}

void OracleProtocol::on_timer(std::uint32_t kind) {
  if (kind != kTick) return;
  host_.set_timer(sim::seconds(period_s_), kTick);
  update();  // takes no simulated time: an update is never still running at the next tick
}

void OracleProtocol::update() {
  UpdateRecord record;
  record.robot = host_.id();
  record.update = ++update_;
  record.started = host_.now();
  record.position = host_.position();
  log_update_start(log_, record, radius());
  RobotCell truth = truth_.true_cell(robot_);
  CentroidAccumulator accumulator(context_.scaling);
  record.readings = truth_.read_sensors_in(truth.polygon, accumulator, &record.geometry);
  record.geometry.half_plane_clips += truth.half_plane_clips;
  // What Cortés' rule would need to certify this cell.
  record.radius = 2.0 * max_vertex_distance(truth.polygon, record.position);
  record.cell = std::move(truth.polygon);
  record.neighbours = std::move(truth.neighbours);
  last_target_ = head_for_centroid(host_, accumulator, record, last_target_);
  last_cell_ = record.cell;
  log_update_end(log_, record);
  host_.update_finished(record);
}

}  // namespace masnet::protocols
