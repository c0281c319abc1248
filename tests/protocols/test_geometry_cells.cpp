// Hand-computed cases and invariants of bounded Voronoi cells (protocols/geometry): neighbours,
// coincident, collinear and cocircular sites, the disk and its truncation, nearest-site
// membership and degenerate site sets.
#include <algorithm>
#include <cmath>
#include <cstdint>
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
using masnet::protocols::Vec2;
namespace geo = masnet::protocols;

Ids all_but(std::uint32_t n, std::uint32_t skip) {
  Ids ids;
  for (std::uint32_t k = 0; k < n; ++k)
    if (k != skip) ids.push_back(k);
  return ids;
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
