// The computation-load counts of the cell builder (docs/protocols.md, "Computation load"):
// every bisector or disk side the builder clips by is one clip, every candidate it dismisses
// is none. The expected numbers are derived from the layout, not read from the builder.
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
using masnet::protocols::Cell;
using masnet::protocols::Vec2;
namespace geo = masnet::protocols;

const Vec2 kCentre{0.5, 0.5};

// Site 0 at the centre, then k sites at distance 0.2 at angles 2πj/k: the cell is the regular
// k-gon of apothem 0.1, circumradius 0.1 / cos(π/k).
std::vector<Vec2> ring(int k) {
  std::vector<Vec2> sites{kCentre};
  for (int j = 0; j < k; ++j) {
    const double angle = 2.0 * std::numbers::pi * j / k;
    sites.push_back(kCentre + 0.2 * Vec2{std::cos(angle), std::sin(angle)});
  }
  return sites;
}

Ids ring_ids(int k) {
  Ids ids;
  for (int j = 1; j <= k; ++j)
    ids.push_back(static_cast<std::uint32_t>(j));
  return ids;
}

}  // namespace

TEST_CASE("Building a cell from k neighbour sites costs k clips, plus one per disk side",
          "[protocols]") {
  for (int k = 3; k <= 8; ++k) {
    INFO("k = " << k);
    std::vector<Vec2> sites = ring(k);
    // Every ring site is within twice the farthest vertex at its turn (the cell never gets
    // smaller than the final k-gon, whose circumradius exceeds 0.1): each one is clipped.
    const Cell plain = geo::voronoi_cell(0, sites, ring_ids(k), kUnitSquare);
    CHECK(plain.neighbours.size() == static_cast<std::size_t>(k));
    CHECK(plain.half_plane_clips == static_cast<std::uint32_t>(k));

    // A site 0.45 away: clipped while the cell is still the square (reach √0.5), dismissed
    // after the ring (4 · circumradius² <= 0.16 < 0.45²).
    sites.push_back(kCentre + Vec2{0.45, 0.0});
    const auto far = static_cast<std::uint32_t>(k + 1);
    Ids ring_then_far = ring_ids(k), far_then_ring{far};
    ring_then_far.push_back(far);
    far_then_ring.insert(far_then_ring.end(), ring_then_far.begin(), ring_then_far.end() - 1);
    CHECK(geo::voronoi_cell(0, sites, ring_then_far, kUnitSquare).half_plane_clips ==
          static_cast<std::uint32_t>(k));
    CHECK(geo::voronoi_cell(0, sites, far_then_ring, kUnitSquare).half_plane_clips ==
          static_cast<std::uint32_t>(k + 1));

    // The site itself and a coincident copy are no clip; a repeated candidate is clipped again.
    sites.push_back(kCentre);
    const auto copy = static_cast<std::uint32_t>(k + 2);
    Ids with_self = ring_ids(k);
    with_self.insert(with_self.end(), {0, copy, 1});
    CHECK(geo::voronoi_cell(0, sites, with_self, kUnitSquare).half_plane_clips ==
          static_cast<std::uint32_t>(k + 1));
    // The copy's cell: its lower-index twin empties it at once, and nothing more is clipped.
    CHECK(geo::voronoi_cell(copy, sites, Ids{0, 1, 2}, kUnitSquare).half_plane_clips == 0);

    // A disk inside the k-gon (radius 0.05 < apothem): all kDiskSides sides clip. A disk past
    // the farthest vertex (0.3 > 0.2 >= circumradius): no side is tried.
    CHECK(geo::voronoi_cell(0, sites, ring_ids(k), kUnitSquare, 0.05).half_plane_clips ==
          static_cast<std::uint32_t>(k + geo::kDiskSides));
    CHECK(geo::voronoi_cell(0, sites, ring_ids(k), kUnitSquare, 0.3).half_plane_clips ==
          static_cast<std::uint32_t>(k));
  }
  // No domain, no disk: nothing is built.
  CHECK(geo::voronoi_cell(0, ring(4), ring_ids(4), geo::ConvexPolygon{}).half_plane_clips == 0);
  CHECK(geo::voronoi_cell(0, ring(4), ring_ids(4), kUnitSquare, 0.0).half_plane_clips == 0);
}

TEST_CASE("Every bisector that bounds a cell was clipped by, and no candidate twice",
          "[protocols]") {
  Rng rng(11);
  std::vector<Vec2> sites;
  for (int i = 0; i < 200; ++i)
    sites.push_back(Vec2{rng.uniform(), rng.uniform()});
  const std::vector<Cell> cells = geo::voronoi_cells(sites, kUnitSquare);
  std::uint64_t clips = 0;
  for (const Cell& cell : cells) {
    CHECK(cell.half_plane_clips >= cell.neighbours.size());
    CHECK(cell.half_plane_clips < sites.size());  // each other site at most once
    clips += cell.half_plane_clips;
  }
  // The grid's ring search keeps a uniform layout at O(1) clips a cell.
  CHECK(clips < 30 * sites.size());
}
