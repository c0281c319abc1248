#include "scenarios/run/tracking_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace masnet::scenarios {

double default_tracking_radius(double domain_area, std::size_t robots) {
  return std::sqrt(domain_area /
                   (std::numbers::pi * static_cast<double>(std::max<std::size_t>(robots, 1))));
}

TrackingSample TrackingMetrics::sample(double t_s, const std::vector<net::Vec2>& robots,
                                       const std::vector<net::Vec2>& targets) {
  TrackingSample out;
  out.group_sizes.assign(targets.size(), 0);
  if (!robots.empty())
    for (const net::Vec2& target : targets) {
      double best = std::numeric_limits<double>::infinity();
      for (const net::Vec2& p : robots)
        best = std::min(best, (p - target).norm());
      out.error_mean += best / static_cast<double>(targets.size());
      out.error_max = std::max(out.error_max, best);
    }

  // Groups: the nearest target (ties: the lower index), if within the radius.
  std::vector<int> groups(robots.size(), kNoGroup);
  std::uint32_t members = 0;
  for (std::size_t i = 0; i < robots.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    int nearest = kNoGroup;
    for (std::size_t k = 0; k < targets.size(); ++k) {
      const double d = (robots[i] - targets[k]).norm();
      if (d < best) {
        best = d;
        nearest = static_cast<int>(k);
      }
    }
    if (nearest != kNoGroup && best <= radius_) {
      groups[i] = nearest;
      ++out.group_sizes[static_cast<std::size_t>(nearest)];
      ++members;
    }
  }

  if (samples_ == 0) {
    first_t_s_ = t_s;
    robots_ = robots.size();
    size_integrals_.assign(targets.size(), 0.0);
  } else {
    const double dt_s = t_s - last_t_s_;
    for (std::size_t k = 0; k < targets.size() && k < sizes_.size(); ++k)
      size_integrals_[k] += 0.5 * (static_cast<double>(sizes_[k]) + out.group_sizes[k]) * dt_s;
    member_integral_ += 0.5 * (static_cast<double>(members_) + members) * dt_s;
    for (std::size_t i = 0; i < groups.size() && i < groups_.size(); ++i)
      group_changes_ += groups[i] != groups_[i] ? 1 : 0;
  }
  error_mean_sum_ += out.error_mean;
  if (t_s >= 1.0) error_max_after_1s_ = std::max(error_max_after_1s_, out.error_max);
  ++samples_;
  last_t_s_ = t_s;
  groups_ = std::move(groups);
  sizes_ = out.group_sizes;
  members_ = members;
  return out;
}

nlohmann::json TrackingMetrics::summary() const {
  const double span_s = last_t_s_ - first_t_s_;
  std::vector<double> per_target(sizes_.size(), 0.0);
  double share = 0;
  if (span_s > 0) {
    for (std::size_t k = 0; k < per_target.size(); ++k)
      per_target[k] = size_integrals_[k] / span_s;
    if (robots_ > 0) share = member_integral_ / span_s / static_cast<double>(robots_);
  } else {  // one sample: its values
    for (std::size_t k = 0; k < per_target.size(); ++k)
      per_target[k] = sizes_[k];
    if (robots_ > 0) share = static_cast<double>(members_) / static_cast<double>(robots_);
  }
  // Changes per robot-second spent in a group: how often members come and go, whatever the
  // size of the groups (docs/outputs.md, "Tracking"). Undefined when no robot was in a group.
  nlohmann::json per_member = nullptr;
  if (member_integral_ > 0) per_member = static_cast<double>(group_changes_) / member_integral_;
  return {{"mean_error", samples_ ? error_mean_sum_ / static_cast<double>(samples_) : 0.0},
          {"max_error_after_1s", error_max_after_1s_},
          {"tracking_radius", radius_},
          {"robots_per_target", per_target},
          {"robots_per_target_final", sizes_},
          {"tracking_share", share},
          {"group_changes", group_changes_},
          {"group_changes_per_member_s", per_member}};
}

}  // namespace masnet::scenarios
