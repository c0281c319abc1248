#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "net/line_index.hpp"
#include "sim/random.hpp"

using namespace masnet;
using net::Vec2;

namespace {

// Every point of `index` that the runs of a query cover, against the float test itself.
void require_runs_match_brute_force(const net::LineIndex& index, const std::vector<Vec2>& points,
                                    const Vec2& center, double radius) {
  std::vector<char> covered(points.size(), 0);
  bool overlap = false, out_of_bounds = false;
  index.for_each_run_within(center, radius, [&](std::uint32_t a, std::uint32_t c) {
    out_of_bounds |= !(a < c && c <= points.size());
    for (std::uint32_t k = a; k < c && k < points.size(); ++k) {
      overlap |= covered[k] != 0;
      covered[k] = 1;
    }
  });
  REQUIRE_FALSE(out_of_bounds);
  REQUIRE_FALSE(overlap);
  for (std::uint32_t k = 0; k < points.size(); ++k) {
    const double dx = index.x(k) - center.x(), dy = index.y(k) - center.y();
    const bool inside = dx * dx + dy * dy <= radius * radius;
    if (static_cast<bool>(covered[k]) == inside) continue;
    INFO("slot " << k << " at (" << index.x(k) << ", " << index.y(k) << "), center (" << center.x()
                 << ", " << center.y() << "), radius " << radius << ", inside " << inside);
    FAIL("the runs disagree with the distance test");
  }
}

// An nx × ny grid at origin + spacing·(i + offset, j + offset), optionally with every x nudged
// by up to `jitter` of the spacing (the line still counts as evenly spaced below 1e-9).
std::vector<Vec2> grid(int nx, int ny, double spacing, Vec2 origin, double offset, double jitter,
                       sim::RandomStream& rng) {
  std::vector<Vec2> points;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double nudge =
          jitter > 0 && i > 0 && i + 1 < nx ? rng.uniform(-jitter, jitter) * spacing : 0.0;
      points.push_back(
          Vec2{origin.x() + spacing * (i + offset) + nudge, origin.y() + spacing * (j + offset)});
    }
  return points;
}

}  // namespace

TEST_CASE("runs of a disk on sensor rows are exactly the points the float distance test accepts",
          "[net]") {
  // The runs come from O(1) slot estimates, trusted without an exact test when the chord's ends
  // are provably far from a slot. Disks are drawn to hit the boundary cases: points exactly at
  // the range, one ulp either side, chord ends on slots, tangent lines, disks beyond the line
  // ends, and coordinates far from the origin (where the rounding bound must refuse the shortcut).
  sim::RandomStream rng(7);
  struct Layout {
    int nx, ny;
    double spacing;
    Vec2 origin;
    double offset, jitter;
  };
  const Layout layouts[] = {
      {40, 40, 1.0 / 40, {0, 0}, 0.5, 0.0},     // the paper's cell-centred grid
      {33, 17, 0.1, {-1.6, -0.8}, 0.0, 0.0},    // corners at points, negative coordinates
      {50, 20, 1e-3, {0.25, 0.5}, 0.0, 3e-10},  // fine spacing, nudged within "even"
      {25, 25, 3.0, {1e6, -1e6}, 0.5, 0.0},     // far from the origin
      {16, 16, 0.25, {-2, -2}, 0.0, 0.0},       // exact arithmetic: chord ends exactly on slots
      {64, 8, 1.0, {0x1p44, 0}, 0.0, 0.0},      // exact points, coarse rounding of the estimates
      {10, 400, 1.0 / 400, {0, 0}, 0.5, 0.0},   // radii of hundreds of spacings: tangents are hard
      {20, 10, 0.05, {0, 0}, 0.0, 0.2},         // uneven rows: no estimates are sure
  };
  for (const Layout& layout : layouts) {
    const std::vector<Vec2> points = grid(layout.nx, layout.ny, layout.spacing, layout.origin,
                                          layout.offset, layout.jitter, rng);
    std::vector<sim::NodeId> ids;
    for (std::uint32_t k = 0; k < points.size(); ++k)
      ids.push_back(sim::node_id(k));
    net::LineIndex index;
    REQUIRE(index.build(points, ids));
    // Points of the index in slot order, for centers and radii.
    std::vector<Vec2> slots;
    for (std::uint32_t k = 0; k < points.size(); ++k)
      slots.push_back(Vec2{index.x(k), index.y(k)});
    const double width = layout.spacing * layout.nx, height = layout.spacing * layout.ny;
    auto random_point = [&] {
      return Vec2{layout.origin.x() + rng.uniform(-0.2, 1.2) * width,
                  layout.origin.y() + rng.uniform(-0.2, 1.2) * height};
    };
    auto random_slot = [&] { return slots[rng.below(slots.size())]; };
    for (int q = 0; q < 3000; ++q) {
      Vec2 center = rng.below(2) == 0 ? random_slot() : random_point();
      double radius = 0;
      switch (rng.below(6)) {
        case 0:
          radius = rng.uniform(0.0, 0.7) * width;
          break;
        case 1:  // exactly at the range of some point, or one ulp either side
        case 2: {
          const Vec2 target = random_slot();
          const double dx = target.x() - center.x(), dy = target.y() - center.y();
          radius = std::sqrt(dx * dx + dy * dy);
          const auto step = rng.below(3);
          if (step == 1) radius = std::nextafter(radius, 0.0);
          if (step == 2) radius = std::nextafter(radius, INFINITY);
          break;
        }
        case 3: {  // chord ends on slots: whole spacings, and Pythagorean 5 = (3, 4)
          radius = layout.spacing *
                   static_cast<double>(rng.below(2) == 0 ? rng.below(30) : 5 * rng.below(6));
          break;
        }
        case 4: {  // a few ulps from tangent to a line: the chord, ~1e-8 of the radius, ends
                   // near a point placed about that far from the center
          const Vec2 target = random_slot();
          radius = std::fabs(target.y() - center.y());
          for (auto ulps = rng.below(4); ulps > 0; --ulps)
            radius = std::nextafter(radius, INFINITY);
          center = Vec2{target.x() + rng.uniform(-4e-8, 4e-8) * radius, center.y()};
          break;
        }
        default:
          radius = rng.uniform(0.0, 3.0) * layout.spacing;
          break;
      }
      require_runs_match_brute_force(index, slots, center, radius);
    }
  }
}

