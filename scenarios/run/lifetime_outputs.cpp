#include "scenarios/run/lifetime_outputs.hpp"

#include <cmath>

#include <fmt/format.h>

#include "scenarios/run/recorder.hpp"

namespace masnet::scenarios {

bool has_lifetime_outputs(const agents::WorldDef& world) {
  if (!world.faults.empty()) return true;
  if (world.radio.energy.battery_j > 0 || world.sensor_battery_j > 0 || world.robot_battery_j > 0)
    return true;
  for (const agents::SensorDef& s : world.sensors)
    if (s.battery_j > 0) return true;
  return false;
}

std::optional<double> settling_time_s(const std::vector<double>& t_s, const std::vector<bool>& ok,
                                      double from_s) {
  const std::size_t n = std::min(t_s.size(), ok.size());
  std::optional<std::size_t> from;
  // Walk back from the end while the condition holds: the earliest sample of that tail.
  for (std::size_t k = n; k-- > 0;) {
    if (t_s[k] < from_s || !ok[k]) break;
    from = k;
  }
  if (!from) return std::nullopt;
  return t_s[*from] - from_s;
}

namespace {

const char* kind_name(agents::FaultKind kind) {
  switch (kind) {
    case agents::FaultKind::kill:
      return "kill";
    case agents::FaultKind::partition:
      return "partition";
    case agents::FaultKind::degrade:
      return "degrade";
  }
  return "unknown";
}

nlohmann::json seconds_or_null(const std::optional<double>& t) {
  return t ? nlohmann::json(*t) : nlohmann::json(nullptr);
}

}  // namespace

nlohmann::json recovery_summary(const std::vector<agents::FaultDef>& faults,
                                const std::vector<Sample>& samples) {
  std::vector<double> t;
  std::vector<bool> coverage_ok, correctness_ok;
  for (const Sample& s : samples) {
    t.push_back(s.t_s);
    // NaN (no robot alive) is never recovered.
    coverage_ok.push_back(s.coverage_cost <= (1.0 + kCoverageRecoveryShare) * s.coverage_cost_twin);
    correctness_ok.push_back(s.cell_correctness_recent > kCorrectnessRecovered);
  }
  const double last_s = t.empty() ? -1.0 : t.back();
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t f = 0; f < faults.size(); ++f) {
    const agents::FaultDef& fault = faults[f];
    const bool struck = fault.at_s <= last_s;
    out.push_back(
        {{"index", f},
         {"kind", kind_name(fault.kind)},
         {"at_s", fault.at_s},
         {"until_s", fault.restarts() ? nlohmann::json(fault.until_s) : nlohmann::json(nullptr)},
         {"struck", struck},
         {"coverage_recovery_s",
          struck ? seconds_or_null(settling_time_s(t, coverage_ok, fault.at_s)) : nullptr},
         {"correctness_recovery_s",
          struck ? seconds_or_null(settling_time_s(t, correctness_ok, fault.at_s)) : nullptr}});
  }
  return out;
}

LifetimeLog::LifetimeLog(std::size_t robots, std::size_t sensors)
    : robots_(robots), sensors_(sensors), down_(robots + sensors, false) {}

void LifetimeLog::down(sim::NodeId node, bool robot, agents::DownCause cause, double t_s) {
  const std::size_t n = sim::index(node);
  if (n >= down_.size() || down_[n]) return;  // the battery hook and the down hook both tell
  down_[n] = true;
  events_.push_back({t_s, robot, true});
  (cause == agents::DownCause::battery ? deaths_battery_ : deaths_fault_) += 1;
}

void LifetimeLog::up(sim::NodeId node, bool robot, double t_s) {
  const std::size_t n = sim::index(node);
  if (n >= down_.size() || !down_[n]) return;
  down_[n] = false;
  events_.push_back({t_s, robot, false});
  ++restarts_;
}

void LifetimeLog::fill(Sample& row, agents::World& world, std::uint64_t updates,
                       std::uint64_t correct) {
  row.alive_robots = world.alive_robot_count();
  row.alive_sensors = world.alive_sensor_count();
  for (std::size_t i = 0; i < world.robot_count(); ++i)
    row.locomotion_j += world.locomotion_energy_j(i);
  if (updates > updates_before_)
    recent_ = static_cast<double>(correct - correct_before_) /
              static_cast<double>(updates - updates_before_);
  updates_before_ = updates;
  correct_before_ = correct;
  row.cell_correctness_recent = recent_;
}

nlohmann::json LifetimeLog::summary(const agents::World& world) const {
  std::optional<double> first_sensor, tenth, half, first_robot;
  std::size_t sensors_down = 0;
  std::uint64_t sensor_deaths = 0, robot_deaths = 0;
  for (const Event& e : events_) {
    if (e.robot) {
      if (e.down && !first_robot) first_robot = e.t_s;
      robot_deaths += e.down ? 1 : 0;
      continue;
    }
    if (!e.down) {
      --sensors_down;
      continue;
    }
    ++sensors_down;
    ++sensor_deaths;
    if (!first_sensor) first_sensor = e.t_s;
    // At least 10 % (50 %) of the sensors down at once.
    if (!tenth && sensors_down * 10 >= sensors_) tenth = e.t_s;
    if (!half && sensors_down * 2 >= sensors_) half = e.t_s;
  }
  return {{"first_sensor_death_s", seconds_or_null(first_sensor)},
          {"sensors_dead_10pct_s", seconds_or_null(tenth)},
          {"sensors_dead_50pct_s", seconds_or_null(half)},
          {"first_robot_death_s", seconds_or_null(first_robot)},
          {"deaths",
           {{"battery", deaths_battery_},
            {"fault", deaths_fault_},
            {"sensors", sensor_deaths},
            {"robots", robot_deaths}}},
          {"restarts", restarts_},
          {"sensors_alive_final", world.alive_sensor_count()},
          {"robots_alive_final", world.alive_robot_count()}};
}

std::string lifetime_columns(bool twin, bool acoustic) {
  std::string s = ",alive_sensors,alive_robots,locomotion_j,cell_correctness_recent";
  if (twin) {
    s += ",coverage_cost_twin";
    if (acoustic) s += ",tracking_error_mean_twin";
    s += ",cell_correctness_recent_twin";
  }
  return s;
}

std::string lifetime_values(const Sample& s, bool twin, bool acoustic) {
  std::string out = fmt::format(",{},{},{},{}", s.alive_sensors, s.alive_robots, s.locomotion_j,
                                s.cell_correctness_recent);
  if (twin) {
    out += fmt::format(",{}", s.coverage_cost_twin);
    if (acoustic) out += fmt::format(",{}", s.tracking_mean_twin);
    out += fmt::format(",{}", s.cell_correctness_recent_twin);
  }
  return out;
}

void attach_twin_samples(std::vector<Sample>& samples, const std::vector<Sample>& twin) {
  for (std::size_t k = 0; k < samples.size() && k < twin.size(); ++k) {
    samples[k].coverage_cost_twin = twin[k].coverage_cost;
    samples[k].tracking_mean_twin = twin[k].tracking_mean;
    samples[k].cell_correctness_recent_twin = twin[k].cell_correctness_recent;
  }
}

}  // namespace masnet::scenarios
