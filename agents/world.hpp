#pragma once
// The world: sensors, robots, targets, the density field and the radio, owned together and
// wired to the protocols through RobotHost / SensorHost. It knows nothing of files: a builder
// in scenarios/ fills a WorldDef, and recorders in scenarios/ observe through a WorldObserver
// and the read-only accessors (output is never written from inside the model).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "agents/density_field.hpp"
#include "agents/diffusion_field.hpp"
#include "agents/faults.hpp"
#include "agents/formation.hpp"
#include "agents/robot_motion.hpp"
#include "agents/sensor_list.hpp"
#include "net/line_index.hpp"
#include "net/radio.hpp"
#include "protocols/ground_truth.hpp"
#include "protocols/protocol.hpp"
#include "protocols/registry.hpp"
#include "sim/log.hpp"
#include "sim/simulator.hpp"

namespace masnet::agents {

using sim::NodeId;

/// Periodic BEACON traffic (the demo scenario): every sender broadcasts once per period at a
/// seeded phase.
enum class BeaconSenders { none, robots, sensors, all };
struct BeaconDef {
  BeaconSenders senders = BeaconSenders::none;
  double period_s = 1.0;
  double range = 0.2;  ///< world units
};

/// The robots' dispensers (paper §VI-B; docs/field-models.md): f_c = −k_s · (mean reading of the
/// sensors in the robot's cell that lie within spray_radius of it), magnitude capped at max_rate.
enum class SprayReadings {
  live,         ///< the current values of those sensors (what Diff-MAS2D did)
  last_update,  ///< the readings the robot received in its last protocol update
};
struct DispenserDef {
  bool enabled = false;
  double gain = 10.0;         ///< k_s, 1/s
  double spray_radius = 0.2;  ///< world units
  double max_rate = 2.0;      ///< cap on |f_c|, field units per second
  double payload = 0.0;       ///< neutraliser each robot carries (rate·s); 0 = unlimited
  SprayReadings readings = SprayReadings::live;
};

struct WorldDef {
  std::uint64_t seed = 1;
  protocols::ConvexPolygon domain;
  SensorList sensors;        ///< shared by the copies of this definition
  std::vector<Vec2> robots;  ///< initial positions (at rest)
  MotionParams motion;
  /// Seconds between a robot's protocol choosing a new target and the robot starting towards it
  /// (0: at once).
  double actuation_delay_s = 0.0;
  FieldDef field;
  double sensor_noise_sigma = 0.0;  ///< additive Gaussian noise on every reading
  net::RadioParams radio;
  protocols::ProtocolChoice protocol;
  protocols::DensityScaling scaling;
  BeaconDef beacons;
  DispenserDef dispenser;
  /// Batteries by class, joules; 0: the radio's `energy.battery_j` (0 there too: unlimited).
  double sensor_battery_j = 0.0, robot_battery_j = 0.0;
  LocomotionEnergy locomotion;
  std::vector<FaultDef> faults;
  /// Robot groups (docs/formations.md): every robot above leads a group of this size.
  FormationDef formation;
};

/// Why a node went down.
enum class DownCause { battery, fault };

/// Hooks for recorders.
class WorldObserver {
 public:
  virtual ~WorldObserver() = default;
  virtual void on_update(std::size_t /*robot*/, const protocols::UpdateRecord& /*record*/) {}
  virtual void on_battery_empty(NodeId /*node*/) {}
  /// A node went down (battery or fault) or came back up (a fault's `until`).
  virtual void on_node_down(NodeId /*node*/, DownCause /*cause*/) {}
  virtual void on_node_up(NodeId /*node*/) {}
  /// Scripted fault `fault` (its index in WorldDef::faults) struck (`begins`) or was lifted.
  virtual void on_fault(std::size_t /*fault*/, bool /*begins*/) {}
};

class World final : public net::RadioListener,
                    public net::MobilePositions,
                    public protocols::GroundTruth {
 public:
  /// Node ids: robots 0..R-1, then sensors R..R+S-1. Random streams are keyed by role and
  /// index, so adding a robot or a sensor never changes another node's draws.
  World(sim::Simulator& simulator, const WorldDef& def);
  ~World() override;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Schedules the start of every protocol and beacon at the current time.
  void start();
  void set_observer(WorldObserver* observer) { observer_ = observer; }

  // ---- Read-only views for recorders -------------------------------------------------------
  const WorldDef& def() const { return def_; }
  sim::Simulator& simulator() { return simulator_; }
  net::Radio& radio() { return radio_; }
  std::size_t robot_count() const { return robots_.size(); }
  std::size_t sensor_count() const { return def_.sensors.size(); }
  NodeId robot_node(std::size_t robot) const {
    return sim::node_id(static_cast<std::uint32_t>(robot));
  }
  NodeId sensor_node(std::size_t sensor) const {
    return sim::node_id(static_cast<std::uint32_t>(robots_.size() + sensor));
  }
  bool is_robot(NodeId node) const { return sim::index(node) < robots_.size(); }
  /// Position and velocity of a robot now.
  MotionState robot_state(std::size_t robot) const;
  Vec2 robot_target(std::size_t robot) const;
  const protocols::RobotProtocol& robot_protocol(std::size_t robot) const;
  /// The definition of the run's protocol (its update columns, whether it reads ground truth).
  const protocols::ProtocolDefinition& protocol_definition() const { return *definition_; }
  bool protocol_uses_ground_truth() const { return truthful_factory_ != nullptr; }
  /// ρ at a sensor now, noiseless and without counting (metrics, figures).
  double true_density(std::size_t sensor);
  /// The exact Voronoi cell of `robot` among the true robot positions now. Candidates are
  /// searched within a radius that doubles until Cortés' rule certifies the cell, starting
  /// from `first_radius` (a guess; <= 0: one that suits a uniform spread of the robots).
  protocols::RobotCell oracle_cell(std::size_t robot, double first_radius = 0.0);
  /// Adds every sensor inside `cell` with its reading now to `accumulator` (the oracle's
  /// sensing pass; no messages); returns how many. With `work`, counts the sensors whose
  /// membership was decided: each exact test, and on sensor rows each sensor of a row's
  /// candidate interval (its inside part is decided at once; docs/protocols.md).
  std::uint32_t read_sensors_in(const protocols::ConvexPolygon& cell,
                                protocols::CentroidAccumulator& accumulator,
                                protocols::GeometryWork* work = nullptr) override;
  // ---- protocols::GroundTruth (the oracle and recorders only) -------------------------------
  protocols::RobotCell true_cell(std::size_t robot) override { return oracle_cell(robot); }
  /// Positions of the field's moving entities now (targets, bump centres).
  std::vector<Vec2> source_positions() const;
  std::uint64_t clamped_readings() const {
    return field_.clamped_readings() + absorbed_.clamped_readings;
  }
  /// The pollution field (diffusion runs), or null.
  const DiffusionField* diffusion() const { return diffusion_.get(); }
  /// Σ of the sensors' noiseless readings now (the paper's Fig. 6 quantity).
  double pollution_total() const;
  /// Neutraliser a robot's dispenser has released so far (rate·s, applied to the field).
  double neutraliser_used(std::size_t robot) const { return neutraliser_used_[robot]; }
  std::uint64_t sensor_readings() const { return readings_taken_ + absorbed_.readings; }
  /// Point-in-cell tests the sensors made answering SENSEs so far (their protocol's count).
  std::uint64_t sensor_point_in_cell_tests() const {
    return sensor_protocol_->point_in_cell_tests() + absorbed_.point_in_cell_tests;
  }

  // ---- Tiles of a partitioned run (docs/decisions/0012-partitioned-runs.md) -----------------
  /// This world is one tile: its radio's static slots [first, end) are its sensors; it runs them
  /// and every robot (unless told otherwise below). Before start().
  void own_sensor_slots(std::uint32_t first, std::uint32_t end) {
    radio_.own_static_slots(first, end);
  }
  /// Robots in one tile (docs/decisions/0012-partitioned-runs.md, "Robots in the first tile"):
  /// here, this tile runs every robot and keeps each course they choose for the other tiles; not
  /// here, its robots are ghosts — no protocol, moved by the courses taken in. Needs an actuation
  /// delay of at least the tiles' window. Before start().
  void home_robots(bool here);
  /// A course a robot chose: it steers towards (x, y) at `when`, as the event `key` of its own —
  /// unless it went down (a new `generation`) meanwhile.
  struct Course {
    sim::Time when{};
    sim::EventKey key;
    std::uint32_t robot = 0, generation = 0;
    double x = 0, y = 0;
  };
  std::vector<Course>& course_outbox() { return course_outbox_; }
  void take_course(const Course& course);
  /// What a tile's sensors counted (readings, point-in-cell tests, clamped readings).
  struct TileCounts {
    std::uint64_t readings = 0, point_in_cell_tests = 0, clamped_readings = 0;
  };
  /// (A tile's own: without the robots' reads, which every tile makes.)
  TileCounts tile_counts() const {
    return {sensor_readings() - robot_reads_.readings, sensor_point_in_cell_tests(),
            clamped_readings() - robot_reads_.clamped_readings};
  }
  /// Takes over another tile's sensors (their radio ledger, net/tile_ledger.hpp, and their
  /// counts): this world then reads as the whole run's. At the end of the run.
  void absorb_tile(const TileCounts& counts, const net::Radio::TileLedger& ledger);

  // ---- Robot groups (docs/formations.md): robot g leads group g --------------------------------
  /// Followers, group by group (follower f is slot f % (size − 1) of group f / (size − 1)); their
  /// node ids follow the sensors'.
  std::size_t follower_count() const { return followers_.size(); }
  std::size_t group_count() const { return def_.formation.enabled() ? robots_.size() : 0; }
  NodeId follower_node(std::size_t follower) const {
    return sim::node_id(
        static_cast<std::uint32_t>(robots_.size() + def_.sensors.size() + follower));
  }
  bool is_follower(NodeId node) const {
    return sim::index(node) >= robots_.size() + def_.sensors.size();
  }
  MotionState follower_state(std::size_t follower) const;
  std::size_t follower_group(std::size_t follower) const;
  const FollowerController& follower_controller(std::size_t follower) const;

  // ---- Faults, lifetime, locomotion (docs/faults-and-lifetime.md) -------------------------
  bool node_alive(NodeId node) const { return radio_.alive(node); }
  std::size_t alive_robot_count() const { return robots_.size() - dead_robots_; }
  std::size_t alive_sensor_count() const { return def_.sensors.size() - dead_sensors_; }
  /// Takes `node` down now: it sends, receives, senses and moves no more (a robot stays where
  /// it is). Nothing if it is down already.
  void kill(NodeId node, DownCause cause = DownCause::fault);
  /// Brings a killed node back now: a robot starts its protocol afresh where it stands. Nothing
  /// if it is up, or if its battery is empty.
  void restart(NodeId node);
  /// Metres a robot has travelled so far, and the locomotion energy that cost (joules).
  double distance_travelled_m(std::size_t robot) const;
  double locomotion_energy_j(std::size_t robot) const;

  // ---- net::RadioListener, net::MobilePositions --------------------------------------------
  void on_frame(NodeId receiver, const net::Frame& frame) override;
  void on_battery_empty(NodeId node) override;
  Vec2 position(NodeId node) const override;
  double speed_bound() const override;

 private:
  class RobotAgent;
  class SensorContext;
  class FollowerAgent;

  /// The reading of `sensor`, which stands at `position` (passed: the caller has it at hand).
  double sensor_reading(std::size_t sensor, const Vec2& position);
  void sensor_timer(std::size_t sensor, std::uint32_t kind);
  /// A host's send: a broadcast with `range` (`to` = kNoNode) or a unicast; its size in bytes,
  /// 0 if the radio refused it.
  std::uint32_t send(NodeId from, NodeId to, double range, net::Payload payload);
  void send_beacon(NodeId node);
  void pde_step();
  double spray_rate(std::size_t robot) const;
  double field_value(const Vec2& s);

  sim::Simulator& simulator_;
  sim::Log log_;  // spdlog's default logger: the command line sets its level and sink
  WorldDef def_;
  net::Radio radio_;
  AnalyticField field_;
  protocols::ProtocolContext protocol_context_;
  const protocols::ProtocolDefinition* definition_;
  const protocols::TruthfulRobotFactory* truthful_factory_;  // null unless the oracle
  std::unique_ptr<protocols::SensorProtocol> sensor_protocol_;
  std::vector<std::unique_ptr<RobotAgent>> robots_;
  std::vector<std::uint32_t> sensor_read_counts_;  // keys the noise draws
  std::vector<double> still_field_values_;         // per sensor, NaN until read; empty unless still
  // The sensors by cell, built on first use (the dispensers, sensors off rows): runs on rows
  // never need it, and a million sensors' grid is 21 MB.
  const net::SpatialGrid& sensor_grid() const;
  mutable net::SpatialGrid sensor_grid_;
  mutable bool sensor_grid_built_ = false;
  const net::LineIndex* sensor_lines_ = nullptr;  // the radio's, for the oracle's scanline pass
  std::vector<double> row_buffer_;
  protocols::RowSlicer slicer_;
  struct PendingRow {
    std::size_t line;
    double y, left, right;
    std::uint32_t first, last;  // the row's sensors, when `sure`
    bool sure;
  };
  std::vector<PendingRow> pending_rows_;
  std::unique_ptr<DiffusionField> diffusion_;
  std::vector<double> spray_rate_, neutraliser_used_;  // per robot
  std::uint64_t readings_taken_ = 0;
  double uniform_sensor_area_ = 0.0;  // > 0 when every sensor stands for the same area
  WorldObserver* observer_ = nullptr;
  sim::Duration actuation_delay_{0};  // def_.actuation_delay_s
  std::size_t dead_robots_ = 0, dead_sensors_ = 0;
  std::vector<std::unique_ptr<FollowerAgent>> followers_;
  void add_followers();
  void start_groups();
  void leader_tick(std::size_t group);
  void follower_tick(std::size_t follower);
  void follower_heard(std::size_t follower, const net::Frame& frame);
  void steer_follower(std::size_t follower);
  void schedule_faults();
  void strike(std::size_t fault);
  void lift(std::size_t fault);
  /// The nodes fault `fault` kills, decided when it strikes.
  std::vector<NodeId> fault_victims(std::size_t fault);
  std::vector<std::vector<NodeId>> fault_victims_;  // [fault]: who it took down
  TileCounts absorbed_;                             // the counts of the tiles this one absorbed
  TileCounts robot_reads_;  // what the robots read themselves (the oracle), of the counts above
  bool robots_here_ = true, keeps_courses_ = false;  // home_robots()
  std::vector<Course> course_outbox_;
  /// A course `robot` chose, for the other tiles' ghosts of it: they steer with the same key. Out
  /// of line: inlined in the robot's set_target, it stopped the senders of world.cpp inlining the
  /// payload's move.
  void keep_course(std::size_t robot, std::uint32_t generation, sim::Time when, const Vec2& target);
};

}  // namespace masnet::agents
