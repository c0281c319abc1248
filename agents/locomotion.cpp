#include "agents/locomotion.hpp"

#include <algorithm>
#include <cmath>

#include <boost/math/quadrature/gauss_kronrod.hpp>

namespace masnet::agents {
namespace {

// Paper eq. (2): the acceleration of the spring-damper law toward the segment's target.
Vec2 acceleration(const MotionParams& params, const MotionState& s, const Vec2& target) {
  return -params.k * (s.position - target) - params.k_v * s.velocity;
}

}  // namespace

TravelIntegrals travel_between(const MotionSegment& segment, const MotionParams& params,
                               double t0_s, double t1_s) {
  TravelIntegrals out;
  if (!(t1_s > t0_s)) return out;
  const Vec2 target = segment.target();
  if (params.max_speed <= 0.0) {
    // Smooth but for kinks where a speed component changes sign: the adaptive rule splits
    // there; short segments (most of them) pass on the first 15 points.
    using Rule = boost::math::quadrature::gauss_kronrod<double, 15>;
    constexpr unsigned kMaxDepth = 10;
    constexpr double kTolerance = 1e-9;
    out.distance = Rule::integrate([&](double t) { return segment.state_at(t).velocity.norm(); },
                                   t0_s, t1_s, kMaxDepth, kTolerance);
    out.accel = Rule::integrate(
        [&](double t) { return acceleration(params, segment.state_at(t), target).norm(); }, t0_s,
        t1_s, kMaxDepth, kTolerance);
    return out;
  }
  // Substepped motion: the trapezoid rule on the substep grid, walked forward (the segment
  // resumes its integration from the last substep it evaluated).
  const double step = params.substep_s;
  const auto steps = static_cast<std::size_t>(std::ceil((t1_s - t0_s) / step));
  MotionState previous = segment.state_at(t0_s);
  double t_previous = t0_s;
  for (std::size_t k = 1; k <= steps; ++k) {
    const double t = std::min(t0_s + static_cast<double>(k) * step, t1_s);
    const MotionState now = segment.state_at(t);
    const double dt = t - t_previous;
    out.distance += 0.5 * dt * (previous.velocity.norm() + now.velocity.norm());
    out.accel +=
        0.5 * dt *
        (acceleration(params, previous, target).norm() + acceleration(params, now, target).norm());
    previous = now;
    t_previous = t;
  }
  return out;
}

}  // namespace masnet::agents
