#pragma once
// The tracking metrics of acoustic runs (docs/outputs.md, "Tracking"): how far each target is
// from its nearest robot, and the robot groups of paper §IV measured so that robots which
// follow a target score better than robots a target only passes by. A robot is in target k's
// group at a sample when k is its nearest target and it lies within the tracking radius of k.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "net/vec2.hpp"

namespace masnet::scenarios {

/// The default tracking radius, world units: √(area / (π · robots)), the radius of the disc in
/// which robots spread uniformly over the domain put one robot on average.
double default_tracking_radius(double domain_area, std::size_t robots);

/// What one sample shows.
struct TrackingSample {
  double error_mean = 0, error_max = 0;    ///< distance from each target to its nearest robot
  std::vector<std::uint32_t> group_sizes;  ///< robots in each target's group
};

/// Samples in time order; the summary integrates between them (trapezoid rule).
class TrackingMetrics {
 public:
  explicit TrackingMetrics(double tracking_radius_world) : radius_(tracking_radius_world) {}

  static constexpr int kNoGroup = -1;

  TrackingSample sample(double t_s, const std::vector<net::Vec2>& robots,
                        const std::vector<net::Vec2>& targets);

  double tracking_radius() const { return radius_; }
  /// Each robot's group at the last sample: a target index or kNoGroup.
  const std::vector<int>& groups() const { return groups_; }

  /// summary.json's tracking keys: mean_error, max_error_after_1s, tracking_radius,
  /// robots_per_target (time averages), robots_per_target_final, tracking_share, group_changes,
  /// group_changes_per_member_s (null when no robot was ever in a group).
  nlohmann::json summary() const;

 private:
  double radius_;
  std::size_t samples_ = 0, robots_ = 0;
  double first_t_s_ = 0, last_t_s_ = 0;
  std::vector<int> groups_;
  std::vector<std::uint32_t> sizes_;    // at the last sample
  std::uint32_t members_ = 0;           // robots in some group at the last sample
  std::vector<double> size_integrals_;  // ∫ group size dt, robot·s, per target
  double member_integral_ = 0;          // ∫ robots in some group dt, robot·s
  std::uint64_t group_changes_ = 0;
  double error_mean_sum_ = 0, error_max_after_1s_ = 0;
};

}  // namespace masnet::scenarios
