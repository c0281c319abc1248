// Hand-computed cases and invariants of protocols/geometry: polygons, clipping, cells,
// integrals, point location, the Gabriel test and degenerate inputs.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "protocols/geometry.hpp"

namespace {

using masnet::protocols::Cell;
using masnet::protocols::ConvexPolygon;
using masnet::protocols::HalfPlane;
using masnet::protocols::Vec2;
namespace geo = masnet::protocols;

using Ids = std::vector<std::uint32_t>;

struct Rng {
  std::mt19937_64 engine;
  explicit Rng(std::uint64_t seed) : engine(seed) {}
  double uniform() { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
};

const ConvexPolygon kUnitSquare = geo::rectangle(0.0, 0.0, 1.0, 1.0);

Ids all_but(std::uint32_t n, std::uint32_t skip) {
  Ids ids;
  for (std::uint32_t k = 0; k < n; ++k)
    if (k != skip) ids.push_back(k);
  return ids;
}

bool same_vertices(const ConvexPolygon& p, const std::vector<Vec2>& expected, double tol = 1e-15) {
  if (p.vertices.size() != expected.size()) return false;
  // Same cyclic sequence, starting anywhere.
  for (std::size_t shift = 0; shift < expected.size(); ++shift) {
    bool all = true;
    for (std::size_t k = 0; k < expected.size() && all; ++k)
      all = (p.vertices[(k + shift) % expected.size()] - expected[k]).norm() <= tol;
    if (all) return true;
  }
  return false;
}

bool finite(const Vec2& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y());
}

// Everything a cell may be asked for is a number, and the polygon is canonical or empty.
void require_sane(const Cell& cell, const Vec2& site) {
  REQUIRE((cell.polygon.empty() || geo::is_convex_ccw(cell.polygon.vertices)));
  for (const Vec2& v : cell.polygon.vertices)
    REQUIRE(finite(v));
  REQUIRE(std::isfinite(geo::area(cell.polygon)));
  REQUIRE(finite(geo::centroid(cell.polygon)));
  REQUIRE(std::isfinite(geo::polar_moment(cell.polygon, site)));
  REQUIRE(std::isfinite(geo::max_vertex_distance(cell.polygon, site)));
  REQUIRE(std::is_sorted(cell.neighbours.begin(), cell.neighbours.end()));
}

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

TEST_CASE("Three sites split the square into three cells meeting at their circumcentre",
          "[protocols]") {
  const std::vector<Vec2> sites{{0.25, 0.25}, {0.75, 0.25}, {0.5, 0.75}};
  const std::vector<Cell> cells = geo::voronoi_cells(sites, kUnitSquare);
  // The circumcentre is (0.5, 0.4375); the bisector of sites 0 and 2 meets x = 0 at y = 0.6875.
  REQUIRE(same_vertices(cells[0].polygon, {{0, 0}, {0.5, 0}, {0.5, 0.4375}, {0, 0.6875}}));
  REQUIRE(same_vertices(cells[1].polygon, {{0.5, 0}, {1, 0}, {1, 0.6875}, {0.5, 0.4375}}));
  REQUIRE(geo::area(cells[0].polygon) == Approx(0.28125).epsilon(1e-15));
  REQUIRE(geo::area(cells[1].polygon) == Approx(0.28125).epsilon(1e-15));
  REQUIRE(geo::area(cells[2].polygon) == Approx(0.4375).epsilon(1e-15));
  REQUIRE(cells[0].neighbours == Ids{1, 2});
  REQUIRE(cells[1].neighbours == Ids{0, 2});
  REQUIRE(cells[2].neighbours == Ids{0, 1});
}

TEST_CASE("Cocircular sites meet at one vertex and sites touching at a point are not neighbours",
          "[protocols]") {
  SECTION("four sites on a square") {
    const std::vector<Vec2> sites{{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}, {0.25, 0.75}};
    const auto cells = geo::voronoi_cells(sites, kUnitSquare);
    REQUIRE(cells[0].neighbours == Ids{1, 3});
    REQUIRE(cells[1].neighbours == Ids{0, 2});
    REQUIRE(cells[2].neighbours == Ids{1, 3});
    REQUIRE(cells[3].neighbours == Ids{0, 2});
    for (const Cell& c : cells)
      REQUIRE(geo::area(c.polygon) == 0.25);
  }
  SECTION("n sites on a circle through rounded sines and cosines") {
    for (int n : {4, 5, 8, 12, 33}) {
      for (double phase : {0.0, 0.1, 0.7853981633974483, 1.234}) {
        std::vector<Vec2> sites;
        for (int k = 0; k < n; ++k) {
          const double angle = phase + 2.0 * std::numbers::pi * k / n;
          sites.emplace_back(0.5 + 0.3 * std::cos(angle), 0.5 + 0.3 * std::sin(angle));
        }
        const auto cells = geo::voronoi_cells(sites, kUnitSquare);
        double total = 0.0;
        for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(n); ++k) {
          INFO("n = " << n << ", phase " << phase << ", site " << k);
          const auto prev = (k + static_cast<std::uint32_t>(n) - 1) % static_cast<std::uint32_t>(n);
          const auto next = (k + 1) % static_cast<std::uint32_t>(n);
          Ids expected{prev, next};
          std::sort(expected.begin(), expected.end());
          REQUIRE(cells[k].neighbours == expected);
          require_sane(cells[k], sites[k]);
          total += geo::area(cells[k].polygon);
        }
        REQUIRE(total == Approx(1.0).epsilon(1e-12));
      }
    }
  }
}

