#include "agents/world.hpp"

#include "net/tile_ledger.hpp"

#include "agents/follower_agent.hpp"
#include "agents/robot_agent.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "sim/random.hpp"

namespace masnet::agents {
namespace {

std::uint32_t interest_mask(const std::vector<net::MessageType>& types) {
  std::uint32_t mask = 0;
  for (net::MessageType t : types)
    mask |= 1u << static_cast<unsigned>(t);
  return mask;
}

// The radio sizes its counters by the message types registered when it is built.
const WorldDef& with_message_types(const WorldDef& def) {
  if (def.formation.enabled()) formation_message_type();
  return def;
}

double diameter(const protocols::ConvexPolygon& polygon) {
  double d = 0.0;
  for (const Vec2& a : polygon.vertices)
    for (const Vec2& b : polygon.vertices)
      d = std::max(d, (a - b).norm());
  return d;
}

}  // namespace

// ---- A sensor's host: made on the stack per event; the state lives in arrays ---------------

class World::SensorContext final : public protocols::SensorHost {
 public:
  SensorContext(World& world, std::size_t sensor) : world_(world), sensor_(sensor) {}
  sim::Time now() const override { return world_.simulator_.now(); }
  NodeId id() const override { return world_.sensor_node(sensor_); }
  std::size_t index() const override { return sensor_; }
  // From the radio's record of the node, which the reply's transmission reads anyway.
  Vec2 position() const override { return world_.radio_.position(id()); }
  double reading() override { return world_.sensor_reading(sensor_, position()); }
  std::uint32_t broadcast(double range, net::Payload payload) override {
    return world_.send(id(), sim::kNoNode, range, std::move(payload));
  }
  std::uint32_t unicast(NodeId to, net::Payload payload) override {
    return world_.send(id(), to, 0.0, std::move(payload));
  }
  const net::MessageSizes& message_sizes() const override { return world_.radio_.params().sizes; }
  void set_timer(sim::Duration delay, std::uint32_t kind) override {
    World* world = &world_;
    const std::size_t sensor = sensor_;
    world_.simulator_.after(delay, [world, sensor, kind] { world->sensor_timer(sensor, kind); });
  }

