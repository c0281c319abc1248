#include "agents/targets.hpp"

#include <cmath>

namespace masnet::agents {
namespace {

// Length of the polyline (closed if looping).
double path_length(const PathDef& p) {
  double length = 0.0;
  for (std::size_t i = 1; i < p.waypoints.size(); ++i)
    length += (p.waypoints[i] - p.waypoints[i - 1]).norm();
  if (p.loop && p.waypoints.size() > 1) length += (p.waypoints.front() - p.waypoints.back()).norm();
  return length;
}

// The segment [a, b] containing arc length s, and the offset inside it.
bool locate(const PathDef& p, double s, Vec2& a, Vec2& b, double& offset) {
  const std::size_t n = p.waypoints.size();
  const std::size_t segments = p.loop ? n : n - 1;
  for (std::size_t i = 0; i < segments; ++i) {
    a = p.waypoints[i];
    b = p.waypoints[(i + 1) % n];
    const double length = (b - a).norm();
    if (s <= length) {
      offset = s;
      return true;
    }
    s -= length;
  }
  return false;
}

}  // namespace

Vec2 position_on(const PathDef& path, double t_s) {
  if (path.waypoints.empty()) return path.start + t_s * path.velocity;
  if (path.waypoints.size() == 1 || path.speed <= 0.0) return path.waypoints.front();
  const double total = path_length(path);
  double s = path.speed * t_s;
  if (path.loop && total > 0.0) s = std::fmod(s, total);
  Vec2 a, b;
  double offset = 0.0;
  if (!locate(path, s, a, b, offset))
    return path.loop ? path.waypoints.front() : path.waypoints.back();
  const double length = (b - a).norm();
  return length > 0.0 ? a + (offset / length) * (b - a) : a;
}

Vec2 heading_on(const PathDef& path, double t_s) {
  if (path.waypoints.empty()) {
    const double speed = path.velocity.norm();
    return speed > 0.0 ? Vec2(path.velocity / speed) : Vec2{0, 0};
  }
  const Vec2 here = position_on(path, t_s), later = position_on(path, t_s + 1e-3);
  const double d = (later - here).norm();
  return d > 0.0 ? Vec2((later - here) / d) : Vec2{0, 0};
}

}  // namespace masnet::agents
