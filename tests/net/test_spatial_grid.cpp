// The uniform grid's range query against a scan of every point, slot by slot.
#include <catch2/catch.hpp>

#include <vector>

#include "net/spatial_grid.hpp"
#include "sim/random.hpp"

using namespace masnet;
using net::Vec2;

TEST_CASE("a grid query visits exactly the points a full scan finds, in slot order, with their d2",
          "[net]") {
  // Cells of many points (runs of slots longer than the 64 tested at a time, with odd tails) and
  // of few; centres anywhere, radii from 0 to past the square; lattice points exactly on the
  // circle (equality decides the same way in every lane).
  for (int layout = 0; layout < 12; ++layout) {
    sim::RandomStream rng(static_cast<std::uint64_t>(100 + layout));
    const bool lattice = layout % 3 == 0;
    const std::size_t n = 50 + static_cast<std::size_t>(rng.below(900));
    std::vector<Vec2> points;
    std::vector<sim::NodeId> ids;
    for (std::size_t i = 0; i < n; ++i) {
      points.push_back(lattice ? Vec2{0.05 * static_cast<double>(rng.below(21)),
                                      0.05 * static_cast<double>(rng.below(21))}
                               : Vec2{rng.uniform01(), rng.uniform01()});
      ids.push_back(sim::node_id(static_cast<std::uint32_t>(i)));
    }
    net::SpatialGrid grid;
    grid.build(points, ids, layout % 2 == 0 ? 0.0 : 0.5);  // ~4 points per cell, or hundreds
    // The indexed positions, by slot (the grid copies them in cell order).
    std::vector<Vec2> by_slot(n);
    grid.for_each_slot_within(Vec2{0.5, 0.5}, 10.0, [&](std::uint32_t k, double) {
      by_slot[k] = points[sim::index(grid.ids()[k])];
    });
    for (int q = 0; q < 200; ++q) {
      const Vec2 c = lattice && q % 2 == 0 ? points[rng.below(n)]
                                           : Vec2{rng.uniform(-0.2, 1.2), rng.uniform(-0.2, 1.2)};
      const double radius =
          lattice && q % 4 == 0 ? 0.05 * static_cast<double>(rng.below(8)) : rng.uniform(0.0, 1.6);
      std::vector<std::pair<std::uint32_t, double>> expected, got;
      for (std::uint32_t k = 0; k < n; ++k) {
        const double dx = by_slot[k].x() - c.x(), dy = by_slot[k].y() - c.y();
        const double d2 = dx * dx + dy * dy;
        if (d2 <= radius * radius) expected.emplace_back(k, d2);
      }
      grid.for_each_slot_within(c, radius,
                                [&](std::uint32_t k, double d2) { got.emplace_back(k, d2); });
      INFO("layout " << layout << " query " << q);
      REQUIRE(got == expected);
    }
  }
}
