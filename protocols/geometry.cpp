#include "protocols/geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <tuple>

#include "protocols/geometry_internal.hpp"
#include "sim/assert.hpp"

namespace masnet::protocols {
namespace {

using geometry_internal::max_abs_coordinate;

// Edge labels of a cell under construction; candidate indices use the rest of the range.
constexpr std::uint32_t kDomainLabel = 0xFFFFFFFFu;
constexpr std::uint32_t kDiskLabel = 0xFFFFFFFEu;

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

// Removes, until none is left, vertices closer than tol_len to their successor and vertices
// whose turn is not strictly left (exact). labels[i] names edge i → i+1; a merged edge keeps
// the label of its longer part. Fewer than 3 vertices left: the polygon is empty.
void canonicalize(std::vector<Vec2>& pts, std::vector<std::uint32_t>& labels, double tol_len) {
  const double tol_sq = tol_len * tol_len;
  bool changed = true;
  while (changed && pts.size() >= 3) {
    changed = false;
    for (std::size_t i = 0; i < pts.size() && pts.size() >= 3;) {
      const std::size_t n = pts.size();
      const std::size_t prev = (i + n - 1) % n, next = (i + 1) % n;
      if ((pts[next] - pts[i]).squaredNorm() <= tol_sq) {
        labels[i] = labels[next];
        pts.erase(pts.begin() + static_cast<std::ptrdiff_t>(next));
        labels.erase(labels.begin() + static_cast<std::ptrdiff_t>(next));
        changed = true;
        continue;
      }
      if (orientation(pts[prev], pts[i], pts[next]) <= 0) {
        if ((pts[next] - pts[i]).squaredNorm() > (pts[i] - pts[prev]).squaredNorm())
          labels[prev] = labels[i];
        pts.erase(pts.begin() + static_cast<std::ptrdiff_t>(i));
        labels.erase(labels.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        continue;
      }
      ++i;
    }
  }
  if (pts.size() < 3) {
    pts.clear();
    labels.clear();
  }
}

// A convex polygon whose edges carry the label of the constraint that made them, clipped in
// place by ping-ponging between two buffers (no allocation once the buffers have grown).
class LabelledClipper {
 public:
  void reset(std::span<const Vec2> vertices, std::uint32_t label) {
    pts_.assign(vertices.begin(), vertices.end());
    labels_.assign(vertices.size(), label);
  }
  bool empty() const { return pts_.empty(); }
  const std::vector<Vec2>& points() const { return pts_; }
  const std::vector<std::uint32_t>& labels() const { return labels_; }
  void clear() {
    pts_.clear();
    labels_.clear();
  }

  template <class Predicate>
  void relabel_if(Predicate&& predicate, std::uint32_t label) {
    for (std::uint32_t& l : labels_)
      if (predicate(l)) l = label;
  }

  double max_distance_sq(const Vec2& p) const {
    double d2 = 0.0;
    for (const Vec2& v : pts_)
      d2 = std::max(d2, (v - p).squaredNorm());
    return d2;
  }

  // Clips by `hp`, giving new edges `label`. `scale` is the coordinate magnitude setting the
  // tolerances (kGeometryRelTol). Returns true when the polygon changed.
  bool clip(const HalfPlane& hp, std::uint32_t label, double scale) {
    const std::size_t n = pts_.size();
    if (n == 0) return false;
    const double nx = hp.normal.x(), ny = hp.normal.y();
    // Rounding error of nx·x + ny·y − offset is a few ulps of this magnitude.
    const double tol =
        kGeometryRelTol * ((std::abs(nx) + std::abs(ny)) * scale + std::abs(hp.offset));
    side_.resize(n);
    bool any_out = false, any_in = false;
    for (std::size_t i = 0; i < n; ++i) {
      const double s = nx * pts_[i].x() + ny * pts_[i].y() - hp.offset;
      side_[i] = s;
      any_out = any_out || s > tol;
      any_in = any_in || s < -tol;
    }
    if (!any_out) return false;
    if (!any_in) {  // at most a tol-thin sliver would remain
      clear();
      return true;
    }
    next_pts_.clear();
    next_labels_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = i + 1 == n ? 0 : i + 1;
      const double si = side_[i], sj = side_[j];
      if (si <= tol) {
        if (sj <= tol) {
          push(pts_[i], labels_[i]);
        } else if (si < -tol) {  // leaving: the edge now ends on the line, which follows
          push(pts_[i], labels_[i]);
          push(intersection(i, j), label);
        } else {  // on the line, next vertex outside: the line follows directly
          push(pts_[i], label);
        }
      } else if (sj < -tol) {  // entering: the rest of edge i stays
        push(intersection(i, j), labels_[i]);
      }
    }
    pts_.swap(next_pts_);
    labels_.swap(next_labels_);
    canonicalize(pts_, labels_, kGeometryRelTol * scale);
    return true;
  }

 private:
  void push(const Vec2& p, std::uint32_t label) {
    next_pts_.push_back(p);
    next_labels_.push_back(label);
  }
  // Crossing of edge i → j (one side strictly in, the other strictly out), interpolated from
  // the inside vertex so both orders of the same edge give the same point.
  Vec2 intersection(std::size_t i, std::size_t j) const {
    const std::size_t in = side_[i] < 0.0 ? i : j, out = in == i ? j : i;
    const double t = side_[in] / (side_[in] - side_[out]);
    return pts_[in] + t * (pts_[out] - pts_[in]);
  }

  std::vector<Vec2> pts_, next_pts_;
  std::vector<std::uint32_t> labels_, next_labels_;
  std::vector<double> side_;
};

// Unit outward normals of the disk polygon's edges, at angles 2πk/kDiskSides.
const std::array<Vec2, kDiskSides>& disk_normals() {
  static const std::array<Vec2, kDiskSides> normals = [] {
    std::array<Vec2, kDiskSides> u;
    for (int k = 0; k < kDiskSides; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / kDiskSides;
      u[static_cast<std::size_t>(k)] = Vec2{std::cos(angle), std::sin(angle)};
    }
    return u;
  }();
  return normals;
}

// One cell under construction: the site, the tolerance scale and the farthest vertex, which
// decides which candidates can still cut the cell.
class CellBuilder {
 public:
  // `sites` (viewed, not copied) resolves coincident candidates.
  void start(std::uint32_t site, std::span<const Vec2> sites, const ConvexPolygon& domain) {
    site_ = site;
    sites_ = sites;
    p_ = sites[site];
    scale_ =
        std::max(max_abs_coordinate(domain.vertices), std::max(std::abs(p_.x()), std::abs(p_.y())));
    clipper_.reset(domain.vertices, kDomainLabel);
    reach_sq_ = clipper_.max_distance_sq(p_);
    clips_ = 0;
  }
  bool empty() const { return clipper_.empty(); }
  double reach_sq() const { return reach_sq_; }

