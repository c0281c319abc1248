// Hand-computed cases and invariants of protocols/geometry: polygons, exact orientation,
// clipping, point location, the row slicer and the Gabriel test. Cells are in
// test_geometry_cells.cpp, measures and user polygons in test_polygon_measures.cpp.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <catch2/catch.hpp>

#include "geometry_test_support.hpp"
#include "protocols/geometry.hpp"

namespace {

using geometry_test::Ids;
using geometry_test::kUnitSquare;
using geometry_test::Rng;
using geometry_test::same_vertices;
using masnet::protocols::Cell;
using masnet::protocols::ConvexPolygon;
using masnet::protocols::HalfPlane;
using masnet::protocols::Vec2;
namespace geo = masnet::protocols;

}  // namespace

TEST_CASE("A rectangle is a counter-clockwise polygon with the given corners", "[protocols]") {
  const ConvexPolygon r = geo::rectangle(0.0, 0.0, 2.0, 1.0);
  REQUIRE(same_vertices(r, {{0, 0}, {2, 0}, {2, 1}, {0, 1}}));
  REQUIRE(geo::is_convex_ccw(r.vertices));
  REQUIRE(geo::area(r) == 2.0);
  REQUIRE(geo::perimeter(r) == 6.0);
  REQUIRE(geo::rectangle(1.0, 0.0, 0.0, 1.0).empty());
  REQUIRE(geo::rectangle(0.0, 0.0, 1.0, 0.0).empty());
}

TEST_CASE("contains treats the boundary as inside and everything else by exact sign",
          "[protocols]") {
  for (const Vec2& v : kUnitSquare.vertices)
    REQUIRE(geo::contains(kUnitSquare, v));
  REQUIRE(geo::contains(kUnitSquare, {0.5, 0.0}));
  REQUIRE(geo::contains(kUnitSquare, {1.0, 0.3}));
  REQUIRE(geo::contains(kUnitSquare, {0.5, 0.5}));
  REQUIRE_FALSE(geo::contains(kUnitSquare, {std::nextafter(1.0, 2.0), 0.5}));
  REQUIRE_FALSE(geo::contains(kUnitSquare, {0.5, std::nextafter(0.0, -1.0)}));
  REQUIRE_FALSE(geo::contains(kUnitSquare, {-3.0, 7.0}));
  // A slanted edge: the hypotenuse of x + y <= 1.
  const ConvexPolygon t{{{0, 0}, {1, 0}, {0, 1}}};
  REQUIRE(geo::contains(t, {0.5, 0.5}));
  REQUIRE(geo::contains(t, {0.25, 0.75}));
  REQUIRE_FALSE(geo::contains(t, {0.5, std::nextafter(0.5, 1.0)}));
  REQUIRE_FALSE(geo::contains(t, {0.25, std::nextafter(0.75, 1.0)}));
  REQUIRE(geo::contains(t, {0.25, std::nextafter(0.75, 0.0)}));
}

TEST_CASE("Orientation signs are exact where plain double arithmetic is not", "[protocols]") {
  // Coordinates are integers times 2^-30 below 2^50, so 128-bit integers give the exact sign.
  __extension__ using Int128 = __int128;
  Rng rng(11);
  int disagreements_with_naive = 0;
  for (int k = 0; k < 20000; ++k) {
    auto rand_int = [&](double range) { return std::llround(rng.uniform(-range, range)); };
    // 2^52: the differences themselves may round; 2^20: plain doubles are exact.
    const double big = k % 3 == 0 ? 0x1.0p20 : (k % 3 == 1 ? 0x1.0p49 : 0x1.0p52);
    const long long ax = rand_int(big), ay = rand_int(big), bx = rand_int(big), by = rand_int(big);
    // c near the line ab.
    const double t = rng.uniform(0, 1);
    const long long cx =
        std::llround(static_cast<double>(ax) + t * static_cast<double>(bx - ax)) + rand_int(2);
    const long long cy =
        std::llround(static_cast<double>(ay) + t * static_cast<double>(by - ay)) + rand_int(2);
    const Int128 exact = Int128{bx - ax} * (cy - ay) - Int128{by - ay} * (cx - ax);
    const int expected = (exact > 0) - (exact < 0);
    auto v = [](long long x, long long y) {
      return Vec2(std::ldexp(static_cast<double>(x), -30), std::ldexp(static_cast<double>(y), -30));
    };
    const Vec2 a = v(ax, ay), b = v(bx, by), c = v(cx, cy);
    REQUIRE(geo::orientation(a, b, c) == expected);
    const double naive = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    disagreements_with_naive += ((naive > 0) - (naive < 0)) != expected;
  }
  // The test exercises the exact path: the naive formula gets some of these wrong.
  REQUIRE(disagreements_with_naive > 0);
}

