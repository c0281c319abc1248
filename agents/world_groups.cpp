// Robot groups in formation (docs/formations.md): robot g leads group g and broadcasts its
// state and cell; its followers steer by what they hear and broadcast their own state.
#include <memory>

#include "agents/follower_agent.hpp"
#include "agents/robot_agent.hpp"
#include "sim/random.hpp"

namespace masnet::agents {

void World::add_followers() {
  const FormationDef& formation = def_.formation;
  if (!formation.enabled() || robots_.empty()) return;
  // Followers start in their slots, scaled to fit the leaders' first Voronoi cells.
  const std::vector<Vec2> offsets = formation_offsets(formation);
  const std::vector<protocols::Cell> cells = protocols::voronoi_cells(def_.robots, def_.domain);
  const std::uint32_t interest = 1u << static_cast<unsigned>(formation_message_type());
  for (std::size_t g = 0; g < robots_.size(); ++g) {
    const FormationFit fit =
        fit_formation(cells[g].polygon, def_.robots[g], offsets, formation.margin_m);
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      const std::size_t f = followers_.size();
      followers_.push_back(std::make_unique<FollowerAgent>(
          *this, g, k, def_.robots[g] + fit.shift + fit.scale * offsets[k]));
      radio_.add_mobile_node(follower_node(f), follower_key(f));
      radio_.set_interest(follower_node(f), interest);
      if (def_.robot_battery_j > 0) radio_.set_battery(follower_node(f), def_.robot_battery_j);
    }
  }
}

void World::start_groups() {
  const double period_s = def_.formation.state_period_s;
  for (std::size_t g = 0; g < group_count(); ++g) {
    auto phase = sim::RandomStream::keyed(def_.seed, robot_key(g), sim::purpose("formation.phase"));
    // Each one's first tick is its own event (the kernel's origin order).
    simulator_.after_as(sim::origin_of(robot_node(g)), sim::seconds(phase.uniform(0.0, period_s)),
                        [this, g] { leader_tick(g); });
  }
  for (std::size_t f = 0; f < followers_.size(); ++f) {
    auto phase =
        sim::RandomStream::keyed(def_.seed, follower_key(f), sim::purpose("formation.phase"));
    simulator_.after_as(sim::origin_of(follower_node(f)),
                        sim::seconds(phase.uniform(0.0, period_s)),
                        [this, f] { follower_tick(f); });
  }
}

namespace {

net::CustomMessage formation_message(FormationState state, const net::MessageSizes& sizes) {
  const std::uint32_t bytes = formation_body_bytes(state, sizes);
  return net::CustomMessage{formation_message_type(), bytes,
                            std::make_shared<const FormationState>(std::move(state))};
}

}  // namespace

void World::leader_tick(std::size_t group) {
  RobotAgent& leader = *robots_[group];
  if (leader.alive()) {
    const MotionState state = leader.state();
    FormationState message{static_cast<std::uint32_t>(group),
                           -1,
                           state.position,
                           state.velocity,
                           leader.segment().target(),
                           leader.protocol().cell()};
    send(robot_node(group), sim::kNoNode, def_.formation.range_m,
         formation_message(std::move(message), radio_.params().sizes));
  }
  simulator_.after(sim::seconds(def_.formation.state_period_s),
                   [this, group] { leader_tick(group); });
}

void World::follower_tick(std::size_t follower) {
  FollowerAgent& agent = *followers_[follower];
  if (agent.alive()) {
    const double now_s = sim::to_seconds(simulator_.now());
    const MotionState state = agent.state(now_s);
    steer_follower(follower);
    FormationState message{static_cast<std::uint32_t>(agent.group()),
                           static_cast<std::int32_t>(agent.slot()),
                           state.position,
                           state.velocity,
                           state.position,
                           {}};
    send(follower_node(follower), sim::kNoNode, def_.formation.range_m,
         formation_message(std::move(message), radio_.params().sizes));
  }
  simulator_.after(sim::seconds(def_.formation.state_period_s),
                   [this, follower] { follower_tick(follower); });
}

void World::follower_heard(std::size_t follower, const net::Frame& frame) {
  FollowerAgent& agent = *followers_[follower];
  const auto* message = std::get_if<net::CustomMessage>(&frame.payload);
  if (!agent.alive() || message == nullptr || message->type != formation_message_type()) return;
  const auto& state = *static_cast<const FormationState*>(message->body.get());
  if (state.group != agent.group()) return;  // another group's member passing by
  const double now_s = sim::to_seconds(simulator_.now());
  agent.controller().hear(now_s, state);
  if (state.slot >= 0) return;
  // A leader's state may bring a smaller cell: steer at once rather than at the next tick.
  steer_follower(follower);
}

void World::steer_follower(std::size_t follower) {
  FollowerAgent& agent = *followers_[follower];
  const double now_s = sim::to_seconds(simulator_.now());
  const std::optional<Vec2> target = agent.controller().target(now_s, agent.state(now_s));
  if (!target) return;  // the leader not heard yet: stay
  agent.steer(def_.motion, now_s, *target);
  radio_.raise_speed_bound(agent.segment().speed_bound());
  if (def_.motion.jump_to_target) radio_.mobile_node_jumped();
}

MotionState World::follower_state(std::size_t follower) const {
  return followers_[follower]->state(sim::to_seconds(simulator_.now()));
}
std::size_t World::follower_group(std::size_t follower) const {
  return followers_[follower]->group();
}
const FollowerController& World::follower_controller(std::size_t follower) const {
  return followers_[follower]->controller();
}

}  // namespace masnet::agents
