#include "agents/robot_motion.hpp"

#include <cmath>

namespace masnet::agents {

namespace {
// The parts of damped_spring's closed form that depend on (k, k_v, t) only: the two axes of a
// robot share one exp (and cos, sin), so a position costs one set of calls, not two.
struct SpringFactors {
  enum class Kind { free, friction, critical, under, over } kind = Kind::free;
  double t = 0.0, a = 0.0, w = 0.0, r1 = 0.0, r2 = 0.0;  // rates
  double e = 0.0, c = 0.0, s = 0.0, e2 = 0.0;            // at t
};

SpringFactors spring_factors(double k, double k_v, double t) {
  SpringFactors f;
  f.t = t;
  if (k == 0.0) {
    f.kind = k_v == 0.0 ? SpringFactors::Kind::free : SpringFactors::Kind::friction;
    if (k_v != 0.0) f.e = std::exp(-k_v * t);
    return f;
  }
  const double disc = k_v * k_v - 4.0 * k;
  f.a = -0.5 * k_v;
  // Near critical damping both textbook forms lose digits; the critical form is exact there
  // and its error for |disc| below the threshold is far under 1e-12 over the times we use.
  if (std::fabs(disc) <= 1e-12 * (k_v * k_v + 4.0 * k)) {
    f.kind = SpringFactors::Kind::critical;
    f.e = std::exp(f.a * t);
  } else if (disc < 0.0) {  // underdamped: e^{at}(A cos ωt + B sin ωt)
    f.kind = SpringFactors::Kind::under;
    f.w = 0.5 * std::sqrt(-disc);
    f.e = std::exp(f.a * t);
    f.c = std::cos(f.w * t);
    f.s = std::sin(f.w * t);
  } else {  // overdamped: C1 e^{r1 t} + C2 e^{r2 t}
    f.kind = SpringFactors::Kind::over;
    const double root = 0.5 * std::sqrt(disc);
    f.r1 = f.a + root;
    f.r2 = f.a - root;
    f.e = std::exp(f.r1 * t);
    f.e2 = std::exp(f.r2 * t);
  }
  return f;
}

AxisState apply(const SpringFactors& f, double k_v, double x0, double v0) {
  const double t = f.t, a = f.a, w = f.w;
  switch (f.kind) {
    case SpringFactors::Kind::free:
      return {x0 + v0 * t, v0};
    case SpringFactors::Kind::friction:
      return {x0 + v0 * (1.0 - f.e) / k_v, v0 * f.e};
    case SpringFactors::Kind::critical: {
      const double b = v0 - a * x0;
      return {(x0 + b * t) * f.e, (a * (x0 + b * t) + b) * f.e};
    }
    case SpringFactors::Kind::under: {
      const double A = x0, B = (v0 - a * x0) / w;
      return {f.e * (A * f.c + B * f.s), f.e * ((a * A + w * B) * f.c + (a * B - w * A) * f.s)};
    }
    case SpringFactors::Kind::over:
      break;
  }
  const double r1 = f.r1, r2 = f.r2;
  const double c1 = (v0 - r2 * x0) / (r1 - r2), c2 = x0 - c1;
  return {c1 * f.e + c2 * f.e2, c1 * r1 * f.e + c2 * r2 * f.e2};
}
}  // namespace

AxisState damped_spring(double k, double k_v, double x0, double v0, double t) {
  return apply(spring_factors(k, k_v, t), k_v, x0, v0);
}

MotionSegment::MotionSegment(const MotionParams& params, double t0_s, const MotionState& start,
                             const Vec2& target)
    : params_(params),
      t0_s_(t0_s),
      start_(start),
      target_(target),
      cached_t_s_(t0_s),
      cached_(start) {
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
  next.position =
      s.position + (h / 6.0) * (k1.position + 2.0 * k2.position + 2.0 * k3.position + k4.position);
  next.velocity =
      s.velocity + (h / 6.0) * (k1.velocity + 2.0 * k2.velocity + 2.0 * k3.velocity + k4.velocity);
  return clamp_speed(p, next);
}
}  // namespace

MotionState MotionSegment::state_at(double t_s) const {
  const double dt = t_s - t0_s_;
  if (dt <= 0.0) return start_;
  if (params_.max_speed <= 0.0) {
    const Vec2 x0 = start_.position - target_;
    const SpringFactors factors = spring_factors(params_.k, params_.k_v, dt);
    const AxisState ax = apply(factors, params_.k_v, x0.x(), start_.velocity.x());
    const AxisState ay = apply(factors, params_.k_v, x0.y(), start_.velocity.y());
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
