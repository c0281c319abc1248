// Nodes going down and up, scripted faults at their times, and the robots' travel
// (docs/faults-and-lifetime.md).
#include <algorithm>
#include <cmath>
#include <numeric>

#include "agents/follower_agent.hpp"
#include "agents/robot_agent.hpp"
#include "agents/world.hpp"

namespace masnet::agents {

void World::kill(NodeId node, DownCause cause) {
  // A battery has already taken the node off the radio; a fault does it here.
  if (cause == DownCause::fault) {
    if (!radio_.alive(node)) return;
    radio_.take_down(node);
  }
  if (is_robot(node)) {
    robots_[sim::index(node)]->halt();
    ++dead_robots_;
  } else if (is_follower(node)) {
    followers_[sim::index(node) - robots_.size() - def_.sensors.size()]->halt(
        def_.motion, sim::to_seconds(simulator_.now()));
  } else {
    ++dead_sensors_;
  }
  simulator_.fingerprint_stream().mix((std::uint64_t{0xD0} << 56) | sim::index(node));
  if (observer_) observer_->on_node_down(node, cause);
}

void World::restart(NodeId node) {
  if (!radio_.bring_up(node)) return;
  if (is_robot(node)) {
    // The revived protocol's start is the robot's own event (the kernel's origin order).
    simulator_.act_as(sim::origin_of(node));
    robots_[sim::index(node)]->revive();
    simulator_.act_as(sim::kWorldOrigin);
    --dead_robots_;
  } else if (is_follower(node)) {
    followers_[sim::index(node) - robots_.size() - def_.sensors.size()]->revive();
  } else {
    --dead_sensors_;
  }
  simulator_.fingerprint_stream().mix((std::uint64_t{0x0B} << 56) | sim::index(node));
  if (observer_) observer_->on_node_up(node);
}

void World::schedule_faults() {
  fault_victims_.assign(def_.faults.size(), {});
  for (std::size_t f = 0; f < def_.faults.size(); ++f) {
    const FaultDef& fault = def_.faults[f];
    simulator_.at(sim::time_at(fault.at_s), [this, f] { strike(f); });
    if (fault.restarts()) simulator_.at(sim::time_at(fault.until_s), [this, f] { lift(f); });
  }
}

std::vector<NodeId> World::fault_victims(std::size_t f) {
  const FaultDef& fault = def_.faults[f];
  const bool robots = fault.nodes == FaultNodes::robots;
  const std::size_t count = robots ? robots_.size() : def_.sensors.size();
  auto node_of = [&](std::size_t i) { return robots ? robot_node(i) : sensor_node(i); };
  std::vector<NodeId> victims;
  if (!fault.ids.empty()) {
    for (std::uint32_t i : fault.ids)
      victims.push_back(node_of(i));
  } else if (fault.fraction) {
    // round(fraction · count) of the class, by a partial shuffle keyed by the seed and the
    // fault's place in the list: the same nodes whatever happened before it.
    const auto take =
        static_cast<std::size_t>(std::llround(*fault.fraction * static_cast<double>(count)));
    std::vector<std::size_t> order(count);
    std::iota(order.begin(), order.end(), std::size_t{0});
    auto random = sim::RandomStream::keyed(def_.seed, std::uint64_t{f}, sim::purpose("fault.pick"));
    for (std::size_t k = 0; k < take; ++k)
      std::swap(order[k], order[k + random.below(count - k)]);
    std::sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(take));
    for (std::size_t k = 0; k < take; ++k)
      victims.push_back(node_of(order[k]));
  } else if (fault.region) {
    for (std::size_t i = 0; i < count; ++i)
      if (fault.region->contains(position(node_of(i)))) victims.push_back(node_of(i));
  }
  return victims;
}

void World::strike(std::size_t f) {
  const FaultDef& fault = def_.faults[f];
  simulator_.fingerprint_stream().mix((std::uint64_t{0xFA} << 56) | (f << 1) | 1);
  const auto id = static_cast<std::uint32_t>(f);
  switch (fault.kind) {
    case FaultKind::kill:
      for (NodeId node : fault_victims(f)) {
        if (!radio_.alive(node)) continue;  // down already: not this fault's to restart
        kill(node, DownCause::fault);
        fault_victims_[f].push_back(node);
      }
      break;
    case FaultKind::partition:
      radio_.link_faults().add_cut(id, fault.line);
      radio_.link_faults_changed();
      break;
    case FaultKind::degrade:
      radio_.link_faults().add_degraded(id, net::DegradedArea{*fault.region, fault.loss});
      radio_.link_faults_changed();
      break;
  }
  if (observer_) observer_->on_fault(f, true);
}

void World::lift(std::size_t f) {
  simulator_.fingerprint_stream().mix((std::uint64_t{0xFA} << 56) | (f << 1));
  if (def_.faults[f].kind == FaultKind::kill)
    for (NodeId node : fault_victims_[f])
      restart(node);
  else {
    radio_.link_faults().remove(static_cast<std::uint32_t>(f));
    radio_.link_faults_changed();
  }
  if (observer_) observer_->on_fault(f, false);
}

double World::distance_travelled_m(std::size_t robot) const {
  return robots_[robot]->travel().distance * def_.radio.meters_per_unit;
}

double World::locomotion_energy_j(std::size_t robot) const {
  const TravelIntegrals travel = robots_[robot]->travel();
  const double metres = def_.radio.meters_per_unit;
  return def_.locomotion.per_metre_j * travel.distance * metres +
         def_.locomotion.per_accel_j * travel.accel * metres;
}

}  // namespace masnet::agents
