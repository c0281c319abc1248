#pragma once
// Convex-polygon geometry for the Voronoi protocols: half-plane clipping, bounded Voronoi
// cells, area/centroid/polar moment, point location and the Gabriel test. Coordinates are
// world units (net/vec2.hpp). Tolerances and degenerate cases: docs/geometry.md.
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "net/vec2.hpp"

namespace masnet::protocols {

using net::Vec2;

/// Relative tolerance of clipping and of the neighbour rule: a vertex within
/// kGeometryRelTol·(coordinate magnitude) of a clipping line lies on it, and a cell edge no
/// longer than kGeometryRelTol·(coordinate magnitude) does not exist.
inline constexpr double kGeometryRelTol = 1e-12;

/// Sides of the polygon standing for the disk B(p, R) in a cell (it circumscribes the disk).
inline constexpr int kDiskSides = 64;

/// "No disk": the default radius of voronoi_cell.
inline constexpr double kNoDisk = std::numeric_limits<double>::infinity();

/// A convex polygon: vertices counter-clockwise, no repeated consecutive vertices, no
/// collinear vertices (every turn strictly left). An empty vector is the empty set.
struct ConvexPolygon {
  std::vector<Vec2> vertices;

  bool empty() const { return vertices.empty(); }
};

/// The axis-aligned rectangle [xmin, xmax] × [ymin, ymax]; empty unless xmin < xmax and
/// ymin < ymax.
ConvexPolygon rectangle(double xmin, double ymin, double xmax, double ymax);

/// The regular n-gon *circumscribing* the disk B(center, radius) — apothem = radius, so the
/// polygon contains the disk; edge k has outward normal at angle 2πk/n. Empty unless n >= 3
/// and radius > 0.
ConvexPolygon regular_polygon(const Vec2& center, double radius, int n);

/// True iff the closed chain has >= 3 vertices, every turn is strictly left (exact sign,
/// so a collinear or repeated vertex gives false) and it winds once: a strictly convex CCW
/// polygon. Used by the scenario loader to reject a bad domain.
bool is_convex_ccw(std::span<const Vec2> vertices);

/// True iff the closed chain has >= 3 vertices and no self-intersection: non-adjacent edges
/// share no point, adjacent edges share only their common vertex (a repeated vertex or a
/// zero-area spike counts as an intersection). Exact predicates; O(n²).
bool is_simple(std::span<const Vec2> vertices);

/// A user polygon made canonical: drops repeated consecutive vertices (also a closing copy of
/// the first), reverses clockwise input, drops vertices lying within the relative tolerance
/// of the segment joining their neighbours. nullopt when what is left is not a simple,
/// strictly convex polygon with >= 3 vertices.
std::optional<ConvexPolygon> normalize_convex_polygon(std::span<const Vec2> vertices);

/// The closed half-plane {q : normal·q <= offset}; normal need not be unit.
struct HalfPlane {
  Vec2 normal;
  double offset;
};

/// The points at least as close to `site` as to `other` (normal = other − site). When the two
/// coincide the normal is zero and the half-plane is the whole plane.
HalfPlane bisector_half_plane(const Vec2& site, const Vec2& other);

/// polygon ∩ half_plane (Sutherland–Hodgman for convex input). Vertices within
/// kGeometryRelTol·(|n|₁·M + |offset|) of the line, M = largest |coordinate| of the polygon,
/// count as on it; the result keeps the representation invariants (near-duplicate vertices
/// merged, non-left turns dropped) and is empty when no vertex is strictly inside.
ConvexPolygon clip(const ConvexPolygon& polygon, const HalfPlane& half_plane);

/// A bounded Voronoi cell and the sites whose bisectors bound it.
struct Cell {
  ConvexPolygon polygon;
  /// Candidate indices whose bisector gives the final polygon an edge longer than
  /// kGeometryRelTol·M (M = largest |coordinate| of domain and site); sorted, unique.
  /// Sites touching the cell at a single point are not neighbours.
  std::vector<std::uint32_t> neighbours;
  /// True when the disk polygon contributes an edge: the cell was cut by the radius.
  bool truncated = false;
  /// Half-plane clips the builder performed: one per bisector or disk side it clipped by (a
  /// candidate dismissed by the distance test, a coincident one or a repeat of the site is
  /// none). The computation-load count of docs/protocols.md.
  std::uint32_t half_plane_clips = 0;
};

/// Geometric work of one update (docs/protocols.md, "Computation load"): plain counters the
/// protocol fills as it works, zero for a protocol that does not.
struct GeometryWork {
  std::uint64_t half_plane_clips = 0;     ///< clips of a cell by a bisector or a disk side
  std::uint64_t point_in_cell_tests = 0;  ///< readings whose membership of the cell was decided

