#include "agents/locomotion.hpp"

#include <algorithm>
#include <cmath>

#include <boost/math/quadrature/gauss.hpp>

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
    // Gauss–Legendre (7 points, Boost's nodes) on pieces of at most kPieceS, both integrands
    // from one evaluation of the closed form: a booking per update must stay cheap. |v| and |a|
    // have kinks where they change sign; a piece that holds one is off by its local second
    // order, a few parts in 10⁵ of the whole (docs/faults-and-lifetime.md).
    using Rule = boost::math::quadrature::gauss<double, 7>;
    constexpr double kPieceS = 0.05;
    const auto pieces = static_cast<std::size_t>(std::ceil((t1_s - t0_s) / kPieceS));
    const double width = (t1_s - t0_s) / static_cast<double>(pieces);
    const auto& x = Rule::abscissa();  // the non-negative half; x[0] = 0
    const auto& w = Rule::weights();
    auto add = [&](double t, double weight, double half) {
      const MotionState s = segment.state_at(t);
      out.distance += weight * half * s.velocity.norm();
      out.accel += weight * half * acceleration(params, s, target).norm();
    };
    for (std::size_t p = 0; p < pieces; ++p) {
      const double a = t0_s + static_cast<double>(p) * width;
      const double half = 0.5 * width, mid = a + half;
      add(mid, w[0], half);
      for (std::size_t i = 1; i < x.size(); ++i) {
        add(mid - half * x[i], w[i], half);
        add(mid + half * x[i], w[i], half);
      }
    }
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
