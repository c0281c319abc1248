// The cell of the positions an update heard (protocols/heard_cell.hpp), the judge of
// protocol.cell_correctness_heard.
#include <catch2/catch.hpp>

#include <set>
#include <utility>
#include <vector>

#include "protocols/heard_cell.hpp"
#include "sim/random.hpp"

using namespace masnet;
using namespace masnet::protocols;
using net::Vec2;
using sim::NodeId;

namespace {

std::vector<NodeId> ids(std::initializer_list<std::uint32_t> indices) {
  std::vector<NodeId> out;
  for (std::uint32_t i : indices)
    out.push_back(sim::node_id(i));
  return out;
}

}  // namespace

TEST_CASE("the heard cell is bounded by the heard robots whose bisectors give it an edge",
          "[protocols]") {
  // Robot 0 at the centre of the unit square; 1 east and 2 south bound its cell, 3 is hidden
  // behind them (its bisector x − y = 0.45 misses the corner (0.71875, 0.3125)).
  const std::vector<HeardRobot> heard = {{sim::node_id(3), Vec2{0.95, 0.05}},
                                         {sim::node_id(1), Vec2{0.9375, 0.5}},
                                         {sim::node_id(2), Vec2{0.5, 0.125}}};
  CHECK(heard_neighbours(Vec2{0.5, 0.5}, heard, rectangle(0, 0, 1, 1)) == ids({1, 2}));
  CHECK(heard_neighbours(Vec2{0.5, 0.5}, {}, rectangle(0, 0, 1, 1)).empty());
  // Four robots on a square grid: the diagonal one meets the corner robot's cell in one point.
  const std::vector<HeardRobot> grid = {{sim::node_id(4), Vec2{0.75, 0.75}},
                                        {sim::node_id(1), Vec2{0.75, 0.25}},
                                        {sim::node_id(2), Vec2{0.25, 0.75}}};
  CHECK(heard_neighbours(Vec2{0.25, 0.25}, grid, rectangle(0, 0, 1, 1)) == ids({1, 2}));
}

TEST_CASE(
    "the heard cell does not depend on the order the replies came in, where clipping order decides "
    "an edge",
    "[protocols]") {
  // A 3 × 3 grid moved by 1e-12 (the geometry's tolerance): the centre's cell has corners where
  // four cells almost meet, and whether a diagonal robot keeps a sub-tolerance edge depends on
  // the order the bisectors clip. voronoi_cell shows it; heard_neighbours must not.
  sim::RandomStream rng(11);
  std::vector<Vec2> sites;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      sites.push_back(Vec2{(i + 0.5) / 3 + 1e-12 * rng.uniform(-1, 1),
                           (j + 0.5) / 3 + 1e-12 * rng.uniform(-1, 1)});
  const ConvexPolygon domain = rectangle(0, 0, 1, 1);
  std::vector<std::uint32_t> order = {0, 1, 2, 3, 5, 6, 7, 8};
  std::set<std::vector<std::uint32_t>> by_clipping_order;
  std::set<std::vector<NodeId>> heard_sets;
  for (int trial = 0; trial < 200; ++trial) {
    for (std::size_t k = order.size() - 1; k > 0; --k)
      std::swap(order[k], order[rng.below(k + 1)]);
    by_clipping_order.insert(voronoi_cell(4, sites, order, domain).neighbours);
    std::vector<HeardRobot> heard;
    for (std::uint32_t i : order)
      heard.push_back({sim::node_id(i), sites[i]});
    heard_sets.insert(heard_neighbours(sites[4], heard, domain));
  }
  CHECK(by_clipping_order.size() > 1);
  CHECK(heard_sets.size() == 1);
}