TEST_CASE("A bisector half-plane holds exactly the points nearer its site", "[protocols]") {
  const Vec2 s(0.2, 0.3), o(0.9, -0.4);
  const HalfPlane h = geo::bisector_half_plane(s, o);
  REQUIRE(h.normal.dot(s) < h.offset);
  REQUIRE(h.normal.dot(o) > h.offset);
  REQUIRE(h.normal.dot(0.5 * (s + o)) == Approx(h.offset).margin(1e-15));
  Rng rng(3);
  for (int k = 0; k < 1000; ++k) {
    const Vec2 q(rng.uniform(-2, 2), rng.uniform(-2, 2));
    const double margin = (q - s).squaredNorm() - (q - o).squaredNorm();
    if (std::abs(margin) < 1e-12) continue;
    REQUIRE((h.normal.dot(q) <= h.offset) == (margin < 0));
  }
  // Coincident points: the whole plane.
  const HalfPlane all = geo::bisector_half_plane(s, s);
  REQUIRE(all.normal == Vec2(0, 0));
  REQUIRE(geo::clip(kUnitSquare, all).vertices == kUnitSquare.vertices);
}

TEST_CASE("Clipping the unit square by one bisector leaves the expected half", "[protocols]") {
  const ConvexPolygon left =
      geo::clip(kUnitSquare, geo::bisector_half_plane({0.25, 0.5}, {0.75, 0.5}));
  REQUIRE(same_vertices(left, {{0, 0}, {0.5, 0}, {0.5, 1}, {0, 1}}));
  // The diagonal passes exactly through two corners: a triangle, no duplicated vertex.
  const ConvexPolygon lower = geo::clip(kUnitSquare, geo::bisector_half_plane({0, 0}, {1, 1}));
  REQUIRE(same_vertices(lower, {{0, 0}, {1, 0}, {0, 1}}));
  REQUIRE(geo::area(lower) == 0.5);
}

TEST_CASE("Clipping by a line that only touches or misses the polygon behaves as documented",
          "[protocols]") {
  // Touching a corner from outside: unchanged.
  REQUIRE(geo::clip(kUnitSquare, {{1, 1}, 2.0}).vertices == kUnitSquare.vertices);
  // Everything inside: unchanged; everything outside: empty.
  REQUIRE(geo::clip(kUnitSquare, {{1, 0}, 5.0}).vertices == kUnitSquare.vertices);
  REQUIRE(geo::clip(kUnitSquare, {{1, 0}, -5.0}).empty());
  // Only a corner is kept: a single point is the empty set.
  REQUIRE(geo::clip(kUnitSquare, {{1, 1}, 0.0}).empty());
  // Cuts thinner than the tolerance (≈ 2e-12 here) change nothing or leave nothing.
  REQUIRE(geo::clip(kUnitSquare, {{1, 0}, 1.0 - 1e-14}).vertices == kUnitSquare.vertices);
  REQUIRE(geo::clip(kUnitSquare, {{1, 0}, 1e-14}).empty());
  // A degenerate half-plane 0 <= offset is everything or nothing.
  REQUIRE(geo::clip(kUnitSquare, {{0, 0}, 0.0}).vertices == kUnitSquare.vertices);
  REQUIRE(geo::clip(kUnitSquare, {{0, 0}, -1.0}).empty());
}

