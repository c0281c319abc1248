#pragma once
// Observes a World from outside the model (output is never written from inside it):
// per-update protocol records with cell correctness, periodic time-series samples,
// trajectories and snapshots. Sampling runs between `run_until` chunks, not as events, so
// what is recorded never changes the event stream or its fingerprint.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "agents/world.hpp"
#include "scenarios/loader/scenario.hpp"
#include "scenarios/run/lifetime_outputs.hpp"
#include "scenarios/run/tracking_metrics.hpp"
#include "scenarios/run/update_statistics.hpp"

namespace masnet::scenarios {

/// One row of timeseries.csv.
struct Sample {
  double t_s = 0;
  double coverage_cost = 0;          ///< Σ_s ρ(s)·A(s)·‖s − p_nearest‖² (discrete eq. 1)
  double mean_dist_to_centroid = 0;  ///< ‖p_i − c_i‖ with c_i the true centroid of i's cell
  double max_dist_to_centroid = 0;
  double mean_radius = 0;                      ///< mean R_i
  std::uint64_t messages = 0, bytes = 0;       ///< transmissions so far
  double energy_j = 0;                         ///< radio energy so far, all nodes
  double tracking_mean = 0, tracking_max = 0;  ///< distance from targets to their nearest robot
  /// Robots in each target's group (docs/outputs.md, "Tracking").
  std::vector<std::uint32_t> robots_per_target;
  double cell_correctness = 1.0;        ///< share of updates so far with the oracle's neighbour set
  double cell_correctness_heard = 1.0;  ///< the same against the cell of the positions heard
  std::uint64_t updates = 0;
  std::uint64_t collisions = 0;  ///< receptions lost to overlap so far (levels collision, csma)
  // Diffusion runs (paper §VI-B).
  double pollution_total = 0;     ///< Σ of the sensors' readings (paper Fig. 6)
  double pollution_integral = 0;  ///< ∫u dA by the solver's quadrature
  double pollution_max = 0;       ///< max u over the PDE grid
  double neutraliser_used = 0;    ///< released by all dispensers so far
  double pollution_total_baseline = 0, pollution_integral_baseline = 0;  ///< same run, no control
  // Runs with faults or batteries (lifetime_outputs.hpp).
  std::size_t alive_sensors = 0, alive_robots = 0;
  double locomotion_j = 0;               ///< all robots so far
  double cell_correctness_recent = 1.0;  ///< among the updates since the previous sample
  double coverage_cost_twin = 0, tracking_mean_twin = 0;  ///< the fault-free twin's
  double cell_correctness_recent_twin = 1.0;
};

class Recorder final : public agents::WorldObserver {
 public:
  Recorder(agents::World& world, const ScenarioDef& def);

  void sample();               ///< a timeseries row at the current time
  void sample_trajectories();  ///< a trajectories row per robot
  void snapshot();             ///< the state for a snapshot figure

  void on_update(std::size_t robot, const protocols::UpdateRecord& record) override;
  /// Called after each update is recorded (the live viewer's "one update at a time").
  void set_update_listener(std::function<void()> listener) {
    update_listener_ = std::move(listener);
  }
  void on_battery_empty(sim::NodeId node) override;
  void on_node_down(sim::NodeId node, agents::DownCause cause) override;
  void on_node_up(sim::NodeId node) override;

  /// Files of the run directory (`dir` exists).
  void write_timeseries(const std::string& path) const;
  void write_trajectories(const std::string& path) const;
  void write_updates(const std::string& path) const;
  void write_nodes(const std::string& path) const;
  void write_snapshots(const std::string& path) const;
  /// The metric sections of summary.json (messages, energy, protocol, coverage, tracking).
  nlohmann::json summary_metrics() const;
  /// The `pollution` section of summary.json (diffusion runs).
  nlohmann::json pollution_summary() const;

  const std::vector<Sample>& samples() const { return samples_; }
  /// Takes the pollution curves of the uncontrolled twin run (same sample times).
  void attach_baseline(const std::vector<Sample>& baseline);
  /// Takes the curves of the fault-free twin run (same sample times).
  void attach_twin(const std::vector<Sample>& twin);

 private:
  struct UpdateRow {
    protocols::UpdateSummary record;  // the robots heard are judged, not kept
    bool correct = false;             ///< the neighbour set of the true positions at the end
    bool correct_heard = false;       ///< the neighbour set of the positions the update heard
  };
  struct TrajectoryRow {
    double t_s;
    std::uint32_t robot;
    Vec2 position, velocity;
    double radius;
    Vec2 target;
  };
  /// Nearest robot of every sensor now (ties: lower index): a scan over few robots, else a grid.
  void assign_sensors(const std::vector<Vec2>& robots, std::vector<std::uint32_t>& nearest) const;
  /// Up to this many robots a plain scan beats building a grid per sample.
  static constexpr std::size_t kScanRobots = 32;

  agents::World& world_;
  const ScenarioDef& def_;
  std::vector<Sample> samples_;
  std::vector<TrajectoryRow> trajectories_;
  std::vector<UpdateRow> updates_;  // only when updates.csv is written
  UpdateStatistics update_stats_;
  nlohmann::json snapshots_ = nlohmann::json::array();
  std::optional<TrackingMetrics> tracking_;  // acoustic runs, from the first sample
  bool has_baseline_ = false;
  LifetimeLog lifetime_;
  bool has_twin_ = false;
  std::function<void()> update_listener_;
};

}  // namespace masnet::scenarios