TEST_CASE("Of two coincident sites the lower index keeps the cell", "[protocols]") {
  const std::vector<Vec2> sites{{0.3, 0.3}, {0.7, 0.7}, {0.3, 0.3}, {0.7, 0.7}};
  const auto cells = geo::voronoi_cells(sites, kUnitSquare);
  REQUIRE_FALSE(cells[0].polygon.empty());
  REQUIRE_FALSE(cells[1].polygon.empty());
  REQUIRE(cells[2].polygon.empty());
  REQUIRE(cells[3].polygon.empty());
  REQUIRE(cells[2].neighbours.empty());
  REQUIRE(cells[0].neighbours == Ids{1});
  REQUIRE(cells[1].neighbours == Ids{0});
  REQUIRE(geo::area(cells[0].polygon) + geo::area(cells[1].polygon) == Approx(1.0));
  for (std::uint32_t k = 0; k < 4; ++k)
    require_sane(cells[k], sites[k]);
  // Candidate order does not matter.
  REQUIRE(geo::voronoi_cell(2, sites, Ids{3, 1, 0}, kUnitSquare).polygon.empty());
  REQUIRE(geo::voronoi_cell(0, sites, Ids{2, 3, 1}, kUnitSquare).neighbours == Ids{1});
  // Five copies of one point: the first owns the whole square.
  const std::vector<Vec2> same(5, Vec2(0.4, 0.6));
  const auto copies = geo::voronoi_cells(same, kUnitSquare);
  REQUIRE(geo::area(copies[0].polygon) == 1.0);
  for (std::size_t k = 1; k < 5; ++k)
    REQUIRE(copies[k].polygon.empty());
}

TEST_CASE("Collinear sites give strips", "[protocols]") {
  const std::vector<Vec2> sites{{0.1, 0.5}, {0.3, 0.5}, {0.6, 0.5}, {0.9, 0.5}};
  const auto cells = geo::voronoi_cells(sites, kUnitSquare);
  const double expected[] = {0.2, 0.25, 0.3, 0.25};
  for (std::size_t k = 0; k < 4; ++k) {
    REQUIRE(geo::area(cells[k].polygon) == Approx(expected[k]).epsilon(1e-14));
    REQUIRE(cells[k].polygon.vertices.size() == 4);
  }
  REQUIRE(cells[0].neighbours == Ids{1});
  REQUIRE(cells[1].neighbours == Ids{0, 2});
  REQUIRE(cells[2].neighbours == Ids{1, 3});
  REQUIRE(cells[3].neighbours == Ids{2});
}

TEST_CASE("A site on the boundary or outside the domain gets the domain part nearest to it",
          "[protocols]") {
  SECTION("on an edge and in a corner") {
    const std::vector<Vec2> sites{{0.0, 0.5}, {1.0, 0.5}};
    const auto cells = geo::voronoi_cells(sites, kUnitSquare);
    REQUIRE(same_vertices(cells[0].polygon, {{0, 0}, {0.5, 0}, {0.5, 1}, {0, 1}}));
    const std::vector<Vec2> corners{{0.0, 0.0}, {1.0, 1.0}};
    REQUIRE(same_vertices(geo::voronoi_cells(corners, kUnitSquare)[0].polygon,
                          {{0, 0}, {1, 0}, {0, 1}}));
  }
  SECTION("outside") {
    const std::vector<Vec2> sites{{-0.1, 0.5}, {0.5, 0.5}, {-3.0, 0.5}};
    const auto cells = geo::voronoi_cells(sites, kUnitSquare);
    REQUIRE(geo::area(cells[0].polygon) == Approx(0.2).epsilon(1e-14));  // bisector x = 0.2
    REQUIRE(cells[2].polygon.empty());  // every point of the square is nearer another site
    REQUIRE(cells[0].neighbours == Ids{1});
    // Alone, an outside site owns the whole domain, unless its disk misses the domain.
    REQUIRE(geo::area(geo::voronoi_cell(2, sites, Ids{}, kUnitSquare).polygon) == 1.0);
    REQUIRE(geo::voronoi_cell(2, sites, Ids{}, kUnitSquare, 1.0).polygon.empty());
  }
}

