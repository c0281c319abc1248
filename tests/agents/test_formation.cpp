// Robot groups in formation (docs/formations.md): the shapes, the fit inside a cell, and the
// follower's control law driven by hand — a leader's messages scripted, the followers' own
// messages passed between them each tick — without a world or a radio.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

#include "agents/formation.hpp"
#include "sim/random.hpp"

using namespace masnet;
using agents::FollowerController;
using agents::FormationDef;
using agents::FormationShape;
using agents::FormationState;
using agents::MotionParams;
using agents::MotionSegment;
using agents::MotionState;
using net::Vec2;
using protocols::ConvexPolygon;

namespace {

FormationDef wedge_of(std::size_t size, double spacing) {
  FormationDef def;
  def.group_size = size;
  def.shape = FormationShape::wedge;
  def.spacing_m = spacing;
  return def;
}

// The largest s with every anchor + s·d inside, by bisection on contains() alone.
double scale_by_bisection(const ConvexPolygon& region, const Vec2& anchor,
                          const std::vector<Vec2>& offsets) {
  auto fits = [&](double s) {
    for (const Vec2& d : offsets)
      if (!protocols::contains(region, anchor + s * d)) return false;
    return true;
  };
  if (fits(1.0)) return 1.0;
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 60; ++i)
    (fits(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

// A group driven tick by tick: every `period` each follower hears the leader (position, zero
// velocity, the cell `cell_at(t)`) and every fellow's state, then steers; between ticks the
// closed-form motion runs. `watch(t, positions, cell)` sees the followers every `watch_step`.
struct Group {
  FormationDef def;
  MotionParams motion;
  std::vector<FollowerController> controllers;
  std::vector<MotionSegment> bodies;

  Group(const FormationDef& formation, const std::vector<Vec2>& starts) : def(formation) {
    for (std::size_t k = 0; k < starts.size(); ++k) {
      controllers.emplace_back(def, motion, k);
      bodies.emplace_back(motion, 0.0, MotionState{starts[k], Vec2{0, 0}}, starts[k]);
    }
  }

  void run(
      double duration_s, const Vec2& leader, const std::function<ConvexPolygon(double)>& cell_at,
      double watch_step_s,
      const std::function<void(double, const std::vector<Vec2>&, const ConvexPolygon&)>& watch) {
    const double period = def.state_period_s;
    ConvexPolygon cell = cell_at(0.0);
    double next_watch = 0.0;
    for (int tick = 0; tick * period < duration_s; ++tick) {
      const double t = tick * period;
      cell = cell_at(t);
      std::vector<MotionState> now;
      for (const MotionSegment& body : bodies)
        now.push_back(body.state_at(t));
      for (std::size_t k = 0; k < controllers.size(); ++k) {
        controllers[k].hear(t, FormationState{0, -1, leader, Vec2{0, 0}, leader, cell});
        for (std::size_t j = 0; j < controllers.size(); ++j)
          if (j != k)
            controllers[k].hear(t, FormationState{0,
                                                  static_cast<std::int32_t>(j),
                                                  now[j].position,
                                                  now[j].velocity,
                                                  now[j].position,
                                                  {}});
      }
      for (std::size_t k = 0; k < controllers.size(); ++k)
        if (auto target = controllers[k].target(t, now[k]))
          bodies[k] = MotionSegment(motion, t, now[k], *target);
      for (; next_watch < t + period && next_watch < duration_s; next_watch += watch_step_s) {
        std::vector<Vec2> positions;
        for (const MotionSegment& body : bodies)
          positions.push_back(body.state_at(next_watch).position);
        watch(next_watch, positions, cell);
      }
    }
  }
};

}  // namespace

TEST_CASE("formation shapes: line, wedge and circle keep the spacing between neighbours") {
  FormationDef def = wedge_of(5, 0.05);
  def.shape = FormationShape::line;
  auto line = agents::formation_offsets(def);
  REQUIRE(line.size() == 4);
  CHECK(line[0].x() == Approx(-0.05));
  CHECK(line[1].x() == Approx(0.05));
  CHECK(line[2].x() == Approx(-0.10));
  for (const Vec2& d : line)
    CHECK(d.y() == 0.0);
  def.shape = FormationShape::wedge;
  auto wedge = agents::formation_offsets(def);
  CHECK(wedge[0].norm() == Approx(0.05));               // first rank: spacing from the leader
  CHECK((wedge[2] - wedge[0]).norm() == Approx(0.05));  // along an arm: spacing
  CHECK(wedge[0].x() == Approx(-wedge[1].x()));         // symmetric
  CHECK(wedge[0].y() < 0.0);                            // behind the leader (−y)
  def.shape = FormationShape::circle;
  auto circle = agents::formation_offsets(def);
  for (std::size_t k = 0; k < circle.size(); ++k) {
    CHECK(circle[k].norm() == Approx(circle[0].norm()));
    CHECK((circle[k] - circle[(k + 1) % circle.size()]).norm() >= 0.05 - 1e-12);
  }
}

TEST_CASE("formation fit: the scale agrees with a bisection on point-in-polygon tests") {
  auto random = sim::RandomStream::keyed(7, 1, sim::purpose("test.fit"));
  for (int trial = 0; trial < 200; ++trial) {
    const int sides = 3 + trial % 6;
    const Vec2 centre{random.uniform(0.3, 0.7), random.uniform(0.3, 0.7)};
    const ConvexPolygon region =
        protocols::regular_polygon(centre, random.uniform(0.05, 0.2), sides);
    const Vec2 anchor = centre + Vec2{random.uniform(-0.03, 0.03), random.uniform(-0.03, 0.03)};
    FormationDef def = wedge_of(2 + trial % 5, random.uniform(0.01, 0.3));
    def.shape = static_cast<FormationShape>(trial % 3);
    const auto offsets = agents::formation_offsets(def);
    const double expected = scale_by_bisection(region, anchor, offsets);
    CHECK(agents::fit_scale(region, anchor, offsets) == Approx(expected).margin(1e-9));
  }
  // An anchor outside the region leaves no room at all.
  CHECK(agents::fit_scale(protocols::rectangle(0, 0, 1, 1), Vec2{2, 0.5}, {Vec2{0.1, 0}}) == 0.0);
}

TEST_CASE("formation inset: a rectangle shrinks by the margin on every side") {
  const ConvexPolygon room = agents::inset(protocols::rectangle(0, 0, 0.4, 0.2), 0.03);
  CHECK(protocols::area(room) == Approx((0.4 - 0.06) * (0.2 - 0.06)));
  CHECK(protocols::contains(room, Vec2{0.031, 0.031}));
  CHECK_FALSE(protocols::contains(room, Vec2{0.029, 0.1}));
  CHECK(agents::inset(protocols::rectangle(0, 0, 0.4, 0.2), 0.2).empty());
  CHECK(agents::distance_outside(protocols::rectangle(0, 0, 1, 1), Vec2{1.5, 2.0}) ==
        Approx(std::hypot(0.5, 1.0)));
  CHECK(agents::distance_outside(protocols::rectangle(0, 0, 1, 1), Vec2{0.5, 0.5}) == 0.0);
}

TEST_CASE("formation control: with a static leader the followers settle in their slots") {
  // Three followers start scattered; the leader stands still in a roomy cell. The law's fixed
  // point is the formation, and the closed loop damps like e^{−k_v t/2}: after 20 s what is
  // left of an initial error of ~0.1 is far below 10⁻⁴.
  FormationDef def = wedge_of(4, 0.05);
  const Vec2 leader{0.5, 0.5};
  Group group(def, {Vec2{0.3, 0.3}, Vec2{0.6, 0.7}, Vec2{0.45, 0.55}});
  const auto offsets = agents::formation_offsets(def);
  std::vector<double> error_at;
  group.run(
      20.0, leader, [](double) { return protocols::rectangle(0, 0, 1, 1); }, 1.0,
      [&](double, const std::vector<Vec2>& p, const ConvexPolygon&) {
        double worst = 0.0;
        for (std::size_t k = 0; k < p.size(); ++k)
          worst = std::max(worst, (p[k] - (leader + offsets[k])).norm());
        error_at.push_back(worst);
      });
  REQUIRE(error_at.size() == 20);
  CHECK(error_at.front() > 0.1);
  CHECK(error_at.back() < 1e-4);
  CHECK(error_at[10] < error_at[0] / 10);
  CHECK(group.controllers[0].scale() == 1.0);
}

TEST_CASE("formation control: followers stay inside a cell that shrinks around the leader") {
  // The leader's cell, a square, shrinks from half-width 0.2 to 0.05 over 10 s (each message
  // brings the new one); the formation (spacing 0.08) must scale down, and no follower may be
  // outside the latest cell at any of the instants watched, 2 ms apart.
  FormationDef def = wedge_of(5, 0.08);
  const Vec2 leader{0.5, 0.5};
  const auto half_width = [](double t) { return 0.2 - 0.015 * std::min(t, 10.0); };
  const auto square = [&](double t) {
    const double h = half_width(t);
    return protocols::rectangle(0.5 - h, 0.5 - h, 0.5 + h, 0.5 + h);
  };
  const auto offsets = agents::formation_offsets(def);
  std::vector<Vec2> starts;
  for (const Vec2& d : offsets)
    starts.push_back(leader + d);
  Group group(def, starts);
  std::size_t watched = 0, outside = 0;
  group.run(12.0, leader, square, 0.002,
            [&](double, const std::vector<Vec2>& p, const ConvexPolygon& cell) {
              ++watched;
              for (const Vec2& q : p)
                if (!protocols::contains(cell, q)) ++outside;
            });
  CHECK(watched == 6000);
  CHECK(outside == 0);
  // Scaled to the last cell: the farthest slot (rank 2 on the wedge, 0.16 away) sits at the
  // inset square's edge.
  const double expected =
      agents::fit_scale(agents::inset(square(12.0), def.margin_m), leader, offsets);
  CHECK(expected < 0.5);
  CHECK(group.controllers[0].scale() == Approx(expected));
}
