// The cell builders' clipper (its shortcut for a cut with one run of vertices out, its
// four-at-a-time and SSE2 passes, its seam tests) against a plain Sutherland–Hodgman clip
// written out here, followed by the full canonicalisation: the same vertices bit for bit,
// in the same order, with the same edge labels.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include <catch2/catch.hpp>

#include "geometry_test_support.hpp"
#include "protocols/cell_builder.hpp"

namespace {

using geometry_test::Rng;
using masnet::protocols::HalfPlane;
using masnet::protocols::kGeometryRelTol;
using masnet::protocols::Vec2;
using masnet::protocols::geometry_internal::canonicalize;
using masnet::protocols::geometry_internal::LabelledClipper;

struct Polygon {
  std::vector<Vec2> points;
  std::vector<std::uint32_t> labels;
};

// The clip by `hp` as the documented rules state it (docs/geometry.md): vertices within tol of
// the line count as on it; a crossing is interpolated from the inside vertex; new edges take
// `label`; then every short edge and every turn that is not strictly left is removed.
Polygon reference_clip(const Polygon& polygon, const HalfPlane& hp, std::uint32_t label,
                       double scale) {
  const std::size_t n = polygon.points.size();
  const double nx = hp.normal.x(), ny = hp.normal.y();
  const double tol =
      kGeometryRelTol * ((std::abs(nx) + std::abs(ny)) * scale + std::abs(hp.offset));
  std::vector<double> side(n);
  bool any_out = false, any_in = false;
  for (std::size_t i = 0; i < n; ++i) {
    side[i] = nx * polygon.points[i].x() + ny * polygon.points[i].y() - hp.offset;
    any_out = any_out || side[i] > tol;
    any_in = any_in || side[i] < -tol;
  }
  if (!any_out) return polygon;
  if (!any_in) return {};
  auto crossing = [&](std::size_t i, std::size_t j) {
    const std::size_t in = side[i] < 0.0 ? i : j, out = in == i ? j : i;
    const double t = side[in] / (side[in] - side[out]);
    return Vec2(polygon.points[in] + t * (polygon.points[out] - polygon.points[in]));
  };
  Polygon result;
  auto emit = [&](const Vec2& point, std::uint32_t edge_label) {
    result.points.push_back(point);
    result.labels.push_back(edge_label);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const bool i_kept = side[i] <= tol, j_kept = side[j] <= tol;
    if (i_kept && j_kept) {
      emit(polygon.points[i], polygon.labels[i]);
    } else if (i_kept && side[i] < -tol) {  // leaves through the line
      emit(polygon.points[i], polygon.labels[i]);
      emit(crossing(i, j), label);
    } else if (i_kept) {  // on the line, the next vertex out: the line follows
      emit(polygon.points[i], label);
    } else if (side[j] < -tol) {  // comes back in
      emit(crossing(i, j), polygon.labels[i]);
    }
  }
  canonicalize(result.points, result.labels, kGeometryRelTol * scale);
  return result;
}

bool same_bits(const LabelledClipper& clipper, const Polygon& expected) {
  if (clipper.points().size() != expected.points.size()) return false;
  for (std::size_t k = 0; k < expected.points.size(); ++k) {
    if (clipper.points()[k].x() != expected.points[k].x() ||
        clipper.points()[k].y() != expected.points[k].y() ||
        clipper.labels()[k] != expected.labels[k])
      return false;
  }
  return true;
}

std::vector<Vec2> regular_polygon(std::size_t sides, const Vec2& centre, double radius) {
  std::vector<Vec2> points;
  for (std::size_t k = 0; k < sides; ++k) {
    const double angle =
        2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(sides);
    points.push_back(centre + radius * Vec2(std::cos(angle), std::sin(angle)));
  }
  return points;
}

// Clips `start` by `clips` half-planes from `next_plane`, checking every step.
template <class NextPlane>
void check_sequence(const std::vector<Vec2>& start, int clips, NextPlane&& next_plane) {
  const double scale = 2.0;
  LabelledClipper clipper;
  clipper.reset(start, 1000);
  Polygon expected{start, std::vector<std::uint32_t>(start.size(), 1000)};
  for (std::uint32_t label = 0; label < static_cast<std::uint32_t>(clips); ++label) {
    const HalfPlane hp = next_plane();
    const bool changed = clipper.clip(hp, label, scale);
    const Polygon reference = reference_clip(expected, hp, label, scale);
    INFO("clip " << label << " of a polygon with " << expected.points.size() << " vertices");
    REQUIRE(changed == (reference.points != expected.points));
    REQUIRE(same_bits(clipper, reference));
    expected = reference;
    if (expected.points.empty()) return;
  }
}

}  // namespace

TEST_CASE("The clipper cuts as a plain Sutherland–Hodgman pass does, bit for bit", "[protocols]") {
  Rng rng(20261203);
  SECTION("bisectors of random sites, as a cell is built") {
    for (int cell = 0; cell < 400; ++cell) {
      const Vec2 site(rng.uniform(), rng.uniform());
      check_sequence(geometry_test::kUnitSquare.vertices, 30, [&] {
        const Vec2 other = site + Vec2(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3));
        return masnet::protocols::geometry_internal::bisector(site, other);
      });
    }
  }
  SECTION("lines in every direction through a shrinking disc, many-sided polygons") {
    for (const std::size_t sides : {3u, 7u, 61u, 64u, 70u}) {
      for (int polygon = 0; polygon < 60; ++polygon) {
        const Vec2 centre(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        check_sequence(regular_polygon(sides, centre, 0.5), 12, [&] {
          const double angle = rng.uniform(0.0, 2.0 * std::numbers::pi);
          const Vec2 normal(std::cos(angle), std::sin(angle));
          return HalfPlane{normal, normal.dot(centre) + rng.uniform(0.05, 0.5)};
        });
      }
    }
  }
  SECTION("lines through vertices and along edges: vertices on the line") {
    for (int polygon = 0; polygon < 200; ++polygon) {
      // Sites on a coarse lattice give bisectors through earlier vertices.
      auto lattice = [&] { return std::round(rng.uniform() * 4.0) / 4.0; };
      const Vec2 site(lattice(), lattice());
      check_sequence(geometry_test::kUnitSquare.vertices, 16, [&] {
        Vec2 other(lattice(), lattice());
        if (other == site) other.x() += 0.25;
        return masnet::protocols::geometry_internal::bisector(site, other);
      });
    }
  }
}
