#pragma once
// A robot of the world: its body (closed-form motion, booked travel), its protocol and the
// host interface the protocol sees. Internal to agents/ (world.cpp and the fault code).
#include "agents/locomotion.hpp"
#include "agents/world.hpp"
#include "sim/random.hpp"

namespace masnet::agents {

// Random keys by role and index: stable when nodes of another role (or later ones) are added.
inline std::uint64_t robot_key(std::size_t i) {
  return (std::uint64_t{1} << 32) | i;
}
inline std::uint64_t sensor_key(std::size_t i) {
  return (std::uint64_t{2} << 32) | i;
}

// ---- A robot: body (closed-form motion) + protocol + its host interface ---------------------

class World::RobotAgent final : public protocols::RobotHost {
 public:
  RobotAgent(World& world, std::size_t index, const Vec2& start)
      : world_(world),
        index_(index),
        segment_(world.def_.motion, 0.0, MotionState{start, Vec2{0, 0}}, start) {
    make_protocol();
  }

  bool alive() const { return alive_; }
  /// Down: the motion so far is booked and the robot stands where it is; the protocol's
  /// pending timers will find it gone.
  void halt() {
    if (!alive_) return;
    book_motion();
    const MotionState here{state().position, Vec2{0, 0}};
    segment_ = MotionSegment(world_.def_.motion, sim::to_seconds(now()), here, here.position);
    cache_valid_ = false;
    alive_ = false;
    ++generation_;
  }
  /// Up again where it stands: a fresh protocol object, started now.
  void revive() {
    if (alive_) return;
    alive_ = true;
    ++restarts_;
    make_protocol();
    if (!world_.robots_here_) return;  // a ghost: its home tile starts the protocol
    const std::uint32_t generation = generation_;
    world_.simulator_.after(sim::Duration{0}, [this, generation] {
      if (generation == generation_) protocol_->start();
    });
  }
  /// Changes when the robot goes down or comes back: a course chosen before does not apply.
  std::uint32_t generation() const { return generation_; }
  /// ∫|v| dt and ∫|a| dt since the start of the run (world units, world units / s).
  TravelIntegrals travel() const {
    TravelIntegrals total = travelled_;
    total += travel_between(segment_, world_.def_.motion, booked_until_s_,
                            sim::to_seconds(world_.simulator_.now()));
    return total;
  }

  protocols::RobotProtocol& protocol() { return *protocol_; }
  const protocols::RobotProtocol& protocol() const { return *protocol_; }
  const MotionSegment& segment() const { return segment_; }

  /// State now; cached per simulated instant (many frames are sent at the same time).
  MotionState state() const {
    const sim::Time now = world_.simulator_.now();
    if (!cache_valid_ || cached_at_ != now) {
      cached_ = segment_.state_at(sim::to_seconds(now));
      cached_at_ = now;
      cache_valid_ = true;
    }
    return cached_;
  }

  // protocols::RobotHost
  sim::Time now() const override { return world_.simulator_.now(); }
  NodeId id() const override { return world_.robot_node(index_); }
  Vec2 position() const override { return state().position; }
  std::uint32_t broadcast(double range, net::Payload payload) override {
    return world_.send(id(), sim::kNoNode, range, std::move(payload));
  }
  std::uint32_t unicast(NodeId to, net::Payload payload) override {
    return world_.send(id(), to, 0.0, std::move(payload));
  }
  const net::MessageSizes& message_sizes() const override { return world_.radio_.params().sizes; }
  protocols::TimerHandle set_timer(sim::Duration delay, std::uint32_t kind) override {
    // A timer of a protocol that has since gone down (or been replaced) does nothing.
    const std::uint32_t generation = generation_;
    return world_.simulator_.after(delay, [this, kind, generation] {
      if (generation == generation_) protocol_->on_timer(kind);
    });
  }
  void cancel_timer(protocols::TimerHandle timer) override { world_.simulator_.cancel(timer); }
  void set_target(const Vec2& target) override {
    if (!alive_) return;
    const sim::Duration delay = world_.actuation_delay_;
    if (delay.count() > 0) {
      // The robot keeps its course until it acts (docs/protocols.md, "Actuation delay"); a
      // robot that went down meanwhile never starts it.
      const double x = target.x(), y = target.y();
      const std::uint32_t generation = generation_;
      const sim::Time when = now() + delay;
      if (world_.keeps_courses_) world_.keep_course(index_, generation, when, target);
      world_.simulator_.after(delay, [this, x, y, generation] {
        if (generation == generation_) steer(Vec2{x, y});
      });
      return;
    }
    steer(target);
  }
  /// Starts towards `target` now.
  void steer(const Vec2& target) {
    book_motion();
    if (world_.def_.motion.jump_to_target)
      travelled_.distance += (target - state().position).norm();
    // A new centroid starts a new closed-form segment from the current state.
    const MotionState now_state =
        world_.def_.motion.jump_to_target ? MotionState{target, Vec2{0, 0}} : state();
    segment_ = MotionSegment(world_.def_.motion, sim::to_seconds(now()), now_state, target);
    cache_valid_ = false;
    world_.radio_.raise_speed_bound(segment_.speed_bound());
    if (world_.def_.motion.jump_to_target) world_.radio_.mobile_node_jumped();
  }
  void update_finished(const protocols::UpdateRecord& record) override {
    world_.simulator_.fingerprint_stream().mix(sim::bits_of(record.centroid.x()));
    world_.simulator_.fingerprint_stream().mix(sim::bits_of(record.centroid.y()));
    if (world_.observer_) world_.observer_->on_update(index_, record);
  }
  double sensor_area(NodeId sensor) const override {
    // Equal areas (every layout but a sensor file with areas): no lookup per reading.
    if (world_.uniform_sensor_area_ > 0.0) return world_.uniform_sensor_area_;
    return world_.def_.sensors[sim::index(sensor) - world_.robots_.size()].area;
  }

 private:
  void make_protocol() {
    // The protocol's own stream: its first draw phases the built-ins' updates. A restarted
    // robot draws from a stream of its own restart.
    const std::uint64_t key = robot_key(index_) ^ (std::uint64_t{restarts_} << 40);
    auto random = sim::RandomStream::keyed(world_.def_.seed, key, sim::purpose("protocol.phase"));
    const protocols::RobotSetup setup{
        *this, index_, world_.protocol_context_, world_.def_.protocol.params, random, &world_.log_};
    protocol_ = world_.truthful_factory_ ? (*world_.truthful_factory_)(setup, world_)
                                         : world_.definition_->make_robot(setup);
  }
  /// Adds the current segment's travel up to now (it is about to be replaced).
  void book_motion() {
    const double now_s = sim::to_seconds(world_.simulator_.now());
    travelled_ += travel_between(segment_, world_.def_.motion, booked_until_s_, now_s);
    booked_until_s_ = now_s;
  }

  World& world_;
  // Next to world_: a position query reads both, and the rest of this object (the protocol's
  // state) is far from this line.
  mutable bool cache_valid_ = false;
  mutable sim::Time cached_at_{};
  mutable MotionState cached_;
  std::size_t index_;
  MotionSegment segment_;
  std::unique_ptr<protocols::RobotProtocol> protocol_;
  bool alive_ = true;
  std::uint32_t generation_ = 0, restarts_ = 0;
  TravelIntegrals travelled_;    // booked segments
  double booked_until_s_ = 0.0;  // the current segment's travel counts from here
};

}  // namespace masnet::agents
