// The radio's per-node counters by message type (Radio::counters), read back against a
// brute-force tally: frames booked one by one and in bulk, nodes added after the first frames
// (the counters are laid out again), and types nobody sent; and the unicasts whose addressee was
// out of reach, kept in the nodes' rarely written records. The radio reads only the part of each
// row that was written (sim::WrittenSpan); a span too narrow would read a count as zero here.
#include <catch2/catch.hpp>

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "net/radio.hpp"
#include "sim/random.hpp"

using namespace masnet;
using net::Vec2;
using sim::NodeId;

namespace {

struct Silent : net::RadioListener {
  void on_frame(NodeId, const net::Frame&) override {}
};

// Robots that stand still where they were put.
struct Standing : net::MobilePositions {
  std::map<std::uint32_t, Vec2> at;
  Vec2 position(NodeId id) const override { return at.at(sim::index(id)); }
  double speed_bound() const override { return 0.0; }
};

}  // namespace

TEST_CASE("per-type counters of every node equal a brute-force tally, nodes added midway too",
          "[net]") {
  net::RadioParams params;
  params.max_range = 0.4;
  sim::Simulator sim;
  net::Radio radio(sim, params, 7);
  Silent listener;
  Standing robots;
  radio.set_listener(&listener);
  radio.set_mobile_positions(&robots);
  const std::uint32_t listens_to_position = 1u << static_cast<unsigned>(net::MessageType::position);
  std::vector<Vec2> where;  // [node]
  sim::RandomStream rng(31);
  auto add_sensor = [&](Vec2 p) {
    const auto id = static_cast<std::uint32_t>(where.size());
    radio.add_static_node(sim::node_id(id), p, id);
    radio.set_interest(sim::node_id(id), listens_to_position);
    where.push_back(p);
  };
  auto add_robot = [&] {
    const auto id = static_cast<std::uint32_t>(where.size());
    const Vec2 p{rng.uniform01(), rng.uniform01()};
    robots.at[id] = p;
    radio.add_mobile_node(sim::node_id(id), id);
    where.push_back(p);
  };
  const int side = 16;  // a grid: indexed as lines, DISCOVERs and unicasts booked in bulk
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i)
      add_sensor(Vec2{(i + 0.5) / side, (j + 0.5) / side});
  for (int r = 0; r < 12; ++r)
    add_robot();

  constexpr std::size_t kTypes = 2;
  const net::MessageType types[kTypes] = {net::MessageType::discover, net::MessageType::position};
  std::map<std::pair<std::uint32_t, std::size_t>, net::TypeCounters> expected;  // (node, type)
  std::map<std::uint32_t, std::uint64_t> unreachable;  // unicasts whose addressee was too far
  auto send = [&](std::uint32_t src, std::uint32_t dst, double range, std::size_t kind) {
    const Vec2 p = where[src];
    net::Payload payload = kind == 0 ? net::Payload{net::Discover{sim::node_id(src), range, p}}
                                     : net::Payload{net::Position{sim::node_id(src), p}};
    const auto bytes = net::size_bytes(payload, params.sizes);
    net::TypeCounters& sent = expected[{src, kind}];
    ++sent.tx_count;
    sent.tx_bytes += bytes;
    if (dst != src) {  // a unicast: received by its addressee alone, when within the max range
      if ((where[dst] - p).norm() <= params.max_range) {
        ++expected[{dst, kind}].rx_count;
        expected[{dst, kind}].rx_bytes += bytes;
      } else {
        ++unreachable[src];
      }
      radio.unicast(sim::node_id(src), sim::node_id(dst), std::move(payload));
      return;
    }
    for (std::uint32_t j = 0; j < where.size(); ++j) {
      const double dx = where[j].x() - p.x(), dy = where[j].y() - p.y();
      if (j == src || dx * dx + dy * dy > range * range) continue;
      ++expected[{j, kind}].rx_count;
      expected[{j, kind}].rx_bytes += bytes;
    }
    radio.broadcast(sim::node_id(src), range, std::move(payload));
  };
  auto send_some = [&](int frames) {
    for (int k = 0; k < frames; ++k) {
      const auto n = static_cast<std::uint32_t>(where.size());
      const auto src = static_cast<std::uint32_t>(rng.below(n));
      const auto kind = static_cast<std::size_t>(rng.below(3));  // DISCOVER, POSITION, unicast
      auto dst = kind == 2 ? static_cast<std::uint32_t>(rng.below(n)) : src;
      if (kind == 2 && dst == src) dst = (src + 1) % n;
      send(src, dst, rng.uniform(0.0, params.max_range), kind == 2 ? 1 : kind);
    }
    sim.run();
  };
  send_some(300);
  // Nodes added after the first frames: every counter is laid out again by the new hot indices.
  add_sensor(Vec2{0.51, 0.49});
  add_sensor(Vec2{0.02, 0.97});
  add_robot();
  add_robot();
  send_some(300);

  const std::vector<net::MessageType> every_type = {
      net::MessageType::discover, net::MessageType::position, net::MessageType::neighbor};
  CHECK(unreachable.size() > 10);  // records written for some nodes only
  for (std::uint32_t j = 0; j < where.size(); ++j) {
    INFO("node " << j);
    const auto it = unreachable.find(j);
    REQUIRE(radio.stats(sim::node_id(j)).unreachable_count ==
            (it == unreachable.end() ? 0 : it->second));
  }
  for (std::uint32_t j = 0; j < where.size(); ++j)
    for (const net::MessageType type : every_type) {
      std::size_t kind = kTypes;
      for (std::size_t k = 0; k < kTypes; ++k)
        if (types[k] == type) kind = k;
      const auto it = expected.find({j, kind});
      const net::TypeCounters want = it == expected.end() ? net::TypeCounters{} : it->second;
      const net::TypeCounters got = radio.counters(sim::node_id(j), type);
      INFO("node " << j << ", type " << static_cast<int>(type));
      REQUIRE(got.tx_count == want.tx_count);
      REQUIRE(got.tx_bytes == want.tx_bytes);
      REQUIRE(got.rx_count == want.rx_count);
      REQUIRE(got.rx_bytes == want.rx_bytes);
    }
}
