#include "protocols/geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <tuple>

#include "protocols/cell_builder.hpp"
#include "protocols/geometry_internal.hpp"
#include "sim/assert.hpp"

namespace masnet::protocols {
namespace {

using geometry_internal::canonicalize;
using geometry_internal::CellBuilder;
using geometry_internal::LabelledClipper;
using geometry_internal::max_abs_coordinate;

// Error-free transformations (Knuth, Dekker): a ∘ b == x + y exactly.
void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  const double a_virtual = x - b_virtual;
  y = (a - a_virtual) + (b - b_virtual);
}
void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  y = std::fma(a, b, -x);  // explicit fma is exact; -ffp-contract=off keeps x unfused
}

// The sign of (b − a) × (c − a) from its 16 exact partial products, summed into a
// non-overlapping expansion (Shewchuk's Grow-Expansion); the largest component has the sign.
int exact_orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  std::array<double, 2> bax, cay, bay, cax;
  two_sum(b.x(), -a.x(), bax[0], bax[1]);
  two_sum(c.y(), -a.y(), cay[0], cay[1]);
  two_sum(b.y(), -a.y(), bay[0], bay[1]);
  two_sum(c.x(), -a.x(), cax[0], cax[1]);
  std::array<double, 16> terms{};
  std::size_t k = 0;
  for (double u : bax)
    for (double v : cay) {
      two_product(u, v, terms[k], terms[k + 1]);
      k += 2;
    }
  for (double u : bay)
    for (double v : cax) {
      two_product(-u, v, terms[k], terms[k + 1]);
      k += 2;
    }
  std::array<double, 17> expansion{};
  std::size_t m = 0;
  for (double t : terms) {
    double q = t;
    std::size_t out = 0;
    for (std::size_t i = 0; i < m; ++i) {
      double sum = 0.0, err = 0.0;
      two_sum(q, expansion[i], sum, err);
      if (err != 0.0) expansion[out++] = err;
      q = sum;
    }
    if (q != 0.0) expansion[out++] = q;
    m = out;
  }
  if (m == 0) return 0;
  return expansion[m - 1] > 0.0 ? 1 : -1;
}

// The sign of a real number as -1, 0, +1.
int sign_of(double x) {
  return (x > 0.0) - (x < 0.0);
}

}  // namespace

int orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double left = (b.x() - a.x()) * (c.y() - a.y());
  const double right = (b.y() - a.y()) * (c.x() - a.x());
  const double det = left - right;
  // Shewchuk's first-stage bound (3 + 16ε)ε: beyond it the double result has the right sign.
  const double bound = 3.3306690738754716e-16 * (std::abs(left) + std::abs(right));
  if (det > bound || -det > bound) return sign_of(det);
  return exact_orientation(a, b, c);
}

ConvexPolygon rectangle(double xmin, double ymin, double xmax, double ymax) {
  if (!(xmin < xmax && ymin < ymax)) return {};
  return ConvexPolygon{{Vec2{xmin, ymin}, Vec2{xmax, ymin}, Vec2{xmax, ymax}, Vec2{xmin, ymax}}};
}

ConvexPolygon regular_polygon(const Vec2& center, double radius, int n) {
  if (n < 3 || !(radius > 0.0) || !std::isfinite(radius)) return {};
  // Vertices halfway between the edge normals, at circumradius radius / cos(π/n).
  const double circumradius = radius / std::cos(std::numbers::pi / n);
  std::vector<Vec2> pts;
  pts.reserve(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double angle = std::numbers::pi * (2 * k + 1) / n;
    pts.push_back(center + circumradius * Vec2{std::cos(angle), std::sin(angle)});
  }
  std::vector<std::uint32_t> labels(pts.size(), 0);
  canonicalize(pts, labels, kGeometryRelTol * max_abs_coordinate(pts));
  return ConvexPolygon{std::move(pts)};
}

HalfPlane bisector_half_plane(const Vec2& site, const Vec2& other) {
  return geometry_internal::bisector(site, other);
}

ConvexPolygon clip(const ConvexPolygon& polygon, const HalfPlane& half_plane) {
  thread_local LabelledClipper clipper;
  clipper.reset(polygon.vertices, 0);
  clipper.clip(half_plane, 0, max_abs_coordinate(polygon.vertices));
  return ConvexPolygon{{clipper.points().begin(), clipper.points().end()}};
}

Cell voronoi_cell(std::uint32_t site, std::span<const Vec2> sites,
                  std::span<const std::uint32_t> candidates, const ConvexPolygon& domain,
                  double disk_radius) {
  MASNET_ASSERT(site < sites.size(), "voronoi_cell: site index out of range");
  if (domain.empty() || !(disk_radius > 0.0)) return Cell{};
  // Reused across calls on this thread: no allocation once its buffers have grown.
  thread_local CellBuilder builder;
  builder.start(site, sites, domain);
  for (std::uint32_t c : candidates) {
    MASNET_ASSERT(c < sites.size(), "voronoi_cell: candidate index out of range");
    if (!builder.add_candidate(c, sites[c])) break;
  }
  builder.add_disk(disk_radius);
  return builder.finish();
}

