#pragma once
// Helpers shared by protocols/geometry.cpp and protocols/polygon_measures.cpp; internal to the
// protocols library, not part of its API.
#include <algorithm>
#include <cmath>
#include <span>

#include "net/vec2.hpp"

namespace masnet::protocols::geometry_internal {

/// The largest |coordinate| of the points, 0 when there are none: the scale of the relative
/// tolerances (kGeometryRelTol).
inline double max_abs_coordinate(std::span<const net::Vec2> points) {
  double m = 0.0;
  for (const net::Vec2& p : points)
    m = std::max({m, std::abs(p.x()), std::abs(p.y())});
  return m;
}

}  // namespace masnet::protocols::geometry_internal
