#pragma once
// The two built-ins that send nothing (docs/protocols.md):
//   oracle — each update takes the exact cell from the true robot positions and the readings of
//            the sensors inside it, without a message: the reference the others are judged by.
//   none   — the robot never updates (demo scenarios).
#include <cstdint>
#include <vector>

#include "protocols/ground_truth.hpp"
#include "protocols/protocol.hpp"
#include "protocols/registry.hpp"
#include "protocols/voronoi_protocol.hpp"
#include "sim/log.hpp"

namespace masnet::protocols {

class OracleProtocol final : public RobotProtocol {
 public:
  enum Timer : std::uint32_t { kTick = 2 };

  OracleProtocol(RobotHost& host, GroundTruth& truth, std::size_t robot,
                 const ProtocolContext& context, double period_s, double phase_s,
                 const sim::Log* log = nullptr);

  void start() override;
  void on_frame(const net::Frame&) override {}
  void on_timer(std::uint32_t kind) override;
  /// No radio radius: R_min, the radius the message-based protocols start from, so that the
  /// radius columns keep one meaning across protocols.
  double radius() const override { return RangeDecay{}.min; }
  const ConvexPolygon& cell() const override { return last_cell_; }
  const std::vector<CellReading>& cell_readings() const override { return no_readings_; }

 private:
  void update();

  RobotHost& host_;
  GroundTruth& truth_;
  std::size_t robot_;
  const ProtocolContext& context_;
  double period_s_, phase_s_;
  const sim::Log* log_;
  std::uint32_t update_ = 0;
  Vec2 last_target_{0, 0};
  ConvexPolygon last_cell_;
  std::vector<CellReading> no_readings_;
};

class IdleProtocol final : public RobotProtocol {
 public:
  void start() override {}
  void on_frame(const net::Frame&) override {}
  void on_timer(std::uint32_t) override {}
  double radius() const override { return RangeDecay{}.min; }  // as the oracle's
  const ConvexPolygon& cell() const override { return no_cell_; }
  const std::vector<CellReading>& cell_readings() const override { return no_readings_; }

 private:
  ConvexPolygon no_cell_;
  std::vector<CellReading> no_readings_;
};

}  // namespace masnet::protocols
