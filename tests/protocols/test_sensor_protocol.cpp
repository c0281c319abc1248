#include <catch2/catch.hpp>

#include <vector>

#include "protocols/sensor_protocol.hpp"

using namespace masnet;
using net::Vec2;
using sim::NodeId;

namespace {

// A sensor at a fixed position that records what it sends.
struct FakeSensorHost final : protocols::SensorHost {
  Vec2 at;
  std::vector<NodeId> replied_to;
  explicit FakeSensorHost(Vec2 position) : at(position) {}
  sim::Time now() const override { return sim::kTimeZero; }
  NodeId id() const override { return sim::node_id(100); }
  std::size_t index() const override { return 0; }
  Vec2 position() const override { return at; }
  double reading() override { return 1.0; }
  std::uint32_t broadcast(double, net::Payload) override { return 1; }
  std::uint32_t unicast(NodeId to, net::Payload) override {
    replied_to.push_back(to);
    return 1;
  }
  const net::MessageSizes& message_sizes() const override { return sizes; }
  net::MessageSizes sizes;
  void set_timer(sim::Duration, std::uint32_t) override {}
};

net::Frame sense(std::uint32_t robot, std::uint64_t number, std::vector<Vec2> cell) {
  net::Frame frame;
  frame.source = sim::node_id(robot);
  frame.type = net::MessageType::sense;
  frame.number = number;
  frame.payload = net::Sense{sim::node_id(robot), 1, std::move(cell)};
  return frame;
}

}  // namespace

TEST_CASE("a sensor answers every SENSE whose cell holds it, and only those, SENSE after SENSE",
          "[protocols]") {
  // The protocol prepares a SENSE's cell once for all its hearers: a reply must still follow
  // each frame's own cell, whether the next frame comes from the same robot or another.
  const std::vector<Vec2> left{Vec2{0, 0}, Vec2{0.5, 0}, Vec2{0.5, 1}, Vec2{0, 1}};
  const std::vector<Vec2> right{Vec2{0.5, 0}, Vec2{1, 0}, Vec2{1, 1}, Vec2{0.5, 1}};
  protocols::PaperSensorProtocol protocol(0.01, 1);
  FakeSensorHost in_left(Vec2{0.25, 0.5}), on_edge(Vec2{0.5, 0.75});
  for (FakeSensorHost* host : {&in_left, &on_edge}) {
    protocol.on_frame(*host, sense(0, 7, left));
    protocol.on_frame(*host, sense(0, 8, right));  // same robot, next frame
    protocol.on_frame(*host, sense(1, 8, left));   // another robot, same number
    protocol.on_frame(*host, sense(1, 9, std::vector<Vec2>{Vec2{0, 0}, Vec2{1, 0}}));  // no polygon
  }
  CHECK(in_left.replied_to == std::vector<NodeId>{sim::node_id(0), sim::node_id(1)});
  // On the shared edge: inside both cells (the boundary belongs to each).
  CHECK(on_edge.replied_to ==
        std::vector<NodeId>{sim::node_id(0), sim::node_id(0), sim::node_id(1)});
}

TEST_CASE("every SENSE a sensor hears costs one point-in-cell test, answered or not",
          "[protocols]") {
  const std::vector<Vec2> left{Vec2{0, 0}, Vec2{0.5, 0}, Vec2{0.5, 1}, Vec2{0, 1}};
  protocols::PaperSensorProtocol protocol(0.01, 1);
  CHECK(protocol.point_in_cell_tests() == 0);
  FakeSensorHost inside(Vec2{0.25, 0.5}), outside(Vec2{0.75, 0.5});
  std::uint64_t heard = 0;
  for (std::uint64_t number = 1; number <= 3; ++number)
    for (FakeSensorHost* host : {&inside, &outside}) {
      protocol.on_frame(*host, sense(0, number, left));
      ++heard;
    }
  CHECK(inside.replied_to.size() == 3);
  CHECK(outside.replied_to.empty());
  CHECK(protocol.point_in_cell_tests() == heard);
  // A POSITION is no test.
  net::Frame position;
  position.type = net::MessageType::position;
  position.payload = net::Position{sim::node_id(0), Vec2{0.1, 0.1}};
  protocol.on_frame(inside, position);
  CHECK(protocol.point_in_cell_tests() == heard);
}