  // Applies candidate c at q. Returns false once the cell is empty (nothing left to do).
  bool add_candidate(std::uint32_t c, const Vec2& q) {
    if (c == site_ || clipper_.empty()) return !clipper_.empty();
    if (q.x() == p_.x() && q.y() == p_.y()) {  // coincident: the lower index keeps the cell
      if (c < site_) clipper_.clear();
      return !clipper_.empty();
    }
    // The bisector lies |q − p|/2 from p; beyond the farthest vertex it cannot cut.
    if ((q - p_).squaredNorm() > 4.0 * reach_sq_) return true;
    ++clips_;
    if (clipper_.clip(bisector_half_plane(p_, q), c, scale_)) {
      reach_sq_ = clipper_.max_distance_sq(p_);
    } else {
      // The same bisector may already bound the cell under a coincident copy of q; the
      // lower index names it, since the higher one's cell is empty.
      clipper_.relabel_if(
          [&](std::uint32_t label) {
            return label > c && label < sites_.size() && sites_[label] == q;
          },
          c);
    }
    return !clipper_.empty();
  }

  // Intersects with the kDiskSides-gon circumscribing B(p, radius); skipped when every vertex
  // is already within the inscribed disk.
  void add_disk(double radius) {
    if (clipper_.empty() || !(radius < kNoDisk) || reach_sq_ <= radius * radius) return;
    for (const Vec2& u : disk_normals()) {
      ++clips_;
      clipper_.clip(HalfPlane{u, u.dot(p_) + radius}, kDiskLabel, scale_);
      if (clipper_.empty()) break;
    }
    reach_sq_ = clipper_.max_distance_sq(p_);
  }

  Cell finish() const {
    Cell cell;
    cell.polygon.vertices = clipper_.points();
    cell.half_plane_clips = clips_;
    for (std::uint32_t label : clipper_.labels()) {
      if (label == kDiskLabel) {
        cell.truncated = true;
      } else if (label != kDomainLabel) {
        cell.neighbours.push_back(label);
      }
    }
    std::sort(cell.neighbours.begin(), cell.neighbours.end());
    cell.neighbours.erase(std::unique(cell.neighbours.begin(), cell.neighbours.end()),
                          cell.neighbours.end());
    return cell;
  }