  GeometryWork& operator+=(const GeometryWork& other) {
    half_plane_clips += other.half_plane_clips;
    point_in_cell_tests += other.point_in_cell_tests;
    return *this;
  }
};

/// The cell of sites[site]: domain ∩ disk(sites[site], disk_radius) ∩ the bisector
/// half-planes of sites[c] for c in `candidates` (the site itself and repeats are ignored).
/// The disk is the circumscribing regular_polygon with kDiskSides sides (it contains the true
/// disk; its vertices reach radius·1.0012). Coincident sites: the lower index keeps the cell,
/// the higher gets the empty cell. A site outside `domain` gets the part of the domain nearer
/// to it than to the candidates (possibly empty). disk_radius must be > 0 (+inf = no disk);
/// otherwise the cell is empty. Preconditions: finite coordinates, `domain` canonical.
Cell voronoi_cell(std::uint32_t site, std::span<const Vec2> sites,
                  std::span<const std::uint32_t> candidates, const ConvexPolygon& domain,
                  double disk_radius = kNoDisk);

/// Every exact cell (all other sites are candidates, no disk); cells[i] belongs to sites[i]
/// and the cells partition the domain. Candidates are visited ring by ring over a uniform
/// grid and only those within twice the current farthest vertex are clipped, so a uniform
/// layout costs O(n) cells × O(1) clips.
std::vector<Cell> voronoi_cells(std::span<const Vec2> sites, const ConvexPolygon& domain);

// Measures of one polygon: defined in polygon_measures.cpp, with the user-polygon checks above.

/// Area (world units²) of a canonical (CCW) polygon, so >= 0; 0 for fewer than 3 vertices.
double area(const ConvexPolygon& polygon);

/// Perimeter (world units); 0 when empty.
double perimeter(const ConvexPolygon& polygon);

/// The area centroid. Zero-area polygons give the vertex average; the empty polygon gives
/// (0, 0). Never NaN for finite input.
Vec2 centroid(const ConvexPolygon& polygon);

/// ∫_P |q − point|² dq (world units⁴): the coverage cost of P with density 1 for a robot at
/// `point`. 0 when empty.
double polar_moment(const ConvexPolygon& polygon, const Vec2& point);

/// max over vertices of |v − point| (world units); 0 when empty. For a convex polygon this is
/// the largest distance from `point` to any point of it.
double max_vertex_distance(const ConvexPolygon& polygon, const Vec2& point);

/// Closed-set membership: boundary points are inside. Decided by the exact sign of each edge's
/// cross product (no tolerance). False for the empty polygon.
bool contains(const ConvexPolygon& polygon, const Vec2& point);
/// The same for the vertices of a convex polygon held elsewhere (e.g. in a message).
bool contains(std::span<const Vec2> vertices, const Vec2& point);

/// The x-extent of a convex polygon on horizontal lines taken bottom to top: a scanline over
/// sensor rows. Each extent end comes from one edge (the two monotone chains are walked once,
/// no search per line) and lies within margin() of the exact end, so a point farther than
/// margin() inside both ends is inside as contains() decides; only points near an end need
/// the exact test.
class RowSlicer {
 public:
  /// Starts on `polygon` (CCW, as ConvexPolygon promises). The slicer keeps its own copy of
  /// what it needs.
  void reset(const ConvexPolygon& polygon) { reset(std::span<const Vec2>(polygon.vertices)); }
  /// The same for the vertices of a convex polygon held elsewhere (e.g. in a message).
  void reset(std::span<const Vec2> vertices);
  /// Back to the bottom: the next extent() may ask for any height again.
  void rewind() { left_.at = right_.at = 0; }
  /// False for fewer than 3 vertices or zero height (not a ConvexPolygon: use contains()).
  bool valid() const { return valid_; }
  double y_min() const { return y_min_; }
  double y_max() const { return y_max_; }
  /// Bound on |computed end − exact end| for every extent(); +inf for absurd input (a slope
  /// that overflows), which sends every point to the exact test.
  double margin() const { return margin_; }
  /// The largest |x| of a vertex: every extent() end lies within margin() of [−it, it].
  double max_abs_x() const { return max_abs_x_; }
  /// {left, right} ends at height y, for y in [y_min, y_max], never below the previous call's
  /// (since reset() or rewind()).
  std::pair<double, double> extent(double y) { return {left_.x(y), right_.x(y)}; }
  /// contains(vertices, point) for a point on the row whose extent() is [left, right]: decided
  /// by the ends where the point is farther than margin() from both, exactly otherwise.
  bool contains_on_row(std::span<const Vec2> vertices, const Vec2& point, double left,
                       double right) const {
    const double x = point.x();
    if (x >= left + margin_ && x <= right - margin_) return true;
    if (x < left - margin_ || x > right + margin_) return false;
    return contains(vertices, point);
  }