TEST_CASE("With no candidates the cell is the domain cut by the 64-gon of the disk",
          "[protocols]") {
  const std::vector<Vec2> sites{{0.5, 0.5}};
  const double t = std::tan(std::numbers::pi / geo::kDiskSides);
  SECTION("a small disk") {
    const Cell c = geo::voronoi_cell(0, sites, Ids{}, kUnitSquare, 0.2);
    REQUIRE(c.truncated);
    REQUIRE(c.neighbours.empty());
    REQUIRE(c.polygon.vertices.size() == static_cast<std::size_t>(geo::kDiskSides));
    REQUIRE(geo::area(c.polygon) == Approx(geo::kDiskSides * 0.04 * t).epsilon(1e-12));
  }
  SECTION("a disk tangent to the domain's sides") {
    const Cell c = geo::voronoi_cell(0, sites, Ids{}, kUnitSquare, 0.5);
    REQUIRE(c.truncated);
    REQUIRE(geo::area(c.polygon) == Approx(geo::kDiskSides * 0.25 * t).epsilon(1e-12));
  }
  SECTION("a disk containing the domain") {
    const Cell c = geo::voronoi_cell(0, sites, Ids{}, kUnitSquare, 0.75);
    REQUIRE_FALSE(c.truncated);
    REQUIRE(c.polygon.vertices == kUnitSquare.vertices);
  }
  SECTION("a disk cutting only the corners") {
    const Cell c = geo::voronoi_cell(0, sites, Ids{}, kUnitSquare, 0.6);
    REQUIRE(c.truncated);
    REQUIRE(geo::area(c.polygon) < 1.0);
    REQUIRE(geo::area(c.polygon) > std::numbers::pi * 0.25);  // holds the inscribed disk
  }
  SECTION("a non-positive radius") {
    REQUIRE(geo::voronoi_cell(0, sites, Ids{}, kUnitSquare, 0.0).polygon.empty());
    REQUIRE(geo::voronoi_cell(0, sites, Ids{}, kUnitSquare, std::nan("")).polygon.empty());
  }
}

TEST_CASE("The truncated flag is set only when the disk gives the cell an edge", "[protocols]") {
  // A 3×3 lattice: the centre cell is [1/3, 2/3]², its bisectors 1/6 from the site.
  std::vector<Vec2> sites;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      sites.emplace_back((c + 0.5) / 3, (r + 0.5) / 3);
  const Ids others = all_but(9, 4);
  const Cell wide = geo::voronoi_cell(4, sites, others, kUnitSquare, 1.0);
  REQUIRE_FALSE(wide.truncated);
  REQUIRE(wide.neighbours == Ids{1, 3, 5, 7});
  REQUIRE(geo::area(wide.polygon) == Approx(1.0 / 9));
  // Radius 0.1 < 1/6: only the disk bounds the cell.
  const Cell small = geo::voronoi_cell(4, sites, others, kUnitSquare, 0.1);
  REQUIRE(small.truncated);
  REQUIRE(small.neighbours.empty());
  // A domain whose corners are just 0.1% beyond the radius (on the 45° normals of the 64-gon).
  const double a = 0.2 * 1.001 / std::sqrt(2.0);
  const Cell corners =
      geo::voronoi_cell(4, sites, Ids{}, geo::rectangle(0.5 - a, 0.5 - a, 0.5 + a, 0.5 + a), 0.2);
  REQUIRE(corners.truncated);
  REQUIRE(corners.polygon.vertices.size() == 8);  // one 64-gon side cuts each corner
  REQUIRE(geo::max_vertex_distance(corners.polygon, sites[4]) < 0.2 * 1.001);
  // Radius 0.2: the square's sides and the disk's arcs near the corners both appear.
  const Cell mixed = geo::voronoi_cell(4, sites, others, kUnitSquare, 0.2);
  REQUIRE(mixed.truncated);
  REQUIRE(mixed.neighbours == Ids{1, 3, 5, 7});
}

