#include "protocols/voronoi_protocol.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/ranges.h>

namespace masnet::protocols {
namespace {
std::uint32_t number(NodeId node) {
  return sim::index(node);
}
std::string node_list(const std::vector<NodeId>& nodes) {
  std::vector<std::uint32_t> numbers;
  for (NodeId node : nodes)
    numbers.push_back(number(node));
  return fmt::format("[{}]", fmt::join(numbers, ", "));
}
}  // namespace

VoronoiProtocol::VoronoiProtocol(RobotHost& host, const ProtocolParams& params,
                                 const ProtocolContext& context, double phase_s,
                                 const sim::Log* log)
    : host_(host), params_(params), context_(context), phase_s_(phase_s), log_(log) {
  switch (params_.variant) {
    case VoronoiVariant::fixed_radius:
      radius_m_ = std::min(params_.fixed_radius, context_.max_range);
      break;
    case VoronoiVariant::gabriel:
      radius_m_ = context_.max_range;
      break;
    case VoronoiVariant::radius_doubling:
      radius_m_ = params_.decay.min;
      break;
  }
}

// ---- Initialisation (paper §III-B, "at the beginning") --------------------------------------

void VoronoiProtocol::start() {
  last_target_ = host_.position();
  if (params_.variant != VoronoiVariant::radius_doubling) {  // only R_i needs initialising
    schedule_ticks();
    return;
  }
  phase_ = Phase::initialising;
  announce_position();
  // Sensors report one reply_timeout after the first POSITION they hear; allow them another two.
  host_.set_timer(sim::seconds(3.0 * params_.reply_timeout_s), kInitEnd);
}

void VoronoiProtocol::announce_position() {  // 1: each robot broadcasts its position p_i
  host_.broadcast(context_.max_range, net::Position{host_.id(), host_.position()});
}

void VoronoiProtocol::on_report(const net::Report& report, std::uint32_t) {
  // 4-5: robot i knows which sensors are in its cell and finds the farthest one.
  farthest_reporter_m_ =
      std::max(farthest_reporter_m_, (report.position - host_.position()).norm());
}

void VoronoiProtocol::finish_initialisation() {
  // 6: R_i = ‖p_i − s_j‖ for the farthest reporter j (R_min if nobody reported).
  radius_m_ = std::max(farthest_reporter_m_, params_.decay.min);
  MASNET_LOG(log_, debug, "robot {} initialised: R {} (farthest reporting sensor {})",
             number(host_.id()), radius_m_, farthest_reporter_m_);
  phase_ = Phase::idle;
  schedule_ticks();
}

void VoronoiProtocol::schedule_ticks() {
  host_.set_timer(sim::seconds(phase_s_), kTick);
}

// ---- The update: steps 1-4 of paper §III-B --------------------------------------------------

void VoronoiProtocol::on_tick() {
  host_.set_timer(sim::seconds(params_.period_s), kTick);
  if (phase_ != Phase::idle) {  // still busy with the previous update: this one waits
    tick_pending_ = true;
    ++delayed_updates_;
    MASNET_LOG(log_, debug,
               "robot {} update {}: still running at the next tick, the next update waits",
               number(host_.id()), update_);
    return;
  }
  begin_update();
}

void VoronoiProtocol::begin_update() {
  // A fresh record that keeps the last one's buffers: freeing them here (written an update ago,
  // long gone from the caches) and allocating anew cost about 2 % of the 10⁶ benchmark.
  std::vector<Vec2> vertices = std::move(record_.cell.vertices);
  std::vector<NodeId> neighbours = std::move(record_.neighbours);
  std::vector<HeardRobot> heard = std::move(record_.heard);
  record_ = UpdateRecord{};
  vertices.clear();
  neighbours.clear();
  heard.clear();
  record_.cell.vertices = std::move(vertices);
  record_.neighbours = std::move(neighbours);
  record_.heard = std::move(heard);
  record_.robot = host_.id();
  record_.update = ++update_;
  record_.started = host_.now();
  record_.delayed = tick_pending_;
  tick_pending_ = false;
  position_ = host_.position();
  record_.position = position_;
  log_update_start(log_, record_, radius_m_);
  neighbours_.clear();
  readings_.clear();
  sensed_cell_.clear();
  discover_round();  // R_i carried over from the preceding update
}

void VoronoiProtocol::discover_round() {
  // 1) detect all neighbouring robots within R_i.
  ++record_.rounds;
  phase_ = Phase::discovering;
  const std::uint32_t bytes =
      host_.broadcast(radius_m_, net::Discover{host_.id(), radius_m_, position_});
  record_.messages.add(net::MessageType::discover, bytes);
  host_.set_timer(sim::seconds(params_.reply_timeout_s), kRoundEnd);
}

void VoronoiProtocol::end_round() {
  // 2) construct V_i from the replies (bisectors within Ω; the disk B(p_i, R_i) is applied
  //    through the sensing range and the distance rule of decide()).
  cell_ = compute_cell();
  cell_sites_ = neighbours_.size();
  MASNET_LOG(
      log_, debug, "robot {} update {}: round {} timed out after {} s with {} neighbours heard",
      number(host_.id()), update_, record_.rounds, params_.reply_timeout_s, neighbours_.size());
  if (record_.rounds > 1) {
    decide();
    return;
  }
  // First round only: ask the sensors inside V_i for their readings (later rounds keep the
  // readings that are still inside the shrinking V_i).
  phase_ = Phase::sensing;
  const double sense_range = std::min(radius_m_, max_vertex_distance(cell_.polygon, position_));
  sensed_cell_ = cell_.polygon.vertices;
  const std::uint32_t bytes =
      host_.broadcast(sense_range, net::Sense{host_.id(), update_, cell_.polygon.vertices});
  record_.messages.add(net::MessageType::sense, bytes);
  host_.set_timer(sim::seconds(params_.reply_timeout_s), kSenseEnd);
}

void VoronoiProtocol::decide() {
  // A reply that came after its round's deadline (while the sensors answered) still bounds V_i:
  // the stop rule certifies a cell only if every robot heard within R bounds it.
  if (cell_sites_ != neighbours_.size()) {
    cell_ = compute_cell();
    cell_sites_ = neighbours_.size();
  }
  if (params_.variant != VoronoiVariant::radius_doubling) {
    // One round only; the cell is not certified when it reaches beyond the radius.
    finish_update(max_vertex_distance(cell_.polygon, position_) > radius_m_);
    return;
  }
  // 3) d_i: the farthest sensor in V_i (the paper) or the farthest point of V_i = Ω ∩ B(p_i, R_i)
  //    ∩ bisectors (Cortés), which is min(R_i, farthest vertex of the unbounded-by-disk cell).
  const double farthest_m =
      params_.criterion == StopCriterion::sensors
          ? farthest_reading_in_cell()
          : std::min(radius_m_, max_vertex_distance(cell_.polygon, position_));
  // 4) If R_i >= 2 d_i, stop (the paper's strict '>' never stops after R_i = 2 d_i; see
  //    docs/decisions/0001-stop-rule.md). Otherwise grow R_i and go to step 1.
  if (radius_m_ >= 2.0 * farthest_m) {
    MASNET_LOG(log_, debug, "robot {} update {}: R {} >= 2 x {}: stop", number(host_.id()), update_,
               radius_m_, farthest_m);
    if (params_.shrink_on_stop) radius_m_ = std::max(2.0 * farthest_m, params_.decay.min);
    finish_update(false);
    return;
  }
  if (radius_m_ >= context_.max_range) {  // cannot grow any more: the cell is truncated
    MASNET_LOG(log_, debug,
               "robot {} update {}: R {} is the max range and {} < 2 x {}: cell truncated",
               number(host_.id()), update_, radius_m_, radius_m_, farthest_m);
    finish_update(true);
    return;
  }
  const double grown_from = radius_m_;
  radius_m_ = params_.growth == Growth::to_2d ? 2.0 * farthest_m : 2.0 * radius_m_;
  radius_m_ = std::min(radius_m_, context_.max_range);
  MASNET_LOG(log_, debug, "robot {} update {}: R {} -> {} (farthest {} {})", number(host_.id()),
             update_, grown_from, radius_m_,
             params_.criterion == StopCriterion::sensors ? "sensor" : "vertex", farthest_m);
  discover_round();
}

void VoronoiProtocol::finish_update(bool truncated) {
  // The Lloyd target: centroid of the readings inside V_i weighted by SK(ρ)·A(s).
  CentroidAccumulator accumulator(context_.scaling);
  cell_readings_.clear();
  const bool all_inside = cell_is_sensed();
  // Each reading takes one point test unless the cell is still the sensed one (then none).
  if (!all_inside) record_.geometry.point_in_cell_tests += readings_.size();
  for (const HeardReading& r : readings_)
    if (all_inside || contains(cell_.polygon, r.position)) {
      accumulator.add(r.position, r.value, host_.sensor_area(r.sensor));
      cell_readings_.push_back({r.position, r.value});
      ++record_.readings;
    }
  record_.radius = radius_m_;
  record_.truncated = truncated;
  if (truncated) {
    Cell disk_cut = voronoi_cell(0, std::vector<Vec2>{position_}, {}, cell_.polygon, radius_m_);
    record_.geometry.half_plane_clips += disk_cut.half_plane_clips;
    record_.cell = std::move(disk_cut.polygon);
  } else {
    record_.cell = cell_.polygon;
  }
  for (std::uint32_t index : cell_.neighbours)
    record_.neighbours.push_back(neighbours_[index - 1].robot);
  for (const HeardNeighbour& n : neighbours_)
    record_.heard.push_back({n.robot, n.position});
  std::sort(record_.neighbours.begin(), record_.neighbours.end());
  last_target_ = head_for_centroid(host_, accumulator, record_, last_target_);
  last_cell_ = record_.cell;
  log_update_end(log_, record_);
  if (params_.variant == VoronoiVariant::radius_doubling) decay_range();
  phase_ = Phase::idle;
  host_.update_finished(record_);
  if (tick_pending_) begin_update();
}

void VoronoiProtocol::decay_range() {
  // "If for successive `patience` updates R_i remains unchanged, R_i = R_i − Δr."
  if (params_.decay.patience == 0) return;
  unchanged_streak_ = radius_m_ == last_final_radius_ ? unchanged_streak_ + 1 : 1;
  last_final_radius_ = radius_m_;
  if (unchanged_streak_ >= params_.decay.patience) {
    const double before = radius_m_;
    radius_m_ = std::max(radius_m_ - params_.decay.step, params_.decay.min);
    MASNET_LOG(log_, debug, "robot {} update {}: R unchanged for {} updates, decays {} -> {}",
               number(host_.id()), update_, params_.decay.patience, before, radius_m_);
    unchanged_streak_ = 0;
  }
}

void log_update_start(const sim::Log* log, const UpdateSummary& record, double radius) {
  MASNET_LOG(log, debug, "robot {} update {}: start at ({}, {}), R {}{}", number(record.robot),
             record.update, record.position.x(), record.position.y(), radius,
             record.delayed ? " (delayed)" : "");
}

void log_update_end(const sim::Log* log, const UpdateSummary& record) {
  MASNET_LOG(log, debug,
             "robot {} update {}: end after {} rounds, R {}{}, {} neighbours {}, {} readings, "
             "centroid ({}, {}){}",
             number(record.robot), record.update, record.rounds, record.radius,
             record.truncated ? " (truncated)" : "", record.neighbours.size(),
             node_list(record.neighbours), record.readings, record.centroid.x(),
             record.centroid.y(), record.no_mass ? " (no mass: target kept)" : "");
}

// ---- Messages and timers --------------------------------------------------------------------

void VoronoiProtocol::on_frame(const net::Frame& frame) {
  if (const auto* discover = std::get_if<net::Discover>(&frame.payload)) {
    answer_discover(*discover);
  } else if (const auto* neighbour = std::get_if<net::Neighbor>(&frame.payload)) {
    if (phase_ != Phase::discovering && phase_ != Phase::sensing) {  // late reply
      MASNET_LOG(log_, debug, "robot {}: ignored a late NEIGHBOR from robot {} (no update running)",
                 number(host_.id()), number(neighbour->robot));
      return;
    }
    record_.messages.add(net::MessageType::neighbor, frame.size_bytes);
    // A neighbour is taken at the position of its first reply in this update: later replies
    // (from later rounds) would move the bisectors under the stop rule, and with R ← 2d — no
    // margin — drifting neighbours could keep an update growing round after round.
    const bool known =
        std::any_of(neighbours_.begin(), neighbours_.end(),
                    [&](const HeardNeighbour& n) { return n.robot == neighbour->robot; });
    if (!known) neighbours_.push_back({neighbour->robot, neighbour->position});
  } else if (const auto* reading = std::get_if<net::Reading>(&frame.payload)) {
    if (phase_ == Phase::idle || phase_ == Phase::initialising || reading->update != update_) {
      MASNET_LOG(log_, debug,
                 "robot {} update {}: ignored a stale READING from sensor {} (for update {})",
                 number(host_.id()), update_, number(reading->sensor), reading->update);
      return;
    }
    record_.messages.add(net::MessageType::reading, frame.size_bytes);
    readings_.push_back({reading->sensor, reading->position, reading->reading});
  } else if (const auto* report = std::get_if<net::Report>(&frame.payload)) {
    if (phase_ == Phase::initialising) on_report(*report, frame.size_bytes);
  }
}

void VoronoiProtocol::answer_discover(const net::Discover& discover) {
  host_.unicast(discover.robot, net::Neighbor{host_.id(), host_.position()});
}

void VoronoiProtocol::on_timer(std::uint32_t kind) {
  switch (kind) {
    case kInitEnd:
      finish_initialisation();
      break;
    case kTick:
      on_tick();
      break;
    case kRoundEnd:
      end_round();
      break;
    case kSenseEnd:
      MASNET_LOG(log_, debug, "robot {} update {}: SENSE timed out after {} s with {} readings",
                 number(host_.id()), update_, params_.reply_timeout_s, readings_.size());
      decide();
      break;
    default:
      break;
  }
}

bool VoronoiProtocol::cell_is_sensed() const {
  // Sensors answered because they lie in the cell sent with SENSE (the same exact test): while
  // the cell is still that one, every reading is inside without testing it again.
  return cell_.polygon.vertices == sensed_cell_;
}

double VoronoiProtocol::farthest_reading_in_cell() {
  double farthest = 0.0;
  const bool all_inside = cell_is_sensed();
  if (!all_inside) record_.geometry.point_in_cell_tests += readings_.size();
  for (const HeardReading& r : readings_)
    if (all_inside || contains(cell_.polygon, r.position))
      farthest = std::max(farthest, (r.position - position_).norm());
  return farthest;
}

Cell VoronoiProtocol::compute_cell() {
  std::vector<Vec2> sites{position_};
  for (const HeardNeighbour& n : neighbours_)
    sites.push_back(n.position);
  std::vector<std::uint32_t> candidates;
  if (params_.variant == VoronoiVariant::gabriel) {
    candidates = gabriel_neighbours(0, sites);  // the paper's approximation for sparse robots
  } else {
    for (std::uint32_t i = 1; i < sites.size(); ++i)
      candidates.push_back(i);
  }
  Cell cell = voronoi_cell(0, sites, candidates, context_.domain);
  record_.geometry.half_plane_clips += cell.half_plane_clips;
  return cell;
}

}  // namespace masnet::protocols