 private:
  struct Edge {
    double y_top, x0, y0, slope;  // x(y) = x0 + (y − y0)·slope on [y0, y_top]
  };
  struct Chain {
    std::vector<Edge> edges;
    std::size_t at = 0;
    double x(double y) {
      while (at + 1 < edges.size() && y > edges[at].y_top)
        ++at;
      const Edge& e = edges[at];
      return e.x0 + (y - e.y0) * e.slope;
    }
  };
  Chain left_, right_;
  double y_min_ = 0.0, y_max_ = 0.0, margin_ = 0.0, max_abs_x_ = 0.0;
  bool valid_ = false;
};

/// contains() for many points against one convex polygon (CCW, as ConvexPolygon promises),
/// always with contains()'s answer but at a fraction of its cost when the points come row by
/// row (a SENSE reaches its sensors in id order, row after row): each height's extent is taken
/// once from a RowSlicer, and only points within its margin of an end take the exact test.
class ConvexMembership {
 public:
  void reset(std::span<const Vec2> vertices);
  bool contains(const Vec2& point);

 private:
  std::vector<Vec2> vertices_;  // for the exact test near the ends
  RowSlicer slicer_;
  double row_y_ = 0.0, left_ = 0.0, right_ = 0.0;
  bool row_valid_ = false;
};

/// Sign of the cross product (b − a) × (c − a), computed exactly: +1 when c is left of the
/// directed line a→b, −1 right, 0 on it. Coordinates must not overflow or underflow.
int orientation(const Vec2& a, const Vec2& b, const Vec2& c);

/// True iff no point of `others` lies strictly inside the circle with diameter ab
/// ((a − q)·(b − q) < 0, no tolerance). a and b themselves may be in `others`.
bool is_gabriel_neighbour(const Vec2& a, const Vec2& b, std::span<const Vec2> others);

/// Indices j != site with is_gabriel_neighbour(sites[site], sites[j], sites), ascending.
/// O(n²) per call: meant for the few robots heard in one beacon round.
std::vector<std::uint32_t> gabriel_neighbours(std::uint32_t site, std::span<const Vec2> sites);

}  // namespace masnet::protocols