bool contains(std::span<const Vec2> v, const Vec2& point) {
  if (v.size() < 3) return false;
  // Edges (prev, i) walk the polygon without a modulo per step: this runs for every sensor that
  // hears a SENSE.
  for (std::size_t prev = v.size() - 1, i = 0; i < v.size(); prev = i++)
    if (orientation(v[prev], v[i], point) < 0) return false;
  return true;
}

bool contains(const ConvexPolygon& polygon, const Vec2& point) {
  return contains(std::span<const Vec2>(polygon.vertices), point);
}

void RowSlicer::reset(std::span<const Vec2> v) {
  const std::size_t n = v.size();
  left_.edges.clear();
  right_.edges.clear();
  left_.at = right_.at = 0;
  valid_ = n >= 3;
  if (!valid_) return;
  auto next = [n](std::size_t i) { return i + 1 == n ? 0 : i + 1; };
  auto prev = [n](std::size_t i) { return i == 0 ? n - 1 : i - 1; };
  std::size_t low = 0, high = 0;
  double largest_x = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (v[i].y() < v[low].y()) low = i;
    if (v[i].y() > v[high].y()) high = i;
    largest_x = std::max(largest_x, std::fabs(v[i].x()));
  }
  y_min_ = v[low].y();
  y_max_ = v[high].y();
  // CCW, the bottom edge (if horizontal) runs left to right and the top edge right to left:
  // the right chain climbs from the last bottom vertex to the first top vertex, the left chain
  // from the first bottom vertex (walking backwards) to the last top vertex.
  std::size_t right_start = low, left_start = low;
  for (std::size_t k = 0; k < n && v[next(right_start)].y() == y_min_; ++k)
    right_start = next(right_start);
  for (std::size_t k = 0; k < n && v[prev(left_start)].y() == y_min_; ++k)
    left_start = prev(left_start);
  // The slope form x0 + (y − y0)·slope has (y − y0)·slope within a few ulps of the edge's Δx
  // (0 <= y − y0 <= Δy), so every end is within a few ulps of max |x|; 64 ulps is ample.
  margin_ = 64.0 * std::numeric_limits<double>::epsilon() * largest_x +
            std::numeric_limits<double>::denorm_min();
  max_abs_x_ = largest_x;
  auto add = [this](Chain& chain, const Vec2& a, const Vec2& b) {
    const double slope = (b.x() - a.x()) / (b.y() - a.y());
    if (!std::isfinite(slope)) margin_ = std::numeric_limits<double>::infinity();
    chain.edges.push_back(Edge{b.y(), a.x(), a.y(), std::isfinite(slope) ? slope : 0.0});
  };
  for (std::size_t i = right_start, k = 0; k < n && v[i].y() < y_max_; i = next(i), ++k)
    add(right_, v[i], v[next(i)]);
  for (std::size_t i = left_start, k = 0; k < n && v[i].y() < y_max_; i = prev(i), ++k)
    add(left_, v[i], v[prev(i)]);
  // Zero height breaks ConvexPolygon's promise; the caller falls back to contains().
  if (right_.edges.empty() || left_.edges.empty()) valid_ = false;
}

void ConvexMembership::reset(std::span<const Vec2> vertices) {
  vertices_.assign(vertices.begin(), vertices.end());
  slicer_.reset(vertices_);
  row_valid_ = false;
}

bool ConvexMembership::contains(const Vec2& point) {
  if (!slicer_.valid()) return protocols::contains(vertices_, point);
  const double y = point.y();
  // Strictly below the lowest vertex or above the highest: outside, as the exact test says.
  if (y < slicer_.y_min() || y > slicer_.y_max()) return false;
  if (!row_valid_ || y != row_y_) {
    if (row_valid_ && y < row_y_) slicer_.rewind();
    std::tie(left_, right_) = slicer_.extent(y);
    row_y_ = y;
    row_valid_ = true;
  }
  return slicer_.contains_on_row(vertices_, point, left_, right_);
}

bool is_gabriel_neighbour(const Vec2& a, const Vec2& b, std::span<const Vec2> others) {
  // q is strictly inside the circle on diameter ab iff the angle aqb is obtuse.
  for (const Vec2& q : others)
    if ((a - q).dot(b - q) < 0.0) return false;
  return true;
}

std::vector<std::uint32_t> gabriel_neighbours(std::uint32_t site, std::span<const Vec2> sites) {
  MASNET_ASSERT(site < sites.size(), "gabriel_neighbours: site index out of range");
  std::vector<std::uint32_t> result;
  for (std::size_t j = 0; j < sites.size(); ++j)
    if (j != site && is_gabriel_neighbour(sites[site], sites[j], sites))
      result.push_back(static_cast<std::uint32_t>(j));
  return result;
}

}  // namespace masnet::protocols
