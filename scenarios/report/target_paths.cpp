#include "scenarios/report/target_paths.hpp"

#include <cmath>
#include <cstddef>

namespace masnet::scenarios {
namespace {

using plot::Point;

double distance(Point a, Point b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  return std::sqrt(dx * dx + dy * dy);
}

// Length of the polyline (closed if looping).
double path_length(const TargetPath& p) {
  double length = 0.0;
  for (std::size_t i = 1; i < p.waypoints.size(); ++i)
    length += distance(p.waypoints[i - 1], p.waypoints[i]);
  if (p.loop && p.waypoints.size() > 1) length += distance(p.waypoints.back(), p.waypoints.front());
  return length;
}

// The segment [a, b] containing arc length s, and the offset inside it.
bool locate(const TargetPath& p, double s, Point& a, Point& b, double& offset) {
  const std::size_t n = p.waypoints.size();
  const std::size_t segments = p.loop ? n : n - 1;
  for (std::size_t i = 0; i < segments; ++i) {
    a = p.waypoints[i];
    b = p.waypoints[(i + 1) % n];
    const double length = distance(a, b);
    if (s <= length) {
      offset = s;
      return true;
    }
    s -= length;
  }
  return false;
}

}  // namespace

std::optional<TargetPath> target_path_from_json(const nlohmann::json& item) {
  using nlohmann::json;
  if (!item.is_object()) return std::nullopt;
  const json& p = item.contains("path") && item["path"].is_object() ? item["path"] : item;
  TargetPath d;
  auto vec = [](const json& j) { return Point{j.at(0).get<double>(), j.at(1).get<double>()}; };
  try {
    if (p.contains("waypoints") && p["waypoints"].is_array())
      for (const json& w : p["waypoints"])
        d.waypoints.push_back(vec(w));
    if (p.contains("start"))
      d.start = vec(p["start"]);
    else if (p.contains("position"))
      d.start = vec(p["position"]);
    else if (d.waypoints.empty())
      return std::nullopt;
    if (p.contains("velocity")) d.velocity = vec(p["velocity"]);
    d.speed = p.value("speed", 0.0);
    d.loop = p.value("loop", false);
  } catch (const json::exception&) {
    return std::nullopt;
  }
  return d;
}

Point position_on(const TargetPath& path, double t_s) {
  if (path.waypoints.empty())
    return {path.start.x + t_s * path.velocity.x, path.start.y + t_s * path.velocity.y};
  if (path.waypoints.size() == 1 || path.speed <= 0.0) return path.waypoints.front();
  const double total = path_length(path);
  double s = path.speed * t_s;
  if (path.loop && total > 0.0) s = std::fmod(s, total);
  Point a, b;
  double offset = 0.0;
  if (!locate(path, s, a, b, offset))
    return path.loop ? path.waypoints.front() : path.waypoints.back();
  const double length = distance(a, b);
  if (!(length > 0.0)) return a;
  const double u = offset / length;
  return {a.x + u * (b.x - a.x), a.y + u * (b.y - a.y)};
}

}  // namespace masnet::scenarios
