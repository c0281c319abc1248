// Hand-computed cases and invariants of protocols/polygon_measures: area, centroid and polar
// moment of polygons (textbook shapes, random and degenerate ones), and the checks and
// normalisation of user polygons.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <vector>

#include <catch2/catch.hpp>

#include "geometry_test_support.hpp"
#include "protocols/geometry.hpp"

namespace {

using geometry_test::kUnitSquare;
using geometry_test::Rng;
using geometry_test::same_vertices;
using masnet::protocols::Cell;
using masnet::protocols::ConvexPolygon;
using masnet::protocols::Vec2;
namespace geo = masnet::protocols;

}  // namespace

TEST_CASE("The unit square has area 1, centroid (1/2, 1/2) and polar moment 1/6 about its centre",
          "[protocols]") {
  REQUIRE(geo::area(kUnitSquare) == 1.0);
  REQUIRE(geo::centroid(kUnitSquare).isApprox(Vec2(0.5, 0.5), 1e-15));
  REQUIRE(geo::polar_moment(kUnitSquare, {0.5, 0.5}) == Approx(1.0 / 6.0).epsilon(1e-14));
  // About a corner: ∫∫ x² + y² over [0,1]² = 2/3.
  REQUIRE(geo::polar_moment(kUnitSquare, {0.0, 0.0}) == Approx(2.0 / 3.0).epsilon(1e-14));
  REQUIRE(geo::max_vertex_distance(kUnitSquare, {0.5, 0.5}) == Approx(std::sqrt(0.5)));
}

TEST_CASE("A right triangle has the textbook area, centroid and polar moments", "[protocols]") {
  const ConvexPolygon t{{{0, 0}, {1, 0}, {0, 1}}};
  REQUIRE(geo::area(t) == 0.5);
  REQUIRE(geo::centroid(t).isApprox(Vec2(1.0 / 3.0, 1.0 / 3.0), 1e-15));
  // About the right-angle corner 2·∫₀¹ x²(1 − x) dx = 1/6; about the centroid 1/6 − A·|c|² = 1/18.
  REQUIRE(geo::polar_moment(t, {0, 0}) == Approx(1.0 / 6.0).epsilon(1e-14));
  REQUIRE(geo::polar_moment(t, {1.0 / 3.0, 1.0 / 3.0}) == Approx(1.0 / 18.0).epsilon(1e-13));
}

TEST_CASE("Regular polygons circumscribe their disk and have the exact area and polar moment",
          "[protocols]") {
  for (int n : {3, 4, 7, 64, 1000}) {
    const Vec2 c(0.3, -2.0);
    const double r = 0.7;
    const ConvexPolygon p = geo::regular_polygon(c, r, n);
    INFO("n = " << n);
    REQUIRE(p.vertices.size() == static_cast<std::size_t>(n));
    REQUIRE(geo::is_convex_ccw(p.vertices));
    // Every edge is tangent to the circle: its distance from the centre is the radius.
    for (std::size_t k = 0; k < p.vertices.size(); ++k) {
      const Vec2 a = p.vertices[k], b = p.vertices[(k + 1) % p.vertices.size()];
      const Vec2 e = (b - a).normalized();
      const double distance = std::abs(e.x() * (c - a).y() - e.y() * (c - a).x());
      REQUIRE(distance == Approx(r).epsilon(1e-12));
    }
    // Triangle fan from the centre with apothem r and half-edge r·t, t = tan(π/n):
    // area n·r²·t, polar moment n·r⁴·t·(1/2 + t²/6).
    const double t = std::tan(std::numbers::pi / n);
    REQUIRE(geo::area(p) == Approx(n * r * r * t).epsilon(1e-12));
    REQUIRE(geo::polar_moment(p, c) ==
            Approx(n * std::pow(r, 4) * t * (0.5 + t * t / 6)).epsilon(1e-12));
    REQUIRE(geo::centroid(p).isApprox(c, 1e-12));
    // Points just inside the circle are inside the polygon.
    Rng rng(static_cast<std::uint64_t>(n));
    for (int k = 0; k < 200; ++k) {
      const double angle = rng.uniform(0.0, 2.0 * std::numbers::pi);
      REQUIRE(geo::contains(p, c + r * (1.0 - 1e-12) * Vec2(std::cos(angle), std::sin(angle))));
    }
  }
  REQUIRE(geo::regular_polygon({0, 0}, 1.0, 2).empty());
  REQUIRE(geo::regular_polygon({0, 0}, 0.0, 8).empty());
}

TEST_CASE("The polar moment obeys the parallel-axis theorem on random polygons", "[protocols]") {
  Rng rng(7);
  for (int k = 0; k < 200; ++k) {
    const Vec2 c(rng.uniform(-5, 5), rng.uniform(-5, 5));
    const ConvexPolygon p = geo::regular_polygon(c, rng.uniform(0.01, 3), 3 + k % 20);
    const geo::HalfPlane cut{Vec2(rng.uniform(-1, 1), rng.uniform(-1, 1)), 0.0};
    const ConvexPolygon q = geo::clip(p, {cut.normal, cut.normal.dot(c) + 0.2});
    if (q.empty()) continue;
    const Vec2 g = geo::centroid(q);
    const Vec2 at(rng.uniform(-5, 5), rng.uniform(-5, 5));
    REQUIRE(geo::polar_moment(q, at) ==
            Approx(geo::polar_moment(q, g) + geo::area(q) * (at - g).squaredNorm()).epsilon(1e-10));
  }
}

