#include "scenarios/run/formation_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scenarios/output/output_file.hpp"

namespace masnet::scenarios {

using agents::MotionState;
using net::Vec2;

FormationRecorder::FormationRecorder(agents::World& world)
    : world_(world), offsets_(agents::formation_offsets(world.def().formation)) {}

Vec2 FormationRecorder::slot_now(std::size_t follower) const {
  const std::size_t group = world_.follower_group(follower);
  const std::size_t slot = follower % offsets_.size();
  const Vec2 leader = world_.robot_state(group).position;
  const protocols::ConvexPolygon& cell = world_.robot_protocol(group).cell();
  const agents::FormationFit fit =
      agents::fit_formation(cell, leader, offsets_, world_.def().formation.margin_m);
  return leader + fit.shift + fit.scale * offsets_[slot];
}

void FormationRecorder::sample() {
  FormationSample row;
  row.t_s = sim::to_seconds(world_.simulator().now());
  const std::size_t leaders = world_.group_count(), followers = world_.follower_count();
  // Every group member with its group: leaders first, then followers.
  std::vector<Vec2> at;
  std::vector<std::size_t> group;
  for (std::size_t g = 0; g < leaders; ++g) {
    at.push_back(world_.robot_state(g).position);
    group.push_back(g);
    const protocols::ConvexPolygon& cell = world_.robot_protocol(g).cell();
    row.outside_leader_max =
        std::max(row.outside_leader_max, agents::distance_outside(cell, at.back()));
    row.scale_mean +=
        agents::fit_formation(cell, at.back(), offsets_, world_.def().formation.margin_m).scale;
  }
  if (leaders > 0) row.scale_mean /= static_cast<double>(leaders);
  for (std::size_t f = 0; f < followers; ++f) {
    const Vec2 p = world_.follower_state(f).position;
    const std::size_t g = world_.follower_group(f);
    at.push_back(p);
    group.push_back(g);
    const double error = (p - slot_now(f)).norm();
    row.error_mean += error;
    row.error_max = std::max(row.error_max, error);
    const double outside = agents::distance_outside(world_.robot_protocol(g).cell(), p);
    row.outside_follower_max = std::max(row.outside_follower_max, outside);
    if (outside > 0.0) ++row.followers_outside;
    row.outside_known_max = std::max(
        row.outside_known_max, agents::distance_outside(world_.follower_controller(f).cell(), p));
  }
  if (followers > 0) row.error_mean /= static_cast<double>(followers);
  follower_samples_ += followers;
  outside_samples_ += row.followers_outside;
  // All pairs: groups are few (a scenario with groups has at most a few thousand robots).
  double between = std::numeric_limits<double>::infinity(), within = between;
  for (std::size_t a = 0; a < at.size(); ++a)
    for (std::size_t b = a + 1; b < at.size(); ++b) {
      double& nearest = group[a] == group[b] ? within : between;
      nearest = std::min(nearest, (at[a] - at[b]).norm());
    }
  row.min_between_groups = std::isfinite(between) ? between : 0.0;
  row.min_within_group = std::isfinite(within) ? within : 0.0;
  samples_.push_back(row);
}

void FormationRecorder::sample_positions() {
  const double t_s = sim::to_seconds(world_.simulator().now());
  for (std::size_t f = 0; f < world_.follower_count(); ++f)
    rows_.push_back({t_s, static_cast<std::uint32_t>(f),
                     static_cast<std::uint32_t>(world_.follower_group(f)),
                     world_.follower_state(f).position, slot_now(f)});
}

void FormationRecorder::write_formation(const std::string& path) const {
  OutputFile out(path);
  out.print(
      "t_s,error_mean,error_max,scale_mean,min_between_groups,min_within_group,"
      "outside_follower_max,outside_leader_max,followers_outside,outside_known_max\n");
  for (const FormationSample& s : samples_)
    out.print("{},{},{},{},{},{},{},{},{},{}\n", s.t_s, s.error_mean, s.error_max, s.scale_mean,
              s.min_between_groups, s.min_within_group, s.outside_follower_max,
              s.outside_leader_max, s.followers_outside, s.outside_known_max);
  out.close();
}

void FormationRecorder::write_followers(const std::string& path) const {
  OutputFile out(path);
  out.print("t_s,follower,group,x,y,slot_x,slot_y\n");
  for (const FollowerRow& r : rows_)
    out.print("{},{},{},{},{},{},{}\n", r.t_s, r.follower, r.group, r.position.x(), r.position.y(),
              r.slot.x(), r.slot.y());
  out.close();
}

nlohmann::json FormationRecorder::summary() const {
  const agents::FormationDef& def = world_.def().formation;
  static constexpr const char* kShapes[] = {"line", "wedge", "circle", "offsets"};
  nlohmann::json j = {{"groups", world_.group_count()},
                      {"group_size", def.group_size},
                      {"shape", kShapes[static_cast<int>(def.shape)]},
                      {"followers", world_.follower_count()}};
  double error_mean = 0, error_max = 0, between = std::numeric_limits<double>::infinity(),
         within = between, outside_follower = 0, outside_leader = 0, outside_known = 0, scale = 0;
  for (const FormationSample& s : samples_) {
    error_mean += s.error_mean;
    error_max = std::max(error_max, s.error_max);
    between = std::min(between, s.min_between_groups);
    within = std::min(within, s.min_within_group);
    outside_follower = std::max(outside_follower, s.outside_follower_max);
    outside_leader = std::max(outside_leader, s.outside_leader_max);
    outside_known = std::max(outside_known, s.outside_known_max);
    scale += s.scale_mean;
  }
  const double n = std::max<double>(1.0, static_cast<double>(samples_.size()));
  j["error_mean"] = error_mean / n;
  j["error_max"] = error_max;
  j["error_final_mean"] = samples_.empty() ? 0.0 : samples_.back().error_mean;
  j["scale_mean"] = scale / n;
  j["min_distance_between_groups"] = std::isfinite(between) ? between : 0.0;
  j["min_distance_within_group"] = std::isfinite(within) ? within : 0.0;
  j["outside_cell_follower_max"] = outside_follower;
  j["outside_cell_leader_max"] = outside_leader;
  j["outside_known_cell_max"] = outside_known;
  j["outside_cell_share"] = follower_samples_ > 0 ? static_cast<double>(outside_samples_) /
                                                        static_cast<double>(follower_samples_)
                                                  : 0.0;
  // What keeping formation cost: the FORMATION messages and the energy they took.
  const net::Radio& radio = world_.radio();
  const net::MessageType type = agents::formation_message_type();
  const auto& totals = radio.totals(type);
  j["messages"] = {{"count", totals.tx_count}, {"bytes", totals.tx_bytes}};
  j["energy_j"] = radio.type_tx_energy_j(type) + radio.type_rx_energy_j(type);
  return j;
}

}  // namespace masnet::scenarios
