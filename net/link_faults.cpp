#include "net/link_faults.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace masnet::net {
namespace {

double cross(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

int sign(double v) {
  return (v > 0) - (v < 0);
}

}  // namespace

bool Region::contains(const Vec2& p) const {
  if (shape == Shape::disk) return (p - center).squaredNorm() <= radius * radius;
  // Even-odd rule: a ray to +x crosses the boundary an odd number of times from inside.
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

double Region::area() const {
  if (shape == Shape::disk) return std::numbers::pi * radius * radius;
  double twice = 0.0;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
    twice += polygon[j].x() * polygon[i].y() - polygon[i].x() * polygon[j].y();
  return 0.5 * std::abs(twice);
}

bool LineCut::separates(const Vec2& p, const Vec2& q) const {
  const int d1 = sign(cross(a, b, p)), d2 = sign(cross(a, b, q));
  const int d3 = sign(cross(p, q, a)), d4 = sign(cross(p, q, b));
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;  // a proper crossing
  // Touching and collinear cases: an end point on the other segment.
  return (d1 == 0 && on_segment(a, b, p)) || (d2 == 0 && on_segment(a, b, q)) ||
         (d3 == 0 && on_segment(p, q, a)) || (d4 == 0 && on_segment(p, q, b));
}

void LinkFaults::remove(std::uint32_t id) {
  std::erase_if(cuts_, [id](const auto& c) { return c.first == id; });
  std::erase_if(areas_, [id](const auto& a) { return a.first == id; });
}

bool LinkFaults::cut(const Vec2& from, const Vec2& to) const {
  for (const auto& [id, c] : cuts_)
    if (c.separates(from, to)) return true;
  return false;
}

double LinkFaults::loss(const Vec2& from, const Vec2& to) const {
  double kept = 1.0;
  for (const auto& [id, area] : areas_)
    if (area.region.contains(from) || area.region.contains(to)) kept *= 1.0 - area.loss;
  return 1.0 - kept;
}

}  // namespace masnet::net
