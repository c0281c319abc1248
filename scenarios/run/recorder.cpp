#include "scenarios/run/recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "protocols/heard_cell.hpp"
#include "scenarios/output/output_file.hpp"
#include "scenarios/run/contention_outputs.hpp"
#include "scenarios/run/curve_summary.hpp"
#include "scenarios/run/energy_outputs.hpp"

namespace masnet::scenarios {
namespace {

constexpr std::size_t kWriteChunkBytes = std::size_t{1} << 16;  // buffered rows per write

nlohmann::json point(const Vec2& p) {
  return nlohmann::json::array({p.x(), p.y()});
}

}  // namespace

Recorder::Recorder(agents::World& world, const ScenarioDef& def)
    : world_(world), def_(def), lifetime_(world.robot_count(), world.sensor_count()) {}

void Recorder::assign_sensors(const std::vector<Vec2>& robots,
                              std::vector<std::uint32_t>& nearest) const {
  const std::size_t n_sensors = world_.sensor_count();
  nearest.assign(n_sensors, 0);
  if (robots.empty()) return;
  if (robots.size() <= kScanRobots) {
    // A few robots: test them all (the grid's arithmetic, ties to the lower index).
    for (std::size_t s = 0; s < n_sensors; ++s) {
      const Vec2 p = world_.def().sensors[s].position;
      double best_d2 = std::numeric_limits<double>::infinity();
      std::uint32_t best = 0;
      for (std::uint32_t i = 0; i < robots.size(); ++i) {
        const double ddx = robots[i].x() - p.x(), ddy = robots[i].y() - p.y();
        const double d2 = ddx * ddx + ddy * ddy;
        if (d2 < best_d2) {
          best_d2 = d2;
          best = i;
        }
      }
      nearest[s] = best;
    }
    return;
  }
  std::vector<sim::NodeId> ids;
  for (std::uint32_t i = 0; i < robots.size(); ++i)
    ids.push_back(sim::node_id(i));
  net::SpatialGrid grid;
  grid.build(robots, ids);
  const double start_radius = std::max(grid.cell_size(), 1e-9);
  for (std::size_t s = 0; s < n_sensors; ++s) {
    const Vec2 p = world_.def().sensors[s].position;
    for (double r = start_radius;; r *= 2.0) {
      double best_d2 = std::numeric_limits<double>::infinity();
      std::uint32_t best = 0;
      bool found = false;
      grid.for_each_within(p, r, [&](sim::NodeId id, const Vec2&, double d2) {
        const std::uint32_t i = sim::index(id);
        if (d2 < best_d2 || (d2 == best_d2 && i < best)) {
          best_d2 = d2;
          best = i;
          found = true;
        }
      });
      if (found) {
        nearest[s] = best;
        break;
      }
    }
  }
}

void Recorder::sample() {
  Sample row;
  row.t_s = sim::to_seconds(world_.simulator().now());
  const std::size_t n_robots = world_.robot_count(), n_sensors = world_.sensor_count();
  std::vector<Vec2> robots(n_robots);
  for (std::size_t i = 0; i < n_robots; ++i)
    robots[i] = world_.robot_state(i).position;

  // Coverage cost and true centroids over the sensor-sampled density SK(ρ)·A, among the robots
  // that are up: a dead robot covers nothing.
  std::vector<Vec2> up;
  std::vector<std::size_t> up_index;
  for (std::size_t i = 0; i < n_robots; ++i)
    if (world_.node_alive(world_.robot_node(i))) {
      up.push_back(robots[i]);
      up_index.push_back(i);
    }
  const std::size_t n_up = up.size();
  if (n_up == 0 && n_robots > 0) row.coverage_cost = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::uint32_t> nearest;
  assign_sensors(up, nearest);
  std::vector<double> mass(n_up, 0.0), mx(n_up, 0.0), my(n_up, 0.0);
  for (std::size_t s = 0; s < n_sensors && n_up > 0; ++s) {
    const auto& sensor = world_.def().sensors[s];
    const double w = world_.def().scaling(world_.true_density(s)) * sensor.area;
    const std::uint32_t i = nearest[s];
    row.coverage_cost += w * (sensor.position - up[i]).squaredNorm();
    mass[i] += w;
    mx[i] += w * sensor.position.x();
    my[i] += w * sensor.position.y();
  }
  std::size_t with_mass = 0;
  for (std::size_t i = 0; i < n_up; ++i) {
    row.mean_radius += world_.robot_protocol(up_index[i]).radius();
    if (mass[i] <= 0.0) continue;
    const double d = (Vec2{mx[i] / mass[i], my[i] / mass[i]} - up[i]).norm();
    row.mean_dist_to_centroid += d;
    row.max_dist_to_centroid = std::max(row.max_dist_to_centroid, d);
    ++with_mass;
  }
  if (with_mass) row.mean_dist_to_centroid /= static_cast<double>(with_mass);
  if (n_up) row.mean_radius /= static_cast<double>(n_up);

  net::Radio& radio = world_.radio();
  for (std::size_t t = 0; t < net::message_type_count(); ++t) {
    row.messages += radio.totals(static_cast<net::MessageType>(t)).tx_count;
    row.bytes += radio.totals(static_cast<net::MessageType>(t)).tx_bytes;
  }
  row.energy_j = radio.total_tx_energy_j() + radio.total_rx_energy_j();
  if (const net::ContendedMedium* medium = radio.contention())
    row.collisions = medium->total_collided();
  if (radio.params().energy.idle_power_w > 0)
    for (std::size_t n = 0; n < radio.node_count(); ++n)
      row.energy_j += radio.stats(sim::node_id(static_cast<std::uint32_t>(n))).energy_idle_j;

  // Tracking: each target's nearest robot, and the robots in each target's group.
  if (world_.def().field.kind == agents::FieldKind::acoustic) {
    if (!tracking_) {
      const double area = protocols::area(world_.def().domain);
      tracking_.emplace(def_.output.tracking_radius > 0 ? def_.output.tracking_radius
                                                        : default_tracking_radius(area, n_robots));
    }
    // A robot that is down tracks nothing: infinitely far, it is nobody's nearest robot.
    std::vector<Vec2> tracking_robots = robots;
    if (n_up < n_robots)
      for (std::size_t i = 0; i < n_robots; ++i)
        if (!world_.node_alive(world_.robot_node(i)))
          tracking_robots[i] = Vec2::Constant(std::numeric_limits<double>::infinity());
    TrackingSample t = tracking_->sample(row.t_s, tracking_robots, world_.source_positions());
    row.tracking_mean = t.error_mean;
    row.tracking_max = t.error_max;
    row.robots_per_target = std::move(t.group_sizes);
  }
  if (const agents::DiffusionField* field = world_.diffusion()) {
    row.pollution_total = world_.pollution_total();
    row.pollution_integral = field->mass();
    row.pollution_max = field->peak();
    for (std::size_t i = 0; i < n_robots; ++i)
      row.neutraliser_used += world_.neutraliser_used(i);
  }
  row.updates = update_stats_.count();
  row.cell_correctness = update_stats_.cell_correctness();
  row.cell_correctness_heard = update_stats_.cell_correctness_heard();
  lifetime_.fill(row, world_, update_stats_.count(), update_stats_.correct());
  samples_.push_back(std::move(row));
}

void Recorder::attach_baseline(const std::vector<Sample>& baseline) {
  for (std::size_t k = 0; k < samples_.size() && k < baseline.size(); ++k) {
    samples_[k].pollution_total_baseline = baseline[k].pollution_total;
    samples_[k].pollution_integral_baseline = baseline[k].pollution_integral;
  }
  has_baseline_ = true;
}

void Recorder::attach_twin(const std::vector<Sample>& twin) {
  attach_twin_samples(samples_, twin);
  has_twin_ = true;
}

void Recorder::sample_trajectories() {
  const double t = sim::to_seconds(world_.simulator().now());
  for (std::size_t i = 0; i < world_.robot_count(); ++i) {
    const agents::MotionState s = world_.robot_state(i);
    trajectories_.push_back({t, static_cast<std::uint32_t>(i), s.position, s.velocity,
                             world_.robot_protocol(i).radius(), world_.robot_target(i)});
  }
}

void Recorder::snapshot() {
  nlohmann::json snap;
  snap["t"] = sim::to_seconds(world_.simulator().now());
  nlohmann::json robots = nlohmann::json::array();
  for (std::size_t i = 0; i < world_.robot_count(); ++i) {
    nlohmann::json r;
    r["position"] = point(world_.robot_state(i).position);
    r["target"] = point(world_.robot_target(i));
    r["radius"] = world_.robot_protocol(i).radius();
    nlohmann::json cell = nlohmann::json::array();
    for (const Vec2& v : world_.robot_protocol(i).cell().vertices)
      cell.push_back(point(v));
    r["cell"] = cell;
    nlohmann::json oracle = nlohmann::json::array();
    for (const Vec2& v : world_.oracle_cell(i).polygon.vertices)
      oracle.push_back(point(v));
    r["oracle_cell"] = oracle;
    robots.push_back(r);
  }
  snap["robots"] = robots;
  nlohmann::json readings = nlohmann::json::array();
  for (std::size_t s = 0; s < world_.sensor_count(); ++s)
    readings.push_back(world_.true_density(s));
  snap["readings"] = readings;
  nlohmann::json sources = nlohmann::json::array();
  const double t = snap["t"];
  for (const agents::PathDef& p : world_.def().field.targets)
    sources.push_back({{"position", point(agents::position_on(p, t))},
                       {"heading", point(agents::heading_on(p, t))}});
  for (const agents::GaussianBump& b : world_.def().field.bumps)
    sources.push_back({{"position", point(agents::position_on(b.path, t))},
                       {"heading", point(agents::heading_on(b.path, t))}});
  for (const agents::SourceDef& src : world_.def().field.sources)
    sources.push_back({{"position", point(agents::position_on(src.path, t))},
                       {"heading", point(agents::heading_on(src.path, t))}});
  snap["sources"] = sources;
  if (const agents::DiffusionField* field = world_.diffusion()) {
    const auto& p = field->params();
    const auto values = field->values();
    snap["field"] = {{"nx", field->nx()},
                     {"ny", field->ny()},
                     {"x0", p.x0},
                     {"y0", p.y0},
                     {"x1", p.x1},
                     {"y1", p.y1},
                     {"values", std::vector<double>(values.begin(), values.end())}};
  }
  snapshots_.push_back(std::move(snap));
}

void Recorder::on_update(std::size_t robot, const protocols::UpdateRecord& record) {
  UpdateRow row{record, true, true};
  // Cell correctness: the neighbour set the robot computed against the true one now, and
  // against the one of the positions it heard (docs/decisions/0010-cell-correctness.md).
  if (!world_.protocol_uses_ground_truth()) {  // the oracle's cells are true by definition
    // The robot's own cell is a good guess of the true one's reach (Cortés' rule needs twice the
    // farthest vertex; a quarter more spares most doublings).
    const double guess =
        2.5 * protocols::max_vertex_distance(record.cell, world_.robot_state(robot).position);
    row.correct = world_.oracle_cell(robot, guess).neighbours == record.neighbours;
    row.correct_heard = protocols::heard_neighbours(record.position, record.heard,
                                                    world_.def().domain) == record.neighbours;
  }
  update_stats_.add(row.record, row.correct, row.correct_heard);
  // Only updates.csv needs every update: a run without it keeps the statistics alone.
  if (def_.output.updates) updates_.push_back(std::move(row));
  if (update_listener_) update_listener_();
}

void Recorder::on_battery_empty(sim::NodeId node) {
  on_node_down(node, agents::DownCause::battery);
}
void Recorder::on_node_down(sim::NodeId node, agents::DownCause cause) {
  lifetime_.down(node, world_.is_robot(node), cause, sim::to_seconds(world_.simulator().now()));
}
void Recorder::on_node_up(sim::NodeId node) {
  lifetime_.up(node, world_.is_robot(node), sim::to_seconds(world_.simulator().now()));
}

void Recorder::write_timeseries(const std::string& path) const {
  OutputFile out(path);
  const std::size_t targets =
      def_.world.field.kind == agents::FieldKind::acoustic ? def_.world.field.targets.size() : 0;
  out.print(
      "t_s,coverage_cost,mean_dist_to_centroid,max_dist_to_centroid,mean_radius,messages,bytes,"
      "energy_j,"
      "updates,cell_correctness,cell_correctness_heard");
  if (targets) out.print(",tracking_error_mean,tracking_error_max");
  for (std::size_t k = 0; k < targets; ++k)
    out.print(",robots_target_{}", k);
  const bool pollution = world_.diffusion() != nullptr;
  if (pollution) out.print(",pollution_total,pollution_integral,pollution_max,neutraliser_used");
  if (pollution && has_baseline_)
    out.print(",pollution_total_baseline,pollution_integral_baseline");
  const bool contended = world_.radio().contention() != nullptr;
  if (contended) out.print(",collisions");
  const bool lifetime = has_lifetime_outputs(def_.world);
  if (lifetime) out.print("{}", lifetime_columns(has_twin_, targets > 0));
  out.print("\n");
  for (const Sample& s : samples_) {
    out.print("{},{},{},{},{},{},{},{},{},{},{}", s.t_s, s.coverage_cost, s.mean_dist_to_centroid,
              s.max_dist_to_centroid, s.mean_radius, s.messages, s.bytes, s.energy_j, s.updates,
              s.cell_correctness, s.cell_correctness_heard);
    if (targets) out.print(",{},{}", s.tracking_mean, s.tracking_max);
    for (std::size_t k = 0; k < targets; ++k)
      out.print(",{}", k < s.robots_per_target.size() ? s.robots_per_target[k] : 0);
    if (pollution)
      out.print(",{},{},{},{}", s.pollution_total, s.pollution_integral, s.pollution_max,
                s.neutraliser_used);
    if (pollution && has_baseline_)
      out.print(",{},{}", s.pollution_total_baseline, s.pollution_integral_baseline);
    if (contended) out.print(",{}", s.collisions);
    if (lifetime) out.print("{}", lifetime_values(s, has_twin_, targets > 0));
    out.print("\n");
  }
  out.close();
}

void Recorder::write_trajectories(const std::string& path) const {
  OutputFile out(path);
  out.print("t_s,robot,x,y,vx,vy,radius,cx,cy\n");
  for (const TrajectoryRow& r : trajectories_)
    out.print("{},{},{},{},{},{},{},{},{}\n", r.t_s, r.robot, r.position.x(), r.position.y(),
              r.velocity.x(), r.velocity.y(), r.radius, r.target.x(), r.target.y());
  out.close();
}

void Recorder::write_updates(const std::string& path) const {
  OutputFile out(path);
  out.print(
      "robot,update,t_start_s,t_end_s,latency_s,rounds,radius,truncated,delayed,no_mass,readings,"
      "neighbours,correct,correct_heard,cx,cy,half_plane_clips,point_in_cell_tests");
  const std::size_t types = net::message_type_count();
  for (std::size_t t = 0; t < types; ++t)
    out.print(",{0}_count,{0}_bytes", net::name_of(t));
  // The protocol's own per-update fields (docs/protocol-api.md).
  const std::vector<std::string>& extra = world_.protocol_definition().update_columns;
  for (const std::string& column : extra)
    out.print(",{}", column);
  out.print("\n");
  for (const UpdateRow& u : updates_) {
    const auto& r = u.record;
    out.print("{},{},{},{},{},{},{},{:d},{:d},{:d},{},{},{:d},{:d},{},{},{},{}",
              sim::index(r.robot), r.update, sim::to_seconds(r.started),
              sim::to_seconds(r.finished), sim::to_seconds(r.finished - r.started), r.rounds,
              r.radius, r.truncated, r.delayed, r.no_mass, r.readings, r.neighbours.size(),
              u.correct, u.correct_heard, r.centroid.x(), r.centroid.y(),
              r.geometry.half_plane_clips, r.geometry.point_in_cell_tests);
    for (std::size_t t = 0; t < types; ++t)
      out.print(",{},{}", r.messages[t].count, r.messages[t].bytes);
    for (std::size_t k = 0; k < extra.size(); ++k) {
      if (k < r.extra.size())
        out.print(",{}", r.extra[k]);
      else
        out.print(",");
    }
    out.print("\n");
  }
  out.close();
}

void Recorder::write_nodes(const std::string& path) const {
  OutputFile out(path);
  out.print(
      "node,role,index,x,y,alive,died_at_s,energy_j,energy_tx_j,energy_rx_j,energy_idle_j,tx_count,"
      "tx_bytes,"
      "rx_count,rx_bytes,overheard_count,heard_bytes,lost_count,unreachable_count,refused_count");
  const std::size_t types = net::message_type_count();
  for (std::size_t t = 0; t < types; ++t)
    out.print(",tx_{0},rx_{0}", net::name_of(t));
  net::Radio& radio = world_.radio();
  const net::ContendedMedium* medium = radio.contention();
  if (medium) out.print("{}", kContentionNodeColumns);
  const bool lifetime = has_lifetime_outputs(def_.world);
  if (lifetime) out.print(",locomotion_j,distance_m");
  out.print("\n");
  // Rows are formatted with compiled formats into a buffer written in large pieces: a million
  // sensors make a 160 MB file, and a runtime format string parsed 20 times a row was most of
  // the time of writing it.
  fmt::memory_buffer rows;
  auto it = std::back_inserter(rows);
  for (std::uint32_t n = 0; n < radio.node_count(); ++n) {
    const sim::NodeId id = sim::node_id(n);
    const bool robot = world_.is_robot(id), follower = world_.is_follower(id);
    const std::size_t index = robot      ? n
                              : follower ? n - world_.robot_count() - world_.sensor_count()
                                         : n - world_.robot_count();
    const Vec2 p = world_.position(id);
    const net::NodeRadioStats& s = radio.stats(id);
    std::uint64_t tx = 0, txb = 0, rx = 0, rxb = 0;
    for (std::size_t t = 0; t < types; ++t) {
      const auto& c = radio.counters(id, static_cast<net::MessageType>(t));
      tx += c.tx_count;
      txb += c.tx_bytes;
      rx += c.rx_count;
      rxb += c.rx_bytes;
    }
    fmt::format_to(it, FMT_COMPILE("{},{},{},{},{},{},"), n,
                   robot      ? "robot"
                   : follower ? "follower"
                              : "sensor",
                   index, p.x(), p.y(), s.alive ? 1 : 0);
    if (!s.alive) fmt::format_to(it, FMT_COMPILE("{}"), sim::to_seconds(s.died_at));
    fmt::format_to(it, FMT_COMPILE(",{},{},{},{},{},{},{},{},{},{},{},{},{}"),
                   s.energy_tx_j + s.energy_rx_j + s.energy_idle_j, s.energy_tx_j, s.energy_rx_j,
                   s.energy_idle_j, tx, txb, rx, rxb, s.overheard_count, s.heard_bytes,
                   s.lost_count, s.unreachable_count, s.refused_count);
    for (std::size_t t = 0; t < types; ++t) {
      const auto& c = radio.counters(id, static_cast<net::MessageType>(t));
      fmt::format_to(it, FMT_COMPILE(",{},{}"), c.tx_count, c.rx_count);
    }
    if (medium) append_contention_node(*medium, id, rows);
    if (lifetime && robot)
      fmt::format_to(it, FMT_COMPILE(",{},{}"), world_.locomotion_energy_j(index),
                     world_.distance_travelled_m(index));
    else if (lifetime)
      rows.append(std::string_view(",,"));
    rows.push_back('\n');
    if (rows.size() >= kWriteChunkBytes) {
      out.write(std::string_view(rows.data(), rows.size()));
      rows.clear();
    }
  }
  out.write(std::string_view(rows.data(), rows.size()));
  out.close();
}

void Recorder::write_snapshots(const std::string& path) const {
  write_file(path, snapshots_.dump() + "\n");
}

nlohmann::json Recorder::pollution_summary() const {
  nlohmann::json p = curve_summary(samples_, &Sample::pollution_total, def_.clean_threshold);
  const auto& d = def_.world.field.diffusion;
  p["mode"] = d.mode == agents::DiffusionMode::fidelity ? "fidelity" : "physical";
  p["boundary"] = d.boundary == agents::Boundary::dirichlet ? "dirichlet" : "no_flux";
  p["control"] = def_.world.dispenser.enabled;
  p["integral_final"] = samples_.back().pollution_integral;
  p["neutraliser_used"] = samples_.back().neutraliser_used;
  std::vector<double> per_robot;
  for (std::size_t i = 0; i < world_.robot_count(); ++i)
    per_robot.push_back(world_.neutraliser_used(i));
  p["neutraliser_per_robot"] = per_robot;
  if (has_baseline_) {
    nlohmann::json b =
        curve_summary(samples_, &Sample::pollution_total_baseline, def_.clean_threshold);
    b["integral_final"] = samples_.back().pollution_integral_baseline;
    p["baseline"] = b;
    const double base_final = samples_.back().pollution_total_baseline;
    p["final_over_baseline_final"] =
        base_final != 0 ? samples_.back().pollution_total / base_final : 0.0;
  }
  return p;
}

nlohmann::json Recorder::summary_metrics() const {
  nlohmann::json j;
  net::Radio& radio = world_.radio();
  // Messages: transmissions, by type.
  std::uint64_t count = 0, bytes = 0;
  nlohmann::json by_type = nlohmann::json::object();
  for (std::size_t t = 0; t < net::message_type_count(); ++t) {
    const auto& c = radio.totals(static_cast<net::MessageType>(t));
    count += c.tx_count;
    bytes += c.tx_bytes;
    by_type[std::string(net::name_of(t))] = {{"count", c.tx_count},
                                             {"bytes", c.tx_bytes},
                                             {"rx_count", c.rx_count},
                                             {"rx_bytes", c.rx_bytes}};
  }
  j["messages"] = {{"total", {{"count", count}, {"bytes", bytes}}}, {"by_type", by_type}};
  if (const net::ContendedMedium* medium = radio.contention())
    add_contention_summary(*medium, j["messages"]);

  // Energy: per node, then totals.
  double tx = 0, rx = 0, idle = 0, max_node = 0, robots_total = 0, sensors_total = 0,
         max_sensor = 0;
  std::uint64_t dead = 0;
  for (std::uint32_t n = 0; n < radio.node_count(); ++n) {
    const sim::NodeId id = sim::node_id(n);
    const net::NodeRadioStats& s = radio.stats(id);
    const double e = s.energy_tx_j + s.energy_rx_j + s.energy_idle_j;
    tx += s.energy_tx_j;
    rx += s.energy_rx_j;
    idle += s.energy_idle_j;
    max_node = std::max(max_node, e);
    dead += s.alive ? 0 : 1;
    if (world_.is_robot(id) || world_.is_follower(id)) {
      robots_total += e;
    } else {
      sensors_total += e;
      max_sensor = std::max(max_sensor, e);
    }
  }
  const double nodes = std::max<double>(1.0, static_cast<double>(radio.node_count()));
  j["energy_j"] = {{"total", tx + rx + idle},
                   {"radio_tx", tx},
                   {"radio_rx", rx},
                   {"idle", idle},
                   {"per_node_max", max_node},
                   {"per_node_mean", (tx + rx + idle) / nodes},
                   {"robots_total", robots_total},
                   {"sensors_total", sensors_total},
                   {"per_sensor_max", max_sensor},
                   {"nodes_dead", dead},
                   {"by_type", energy_by_type(radio)}};
  add_energy_details(j["energy_j"], world_, update_stats_.count());
  if (has_lifetime_outputs(def_.world)) j["lifetime"] = lifetime_.summary(world_);
  if (has_twin_) j["recovery"] = recovery_summary(def_.world.faults, samples_);

  // Protocol statistics over all updates.
  nlohmann::json p;
  p["name"] = def_.world.protocol.kind;
  update_stats_.fill_summary(p, world_.sensor_point_in_cell_tests());
  j["protocol"] = p;

  if (world_.diffusion() && !samples_.empty()) j["pollution"] = pollution_summary();
  if (!samples_.empty()) {
    const Sample& last = samples_.back();
    j["coverage"] = {{"final_cost", last.coverage_cost},
                     {"max_dist_to_centroid", last.max_dist_to_centroid},
                     {"mean_dist_to_centroid", last.mean_dist_to_centroid}};
    if (tracking_) {
      nlohmann::json tracking = tracking_->summary();
      tracking["clamped_readings"] = world_.clamped_readings();
      tracking["sensor_readings"] = world_.sensor_readings();
      j["tracking"] = std::move(tracking);
    }
  }
  return j;
}

}  // namespace masnet::scenarios
