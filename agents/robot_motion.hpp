#pragma once
// Robot dynamics of paper eq. (2): p̈ = −k (p − c) − k_v ṗ, with c the last computed centroid.
// The law is linear, so between centroid changes the motion has a closed form;
// with a speed limit it is not, and we integrate with fixed RK4 substeps from the segment start.
#include <cstdint>

#include "net/vec2.hpp"

namespace masnet::agents {

using net::Vec2;

struct MotionParams {
  double k = 3.0;           ///< spring gain, 1/s²
  double k_v = 1.0;         ///< viscous friction, 1/s
  double max_speed = 0.0;   ///< world units / s; 0 = unlimited
  double substep_s = 1e-3;  ///< RK4 step used only when max_speed > 0
  /// Discrete Lloyd iterations: the robot is placed on each new target at once (no dynamics).
  bool jump_to_target = false;
};

struct MotionState {
  Vec2 position{0, 0};
  Vec2 velocity{0, 0};
};

/// One segment of motion toward a fixed target, starting at `t0_s` from `start`.
class MotionSegment {
 public:
  MotionSegment() = default;
  MotionSegment(const MotionParams& params, double t0_s, const MotionState& start,
                const Vec2& target);

  /// The state at time `t_s` >= start time (exact for the linear law; RK4 substeps if limited).
  MotionState state_at(double t_s) const;
  const Vec2& target() const { return target_; }
  double start_time() const { return t0_s_; }
  /// Upper bound on the speed for the whole segment (the energy |v|² + k|p−c|² never grows).
  double speed_bound() const { return speed_bound_; }

 private:
  MotionParams params_;
  double t0_s_ = 0.0;
  MotionState start_;
  Vec2 target_{0, 0};
  double speed_bound_ = 0.0;
  // Cache for the substepped case: integration resumes from the last evaluated substep.
  mutable double cached_t_s_ = 0.0;
  mutable MotionState cached_;
};

/// Exact solution of x'' = −k x − k_v x' for one axis: returns (x(t), x'(t)).
struct AxisState {
  double x, v;
};
AxisState damped_spring(double k, double k_v, double x0, double v0, double t);

}  // namespace masnet::agents
