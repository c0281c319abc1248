// protocols::voronoi_cells: every exact cell, candidates visited ring by ring over a uniform
// grid (docs/geometry.md, "All cells").
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "protocols/cell_builder.hpp"
#include "protocols/geometry.hpp"

namespace masnet::protocols {
namespace {

using geometry_internal::CellBuilder;

// True when two sites coincide. Coincident sites share a bucket (a bucket is a function of the
// coordinates), so buckets are searched one by one: pairwise when small, sorted otherwise.
bool any_coincident(std::span<const Vec2> item_sites, std::span<const std::uint32_t> start) {
  std::vector<std::pair<double, double>> sorted;
  for (std::size_t b = 0; b + 1 < start.size(); ++b) {
    const std::uint32_t first = start[b], last = start[b + 1];
    if (last - first <= 16) {
      for (std::uint32_t k = first; k < last; ++k)
        for (std::uint32_t l = k + 1; l < last; ++l)
          if (item_sites[k] == item_sites[l]) return true;
      continue;
    }
    sorted.clear();
    for (std::uint32_t k = first; k < last; ++k)
      sorted.emplace_back(item_sites[k].x(), item_sites[k].y());
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 1; k < sorted.size(); ++k)
      if (sorted[k].first == sorted[k - 1].first && sorted[k].second == sorted[k - 1].second)
        return true;
  }
  return false;
}

}  // namespace

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
  // An overflowing extent leaves the placement of sites in buckets meaningless: no bucket is
  // then skipped by its box.
  const bool boxes_hold_sites = std::isfinite(bucket);
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
  // The sites again in bucket order, so a cell reads its candidates' coordinates in sequence.
  std::vector<Vec2> item_sites(n);
  for (std::size_t k = 0; k < n; ++k)
    item_sites[k] = sites[items[k]];
  // A bucket's box grown by this much holds all its sites despite the rounding of col_of and
  // row_of (a few ulps of the extent, far below a billionth of a bucket).
  const double box_slack = 1e-9 * bucket;
  const bool sites_may_coincide = any_coincident(item_sites, start);

  CellBuilder builder;
  // One ring's candidate positions, with room for gather()'s fixed-width writes.
  constexpr std::uint32_t kGatherWidth = 4;
  std::vector<std::uint32_t> ring(n + kGatherWidth);
  // Cells in bucket order: consecutive cells share most candidates, which stay in cache.
  for (std::size_t item = 0; item < n; ++item) {
    const std::size_t i = items[item];
    const auto site = static_cast<std::uint32_t>(i);
    builder.start(site, sites, domain, sites_may_coincide);
    if (builder.empty()) {
      cells[i] = builder.finish();
      continue;
    }
    const Vec2 p = item_sites[item];
    const int bx = col_of(p.x()), by = row_of(p.y());
    // Sites of a bucket (or of a whole row or column of buckets) whose box, grown by
    // box_slack, lies beyond twice the farthest vertex would all be dismissed by
    // add_candidate's distance test: they are skipped (same cells, same clip counts). The
    // farthest vertex only comes nearer as the cell is clipped, so a skip stays right.
    auto beyond = [&](double gap_sq) { return gap_sq > 4.0 * builder.reach_sq() * (1.0 + 1e-9); };
    auto gap_x = [&](int col) {
      const double x0 = lo.x() + col * bucket - box_slack, x1 = x0 + bucket + 2.0 * box_slack;
      return std::max(0.0, std::max(x0 - p.x(), p.x() - x1));
    };
    auto gap_y = [&](int row) {
      const double y0 = lo.y() + row * bucket - box_slack, y1 = y0 + bucket + 2.0 * box_slack;
      return std::max(0.0, std::max(y0 - p.y(), p.y() - y1));
    };
    // A ring's candidates are gathered (their positions in bucket order) before they are
    // applied: a bucket holds 0, 1, 2… sites at random, and a loop per bucket would take a
    // mispredicted branch for nearly every bucket. Gathering writes kGatherWidth positions
    // whatever the bucket holds and counts only its own.
    std::size_t count = 0;
    auto gather = [&](std::size_t b, bool skip) __attribute__((always_inline)) {
      const std::uint32_t first = start[b];
      const std::uint32_t size = skip ? 0u : start[b + 1] - first;
      for (std::uint32_t j = 0; j < kGatherWidth; ++j)
        ring[count + j] = first + j;
      if (size > kGatherWidth) [[unlikely]] {
        for (std::uint32_t j = kGatherWidth; j < size; ++j)
          ring[count + j] = first + j;
      }
      count += size;
    };
    // Applies the gathered candidates in order; false once the cell is empty.
    auto apply_gathered = [&]() __attribute__((always_inline)) {
      for (std::size_t g = 0; g < count; ++g) {
        const std::uint32_t k = ring[g];
        if (!builder.add_candidate(items[k], item_sites[k])) return false;
      }
      return true;
    };
    gather(static_cast<std::size_t>(by * nx + bx), false);
    for (int r = 1;; ++r) {
      // Sites in ring r are at least (r − 1)·bucket away; the slack absorbs the rounding of
      // bucket assignment.
      const double gap = (r - 1 - 1e-9) * bucket;
      if (r >= 2 && gap * gap > 4.0 * builder.reach_sq()) break;
      // Ring r in a fixed order: bottom and top rows column by column, then the left and
      // right columns row by row. From ring 2 on, buckets whose box, grown by box_slack, lies
      // beyond are passed over, judged by the farthest vertex when the ring starts (it only
      // comes nearer, so add_candidate then dismisses what a later judgement would skip); a
      // box's gap along one axis is computed once for the side or the pair sharing it.
      const bool test_box = boxes_hold_sites && r >= 2;
      auto side_open = [&](int index, int count_along, double side_gap) {
        return index >= 0 && index < count_along && !(test_box && beyond(side_gap * side_gap));
      };
      auto skipped = [&](double gap_a, double gap_b) {
        return test_box && beyond(gap_a * gap_a + gap_b * gap_b);
      };
      const int bottom = by - r, top = by + r, left = bx - r, right = bx + r;
      const double bottom_gap = test_box ? gap_y(bottom) : 0.0;
      const double top_gap = test_box ? gap_y(top) : 0.0;
      const bool bottom_open = side_open(bottom, ny, bottom_gap);
      const bool top_open = side_open(top, ny, top_gap);
      if (bottom_open || top_open) {
        for (int col = std::max(left, 0), end = std::min(right, nx - 1); col <= end; ++col) {
          const double gx = test_box ? gap_x(col) : 0.0;
          if (bottom_open)
            gather(static_cast<std::size_t>(bottom * nx + col), skipped(gx, bottom_gap));
          if (top_open) gather(static_cast<std::size_t>(top * nx + col), skipped(gx, top_gap));
        }
      }
      const double left_gap = test_box ? gap_x(left) : 0.0;
      const double right_gap = test_box ? gap_x(right) : 0.0;
      const bool left_open = side_open(left, nx, left_gap);
      const bool right_open = side_open(right, nx, right_gap);
      if (left_open || right_open) {
        for (int row = std::max(bottom + 1, 0), end = std::min(top - 1, ny - 1); row <= end;
             ++row) {
          const double gy = test_box ? gap_y(row) : 0.0;
          if (left_open) gather(static_cast<std::size_t>(row * nx + left), skipped(left_gap, gy));
          if (right_open)
            gather(static_cast<std::size_t>(row * nx + right), skipped(right_gap, gy));
        }
      }
      const bool alive = apply_gathered();
      count = 0;
      if (!alive || (left <= 0 && bottom <= 0 && right >= nx - 1 && top >= ny - 1)) break;
    }
    cells[i] = builder.finish();
  }
  return cells;
}

}  // namespace masnet::protocols
