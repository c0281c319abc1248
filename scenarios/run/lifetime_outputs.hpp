#pragma once
// Faults and network lifetime in the run's files (docs/outputs.md): which nodes went down and
// came back, the extra timeseries.csv columns of runs with faults or batteries, summary.json's
// `lifetime` and `recovery`, and the fault-free twin's curves beside the run's own.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "agents/world.hpp"
#include "scenarios/loader/scenario.hpp"

namespace masnet::scenarios {

struct Sample;

/// Runs with scripted faults or any battery write the lifetime columns and sections; other
/// runs' files stay as they were before faults existed.
bool has_lifetime_outputs(const agents::WorldDef& world);

/// The time t_k − `from_s` of the earliest sample k with t_k ≥ `from_s` from which `ok` holds
/// at every sample to the end; none when the last sample fails or no sample is that late.
std::optional<double> settling_time_s(const std::vector<double>& t_s, const std::vector<bool>& ok,
                                      double from_s);

/// Coverage has recovered when the cost is at most this far above the twin's (a share).
inline constexpr double kCoverageRecoveryShare = 0.05;
/// Cell correctness has recovered when the windowed share is above this.
inline constexpr double kCorrectnessRecovered = 0.95;

/// summary.json's `recovery`: one entry per scripted fault, measured on the samples (which
/// carry the twin's columns).
nlohmann::json recovery_summary(const std::vector<agents::FaultDef>& faults,
                                const std::vector<Sample>& samples);

/// Who went down and came back, heard through the world's hooks, and the per-sample columns
/// that depend on it.
class LifetimeLog {
 public:
  LifetimeLog(std::size_t robots, std::size_t sensors);

  /// A node went down (once: a second report of the same death is ignored) or came back up.
  void down(sim::NodeId node, bool robot, agents::DownCause cause, double t_s);
  void up(sim::NodeId node, bool robot, double t_s);

  /// The lifetime fields of a sample: alive counts, locomotion so far, and the share of
  /// correct updates among those finished since the previous sample (the previous share when
  /// none finished).
  void fill(Sample& row, agents::World& world, std::uint64_t updates, std::uint64_t correct);

  /// summary.json's `lifetime`.
  nlohmann::json summary(const agents::World& world) const;

 private:
  struct Event {
    double t_s;
    bool robot;
    bool down;
  };
  std::size_t robots_, sensors_;
  std::vector<bool> down_;  // by node id
  std::vector<Event> events_;
  std::uint64_t deaths_battery_ = 0, deaths_fault_ = 0, restarts_ = 0;
  std::uint64_t updates_before_ = 0, correct_before_ = 0;
  double recent_ = 1.0;
};

/// The header of the extra timeseries.csv columns (each with its leading comma), and one
/// row's values; `twin`: the fault-free twin's columns too; `acoustic`: its tracking column.
std::string lifetime_columns(bool twin, bool acoustic);
std::string lifetime_values(const Sample& s, bool twin, bool acoustic);

/// The twin's columns copied onto the run's samples (same sample times).
void attach_twin_samples(std::vector<Sample>& samples, const std::vector<Sample>& twin);

}  // namespace masnet::scenarios