 private:
  LabelledClipper clipper_;
  std::uint32_t site_ = 0;
  std::span<const Vec2> sites_;
  Vec2 p_ = Vec2::Zero();
  double scale_ = 0.0, reach_sq_ = 0.0;
  std::uint32_t clips_ = 0;  // since start(): the cell's computation-load count
};

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
  // |q − site|² <= |q − other|²  ⟺  (other − site)·q <= (|other|² − |site|²) / 2.
  const Vec2 normal = other - site;
  return HalfPlane{normal, 0.5 * normal.dot(other + site)};
}

ConvexPolygon clip(const ConvexPolygon& polygon, const HalfPlane& half_plane) {
  thread_local LabelledClipper clipper;
  clipper.reset(polygon.vertices, 0);
  clipper.clip(half_plane, 0, max_abs_coordinate(polygon.vertices));
  return ConvexPolygon{clipper.points()};
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

std::vector<Cell> voronoi_cells(std::span<const Vec2> sites, const ConvexPolygon& domain) {
  const std::size_t n = sites.size();
  std::vector<Cell> cells(n);
  if (n == 0 || domain.empty()) return cells;

  // Uniform grid over the sites' bounding box, about one site per bucket, stored as CSR.
  Vec2 lo = sites[0], hi = sites[0];
  for (const Vec2& s : sites) {
    lo = lo.cwiseMin(s);
    hi = hi.cwiseMax(s);
  }
  const int per_side = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)))));
  double bucket = std::max(hi.x() - lo.x(), hi.y() - lo.y()) / per_side;
  if (!(bucket > 0.0) || !std::isfinite(bucket)) bucket = 1.0;
  auto buckets_along = [&](double extent) {
    return std::clamp(static_cast<int>(std::floor(extent / bucket)) + 1, 1, per_side + 1);
  };
  const int nx = buckets_along(hi.x() - lo.x()), ny = buckets_along(hi.y() - lo.y());
  auto col_of = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - lo.x()) / bucket)), 0, nx - 1);
  };
  auto row_of = [&](double y) {
    return std::clamp(static_cast<int>(std::floor((y - lo.y()) / bucket)), 0, ny - 1);
  };
  std::vector<std::uint32_t> start(static_cast<std::size_t>(nx * ny) + 1, 0), items(n);
  std::vector<std::uint32_t> bucket_of(n);
  for (std::size_t i = 0; i < n; ++i) {
    bucket_of[i] = static_cast<std::uint32_t>(row_of(sites[i].y()) * nx + col_of(sites[i].x()));
    ++start[bucket_of[i] + 1];
  }
  for (std::size_t b = 1; b < start.size(); ++b)
    start[b] += start[b - 1];
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      items[fill[bucket_of[i]]++] = static_cast<std::uint32_t>(i);
  }

  CellBuilder builder;
  for (std::size_t i = 0; i < n; ++i) {
    const auto site = static_cast<std::uint32_t>(i);
    builder.start(site, sites, domain);
    const int bx = col_of(sites[i].x()), by = row_of(sites[i].y());
    bool alive = !builder.empty();
    auto visit_bucket = [&](int col, int row) {
      if (!alive || col < 0 || col >= nx || row < 0 || row >= ny) return;
      const std::size_t b = static_cast<std::size_t>(row * nx + col);
      for (std::uint32_t k = start[b]; k < start[b + 1] && alive; ++k)
        alive = builder.add_candidate(items[k], sites[items[k]]);
    };
    for (int r = 0; alive; ++r) {
      // Sites in ring r are at least (r − 1)·bucket away; the slack absorbs the rounding of
      // bucket assignment.
      const double gap = (r - 1 - 1e-9) * bucket;
      if (r >= 2 && gap * gap > 4.0 * builder.reach_sq()) break;
      if (r == 0) {
        visit_bucket(bx, by);
      } else {
        for (int col = bx - r; col <= bx + r; ++col) {
          visit_bucket(col, by - r);
          visit_bucket(col, by + r);
        }
        for (int row = by - r + 1; row <= by + r - 1; ++row) {
          visit_bucket(bx - r, row);
          visit_bucket(bx + r, row);
        }
      }
      if (bx - r <= 0 && by - r <= 0 && bx + r >= nx - 1 && by + r >= ny - 1) break;
    }
    cells[i] = builder.finish();
  }
  return cells;
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
