#pragma once
// The robots' message-based Voronoi protocols as one state machine (docs/protocols.md). The
// variants differ in a rule, not in a file: how many DISCOVER rounds, how R grows, when to stop,
// how R decays.
//   radius_doubling — the paper's protocol (paper §III-B) after Cortés et al.
//   fixed_radius    — one DISCOVER round with a constant R
//   gabriel         — one round at max range, only Gabriel neighbours bound the cell
// (The `oracle` and `none` protocols are in protocols/oracle_protocol.hpp.)
// Paper names: R_i → radius_m_, d_i → farthest_m, p_i → position_, V_i → cell.
#include <cstdint>
#include <vector>

#include "protocols/density_scaling.hpp"
#include "protocols/geometry.hpp"
#include "protocols/host.hpp"
#include "protocols/protocol.hpp"
#include "protocols/registry.hpp"
#include "sim/log.hpp"

namespace masnet::protocols {

enum class VoronoiVariant { radius_doubling, fixed_radius, gabriel };

/// How R grows when the stop rule fails: R ← 2·d (the paper) or R ← 2·R (Cortés).
enum class Growth { to_2d, doubling };
/// What d is: the farthest reading sensor in V (the paper) or the farthest vertex of V (Cortés,
/// which guarantees the exact cell).
enum class StopCriterion { sensors, vertices };

/// Paper: "if for some time, e.g. successive 3 updates, R_i remains unchanged, R_i = R_i − Δr".
struct RangeDecay {
  std::uint32_t patience = 3;  ///< unchanged updates before R shrinks; 0 = never
  double step = 0.02;          ///< Δr, world units
  double min = 0.02;           ///< R_min, world units: the floor, and R when nobody reports
};

/// The variants' rules, read from the scenario's `protocol:` keys
/// (protocols/builtin_protocols.cpp).
struct ProtocolParams {
  VoronoiVariant variant = VoronoiVariant::radius_doubling;
  double period_s = 0.01;  ///< Δt between updates (paper: 0.01 s)
  Growth growth = Growth::to_2d;
  StopCriterion criterion = StopCriterion::sensors;
  bool shrink_on_stop = false;  ///< Cortés: on stop set R ← 2·d exactly
  RangeDecay decay;
  double reply_timeout_s = 0.002;  ///< how long a round waits for replies
  double fixed_radius = 0.3;       ///< R of `fixed_radius`, world units
};

/// An update's first and last debug lines (docs/logging.md), shared by the built-ins.
void log_update_start(const sim::Log* log, const UpdateSummary& record, double radius);
void log_update_end(const sim::Log* log, const UpdateSummary& record);

class VoronoiProtocol final : public RobotProtocol {
 public:
  /// Timer kinds.
  enum Timer : std::uint32_t { kInitEnd = 1, kTick, kRoundEnd, kSenseEnd };

  /// `phase_s` in [0, period) staggers this robot's updates (seeded per robot by the world).
  /// `log` (may be null) gets the update's steps at debug level (docs/logging.md).
  VoronoiProtocol(RobotHost& host, const ProtocolParams& params, const ProtocolContext& context,
                  double phase_s, const sim::Log* log = nullptr);

  /// Starts at time now(): the initialisation of paper §III-B, then periodic updates.
  void start() override;
  void on_frame(const net::Frame& frame) override;
  void on_timer(std::uint32_t kind) override;

  double radius() const override { return radius_m_; }  ///< R_i
  const ConvexPolygon& cell() const override { return last_cell_; }
  const std::vector<CellReading>& cell_readings() const override { return cell_readings_; }
  bool busy() const { return phase_ != Phase::idle; }
  std::uint64_t delayed_updates() const { return delayed_updates_; }

 private:
  enum class Phase { idle, initialising, discovering, sensing };
  struct HeardNeighbour {
    NodeId robot;
    Vec2 position;
  };
  struct HeardReading {
    NodeId sensor;
    Vec2 position;
    double value;
  };

  // Paper §III-B "at the beginning": 1) broadcast POSITION, 5-6) R_i = farthest reporter.
  void announce_position();
  void on_report(const net::Report& report, std::uint32_t bytes);
  void finish_initialisation();
  void schedule_ticks();

  // One update (steps 1-4 of paper §III-B).
  void on_tick();
  void begin_update();
  void discover_round();  // step 1: detect neighbours within R_i
  void end_round();       // step 2: construct V_i within R_i
  void decide();          // steps 3-4: d_i, then stop or grow R_i
  void finish_update(bool truncated);
  void decay_range();

  void answer_discover(const net::Discover& discover);
  /// Counts its point tests in the update's record, as compute_cell() counts its clips.
  double farthest_reading_in_cell();
  /// True while the cell is the one sent with the last SENSE: every reading is then inside.
  bool cell_is_sensed() const;
  Cell compute_cell();

  RobotHost& host_;
  ProtocolParams params_;
  ProtocolContext context_;
  double phase_s_;
  const sim::Log* log_;

  Phase phase_ = Phase::idle;
  double radius_m_;  // R_i, carried over between updates
  double farthest_reporter_m_ = 0.0;
  std::uint32_t update_ = 0;
  bool tick_pending_ = false;
  std::uint64_t delayed_updates_ = 0;
  std::uint32_t unchanged_streak_ = 0;
  double last_final_radius_ = -1.0;
  Vec2 last_target_{0, 0};
  ConvexPolygon last_cell_;
  std::vector<CellReading> cell_readings_;

  // State of the update in progress.
  UpdateRecord record_;
  Vec2 position_{0, 0};  // p_i for the whole update
  std::vector<HeardNeighbour> neighbours_;
  std::vector<HeardReading> readings_;
  Cell cell_;                      // Ω ∩ bisectors (no disk): the current V_i
  std::size_t cell_sites_ = 0;     // how many of neighbours_ cell_ was computed from
  std::vector<Vec2> sensed_cell_;  // the V_i sent in this update's SENSE
};

}  // namespace masnet::protocols