TEST_CASE("A cell is exact once the disk radius reaches twice its farthest vertex", "[protocols]") {
  Rng rng(9);
  for (int s = 0; s < 100; ++s) {
    const auto n = static_cast<std::uint32_t>(5 + s % 40);
    std::vector<Vec2> sites;
    for (std::uint32_t k = 0; k < n; ++k)
      sites.emplace_back(rng.uniform(), rng.uniform());
    const auto exact = geo::voronoi_cells(sites, kUnitSquare);
    for (std::uint32_t i = 0; i < n; ++i) {
      const double radius = 2.0 * geo::max_vertex_distance(exact[i].polygon, sites[i]) * (1 + 1e-9);
      Ids heard;  // as if replies came only from sites within the radius
      for (std::uint32_t j = 0; j < n; ++j)
        if (j != i && (sites[j] - sites[i]).norm() <= radius) heard.push_back(j);
      const Cell c = geo::voronoi_cell(i, sites, heard, kUnitSquare, radius);
      REQUIRE_FALSE(c.truncated);
      REQUIRE(c.neighbours == exact[i].neighbours);
      REQUIRE(geo::area(c.polygon) == Approx(geo::area(exact[i].polygon)).margin(1e-12));
      // A smaller radius gives a subset of the disk, still containing the exact cell ∩ disk.
      const Cell cut = geo::voronoi_cell(i, sites, heard, kUnitSquare, radius / 4);
      REQUIRE(geo::max_vertex_distance(cut.polygon, sites[i]) <= radius / 4 * 1.0013);
      REQUIRE(geo::area(cut.polygon) <= geo::area(exact[i].polygon) + 1e-12);
    }
  }
}

TEST_CASE("Random points lie in the cell of their nearest site", "[protocols]") {
  Rng rng(13);
  for (int s = 0; s < 50; ++s) {
    const auto n = static_cast<std::uint32_t>(2 + s);
    std::vector<Vec2> sites;
    for (std::uint32_t k = 0; k < n; ++k)
      sites.emplace_back(rng.uniform(), rng.uniform());
    const auto cells = geo::voronoi_cells(sites, kUnitSquare);
    for (int k = 0; k < 200; ++k) {
      const Vec2 q(rng.uniform(), rng.uniform());
      std::uint32_t best = 0;
      for (std::uint32_t j = 1; j < n; ++j)
        if ((q - sites[j]).squaredNorm() < (q - sites[best]).squaredNorm()) best = j;
      // Skip points within rounding of a bisector.
      bool near_tie = false;
      for (std::uint32_t j = 0; j < n; ++j)
        near_tie =
            near_tie || (j != best && (q - sites[j]).norm() - (q - sites[best]).norm() < 1e-9);
      if (near_tie) continue;
      REQUIRE(geo::contains(cells[best].polygon, q));
      for (std::uint32_t j = 0; j < n; ++j)
        if (j != best) REQUIRE_FALSE(geo::contains(cells[j].polygon, q));
    }
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

TEST_CASE("Degenerate and extreme site sets give finite cells that partition the domain",
          "[protocols]") {
  const std::vector<std::vector<Vec2>> sets{
      {{0.5, 0.5}},
      {{0.5, 0.5}, {0.5, 0.5 + 1e-200}},  // 0.5 + 1e-200 == 0.5: coincident
      {{0.5, 0.5}, {0.5, std::nextafter(0.5, 1.0)}, {0.5, std::nextafter(0.5, 0.0)}},
      {{0.5, 0.5}, {0.5 + 1e-15, 0.5}, {0.5, 0.5 - 1e-15}},
      {{0.2, 0.1}, {0.2, 0.2}, {0.2, 0.3}, {0.2, 0.9}},
      {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}},
      {{0, 0}, {0, 0}, {1e-300, 0}, {1, 1}},
      {{1e6, 1e6}, {-1e6, 3.0}, {0.5, 0.5}},
  };
  for (std::size_t s = 0; s < sets.size(); ++s) {
    INFO("set " << s);
    const auto& sites = sets[s];
    const auto cells = geo::voronoi_cells(sites, kUnitSquare);
    double total = 0.0;
    for (std::uint32_t k = 0; k < sites.size(); ++k) {
      require_sane(cells[k], sites[k]);
      total += geo::area(cells[k].polygon);
      for (double radius : {1e-9, 0.1, 1.0})
        require_sane(
            geo::voronoi_cell(k, sites, all_but(static_cast<std::uint32_t>(sites.size()), k),
                              kUnitSquare, radius),
            sites[k]);
    }
    REQUIRE(total == Approx(1.0).epsilon(1e-12));
  }
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