TEST_CASE("Clipping near vertices never produces duplicate, collinear or outside vertices",
          "[protocols]") {
  Rng rng(5);
  for (int k = 0; k < 3000; ++k) {
    const ConvexPolygon p = geo::regular_polygon({rng.uniform(-1, 1), rng.uniform(-1, 1)},
                                                 rng.uniform(0.1, 2), 3 + k % 12);
    // A line through one vertex (or through two), nudged by a tiny amount.
    const Vec2& v = p.vertices[static_cast<std::size_t>(k) % p.vertices.size()];
    const Vec2& w = p.vertices[static_cast<std::size_t>(k / 3 + 1) % p.vertices.size()];
    Vec2 normal(rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (k % 3 == 0 && (w - v).norm() > 0) normal = Vec2(-(w - v).y(), (w - v).x());
    const double nudge = std::ldexp(rng.uniform(-1, 1), -static_cast<int>(30 + k % 30));
    const HalfPlane h{normal, normal.dot(v) + nudge};
    const ConvexPolygon q = geo::clip(p, h);
    INFO("case " << k);
    REQUIRE((q.empty() || geo::is_convex_ccw(q.vertices)));
    const double tol = 1e-11 * (std::abs(normal.x()) + std::abs(normal.y()) + std::abs(h.offset));
    for (const Vec2& u : q.vertices) {
      REQUIRE(normal.dot(u) <= h.offset + tol);
      // Within rounding of the original polygon.
      for (std::size_t e = 0; e < p.vertices.size(); ++e) {
        const Vec2 a = p.vertices[e], b = p.vertices[(e + 1) % p.vertices.size()];
        const Vec2 ab = b - a, au = u - a;
        REQUIRE(ab.x() * au.y() - ab.y() * au.x() >= -1e-12 * ab.norm());
      }
    }
    REQUIRE(geo::area(q) <= geo::area(p) * (1 + 1e-12));
  }
}

TEST_CASE("Clipping a sharp corner by a hair leaves no edge shorter than the tolerance",
          "[protocols]") {
  // Apex angle 1e-3: cutting 1e-11 off the apex would create an edge 1e-14 long.
  const ConvexPolygon thin{{{0, 0}, {1, 0}, {1, 1e-3}}};
  const ConvexPolygon cut = geo::clip(thin, {{-1, 0}, -1e-11});
  REQUIRE(cut.vertices.size() == 3);
  REQUIRE(geo::is_convex_ccw(cut.vertices));
  double min_x = 1.0;
  for (const Vec2& v : cut.vertices)
    min_x = std::min(min_x, v.x());
  REQUIRE(min_x == Approx(1e-11).margin(1e-15));
  // The same over many thin triangles and cuts at every depth.
  Rng rng(17);
  for (int k = 0; k < 5000; ++k) {
    const double angle = std::ldexp(1.0, -static_cast<int>(5 + k % 25));
    const Vec2 apex(rng.uniform(-1, 1), rng.uniform(-1, 1));
    const double turn = rng.uniform(0, 2 * std::numbers::pi);
    const Vec2 u(std::cos(turn), std::sin(turn)), w(std::cos(turn + angle), std::sin(turn + angle));
    const auto p = geo::normalize_convex_polygon(std::vector<Vec2>{apex, apex + u, apex + w});
    if (!p) continue;
    const Vec2 axis = (u + w).normalized();
    const double depth = std::ldexp(1.0, -static_cast<int>(20 + k % 30));
    const ConvexPolygon q = geo::clip(*p, {-axis, -axis.dot(apex) - depth});
    INFO("case " << k);
    REQUIRE((q.empty() || geo::is_convex_ccw(q.vertices)));
    double m = 0.0;
    for (const Vec2& v : p->vertices)
      m = std::max({m, std::abs(v.x()), std::abs(v.y())});
    for (std::size_t e = 0; e < q.vertices.size(); ++e)
      REQUIRE((q.vertices[(e + 1) % q.vertices.size()] - q.vertices[e]).norm() >
              geo::kGeometryRelTol * m);
  }
}

TEST_CASE("Gabriel neighbours on a hand-made configuration", "[protocols]") {
  // c sits inside the circle on diameter ab (centre (1, 0), radius 1); d lies on it.
  const Vec2 a(0, 0), b(2, 0), c(1, 0.5), d(1, -1);
  const std::vector<Vec2> sites{a, b, c};
  REQUIRE_FALSE(geo::is_gabriel_neighbour(a, b, sites));
  REQUIRE(geo::is_gabriel_neighbour(a, c, sites));
  REQUIRE(geo::gabriel_neighbours(0, sites) == Ids{2});
  REQUIRE(geo::gabriel_neighbours(1, sites) == Ids{2});
  REQUIRE(geo::gabriel_neighbours(2, sites) == Ids{0, 1});
  // A point exactly on the circle does not block the edge.
  const std::vector<Vec2> on_circle{a, b, d};
  REQUIRE(geo::is_gabriel_neighbour(a, b, on_circle));
  REQUIRE(geo::gabriel_neighbours(0, on_circle) == Ids{1, 2});
  // A point far away does not matter; a point just inside does.
  REQUIRE(geo::is_gabriel_neighbour(a, b, std::vector<Vec2>{{1, 1.0000001}, {5, 5}}));
  REQUIRE_FALSE(geo::is_gabriel_neighbour(a, b, std::vector<Vec2>{{1, 0.9999999}}));
}

TEST_CASE("The row slicer's ends are within its margin of the exact ones on random cells",
          "[protocols]") {
  // Points margin() inside a computed end must be inside as contains() decides, points
  // 2·margin() outside must be out. Random Voronoi cells (tilted edges), the rectangle (flat
  // top and bottom, rows exactly on them) and a sliver with edges almost horizontal.
  Rng rng(11);
  std::vector<ConvexPolygon> polygons{
      geo::rectangle(0.1, 0.2, 0.7, 0.9),
      ConvexPolygon{{Vec2{0, 0.5}, Vec2{1, 0.5 + 1e-9}, Vec2{0.2, 0.5 + 3e-9}}}};
  for (int set = 0; set < 40; ++set) {
    std::vector<Vec2> sites;
    for (int i = 0; i < 12; ++i)
      sites.push_back(Vec2{rng.uniform(), rng.uniform()});
    for (const Cell& cell : geo::voronoi_cells(sites, geo::rectangle(0, 0, 1, 1)))
      polygons.push_back(cell.polygon);
  }
  int tested = 0;
  geo::RowSlicer slicer;
  for (const ConvexPolygon& polygon : polygons) {
    slicer.reset(polygon);
    REQUIRE(slicer.valid());
    const double m = slicer.margin();
    REQUIRE(m < 1e-13);
    std::vector<double> rows{slicer.y_min(), slicer.y_max()};
    for (const Vec2& v : polygon.vertices)
      rows.push_back(v.y());  // rows through vertices
    for (int k = 0; k < 30; ++k)
      rows.push_back(rng.uniform(slicer.y_min(), slicer.y_max()));
    std::sort(rows.begin(), rows.end());
    for (const double y : rows) {
      const auto [left, right] = slicer.extent(y);
      INFO("y " << y << " left " << left << " right " << right);
      REQUIRE(left <= right + 2 * m);
      CHECK_FALSE(geo::contains(polygon, Vec2{left - 2 * m, y}));
      CHECK_FALSE(geo::contains(polygon, Vec2{right + 2 * m, y}));
      if (left + m <= right - m) {
        CHECK(geo::contains(polygon, Vec2{left + m, y}));
        CHECK(geo::contains(polygon, Vec2{right - m, y}));
        ++tested;
      }
    }
  }
  CHECK(tested > 10000);
  // Fewer than three vertices, or no height: not a polygon to slice.
  slicer.reset(ConvexPolygon{{Vec2{0, 0}, Vec2{1, 1}}});
  CHECK_FALSE(slicer.valid());
  slicer.reset(ConvexPolygon{{Vec2{0, 0.5}, Vec2{1, 0.5}, Vec2{0.5, 0.5}}});
  CHECK_FALSE(slicer.valid());
}

TEST_CASE(
    "Convex membership answers exactly as contains() for points in rows, in any order and on the "
    "boundary",
    "[protocols]") {
  // The prepared test decides most points from a row's extent and its margin; a wrong margin,
  // a stale row or a chain not rewound when rows go down would disagree with the exact test
  // somewhere among these: sensor rows in id order, the same points shuffled, every vertex,
  // points on edges and one ulp either side of them.
  Rng rng(5);
  std::vector<ConvexPolygon> polygons{
      geo::rectangle(0.1, 0.2, 0.7, 0.9),
      ConvexPolygon{{Vec2{0, 0.5}, Vec2{1, 0.5 + 1e-9}, Vec2{0.2, 0.5 + 3e-9}}},
      ConvexPolygon{{Vec2{0, 0}, Vec2{1, 1}}},                       // not a polygon
      ConvexPolygon{{Vec2{0, 0.5}, Vec2{1, 0.5}, Vec2{0.5, 0.5}}}};  // no height
  for (int set = 0; set < 20; ++set) {
    std::vector<Vec2> sites;
    for (int i = 0; i < 10; ++i)
      sites.push_back(Vec2{rng.uniform(), rng.uniform()});
    for (const Cell& cell : geo::voronoi_cells(sites, geo::rectangle(0, 0, 1, 1)))
      polygons.push_back(cell.polygon);
  }
  std::vector<Vec2> points;  // a 40 × 40 cell-centred grid, row by row
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i)
      points.push_back(Vec2{(i + 0.5) / 40, (j + 0.5) / 40});
  std::vector<Vec2> shuffled = points;
  std::shuffle(shuffled.begin(), shuffled.end(), rng.engine);
  geo::ConvexMembership membership;
  std::size_t inside = 0, boundary = 0;
  for (const ConvexPolygon& polygon : polygons) {
    std::vector<Vec2> edge_points;
    const auto& v = polygon.vertices;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const Vec2 a = v[i], b = v[(i + 1) % v.size()];
      for (const double t : {0.0, 0.25, 0.5}) {
        const Vec2 p = a + t * (b - a);
        edge_points.push_back(p);
        edge_points.push_back(Vec2{std::nextafter(p.x(), -1.0), p.y()});
        edge_points.push_back(Vec2{std::nextafter(p.x(), 2.0), p.y()});
      }
    }
    membership.reset(polygon.vertices);
    for (const std::vector<Vec2>* list : {&points, &shuffled, &edge_points, &points})
      for (const Vec2& p : *list) {
        const bool exact = geo::contains(polygon, p);
        INFO("point (" << p.x() << ", " << p.y() << ") in a polygon of " << v.size()
                       << " vertices");
        REQUIRE(membership.contains(p) == exact);
        inside += exact ? 1 : 0;
        boundary += list == &edge_points && exact ? 1 : 0;
      }
  }
  CHECK(inside > 10000);
  CHECK(boundary > 1000);
}
