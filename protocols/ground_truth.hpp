#pragma once
// Ground truth: what no message could tell a robot. Only the `oracle` protocol (zero messages by
// definition) and the recorders receive it; the hosts of ordinary protocols have no such
// method, and this header is not installed with the public ones (docs/protocol-api.md).
#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "protocols/geometry.hpp"
#include "protocols/lloyd.hpp"
#include "protocols/registry.hpp"
#include "sim/ids.hpp"

namespace masnet::protocols {

/// A cell with its bounding robots named by node id.
struct RobotCell {
  ConvexPolygon polygon;
  std::vector<sim::NodeId> neighbours;  ///< ascending
  /// Half-plane clips spent finding it: every cell built on the way (Cell::half_plane_clips).
  std::uint64_t half_plane_clips = 0;
};

class GroundTruth {
 public:
  virtual ~GroundTruth() = default;
  /// The exact Voronoi cell of `robot` (a robot index) among the true robot positions now.
  virtual RobotCell true_cell(std::size_t robot) = 0;
  /// Adds every sensor inside `cell` with its reading now to `accumulator`; returns how many.
  /// With `work`, adds to its point_in_cell_tests the sensors whose membership was decided.
  virtual std::uint32_t read_sensors_in(const ConvexPolygon& cell, CentroidAccumulator& accumulator,
                                        GeometryWork* work = nullptr) = 0;
};

using TruthfulRobotFactory =
    std::function<std::unique_ptr<RobotProtocol>(const RobotSetup&, GroundTruth&)>;

/// Registers a protocol whose robots are made with ground truth (`make_robot` of the definition
/// is then unused). Same rules as register_protocol.
void register_ground_truth_protocol(ProtocolDefinition definition, TruthfulRobotFactory make);
/// The ground-truth factory of the protocol `name`, or null for an ordinary protocol.
const TruthfulRobotFactory* ground_truth_factory(std::string_view name);

}  // namespace masnet::protocols
