// Link faults and nodes taken down at the radio: a partition line no frame crosses, a degraded
// area's extra loss, a node that neither sends nor receives while down
// (docs/faults-and-lifetime.md).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "net/link_faults.hpp"
#include "net/radio.hpp"

using namespace masnet;
using net::Vec2;
using sim::NodeId;

namespace {

struct Deliveries : net::RadioListener {
  std::vector<std::pair<NodeId, NodeId>> heard;  // (receiver, source)
  void on_frame(NodeId receiver, const net::Frame& f) override {
    heard.emplace_back(receiver, f.source);
  }
};

struct NoMobiles : net::MobilePositions {
  Vec2 position(NodeId) const override { return Vec2{0, 0}; }
  double speed_bound() const override { return 0.0; }
};

// A 10 × 10 grid of static nodes in the unit square, every one in range of every other.
struct Grid {
  sim::Simulator sim;
  net::Radio radio;
  Deliveries listener;
  NoMobiles mobiles;
  std::vector<Vec2> positions;
  explicit Grid(net::RadioParams params = {}) : radio(sim, params, 7) {
    radio.set_listener(&listener);
    radio.set_mobile_positions(&mobiles);
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 10; ++i) {
        const auto id = static_cast<std::uint32_t>(positions.size());
        positions.push_back(Vec2{(i + 0.5) / 10, (j + 0.5) / 10});
        radio.add_static_node(sim::node_id(id), positions.back(), id);
      }
  }
  void broadcast_from_all(double range) {
    for (std::uint32_t n = 0; n < positions.size(); ++n)
      radio.broadcast(sim::node_id(n), range, net::Beacon{sim::node_id(n), positions[n]});
    sim.run();
  }
};

}  // namespace

TEST_CASE("A line cut separates exactly the segments that meet it", "[faults]") {
  const net::LineCut cut{Vec2{0.5, 0.0}, Vec2{0.5, 1.0}};
  CHECK(cut.separates(Vec2{0.2, 0.5}, Vec2{0.8, 0.5}));
  CHECK(cut.separates(Vec2{0.2, 0.1}, Vec2{0.9, 0.95}));
  CHECK_FALSE(cut.separates(Vec2{0.2, 0.5}, Vec2{0.4, 0.9}));
  CHECK_FALSE(cut.separates(Vec2{0.2, 1.2}, Vec2{0.8, 1.2}));  // past the segment's end
  CHECK(cut.separates(Vec2{0.5, 0.3}, Vec2{0.8, 0.3}));        // touching counts
  CHECK(cut.separates(Vec2{0.5, -0.5}, Vec2{0.5, 0.2}));       // collinear, overlapping
  CHECK_FALSE(cut.separates(Vec2{0.5, 1.5}, Vec2{0.5, 2.0}));  // collinear, apart
}

TEST_CASE("Regions: disks and polygons, convex or not", "[faults]") {
  net::Region disk;
  disk.center = Vec2{0.5, 0.5};
  disk.radius = 0.2;
  CHECK(disk.contains(Vec2{0.6, 0.6}));
  CHECK_FALSE(disk.contains(Vec2{0.7, 0.7}));
  CHECK(disk.area() == Approx(M_PI * 0.04));
  net::Region ell;  // an L: the unit square without its top-right quarter
  ell.shape = net::Region::Shape::polygon;
  ell.polygon = {Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 0.5}, Vec2{0.5, 0.5}, Vec2{0.5, 1}, Vec2{0, 1}};
  CHECK(ell.contains(Vec2{0.25, 0.75}));
  CHECK(ell.contains(Vec2{0.75, 0.25}));
  CHECK_FALSE(ell.contains(Vec2{0.75, 0.75}));
  CHECK_FALSE(ell.contains(Vec2{1.5, 0.25}));
  CHECK(ell.area() == Approx(0.75));
}

TEST_CASE("While a partition stands no frame crosses it, and afterwards frames do again",
          "[faults]") {
  Grid grid;
  const net::LineCut cut{Vec2{0.5, 0.0}, Vec2{0.5, 1.0}};
  grid.radio.link_faults().add_cut(3, cut);
  grid.broadcast_from_all(1.5);
  std::size_t same_side = 0;
  for (const auto& [receiver, source] : grid.listener.heard) {
    const bool left_r = grid.positions[sim::index(receiver)].x() < 0.5;
    const bool left_s = grid.positions[sim::index(source)].x() < 0.5;
    CHECK(left_r == left_s);
    ++same_side;
  }
  // Every node hears every other node on its side: 2 sides × 50 × 49.
  CHECK(same_side == 2 * 50 * 49);
  grid.listener.heard.clear();
  grid.radio.link_faults().remove(3);
  CHECK_FALSE(grid.radio.link_faults().any());
  grid.broadcast_from_all(1.5);
  CHECK(grid.listener.heard.size() == 100 * 99);
}

TEST_CASE("A degraded area loses its share of the receptions of its nodes", "[faults]") {
  Grid grid;
  net::DegradedArea area;
  area.region.center = Vec2{0.25, 0.25};
  area.region.radius = 0.2;
  area.loss = 0.3;
  grid.radio.link_faults().add_degraded(1, area);
  for (int round = 0; round < 5; ++round)
    grid.broadcast_from_all(1.5);
  std::size_t involved = 0, kept = 0, others = 0;
  std::vector<std::size_t> expected_by_pair_kind(2, 0);
  for (const auto& [receiver, source] : grid.listener.heard) {
    if (area.region.contains(grid.positions[sim::index(receiver)]) ||
        area.region.contains(grid.positions[sim::index(source)]))
      ++kept;
    else
      ++others;
  }
  // Pairs touching the area: senders in it × everyone, plus everyone × receivers in it.
  std::size_t in_area = 0;
  for (const Vec2& p : grid.positions)
    in_area += area.region.contains(p) ? 1 : 0;
  involved = 5 * (in_area * 99 + (100 - in_area) * in_area);
  CHECK(others == 5 * (100 - in_area) * (99 - in_area));  // untouched pairs lose nothing
  const double share = static_cast<double>(kept) / static_cast<double>(involved);
  const double sigma = std::sqrt(0.3 * 0.7 / static_cast<double>(involved));
  CHECK(std::abs(share - 0.7) < 4 * sigma);
}

TEST_CASE("A node taken down neither sends nor receives until it is brought up", "[faults]") {
  Grid grid;
  grid.radio.enable_failures();
  const NodeId down = sim::node_id(42);
  grid.radio.take_down(down);
  CHECK_FALSE(grid.radio.alive(down));
  CHECK_FALSE(grid.radio.broadcast(down, 1.5, net::Beacon{down, grid.positions[42]}));
  grid.broadcast_from_all(1.5);
  for (const auto& [receiver, source] : grid.listener.heard) {
    CHECK(receiver != down);
    CHECK(source != down);
  }
  CHECK(grid.listener.heard.size() == 99 * 98);
  CHECK(grid.radio.stats(down).heard_bytes == 0);
  CHECK(grid.radio.bring_up(down));
  grid.listener.heard.clear();
  grid.broadcast_from_all(1.5);
  CHECK(grid.listener.heard.size() == 100 * 99);
}
