#pragma once
// Moving, non-networked entities that shape ρ: acoustic targets, pollution sources, Gaussian
// bumps. Each follows a straight line (start + velocity·t) or a polyline of waypoints at a
// constant speed.
#include <vector>

#include "net/vec2.hpp"

namespace masnet::agents {

using net::Vec2;

struct PathDef {
  Vec2 start{0, 0};
  Vec2 velocity{0, 0};          ///< world units / s (straight line)
  std::vector<Vec2> waypoints;  ///< if not empty: the path, from waypoints[0]
  double speed = 0.0;           ///< along the waypoints, world units / s
  bool loop = false;            ///< back to waypoints[0] after the last one, forever
};

/// Position on the path at time t (seconds from the start of the run). Past the last
/// waypoint (without loop) the entity stays there.
Vec2 position_on(const PathDef& path, double t_s);
/// Direction of motion at time t (unit vector, or zero when standing still).
Vec2 heading_on(const PathDef& path, double t_s);

}  // namespace masnet::agents
