#include "agents/robot_motion.hpp"

#include <cmath>

namespace masnet::agents {

AxisState damped_spring(double k, double k_v, double x0, double v0, double t) {
  if (k == 0.0) {
    if (k_v == 0.0) return {x0 + v0 * t, v0};
    const double decay = std::exp(-k_v * t);
    return {x0 + v0 * (1.0 - decay) / k_v, v0 * decay};
  }
  const double disc = k_v * k_v - 4.0 * k;
  const double a = -0.5 * k_v;
  // Near critical damping both textbook forms lose digits; the critical form is exact there
  // and its error for |disc| below the threshold is far under 1e-12 over the times we use.
  if (std::fabs(disc) <= 1e-12 * (k_v * k_v + 4.0 * k)) {
    const double e = std::exp(a * t);
    const double b = v0 - a * x0;
    return {(x0 + b * t) * e, (a * (x0 + b * t) + b) * e};
  }
  if (disc < 0.0) {  // underdamped: e^{at}(A cos ωt + B sin ωt)
    const double w = 0.5 * std::sqrt(-disc);
    const double A = x0, B = (v0 - a * x0) / w;
    const double e = std::exp(a * t), c = std::cos(w * t), s = std::sin(w * t);
    return {e * (A * c + B * s), e * ((a * A + w * B) * c + (a * B - w * A) * s)};
  }
  // overdamped: C1 e^{r1 t} + C2 e^{r2 t}
  const double root = 0.5 * std::sqrt(disc);
  const double r1 = a + root, r2 = a - root;
  const double c1 = (v0 - r2 * x0) / (r1 - r2), c2 = x0 - c1;
  const double e1 = std::exp(r1 * t), e2 = std::exp(r2 * t);
  return {c1 * e1 + c2 * e2, c1 * r1 * e1 + c2 * r2 * e2};
}

MotionSegment::MotionSegment(const MotionParams& params, double t0_s, const MotionState& start,
                             const Vec2& target)
    : params_(params), t0_s_(t0_s), start_(start), target_(target), cached_t_s_(t0_s), cached_(start) {
  const Vec2 x0 = start.position - target;
  speed_bound_ = std::sqrt(start.velocity.squaredNorm() + params.k * x0.squaredNorm());
  if (params.max_speed > 0.0) speed_bound_ = std::fmin(speed_bound_, params.max_speed);
}

namespace {
// Acceleration of the speed-limited law: the spring-damper force, with the velocity clamped
// to the limit's disk.
Vec2 limited_acceleration(const MotionParams& p, const Vec2& target, const MotionState& s) {
  return -p.k * (s.position - target) - p.k_v * s.velocity;
}
MotionState clamp_speed(const MotionParams& p, MotionState s) {
  const double speed = s.velocity.norm();
  if (speed > p.max_speed) s.velocity *= p.max_speed / speed;
  return s;
}
MotionState rk4_step(const MotionParams& p, const Vec2& target, const MotionState& s, double h) {
  auto f = [&](const MotionState& q) {
    MotionState d;
    d.position = q.velocity;
    d.velocity = limited_acceleration(p, target, q);
    return d;
  };
  auto add = [](const MotionState& a, const MotionState& d, double w) {
    return MotionState{a.position + w * d.position, a.velocity + w * d.velocity};
  };
  const MotionState k1 = f(s);
  const MotionState k2 = f(add(s, k1, 0.5 * h));
  const MotionState k3 = f(add(s, k2, 0.5 * h));
  const MotionState k4 = f(add(s, k3, h));
  MotionState next;
  next.position = s.position + (h / 6.0) * (k1.position + 2.0 * k2.position + 2.0 * k3.position + k4.position);
  next.velocity = s.velocity + (h / 6.0) * (k1.velocity + 2.0 * k2.velocity + 2.0 * k3.velocity + k4.velocity);
  return clamp_speed(p, next);
}
}  // namespace

MotionState MotionSegment::state_at(double t_s) const {
  const double dt = t_s - t0_s_;
  if (dt <= 0.0) return start_;
  if (params_.max_speed <= 0.0) {
    const Vec2 x0 = start_.position - target_;
    const AxisState ax = damped_spring(params_.k, params_.k_v, x0.x(), start_.velocity.x(), dt);
    const AxisState ay = damped_spring(params_.k, params_.k_v, x0.y(), start_.velocity.y(), dt);
    return MotionState{target_ + Vec2{ax.x, ay.x}, Vec2{ax.v, ay.v}};
  }
  // Substeps on a grid anchored at the segment start, so the result does not depend on when
  // (or how often) the state was asked for.
  const double h = params_.substep_s;
  if (t_s < cached_t_s_) {
    cached_t_s_ = t0_s_;
    cached_ = start_;
  }
  while (cached_t_s_ + h <= t_s) {
    const auto steps_done = std::llround((cached_t_s_ - t0_s_) / h);
    cached_ = rk4_step(params_, target_, cached_, h);
    cached_t_s_ = t0_s_ + static_cast<double>(steps_done + 1) * h;
  }
  const double rest = t_s - cached_t_s_;
  return rest > 0.0 ? rk4_step(params_, target_, cached_, rest) : cached_;
}

}  // namespace masnet::agents