TEST_CASE("Area, centroid and polar moment of empty and flat polygons are defined and finite",
          "[protocols]") {
  const ConvexPolygon empty;
  REQUIRE(geo::area(empty) == 0.0);
  REQUIRE(geo::perimeter(empty) == 0.0);
  REQUIRE(geo::centroid(empty) == Vec2(0, 0));
  REQUIRE(geo::polar_moment(empty, {1, 1}) == 0.0);
  REQUIRE(geo::max_vertex_distance(empty, {1, 1}) == 0.0);
  REQUIRE_FALSE(geo::contains(empty, {0, 0}));
  // Not canonical, but the documented fallback is the vertex average.
  const ConvexPolygon flat{{{0, 0}, {1, 1}, {2, 2}}};
  REQUIRE(geo::area(flat) == 0.0);
  REQUIRE(geo::centroid(flat) == Vec2(1, 1));
  const ConvexPolygon segment{{{0, 0}, {3, 0}}};
  REQUIRE(geo::centroid(segment) == Vec2(1.5, 0));
  REQUIRE(geo::polar_moment(segment, {0, 0}) == 0.0);
}

TEST_CASE("Convexity and simplicity checks reject bad domains", "[protocols]") {
  const std::vector<Vec2> ccw{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Vec2> cw{{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  const std::vector<Vec2> bow_tie{{0, 0}, {1, 1}, {1, 0}, {0, 1}};
  const std::vector<Vec2> l_shape{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const std::vector<Vec2> with_collinear{{0, 0}, {0.5, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Vec2> spike{{0, 0}, {1, 0}, {2, 0}, {1, 0}, {1, 1}};
  std::vector<Vec2> pentagram;  // every turn left, but winds twice
  for (int k = 0; k < 5; ++k) {
    const double angle = 4.0 * std::numbers::pi * k / 5;
    pentagram.emplace_back(std::cos(angle), std::sin(angle));
  }
  REQUIRE(geo::is_convex_ccw(ccw));
  REQUIRE(geo::is_simple(ccw));
  REQUIRE_FALSE(geo::is_convex_ccw(cw));
  REQUIRE(geo::is_simple(cw));
  REQUIRE_FALSE(geo::is_convex_ccw(bow_tie));
  REQUIRE_FALSE(geo::is_simple(bow_tie));
  REQUIRE_FALSE(geo::is_convex_ccw(l_shape));
  REQUIRE(geo::is_simple(l_shape));
  REQUIRE_FALSE(geo::is_convex_ccw(with_collinear));
  REQUIRE(geo::is_simple(with_collinear));
  REQUIRE_FALSE(geo::is_simple(spike));
  REQUIRE_FALSE(geo::is_convex_ccw(pentagram));
  REQUIRE_FALSE(geo::is_simple(pentagram));
  REQUIRE_FALSE(geo::is_simple(std::vector<Vec2>{{0, 0}, {1, 0}}));
  REQUIRE_FALSE(geo::is_simple(std::vector<Vec2>{{0, 0}, {1, 0}, {1, 0}, {0, 1}}));
}

TEST_CASE("A user polygon is normalised to the canonical form or rejected", "[protocols]") {
  // Clockwise, closed by a copy of the first vertex, with a repeated and a collinear vertex.
  const std::vector<Vec2> messy{{0, 0}, {0, 1}, {0, 1}, {1, 1}, {1, 0.5}, {1, 0}, {0, 0}};
  const auto p = geo::normalize_convex_polygon(messy);
  REQUIRE(p.has_value());
  REQUIRE(same_vertices(*p, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  // A vertex off the line by far less than the tolerance is dropped too.
  const std::vector<Vec2> nearly{{0, 0}, {0.5, 1e-17}, {1, 0}, {1, 1}};
  REQUIRE(geo::normalize_convex_polygon(nearly)->vertices.size() == 3);
  REQUIRE_FALSE(
      geo::normalize_convex_polygon(std::vector<Vec2>{{0, 0}, {1, 1}, {2, 2}}).has_value());
  REQUIRE_FALSE(geo::normalize_convex_polygon(
                    std::vector<Vec2>{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}})
                    .has_value());
  REQUIRE_FALSE(
      geo::normalize_convex_polygon(std::vector<Vec2>{{0, 0}, {1, 1}, {1, 0}, {0, 1}}).has_value());
  REQUIRE_FALSE(geo::normalize_convex_polygon(std::vector<Vec2>{{0, 0}, {1, 0}}).has_value());
  // Cells over a normalised pentagon partition it.
  const auto pentagon = geo::normalize_convex_polygon(geo::regular_polygon({0, 0}, 1, 5).vertices);
  REQUIRE(pentagon.has_value());
  const std::vector<Vec2> sites{{0, 0}, {0.3, 0.1}, {-0.5, 0.2}, {0.1, -0.6}};
  double total = 0.0;
  for (const Cell& c : geo::voronoi_cells(sites, *pentagon))
    total += geo::area(c.polygon);
  REQUIRE(total == Approx(geo::area(*pentagon)).epsilon(1e-12));
}
