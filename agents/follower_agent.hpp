#pragma once
// A follower of a robot group: a body with the robots' dynamics and a formation controller fed
// by the FORMATION messages it hears (docs/formations.md). Internal to agents/.
#include "agents/formation.hpp"
#include "agents/world.hpp"

namespace masnet::agents {

inline std::uint64_t follower_key(std::size_t i) {
  return (std::uint64_t{3} << 32) | i;
}

class World::FollowerAgent {
 public:
  FollowerAgent(const World& world, std::size_t group, std::size_t slot, const Vec2& start)
      : group_(group),
        slot_(slot),
        controller_(world.def_.formation, world.def_.motion, slot),
        segment_(world.def_.motion, 0.0, MotionState{start, Vec2{0, 0}}, start) {}

  std::size_t group() const { return group_; }
  std::size_t slot() const { return slot_; }
  bool alive() const { return alive_; }
  const FollowerController& controller() const { return controller_; }
  FollowerController& controller() { return controller_; }
  const MotionSegment& segment() const { return segment_; }
  MotionState state(double now_s) const { return segment_.state_at(now_s); }

  /// A new target from now: a new closed-form segment from the current state.
  void steer(const MotionParams& motion, double now_s, const Vec2& target) {
    if (!alive_) return;
    const MotionState from = motion.jump_to_target ? MotionState{target, Vec2{0, 0}} : state(now_s);
    segment_ = MotionSegment(motion, now_s, from, target);
  }
  /// Down: stands where it is.
  void halt(const MotionParams& motion, double now_s) {
    const MotionState here{state(now_s).position, Vec2{0, 0}};
    segment_ = MotionSegment(motion, now_s, here, here.position);
    alive_ = false;
  }
  void revive() { alive_ = true; }

 private:
  std::size_t group_, slot_;
  FollowerController controller_;
  MotionSegment segment_;
  bool alive_ = true;
};

}  // namespace masnet::agents