TEST_CASE(
    "sure slots of an interval are exactly the points inside it, and the rest clear the guard",
    "[net]") {
  // The oracle's scanline takes a row's sensors between two x values from O(1) estimates when
  // sure_slots says no point is near either end. Intervals are drawn with ends exactly on points,
  // one ulp either side, a few ulps away, beyond the line ends and reversed.
  sim::RandomStream rng(13);
  struct Layout {
    int nx, ny;
    double spacing, x0, jitter;
    bool allowed;  // far from the origin the rounding bound must refuse
  };
  const Layout layouts[] = {{40, 3, 1.0 / 40, 0.0, 0.0, true},
                            {316, 2, 1.0 / 316, 0.0, 0.0, true},
                            {50, 2, 1e-3, 0.25, 3e-10, true},
                            {25, 2, 3.0, 1e6, 0.0, true},
                            {64, 2, 1.0, 0x1p44, 0.0, false}};
  for (const Layout& layout : layouts) {
    const std::vector<Vec2> points =
        grid(layout.nx, layout.ny, layout.spacing, Vec2{layout.x0, 0.0}, 0.5, layout.jitter, rng);
    std::vector<sim::NodeId> ids;
    for (std::uint32_t k = 0; k < points.size(); ++k)
      ids.push_back(sim::node_id(k));
    net::LineIndex index;
    REQUIRE(index.build(points, ids));
    const double guard = 1e-14, extent = std::fabs(layout.x0) + 2.0 * layout.spacing * layout.nx;
    const bool allowed = index.slot_estimates_are_sure(extent, guard);
    CHECK(allowed == layout.allowed);
    if (!allowed) continue;
    int sure = 0;
    auto pick = [&] {
      const double x =
          index.x(static_cast<std::uint32_t>(rng.below(static_cast<std::uint64_t>(layout.nx))));
      switch (rng.below(5)) {
        case 0:
          return x;
        case 1:
          return std::nextafter(x, -INFINITY);
        case 2:
          return std::nextafter(x, INFINITY);
        case 3:
          return x + rng.uniform(-1.0, 1.0) * layout.spacing;
        default:
          return layout.x0 + rng.uniform(-0.3, 1.3) * layout.spacing * layout.nx;
      }
    };
    for (int q = 0; q < 20000; ++q) {
      const double lo = pick(), hi = pick();
      std::uint32_t a = 0, c = 0;
      if (!index.sure_slots(0, lo, hi, a, c)) continue;
      ++sure;
      for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(layout.nx); ++k) {
        const double x = index.x(k);
        const bool in_run = k >= a && k < c;
        INFO("slot " << k << " x " << x << " interval [" << lo << ", " << hi << "] run [" << a
                     << ", " << c << ")");
        REQUIRE(in_run == (x >= lo && x <= hi));
        if (!in_run) REQUIRE((x < lo - guard || x > hi + guard));
      }
    }
    CHECK(sure > 2000);
  }
}
