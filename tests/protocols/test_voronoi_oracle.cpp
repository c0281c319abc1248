// Voronoi cells checked against independent computations: Boost.Polygon's Voronoi diagram
// (exact predicates on integer input) for neighbour sets and shared-edge lengths, and a
// nearest-site labelling of pixel centres for areas.
#include <boost/polygon/voronoi.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "protocols/geometry.hpp"

namespace {

struct IPoint {
  std::int32_t x, y;
};

}  // namespace

namespace boost::polygon {
template <>
struct geometry_concept<IPoint> {
  using type = point_concept;
};
template <>
struct point_traits<IPoint> {
  using coordinate_type = std::int32_t;
  static coordinate_type get(const IPoint& p, orientation_2d o) {
    return o == HORIZONTAL ? p.x : p.y;
  }
};
}  // namespace boost::polygon

namespace {

using masnet::protocols::Cell;
using masnet::protocols::Vec2;
namespace geo = masnet::protocols;

// Sites live on the 2^-20 grid of the unit square, so Boost's integer input and our doubles
// describe the same points exactly.
constexpr std::int32_t kGrid = 1 << 20;
constexpr double kGridStep = 1.0 / kGrid;

// A shared edge longer than kLongEdge must be found by both; shorter than kShortEdge by
// neither. In between — a band around our tolerance kGeometryRelTol = 1e-12 (the unit square
// has coordinate magnitude 1) — the answer depends on rounding: such edges are counted and
// reported, not judged. Boost's vertices carry errors of order 1e-15 here.
constexpr double kLongEdge = 1e-11;
constexpr double kShortEdge = 1e-13;

struct Rng {
  std::mt19937_64 engine;
  explicit Rng(std::uint64_t seed) : engine(seed) {}
  double uniform() { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }
  std::int32_t below(std::int32_t n) {  // in [0, n)
    return static_cast<std::int32_t>(engine() % static_cast<std::uint64_t>(n));
  }
};

struct SiteSet {
  std::vector<IPoint> ints;
  std::vector<Vec2> sites;
};

SiteSet make_set(const std::vector<IPoint>& ints) {
  SiteSet set{ints, {}};
  for (const IPoint& p : ints)
    set.sites.emplace_back(p.x * kGridStep, p.y * kGridStep);
  return set;
}

// n distinct random grid points in [0, 1]²; `boundary_every` > 0 pushes every such site onto
// an edge or corner of the square.
SiteSet random_set(Rng& rng, int n, int boundary_every = 0) {
  std::set<std::pair<std::int32_t, std::int32_t>> seen;
  std::vector<IPoint> ints;
  while (static_cast<int>(ints.size()) < n) {
    IPoint p{rng.below(kGrid + 1), rng.below(kGrid + 1)};
    if (boundary_every > 0 && static_cast<int>(ints.size()) % boundary_every == 0) {
      switch (rng.below(3)) {
        case 0:
          p.x = rng.below(2) * kGrid;
          break;
        case 1:
          p.y = rng.below(2) * kGrid;
          break;
        default:
          p = IPoint{rng.below(2) * kGrid, rng.below(2) * kGrid};
      }
    }
    if (seen.insert({p.x, p.y}).second) ints.push_back(p);
  }
  return make_set(ints);
}

// Sites in a few tight clusters (stress for the pruned all-cells path).
SiteSet clustered_set(Rng& rng, int n) {
  std::set<std::pair<std::int32_t, std::int32_t>> seen;
  std::vector<IPoint> ints;
  const int clusters = 1 + rng.below(4);
  std::vector<IPoint> centres;
  for (int c = 0; c < clusters; ++c)
    centres.push_back({rng.below(kGrid + 1), rng.below(kGrid + 1)});
  const std::int32_t spread = 1 + rng.below(kGrid / 50);
  while (static_cast<int>(ints.size()) < n) {
    const IPoint& c = centres[static_cast<std::size_t>(rng.below(clusters))];
    IPoint p{std::clamp(c.x + rng.below(2 * spread + 1) - spread, 0, kGrid),
             std::clamp(c.y + rng.below(2 * spread + 1) - spread, 0, kGrid)};
    if (seen.insert({p.x, p.y}).second) ints.push_back(p);
  }
  return make_set(ints);
}

using PairKey = std::pair<std::uint32_t, std::uint32_t>;

struct BoostResult {
  std::map<PairKey, double> edge_length_in_domain;  // unit-square units, pairs (i < j)
  std::set<PairKey> unbounded_neighbours;           // any Voronoi edge, clipped or not
};

// Length of the part of the line origin + t·dir, t in [t0, t1], inside [0, kGrid]².
double clipped_length(const Vec2& origin, const Vec2& dir, double t0, double t1) {
  const double lo = 0.0, hi = static_cast<double>(kGrid);
  for (int axis = 0; axis < 2; ++axis) {
    const double o = origin[axis], d = dir[axis];
    if (d == 0.0) {
      if (o < lo || o > hi) return 0.0;
      continue;
    }
    double ta = (lo - o) / d, tb = (hi - o) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t1 > t0 ? (t1 - t0) * dir.norm() * kGridStep : 0.0;
}

BoostResult boost_voronoi(const SiteSet& set) {
  boost::polygon::voronoi_diagram<double> vd;
  boost::polygon::construct_voronoi(set.ints.begin(), set.ints.end(), &vd);
  BoostResult out;
  const double inf = std::numeric_limits<double>::infinity();
  for (const auto& edge : vd.edges()) {
    const auto i = static_cast<std::uint32_t>(edge.cell()->source_index());
    const auto j = static_cast<std::uint32_t>(edge.twin()->cell()->source_index());
    if (i >= j) continue;  // each undirected edge once
    out.unbounded_neighbours.insert({i, j});
    // Boost's convention (voronoi_visual_utils): the edge runs along
    // direction = rot90(p_twin − p_cell) from vertex0 to vertex1; a missing vertex is at infinity.
    const Vec2 p1(set.ints[i].x, set.ints[i].y), p2(set.ints[j].x, set.ints[j].y);
    const Vec2 origin = 0.5 * (p1 + p2);
    const Vec2 dir(p1.y() - p2.y(), p2.x() - p1.x());
    auto param = [&](const auto* v) {
      return (Vec2(v->x(), v->y()) - origin).dot(dir) / dir.squaredNorm();
    };
    double t0 = edge.vertex0() ? param(edge.vertex0()) : -inf;
    double t1 = edge.vertex1() ? param(edge.vertex1()) : inf;
    if (t0 > t1) std::swap(t0, t1);
    // The convention matters for rays: far along one, p1 and p2 must still be the nearest.
    if (std::isfinite(t0) != std::isfinite(t1)) {
      const double t_far =
          std::isfinite(t0) ? t0 + 8.0 * kGrid / dir.norm() : t1 - 8.0 * kGrid / dir.norm();
      const Vec2 far = origin + t_far * dir;
      const double d_own = (far - p1).norm();
      for (const IPoint& q : set.ints)
        REQUIRE((far - Vec2(q.x, q.y)).norm() >= d_own * (1.0 - 1e-9));
    }
    out.edge_length_in_domain[{i, j}] += clipped_length(origin, dir, t0, t1);
  }
  return out;
}

// Total length of the edges of cell i lying on the bisector of sites i and j: each edge is
// given to the candidate bisector (neighbour or domain side) its endpoints fit best.
double shared_edge_length(const Cell& cell, const std::vector<Vec2>& sites, std::uint32_t i,
                          std::uint32_t j) {
  const auto& v = cell.polygon.vertices;
  const Vec2& pi = sites[i];
  auto distance_to_bisector = [&](const Vec2& q, std::uint32_t k) {
    return std::abs((q - pi).squaredNorm() - (q - sites[k]).squaredNorm()) /
           (2.0 * (sites[k] - pi).norm());
  };
  // How far the segment ab is from lying on one side of the unit square.
  auto distance_to_side = [](const Vec2& a, const Vec2& b) {
    return std::min({std::max(std::abs(a.x()), std::abs(b.x())),
                     std::max(std::abs(a.y()), std::abs(b.y())),
                     std::max(std::abs(1.0 - a.x()), std::abs(1.0 - b.x())),
                     std::max(std::abs(1.0 - a.y()), std::abs(1.0 - b.y()))});
  };
  double length = 0.0;
  for (std::size_t e = 0; e < v.size(); ++e) {
    const Vec2& a = v[e];
    const Vec2& b = v[(e + 1) % v.size()];
    const double own = std::max(distance_to_bisector(a, j), distance_to_bisector(b, j));
    if (own > 1e-9) continue;
    bool best = own <= distance_to_side(a, b);
    for (std::uint32_t k : cell.neighbours)
      if (k != j && std::max(distance_to_bisector(a, k), distance_to_bisector(b, k)) < own)
        best = false;
    if (best) length += (b - a).norm();
  }
  return length;
}

struct Tally {
  int sets = 0;
  long long pairs_checked = 0;
  long long ambiguous = 0;
  int pixel_sets = 0;
};

// Pixel-centre labelling by nearest site (lowest index on ties) on an m×m grid.
std::vector<double> pixel_areas(const std::vector<Vec2>& sites, int m) {
  std::vector<double> areas(sites.size(), 0.0);
  const double h = 1.0 / m;
  for (int r = 0; r < m; ++r) {
    for (int c = 0; c < m; ++c) {
      const Vec2 q((c + 0.5) * h, (r + 0.5) * h);
      std::size_t best = 0;
      double best_d2 = (q - sites[0]).squaredNorm();
      for (std::size_t k = 1; k < sites.size(); ++k) {
        const double d2 = (q - sites[k]).squaredNorm();
        if (d2 < best_d2) {
          best_d2 = d2;
          best = k;
        }
      }
      areas[best] += h * h;
    }
  }
  return areas;
}

// Everything we assert about one site set.
void check_against_oracles(const SiteSet& set, bool with_pixels, Tally& tally) {
  const auto domain = geo::rectangle(0.0, 0.0, 1.0, 1.0);
  const auto n = static_cast<std::uint32_t>(set.sites.size());
  const std::vector<Cell> cells = geo::voronoi_cells(set.sites, domain);
  REQUIRE(cells.size() == n);
  const BoostResult boost = boost_voronoi(set);
  ++tally.sets;

  // Areas partition the square; each polygon is canonical and never NaN.
  double total = 0.0;
  for (const Cell& cell : cells) {
    REQUIRE((cell.polygon.empty() || geo::is_convex_ccw(cell.polygon.vertices)));
    REQUIRE_FALSE(cell.truncated);
    const double a = geo::area(cell.polygon);
    REQUIRE(std::isfinite(a));
    total += a;
  }
  INFO("n = " << n);
  REQUIRE(total == Approx(1.0).epsilon(1e-9));

  // Neighbour sets: symmetric, and equal to Boost's edges of positive length inside Ω.
  for (std::uint32_t i = 0; i < n; ++i) {
    const auto& ni = cells[i].neighbours;
    REQUIRE(std::is_sorted(ni.begin(), ni.end()));
    for (std::uint32_t j : ni) {
      REQUIRE(j != i);
      REQUIRE(std::binary_search(cells[j].neighbours.begin(), cells[j].neighbours.end(), i));
      INFO("sites " << i << " and " << j << " are neighbours here but share no edge in Boost");
      if (i < j) REQUIRE(boost.edge_length_in_domain.count({i, j}) == 1);
    }
  }
  for (const auto& [pair, boost_len] : boost.edge_length_in_domain) {
    const auto [i, j] = pair;
    const auto& ni = cells[i].neighbours;
    const bool mine = std::binary_search(ni.begin(), ni.end(), j);
    INFO("sites " << i << " and " << j << ", Boost edge length " << boost_len);
    ++tally.pairs_checked;
    if (boost_len > kLongEdge) {
      REQUIRE(mine);
      const double len = shared_edge_length(cells[i], set.sites, i, j);
      REQUIRE(len == Approx(boost_len).margin(1e-9));
    } else if (boost_len < kShortEdge) {
      REQUIRE_FALSE(mine);
    } else {
      ++tally.ambiguous;
      WARN("ambiguous edge: sites " << i << " and " << j << " of " << n << ", Boost length "
                                    << boost_len << ", neighbours here: " << mine);
    }
  }

  // The single-cell entry point with every site as a candidate (no pruning, index order)
  // agrees with the pruned all-cells path.
  std::vector<std::uint32_t> all(n);
  for (std::uint32_t k = 0; k < n; ++k)
    all[k] = k;
  for (std::uint32_t i = 0; i < n; i += std::max<std::uint32_t>(1, n / 8)) {
    const Cell one = geo::voronoi_cell(i, set.sites, all, domain);
    REQUIRE(one.neighbours == cells[i].neighbours);
    REQUIRE(geo::area(one.polygon) == Approx(geo::area(cells[i].polygon)).margin(1e-12));
  }

  // Gabriel edges are Delaunay edges (unless a fourth site sits exactly on the circle).
  for (std::uint32_t i = 0; i < n && n <= 200; ++i) {
    for (std::uint32_t j : geo::gabriel_neighbours(i, set.sites)) {
      if (j < i) continue;
      bool on_circle = false;
      for (const IPoint& q : set.ints) {
        const std::int64_t dot = std::int64_t{set.ints[i].x - q.x} * (set.ints[j].x - q.x) +
                                 std::int64_t{set.ints[i].y - q.y} * (set.ints[j].y - q.y);
        const bool is_end = (q.x == set.ints[i].x && q.y == set.ints[i].y) ||
                            (q.x == set.ints[j].x && q.y == set.ints[j].y);
        on_circle = on_circle || (dot == 0 && !is_end);
      }
      if (!on_circle) REQUIRE(boost.unbounded_neighbours.count({i, j}) == 1);
    }
  }

  if (with_pixels) {
    constexpr int kPixels = 400;
    const double h = 1.0 / kPixels;
    const std::vector<double> estimate = pixel_areas(set.sites, kPixels);
    for (std::uint32_t i = 0; i < n; ++i) {
      // Only pixels crossed by the boundary can be misattributed, each by at most h²; a polygon
      // of perimeter P with k edges crosses at most √2·P/h + 3k pixels.
      const auto& poly = cells[i].polygon;
      const double bound = std::sqrt(2.0) * geo::perimeter(poly) * h +
                           3.0 * static_cast<double>(poly.vertices.size()) * h * h;
      INFO("cell " << i);
      REQUIRE(std::abs(geo::area(poly) - estimate[i]) <= bound + 1e-12);
    }
    ++tally.pixel_sets;
  }
}

// Sites on one line p0 + k·step (k = 0..n−1), all inside the grid.
SiteSet collinear_set(IPoint p0, IPoint step, int n) {
  std::vector<IPoint> ints;
  for (int k = 0; k < n; ++k)
    ints.push_back({p0.x + k * step.x, p0.y + k * step.y});
  return make_set(ints);
}

// A k×k lattice with spacing kGrid/(k−1) when `to_edges` (sites on the boundary and corners),
// otherwise cell-centred; rounded to the grid (exact when the spacing is a power of two).
SiteSet lattice_set(int k, bool to_edges) {
  std::vector<IPoint> ints;
  for (int r = 0; r < k; ++r)
    for (int c = 0; c < k; ++c) {
      auto coord = [&](int i) {
        const double u = to_edges ? static_cast<double>(i) / (k - 1) : (i + 0.5) / k;
        return static_cast<std::int32_t>(std::lround(u * kGrid));
      };
      ints.push_back({coord(c), coord(r)});
    }
  return make_set(ints);
}

// 12 integer points on one circle (3-4-5 triangles), optionally with its centre.
SiteSet pythagorean_circle(std::int32_t unit, bool with_centre) {
  const std::int32_t c = kGrid / 2;
  std::vector<IPoint> ints;
  const int offsets[][2] = {{5, 0},  {4, 3},   {3, 4},   {0, 5},  {-3, 4}, {-4, 3},
                            {-5, 0}, {-4, -3}, {-3, -4}, {0, -5}, {3, -4}, {4, -3}};
  for (const auto& o : offsets)
    ints.push_back({c + o[0] * unit, c + o[1] * unit});
  if (with_centre) ints.push_back({c, c});
  return make_set(ints);
}

}  // namespace

TEST_CASE("Cells of 1000 random site sets match Boost's Voronoi diagram inside the square",
          "[protocols]") {
  Tally tally;
  Rng rng(0x5eed'0001);
  for (int s = 0; s < 1000; ++s) {
    const int n = 2 + s % 59;  // 2 .. 60
    const SiteSet set =
        s % 10 == 9 ? clustered_set(rng, n) : random_set(rng, n, s % 7 == 3 ? 4 : 0);
    check_against_oracles(set, s % 25 == 0, tally);
  }
  WARN("random sets: " << tally.sets << ", Boost edges compared: " << tally.pairs_checked
                       << ", ambiguous edges: " << tally.ambiguous
                       << ", sets with pixel areas: " << tally.pixel_sets);
  CHECK(tally.ambiguous == 0);
}

TEST_CASE("Cells of degenerate site sets match Boost's Voronoi diagram inside the square",
          "[protocols]") {
  Tally tally;
  SECTION("collinear sites give strips") {
    for (int n = 2; n <= 20; ++n) {
      check_against_oracles(collinear_set({1000, kGrid / 2}, {kGrid / 25, 0}, n), n % 5 == 0,
                            tally);
      check_against_oracles(collinear_set({0, 0}, {kGrid / 20, kGrid / 20}, n), false, tally);
      check_against_oracles(collinear_set({100, 200}, {kGrid / 40, kGrid / 30}, n), false, tally);
      check_against_oracles(collinear_set({kGrid / 3, 0}, {0, kGrid / (n - 1) - 1}, n), false,
                            tally);
    }
  }
  SECTION("lattices are cocircular everywhere, some on the boundary and corners") {
    for (int k = 2; k <= 9; ++k) {
      check_against_oracles(lattice_set(k, false), k == 4, tally);
      check_against_oracles(lattice_set(k, true), k == 5, tally);
    }
  }
  SECTION("twelve cocircular sites meet at one vertex") {
    for (std::int32_t unit : {1, 7, 1000, 50000}) {
      check_against_oracles(pythagorean_circle(unit, false), unit == 50000, tally);
      check_against_oracles(pythagorean_circle(unit, true), false, tally);
    }
  }
  SECTION("a site on an edge and one in a corner") {
    check_against_oracles(make_set({{0, kGrid / 2}, {kGrid, kGrid}, {kGrid / 2, kGrid / 3}}), true,
                          tally);
    check_against_oracles(make_set({{0, 0}, {kGrid / 2, 0}, {kGrid, 0}, {kGrid / 2, kGrid / 2}}),
                          false, tally);
  }
  CHECK(tally.ambiguous == 0);
}

TEST_CASE("Cells of 2000 uniform sites match Boost's Voronoi diagram", "[protocols]") {
  Tally tally;
  Rng rng(0x5eed'0002);
  check_against_oracles(random_set(rng, 2000), false, tally);
  check_against_oracles(clustered_set(rng, 2000), false, tally);
  CHECK(tally.ambiguous == 0);
}

TEST_CASE("Cells of 20000 more random site sets match Boost's Voronoi diagram",
          "[protocols][slow]") {
  Tally tally;
  Rng rng(0x5eed'0003);
  for (int s = 0; s < 20000; ++s) {
    const int n = 2 + rng.below(199);
    const SiteSet set =
        s % 10 == 9 ? clustered_set(rng, n) : random_set(rng, n, s % 7 == 3 ? 4 : 0);
    check_against_oracles(set, s % 200 == 0, tally);
  }
  for (int n : {10000, 20000}) {
    check_against_oracles(random_set(rng, n), false, tally);
    check_against_oracles(clustered_set(rng, n), false, tally);
  }
  WARN("random sets: " << tally.sets << ", Boost edges compared: " << tally.pairs_checked
                       << ", ambiguous edges: " << tally.ambiguous
                       << ", sets with pixel areas: " << tally.pixel_sets);
  CHECK(tally.ambiguous == 0);
}
