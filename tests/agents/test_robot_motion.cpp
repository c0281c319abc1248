#include <catch2/catch.hpp>

#include <cmath>

#include <unsupported/Eigen/MatrixFunctions>

#include "agents/robot_motion.hpp"

using namespace masnet;
using agents::MotionParams;
using agents::MotionSegment;
using agents::MotionState;
using net::Vec2;

namespace {

// Independent solution of x'' = −k x − k_v x': the matrix exponential of the first-order
// system [x, v]' = [[0, 1], [−k, −k_v]] [x, v].
Eigen::Vector2d by_matrix_exponential(double k, double k_v, double x0, double v0, double t) {
  Eigen::Matrix2d a;
  a << 0.0, 1.0, -k, -k_v;
  const Eigen::Matrix2d e = (a * t).exp();
  return e * Eigen::Vector2d(x0, v0);
}

}  // namespace

TEST_CASE("the closed-form robot motion equals the matrix exponential of the linear ODE",
          "[agents]") {
  struct Gains {
    double k, k_v;
  };
  // Paper gains (underdamped), overdamped, critical, pure friction, free flight.
  const Gains cases[] = {{3.0, 1.0}, {1.0, 5.0}, {1.0, 2.0},   {0.0, 1.0},
                         {0.0, 0.0}, {4.0, 0.1}, {2.5, 3.1622}};
  for (const Gains& g : cases)
    for (double x0 : {-0.7, 0.0, 0.3})
      for (double v0 : {-0.4, 0.0, 0.25})
        for (double t : {0.0, 0.01, 0.37, 1.0, 2.5, 5.0, 10.0}) {
          const agents::AxisState closed = agents::damped_spring(g.k, g.k_v, x0, v0, t);
          const Eigen::Vector2d reference = by_matrix_exponential(g.k, g.k_v, x0, v0, t);
          INFO("k=" << g.k << " k_v=" << g.k_v << " x0=" << x0 << " v0=" << v0 << " t=" << t);
          CHECK(std::fabs(closed.x - reference[0]) <= 1e-9);
          CHECK(std::fabs(closed.v - reference[1]) <= 1e-9);
        }
}

TEST_CASE("a motion segment moves each axis toward the target by the closed form", "[agents]") {
  MotionParams p;  // paper: k = 3, k_v = 1
  const MotionState start{Vec2{0.2, 0.9}, Vec2{0.1, -0.3}};
  const Vec2 target{0.6, 0.4};
  const MotionSegment segment(p, 1.5, start, target);
  for (double dt : {0.0, 0.1, 1.0, 4.0}) {
    const MotionState s = segment.state_at(1.5 + dt);
    const Eigen::Vector2d x =
        by_matrix_exponential(p.k, p.k_v, start.position.x() - target.x(), start.velocity.x(), dt);
    const Eigen::Vector2d y =
        by_matrix_exponential(p.k, p.k_v, start.position.y() - target.y(), start.velocity.y(), dt);
    CHECK(s.position.x() == Approx(target.x() + x[0]).margin(1e-9));
    CHECK(s.position.y() == Approx(target.y() + y[0]).margin(1e-9));
    CHECK(s.velocity.x() == Approx(x[1]).margin(1e-9));
    CHECK(s.velocity.y() == Approx(y[1]).margin(1e-9));
  }
  // Long after, the robot rests at the target.
  CHECK((segment.state_at(60.0).position - target).norm() < 1e-9);
}

TEST_CASE("the speed bound of a segment holds along the whole motion", "[agents]") {
  MotionParams p;
  const MotionSegment segment(p, 0.0, MotionState{Vec2{0.0, 0.0}, Vec2{0.5, 0.2}}, Vec2{1.0, 1.0});
  for (double t = 0.0; t < 10.0; t += 0.01)
    CHECK(segment.state_at(t).velocity.norm() <= segment.speed_bound() + 1e-12);
}

TEST_CASE("a speed-limited robot never exceeds the limit and still reaches its target",
          "[agents]") {
  MotionParams p;
  p.max_speed = 0.05;
  const Vec2 target{0.9, 0.9};
  const MotionSegment segment(p, 0.0, MotionState{Vec2{0.1, 0.1}, Vec2{0, 0}}, target);
  for (double t = 0.0; t < 5.0; t += 0.013)
    CHECK(segment.state_at(t).velocity.norm() <= p.max_speed * (1 + 1e-12));
  // 1.13 units at 0.05 units/s takes at least 22.6 s.
  CHECK((segment.state_at(20.0).position - target).norm() > 0.05);
  CHECK((segment.state_at(200.0).position - target).norm() < 1e-6);
  // Asking out of order gives the same answer: the substep grid is anchored at the start.
  const MotionState late = segment.state_at(3.0017);
  segment.state_at(1.0);
  CHECK(segment.state_at(3.0017).position == late.position);
}