 private:
  World& world_;
  std::size_t sensor_;
};

// ---- The world -------------------------------------------------------------------------------

World::World(sim::Simulator& simulator, const WorldDef& def)
    : simulator_(simulator),
      log_(simulator),
      def_(def),
      radio_(simulator, with_message_types(def).radio, def.seed),
      field_(def.field),
      protocol_context_{def.domain,        def.scaling,        def.radio.max_range,
                        def.robots.size(), def.sensors.size(), def.seed},
      definition_(&protocols::protocol_named(def.protocol.kind)),
      truthful_factory_(protocols::ground_truth_factory(def.protocol.kind)),
      sensor_protocol_(definition_->make_sensor(
          protocols::SensorSetup{protocol_context_, def_.protocol.params, &log_})) {
  radio_.set_listener(this);
  radio_.set_mobile_positions(this);
  actuation_delay_ = sim::seconds(def_.actuation_delay_s);
  const std::uint32_t robot_interest = interest_mask(definition_->robots_hear);
  const std::uint32_t sensor_interest = interest_mask(definition_->sensors_hear);
  robots_.reserve(def_.robots.size());
  for (std::size_t i = 0; i < def_.robots.size(); ++i) {
    robots_.push_back(std::make_unique<RobotAgent>(*this, i, def_.robots[i]));
    radio_.add_mobile_node(robot_node(i), robot_key(i));
    radio_.set_interest(robot_node(i), robot_interest);
  }
  for (std::size_t s = 0; s < def_.sensors.size(); ++s) {
    radio_.add_static_node(sensor_node(s), def_.sensors[s].position, sensor_key(s));
    radio_.set_interest(sensor_node(s), sensor_interest);
  }
  add_followers();
  if (!def_.sensors.empty()) {
    uniform_sensor_area_ = def_.sensors.front().area;
    for (const SensorDef& s : def_.sensors)
      if (s.area != uniform_sensor_area_) uniform_sensor_area_ = 0.0;
  }
  // Batteries: a sensor's own, else its class's, else the radio's (which the radio has already).
  for (std::size_t i = 0; i < def_.robots.size(); ++i)
    if (def_.robot_battery_j > 0) radio_.set_battery(robot_node(i), def_.robot_battery_j);
  for (std::size_t s = 0; s < def_.sensors.size(); ++s) {
    const double battery_j =
        def_.sensors[s].battery_j > 0 ? def_.sensors[s].battery_j : def_.sensor_battery_j;
    if (battery_j > 0) radio_.set_battery(sensor_node(s), battery_j);
  }
  if (!def_.faults.empty()) radio_.enable_failures();
  sensor_read_counts_.assign(def_.sensors.size(), 0);
  if (field_.time_invariant())
    still_field_values_.assign(def_.sensors.size(), std::numeric_limits<double>::quiet_NaN());
  if (def_.field.kind == FieldKind::diffusion)
    diffusion_ = std::make_unique<DiffusionField>(def_.field.diffusion);
  spray_rate_.assign(robots_.size(), 0.0);
  neutraliser_used_.assign(robots_.size(), 0.0);
  // The radio indexes the sensors by rows anyway (they are its static nodes, in the same order):
  // the oracle's pass reads that index instead of a copy of its own.
  sensor_lines_ = &radio_.static_lines();
}

World::~World() = default;

const net::SpatialGrid& World::sensor_grid() const {
  if (!sensor_grid_built_) {
    std::vector<Vec2> positions;
    std::vector<NodeId> ids;
    positions.reserve(def_.sensors.size());
    ids.reserve(def_.sensors.size());
    for (std::size_t s = 0; s < def_.sensors.size(); ++s) {
      positions.push_back(def_.sensors[s].position);
      ids.push_back(sensor_node(s));
    }
    sensor_grid_.build(positions, ids);
    sensor_grid_built_ = true;
  }
  return sensor_grid_;
}

void World::start() {
  // Each node's first events are scheduled acting as the node (the kernel's origin order:
  // counted as the world's, they would be numbered by how many nodes came before).
  for (std::size_t i = 0; i < robots_.size() && robots_here_; ++i) {
    RobotAgent* agent = robots_[i].get();
    simulator_.after_as(sim::origin_of(robot_node(i)), sim::Duration{0},
                        [agent] { agent->protocol().start(); });
  }
  schedule_faults();
  start_groups();
  if (diffusion_)  // the PDE is the one thing that advances on a fixed step
    simulator_.after(sim::seconds(def_.field.diffusion.dt_s), [this] { pde_step(); });
  const BeaconDef& b = def_.beacons;
  if (b.senders == BeaconSenders::none) return;
  auto schedule = [&](NodeId node, std::uint64_t key) {
    auto phase = sim::RandomStream::keyed(def_.seed, key, sim::purpose("beacon.phase"));
    simulator_.after_as(sim::origin_of(node), sim::seconds(phase.uniform(0.0, b.period_s)),
                        [this, node] { send_beacon(node); });
  };
  if (b.senders == BeaconSenders::robots || b.senders == BeaconSenders::all)
    for (std::size_t i = 0; i < robots_.size() && robots_here_; ++i)
      schedule(robot_node(i), robot_key(i));
  // A tile of a partitioned run sends its own sensors' beacons (every tile runs every robot).
  if (b.senders == BeaconSenders::sensors || b.senders == BeaconSenders::all)
    for (std::size_t s = 0; s < def_.sensors.size(); ++s)
      if (radio_.owns(sensor_node(s))) schedule(sensor_node(s), sensor_key(s));
}

void World::absorb_tile(const TileCounts& counts, const net::Radio::TileLedger& ledger) {
  radio_.absorb_tile(ledger);
  absorbed_.readings += counts.readings;
  absorbed_.point_in_cell_tests += counts.point_in_cell_tests;
  absorbed_.clamped_readings += counts.clamped_readings;
}

std::uint32_t World::send(NodeId from, NodeId to, double range, net::Payload payload) {
  const std::uint32_t bytes = net::size_bytes(payload, radio_.params().sizes);
  const bool sent = to == sim::kNoNode ? radio_.broadcast(from, range, std::move(payload))
                                       : radio_.unicast(from, to, std::move(payload));
  return sent ? bytes : 0;
}

void World::send_beacon(NodeId node) {
  radio_.broadcast(node, def_.beacons.range, net::Beacon{node, position(node)});
  simulator_.after(sim::seconds(def_.beacons.period_s), [this, node] { send_beacon(node); });
}

MotionState World::robot_state(std::size_t robot) const {
  return robots_[robot]->state();
}
Vec2 World::robot_target(std::size_t robot) const {
  return robots_[robot]->segment().target();
}
const protocols::RobotProtocol& World::robot_protocol(std::size_t robot) const {
  return robots_[robot]->protocol();
}

std::vector<Vec2> World::source_positions() const {
  return field_.sources_at(sim::to_seconds(simulator_.now()));
}

double World::true_density(std::size_t sensor) {
  if (diffusion_) return diffusion_->value_at(def_.sensors[sensor].position);
  return field_.peek(def_.sensors[sensor].position, sim::to_seconds(simulator_.now()));
}

double World::field_value(const Vec2& s) {
  return diffusion_ ? diffusion_->value_at(s) : field_.value(s, sim::to_seconds(simulator_.now()));
}

double World::pollution_total() const {
  double total = 0.0;
  if (diffusion_)
    for (const SensorDef& s : def_.sensors)
      total += diffusion_->value_at(s.position);
  return total;
}

void World::pde_step() {
  // This event at t1 advances the field over [t1 − dt, t1]; readings between steps see the
  // last completed step.
  const double dt = def_.field.diffusion.dt_s;
  const double t0 = sim::to_seconds(simulator_.now()) - dt;
  const bool spraying = def_.dispenser.enabled;
  if (spraying)
    for (std::size_t i = 0; i < robots_.size(); ++i)
      spray_rate_[i] = spray_rate(i);
  const InjectionFn injections = [this, spraying](double t, std::vector<PointInjection>& out) {
    for (const SourceDef& source : def_.field.sources)
      out.push_back({position_on(source.path, t), source.rate(t)});
    if (spraying)
      for (std::size_t i = 0; i < robots_.size(); ++i)
        out.push_back({robots_[i]->segment().state_at(t).position, spray_rate_[i]});
  };
  const StepReport report = diffusion_->step(t0, injections);
  if (spraying)
    for (std::size_t i = 0; i < robots_.size(); ++i)
      neutraliser_used_[i] -= report.injections[def_.field.sources.size() + i].applied;
  simulator_.fingerprint_stream().mix(sim::bits_of(diffusion_->mass()));
  simulator_.after(sim::seconds(dt), [this] { pde_step(); });
}

double World::spray_rate(std::size_t robot) const {
  const DispenserDef& d = def_.dispenser;
  if (d.payload > 0 && neutraliser_used_[robot] >= d.payload) return 0.0;  // tank empty
  const Vec2 p = robots_[robot]->state().position;
  const protocols::RobotProtocol& protocol = robots_[robot]->protocol();
  double sum = 0.0;
  std::size_t count = 0;
  if (d.readings == SprayReadings::live) {
    const protocols::ConvexPolygon& cell = protocol.cell();
    sensor_grid().for_each_within(p, d.spray_radius, [&](NodeId id, const Vec2& s, double) {
      if (!protocols::contains(cell, s) || (dead_sensors_ > 0 && !radio_.alive(id))) return;
      sum += diffusion_->value_at(s);
      ++count;
    });
  } else {
    for (const protocols::CellReading& r : protocol.cell_readings())
      if ((r.position - p).norm() <= d.spray_radius) {
        sum += r.value;
        ++count;
      }
  }
  if (count == 0) return 0.0;
  // Only pollution is neutralised: a non-positive mean asks for no spray (never a source).
  const double mean = sum / static_cast<double>(count);
  double magnitude = std::min(d.gain * std::max(mean, 0.0), d.max_rate);
  if (d.payload > 0)
    magnitude =
        std::min(magnitude, (d.payload - neutraliser_used_[robot]) / def_.field.diffusion.dt_s);
  return -magnitude;
}

double World::sensor_reading(std::size_t sensor, const Vec2& position) {
  ++readings_taken_;
  double value;
  if (!still_field_values_.empty()) {
    // A still field: the sensor's value is computed once (an exp per bump) and then read back.
    double& kept = still_field_values_[sensor];
    if (std::isnan(kept)) kept = field_value(position);
    value = kept;
  } else {
    value = field_value(position);
  }
  if (def_.sensor_noise_sigma > 0.0) {
    // Box-Muller from two keyed draws: the n-th reading of a sensor has fixed noise.
    const std::uint64_t n = sensor_read_counts_[sensor]++;
    const std::uint64_t key = sensor_key(sensor), purpose = sim::purpose("sensor.noise");
    const double u1 = sim::keyed_uniform01(def_.seed, purpose, key, n, 0);
    const double u2 = sim::keyed_uniform01(def_.seed, purpose, key, n, 1);
    value += def_.sensor_noise_sigma * std::sqrt(-2.0 * std::log(1.0 - u1)) *
             std::cos(2.0 * std::numbers::pi * u2);
  }
  return value;
}

protocols::RobotCell World::oracle_cell(std::size_t robot, double first_radius) {
  const Vec2 p = robot_state(robot).position;
  const double span = diameter(def_.domain);
  // Cortés' rule with true positions: neighbours within r certify the cell once r >= 2·(farthest
  // vertex); start from the caller's guess or a radius that suits a uniform spread, and double.
  double r = first_radius > 0.0
                 ? first_radius
                 : std::max(2.0 * span / std::sqrt(static_cast<double>(robots_.size())), 1e-6);
  struct Site {
    double d2;
    NodeId node;
  };
  std::vector<Site> found;
  std::vector<Vec2> sites;
  std::vector<NodeId> site_nodes;
  std::vector<std::uint32_t> candidates;
  protocols::Cell cell;
  std::uint64_t clips = 0;
  for (;;) {
    found.clear();
    radio_.for_each_mobile_within(p, r, [&](NodeId id) {
      // A robot that is down covers nothing: the cells are those of the robots up. Followers
      // of robot groups are mobile nodes too, but no sites.
      if (id != robot_node(robot) && is_robot(id) &&
          (dead_robots_ == 0 || robots_[sim::index(id)]->alive()))
        found.push_back({(robots_[sim::index(id)]->state().position - p).squaredNorm(), id});
    });
    // Nearest first, ties by id: the first few clips shrink the cell and the farther candidates
    // are dismissed by one distance test each; and the order (so the last bits of the cell)
    // does not depend on when the radio last rebuilt its mobile index.
    std::sort(found.begin(), found.end(), [](const Site& a, const Site& b) {
      return a.d2 < b.d2 || (a.d2 == b.d2 && a.node < b.node);
    });
    sites.assign(1, p);
    site_nodes.assign(1, robot_node(robot));
    for (const Site& site : found) {
      sites.push_back(robots_[sim::index(site.node)]->state().position);
      site_nodes.push_back(site.node);
    }
    candidates.clear();
    for (std::uint32_t i = 1; i < sites.size(); ++i)
      candidates.push_back(i);
    cell = protocols::voronoi_cell(0, sites, candidates, def_.domain);
    clips += cell.half_plane_clips;
    if (r >= 2.0 * protocols::max_vertex_distance(cell.polygon, p) || r >= span) break;
    r *= 2.0;
  }
  protocols::RobotCell out;
  out.polygon = std::move(cell.polygon);
  out.half_plane_clips = clips;
  for (std::uint32_t i : cell.neighbours)
    out.neighbours.push_back(site_nodes[i]);
  std::sort(out.neighbours.begin(), out.neighbours.end());
  return out;
}

std::uint32_t World::read_sensors_in(const protocols::ConvexPolygon& cell,
                                     protocols::CentroidAccumulator& accumulator,
                                     protocols::GeometryWork* work) {
  if (cell.empty()) return 0;
  // A robot's own reads (the oracle's pass): every tile of a partitioned run makes them, so what
  // a tile counts for its sensors leaves them out (tile_counts).
  struct RobotReads {
    World& world;
    std::uint64_t readings, clamped;
    ~RobotReads() {
      world.robot_reads_.readings += world.readings_taken_ - readings;
      world.robot_reads_.clamped_readings += world.field_.clamped_readings() - clamped;
    }
  } robot_reads{*this, readings_taken_, field_.clamped_readings()};
  std::uint32_t inside = 0;
  std::uint64_t decided = 0;  // sensors whose membership was settled: the point tests
  const std::size_t first_sensor = robots_.size();
  auto take = [&](NodeId id, const Vec2& s) {
    if (dead_sensors_ > 0 && !radio_.alive(id)) return;  // a sensor that is down reads nothing
    const std::size_t sensor = sim::index(id) - first_sensor;
    accumulator.add(s, sensor_reading(sensor, s), def_.sensors[sensor].area);
    ++inside;
  };
  if (!sensor_lines_->empty()) slicer_.reset(cell);
  if (sensor_lines_->empty() || !slicer_.valid()) {  // no rows, or not a proper polygon
    Vec2 lo = cell.vertices[0], hi = cell.vertices[0];
    for (const Vec2& v : cell.vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    sensor_grid().for_each_within(0.5 * (lo + hi), 0.5 * (hi - lo).norm(),
                                  [&](NodeId id, const Vec2& s, double) {
                                    ++decided;
                                    if (protocols::contains(cell, s)) take(id, s);
                                  });
    if (work) work->point_in_cell_tests += decided;
    return inside;
  }
  // Sensor rows: the cell meets each row in one interval, whose ends the slicer gives within
  // its margin; only sensors that close to an end need the exact test, so the per-sensor work
  // is the accumulation itself. Two passes: first every row's interval, prefetching the
  // coordinates it will read (on large networks each row is a cache miss: overlapping them is
  // most of the cost), then the exact ends and the readings.
  const double margin = slicer_.margin();
  // On evenly spaced rows the sensors between xl + margin and xr − margin come from O(1) slot
  // estimates when no sensor is near either end (LineIndex::sure_slots): all of them are inside,
  // and the guard of 2·margin puts every other sensor beyond the exact ends, outside.
  const bool sure_rows =
      sensor_lines_->slot_estimates_are_sure(slicer_.max_abs_x() + 2.0 * margin, 2.0 * margin);
  pending_rows_.clear();
  sensor_lines_->for_each_line_between(
      slicer_.y_min(), slicer_.y_max(),
      [&](std::size_t line, double y, std::uint32_t begin, std::uint32_t end) {
        const auto [xl, xr] = slicer_.extent(y);
        if (!(xl <= xr + 2.0 * margin)) return;
        std::uint32_t a, c;
        const bool sure = sure_rows && xl + margin <= xr - margin &&
                          sensor_lines_->sure_slots(line, xl + margin, xr - margin, a, c);
        if (!sure) {  // the exact search starts one slot before the guess and ends one past the
                      // right end
          a = sensor_lines_->guess_at_or_after(line, xl - margin);
          c = sensor_lines_->guess_at_or_after(line, xr);
        }
        __builtin_prefetch(&sensor_lines_->x(a > begin ? a - 1 : begin));
        __builtin_prefetch(&sensor_lines_->x(c < end ? c : end - 1));
        // Field by field into the vector: a temporary copied in whole makes the compiler reload
        // it across two stores, which the CPU cannot forward (a stall per row).
        PendingRow& row = pending_rows_.emplace_back();
        row.line = line;
        row.y = y;
        row.left = xl;
        row.right = xr;
        row.first = a;
        row.last = c;
        row.sure = sure;
      });
  const bool row_wise = def_.sensor_noise_sigma <= 0.0 && uniform_sensor_area_ > 0.0 &&
                        !diffusion_ && dead_sensors_ == 0;
  const std::optional<double> uniform = field_.uniform_value();
  const std::vector<NodeId>& ids = sensor_lines_->ids();
  for (const PendingRow& row : pending_rows_) {
    const double y = row.y, xl = row.left, xr = row.right;
    std::uint32_t first = row.first, last = row.last;
    if (!row.sure) {
      // Candidates: x in [xl − margin, xr + margin] (and a hair more on the right, tested).
      first = sensor_lines_->first_at_or_after(row.line, xl - margin);
      last = sensor_lines_->first_at_or_after(row.line, xr + 2.0 * margin);
      // Every candidate is settled: by the ends' tests or, between them, by convexity.
      decided += last > first ? last - first : 0;
      auto inside_at = [&](std::uint32_t k) {
        return slicer_.contains_on_row(cell.vertices, Vec2{sensor_lines_->x(k), y}, xl, xr);
      };
      // Exact at the ends; everything between is inside (convexity).
      while (first < last && !inside_at(first))
        ++first;
      while (last > first && !inside_at(last - 1))
        --last;
    }
    if (row.sure) decided += last > first ? last - first : 0;  // the row at once: all inside
    if (first >= last) continue;
    // Without noise and with equal areas a reading needs only the position: evaluate the row in
    // one call and stream through its coordinates, never touching per-sensor records.
    if (row_wise && uniform) {
      accumulator.add_row_uniform(y, &sensor_lines_->x(first), last - first, *uniform,
                                  uniform_sensor_area_);
      readings_taken_ += last - first;
      inside += last - first;
      continue;
    }
    if (row_wise) {
      row_buffer_.resize(last - first);
      field_.row_values(y, &sensor_lines_->x(first), last - first,
                        sim::to_seconds(simulator_.now()), row_buffer_.data());
      accumulator.add_row(y, &sensor_lines_->x(first), row_buffer_.data(), last - first,
                          uniform_sensor_area_);
      readings_taken_ += last - first;
      inside += last - first;
      continue;
    }
    for (std::uint32_t k = first; k < last; ++k)
      take(ids[k], Vec2{sensor_lines_->x(k), y});
  }
  if (work) work->point_in_cell_tests += decided;
  return inside;
}

void World::on_frame(NodeId receiver, const net::Frame& frame) {
  const std::size_t i = sim::index(receiver);
  if (i < robots_.size()) {
    robots_[i]->protocol().on_frame(frame);
    return;
  }
  if (i >= robots_.size() + def_.sensors.size())
    return follower_heard(i - robots_.size() - def_.sensors.size(), frame);
  SensorContext context(*this, i - robots_.size());
  sensor_protocol_->on_frame(context, frame);
}

void World::sensor_timer(std::size_t sensor, std::uint32_t kind) {
  SensorContext context(*this, sensor);
  sensor_protocol_->on_timer(context, kind);
}

void World::on_battery_empty(NodeId node) {
  if (observer_) observer_->on_battery_empty(node);
  kill(node, DownCause::battery);
}

Vec2 World::position(NodeId node) const {
  const std::size_t i = sim::index(node);
  if (i < robots_.size()) return robots_[i]->state().position;
  const std::size_t s = i - robots_.size();
  if (s < def_.sensors.size()) return def_.sensors[s].position;
  return follower_state(s - def_.sensors.size()).position;
}

double World::speed_bound() const {
  double bound = 0.0;
  for (const auto& robot : robots_)
    bound = std::max(bound, robot->segment().speed_bound());
  for (const auto& follower : followers_)
    bound = std::max(bound, follower->segment().speed_bound());
  return bound;
}

}  // namespace masnet::agents
