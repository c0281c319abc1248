#pragma once
// Positions and velocities in world units (the domain is the unit square by default;
// `radio.meters_per_unit` converts to metres for the energy model).
#include <Eigen/Core>

namespace masnet::net {

using Vec2 = Eigen::Vector2d;

}  // namespace masnet::net
