// voronoi_cells (grid rings, skipped buckets, shortcuts in the clipper) against the brute force:
// voronoi_cell of each site with every other site as a candidate, nearest first. Random
// layouts and degenerate ones: cocircular sites on a grid, duplicates, collinear sites.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <string>
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
using masnet::protocols::Vec2;
namespace geo = masnet::protocols;

// Every cell equals the brute-force cell: same neighbours, same emptiness, vertices within
// 1e-12 (the clips come in another order, so the last bits may differ).
void require_brute_force(const std::vector<Vec2>& sites, const geo::ConvexPolygon& domain) {
  const std::vector<Cell> cells = geo::voronoi_cells(sites, domain);
  REQUIRE(cells.size() == sites.size());
  const auto n = static_cast<std::uint32_t>(sites.size());
  for (std::uint32_t i = 0; i < n; ++i) {
    Ids others(n);
    std::iota(others.begin(), others.end(), 0u);
    std::stable_sort(others.begin(), others.end(), [&](std::uint32_t a, std::uint32_t b) {
      return (sites[a] - sites[i]).squaredNorm() < (sites[b] - sites[i]).squaredNorm();
    });
    const Cell expected = geo::voronoi_cell(i, sites, others, domain);
    INFO("site " << i << " at " << sites[i].x() << ", " << sites[i].y());
    REQUIRE(cells[i].neighbours == expected.neighbours);
    REQUIRE(cells[i].polygon.empty() == expected.polygon.empty());
    if (!expected.polygon.empty())
      REQUIRE(same_vertices(cells[i].polygon, expected.polygon.vertices, 1e-12));
    REQUIRE(!cells[i].truncated);
    // Each other site is clipped by at most once, and every neighbour was clipped by.
    REQUIRE(cells[i].half_plane_clips < n);
    REQUIRE(cells[i].half_plane_clips >= cells[i].neighbours.size());
  }
}

std::vector<Vec2> uniform(Rng& rng, int n, double lo, double hi) {
  std::vector<Vec2> sites;
  for (int k = 0; k < n; ++k)
    sites.push_back(Vec2{rng.uniform(lo, hi), rng.uniform(lo, hi)});
  return sites;
}

std::vector<Vec2> grid(int side) {
  std::vector<Vec2> sites;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i)
      sites.push_back(Vec2{(i + 0.5) / side, (j + 0.5) / side});
  return sites;
}

}  // namespace

TEST_CASE("All cells match the brute force on uniform random sites", "[protocols]") {
  Rng rng(20261203);
  for (int n : {2, 3, 10, 57, 300, 1000}) {
    INFO(n << " sites");
    require_brute_force(uniform(rng, n, 0.0, 1.0), kUnitSquare);
  }
  // Sites spilling out of the domain, and a pentagon domain.
  require_brute_force(uniform(rng, 200, -0.5, 1.5), kUnitSquare);
  const auto pentagon = geo::normalize_convex_polygon(
      std::vector<Vec2>{{0.5, 0.0}, {1.0, 0.4}, {0.8, 1.0}, {0.2, 1.0}, {0.0, 0.4}});
  REQUIRE(pentagon.has_value());
  require_brute_force(uniform(rng, 300, 0.0, 1.0), *pentagon);
}

TEST_CASE("All cells match the brute force on cocircular sites of a grid", "[protocols]") {
  for (int side : {2, 3, 7, 20})
    require_brute_force(grid(side), kUnitSquare);
  // Sites snapped to a coarse lattice: many cocircular quadruples and some duplicates.
  Rng rng(7);
  std::vector<Vec2> snapped;
  for (int k = 0; k < 400; ++k)
    snapped.push_back(
        Vec2{std::round(rng.uniform() * 12) / 12, std::round(rng.uniform() * 12) / 12});
  require_brute_force(snapped, kUnitSquare);
}

TEST_CASE("All cells match the brute force with duplicate sites", "[protocols]") {
  Rng rng(11);
  std::vector<Vec2> sites = uniform(rng, 150, 0.0, 1.0);
  for (int k = 0; k < 40; ++k)
    sites.push_back(sites[static_cast<std::size_t>(rng.uniform() * 150)]);
  std::shuffle(sites.begin(), sites.end(), rng.engine);
  require_brute_force(sites, kUnitSquare);
  // Every copy after the first of a site gets the empty cell.
  const std::vector<Cell> cells = geo::voronoi_cells(sites, kUnitSquare);
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const bool earlier_copy =
        std::find(sites.begin(), sites.begin() + static_cast<std::ptrdiff_t>(i), sites[i]) !=
        sites.begin() + static_cast<std::ptrdiff_t>(i);
    REQUIRE(cells[i].polygon.empty() == earlier_copy);
  }
  require_brute_force(std::vector<Vec2>(9, Vec2{0.3, 0.6}), kUnitSquare);
  require_brute_force(grid(5), kUnitSquare);
}

TEST_CASE("All cells match the brute force on collinear sites", "[protocols]") {
  Rng rng(3);
  std::vector<Vec2> horizontal, diagonal, vertical;
  for (int k = 0; k < 60; ++k) {
    horizontal.push_back(Vec2{rng.uniform(), 0.5});
    const double t = rng.uniform();
    diagonal.push_back(Vec2{t, t});
    vertical.push_back(Vec2{0.25, k / 59.0});
  }
  require_brute_force(horizontal, kUnitSquare);
  require_brute_force(diagonal, kUnitSquare);
  require_brute_force(vertical, kUnitSquare);
}
