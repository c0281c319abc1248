#pragma once
// The paths of targets, sources and Gaussian bumps as the resolved scenario in summary.json
// writes them, so that the trajectory figure can draw them without the simulator's agents.
// position_on follows agents::position_on exactly (a test compares the two).
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenarios/report/plot/plot.hpp"

namespace masnet::scenarios {

/// A straight line (start + velocity·t) or a polyline of waypoints at a constant speed.
struct TargetPath {
  plot::Point start;
  plot::Point velocity;                ///< world units / s (straight line)
  std::vector<plot::Point> waypoints;  ///< if not empty: the path, from waypoints[0]
  double speed = 0.0;                  ///< along the waypoints, world units / s
  bool loop = false;                   ///< back to waypoints[0] after the last one, forever
};

/// A path of the resolved scenario: {start or position, velocity} or waypoints, possibly
/// nested under "path" (Gaussian bumps). Nothing when the item describes no path.
std::optional<TargetPath> target_path_from_json(const nlohmann::json& item);

/// Position on the path at time t (seconds from the start of the run). Past the last waypoint
/// (without loop) the entity stays there.
plot::Point position_on(const TargetPath& path, double t_s);

}  // namespace masnet::scenarios
