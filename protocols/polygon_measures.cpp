// Questions asked of one polygon rather than constructions: its measures (area, perimeter,
// centroid, polar moment, farthest vertex) and the checks that make a user polygon canonical.
// None of it runs inside the clipping of cells (protocols/geometry.cpp).
#include <algorithm>
#include <cmath>

#include "protocols/geometry.hpp"
#include "protocols/geometry_internal.hpp"

namespace masnet::protocols {
namespace {

using geometry_internal::max_abs_coordinate;

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Closed-segment intersection with exact predicates.
bool on_segment_if_collinear(const Vec2& a, const Vec2& b, const Vec2& q) {
  return std::min(a.x(), b.x()) <= q.x() && q.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= q.y() && q.y() <= std::max(a.y(), b.y());
}
bool segments_intersect(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
  const int o1 = orientation(p1, p2, q1), o2 = orientation(p1, p2, q2);
  const int o3 = orientation(q1, q2, p1), o4 = orientation(q1, q2, p2);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && on_segment_if_collinear(p1, p2, q1)) ||
         (o2 == 0 && on_segment_if_collinear(p1, p2, q2)) ||
         (o3 == 0 && on_segment_if_collinear(q1, q2, p1)) ||
         (o4 == 0 && on_segment_if_collinear(q1, q2, p2));
}

// Twice the signed area, fanned from the first vertex for accuracy.
double twice_signed_area(std::span<const Vec2> v) {
  double sum = 0.0;
  for (std::size_t i = 1; i + 1 < v.size(); ++i)
    sum += cross(v[i] - v[0], v[i + 1] - v[0]);
  return sum;
}

}  // namespace

bool is_convex_ccw(std::span<const Vec2> v) {
  const std::size_t n = v.size();
  if (n < 3) return false;
  // Every turn is in (0, π), so the edge direction crosses angle 0 exactly once per
  // revolution: going from the lower half-plane [π, 2π) into the upper one [0, π).
  auto upper = [](const Vec2& d) { return d.y() > 0.0 || (d.y() == 0.0 && d.x() > 0.0); };
  int wraps = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = v[i];
    const Vec2& b = v[(i + 1) % n];
    const Vec2& c = v[(i + 2) % n];
    if (orientation(a, b, c) <= 0) return false;
    if (!upper(b - a) && upper(c - b)) ++wraps;
  }
  return wraps == 1;
}

bool is_simple(std::span<const Vec2> v) {
  const std::size_t n = v.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (v[i] == v[(i + 1) % n]) return false;
  // Adjacent edges a→b, b→c overlap when c turns straight back along b→a.
  auto folds_back = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    if (orientation(a, b, c) != 0) return false;
    if (a.x() != b.x()) return (a.x() < b.x()) == (c.x() < b.x());
    return (a.y() < b.y()) == (c.y() < b.y());
  };
  for (std::size_t i = 0; i < n; ++i)
    if (folds_back(v[i], v[(i + 1) % n], v[(i + 2) % n])) return false;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (segments_intersect(v[i], v[i + 1], v[j], v[(j + 1) % n])) return false;
    }
  }
  return true;
}

std::optional<ConvexPolygon> normalize_convex_polygon(std::span<const Vec2> vertices) {
  std::vector<Vec2> v;
  v.reserve(vertices.size());
  for (const Vec2& p : vertices)
    if (v.empty() || p != v.back()) v.push_back(p);
  while (v.size() > 1 && v.back() == v.front())
    v.pop_back();
  if (v.size() < 3) return std::nullopt;
  const double a2 = twice_signed_area(v);
  if (!(a2 != 0.0) || !std::isfinite(a2)) return std::nullopt;
  if (a2 < 0.0) std::reverse(v.begin(), v.end());
  // Drop a vertex lying (within tolerance) on the segment between its neighbours.
  const double tol = kGeometryRelTol * max_abs_coordinate(v);
  bool changed = true;
  while (changed && v.size() >= 3) {
    changed = false;
    for (std::size_t i = 0; i < v.size() && v.size() >= 3; ++i) {
      const std::size_t n = v.size();
      const Vec2& a = v[(i + n - 1) % n];
      const Vec2& b = v[i];
      const Vec2& c = v[(i + 1) % n];
      const Vec2 ac = c - a;
      const double along = (b - a).dot(ac);
      if (std::abs(cross(ac, b - a)) <= tol * ac.norm() && along >= 0.0 &&
          along <= ac.squaredNorm()) {
        v.erase(v.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        break;
      }
    }
  }
  if (!is_simple(v) || !is_convex_ccw(v)) return std::nullopt;
  return ConvexPolygon{std::move(v)};
}

double area(const ConvexPolygon& polygon) {
  if (polygon.vertices.size() < 3) return 0.0;
  return 0.5 * twice_signed_area(polygon.vertices);
}

double perimeter(const ConvexPolygon& polygon) {
  const auto& v = polygon.vertices;
  double sum = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i)
    sum += (v[(i + 1) % v.size()] - v[i]).norm();
  return sum;
}

Vec2 centroid(const ConvexPolygon& polygon) {
  const auto& v = polygon.vertices;
  if (v.empty()) return Vec2::Zero();
  // Fan from v[0]: each triangle's centroid weighted by its (doubled) area.
  double a2 = 0.0;
  Vec2 moment = Vec2::Zero();
  for (std::size_t i = 1; i + 1 < v.size(); ++i) {
    const Vec2 a = v[i] - v[0], b = v[i + 1] - v[0];
    const double w = cross(a, b);
    a2 += w;
    moment += w * (a + b);
  }
  if (a2 > 0.0) {
    const Vec2 c = v[0] + moment / (3.0 * a2);
    if (std::isfinite(c.x()) && std::isfinite(c.y())) return c;
  }
  Vec2 mean = Vec2::Zero();
  for (const Vec2& p : v)
    mean += p;
  return mean / static_cast<double>(v.size());
}

double polar_moment(const ConvexPolygon& polygon, const Vec2& point) {
  const auto& v = polygon.vertices;
  if (v.size() < 3) return 0.0;
  // Triangle (point, a, b): ∫|q − point|² = cross(a, b)·(|a|² + a·b + |b|²) / 12.
  double sum = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 a = v[i] - point, b = v[(i + 1) % v.size()] - point;
    sum += cross(a, b) * (a.squaredNorm() + a.dot(b) + b.squaredNorm());
  }
  return sum / 12.0;
}

double max_vertex_distance(const ConvexPolygon& polygon, const Vec2& point) {
  double d2 = 0.0;
  for (const Vec2& v : polygon.vertices)
    d2 = std::max(d2, (v - point).squaredNorm());
  return std::sqrt(d2);
}

}  // namespace masnet::protocols
