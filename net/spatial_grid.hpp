#pragma once
// A uniform grid over a set of points, stored cell by cell (CSR) with positions copied in
// cell order, so a range query scans a few contiguous runs of memory (one per grid row).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#if defined(__SSE2__)
#include <emmintrin.h>  // baseline x86-64
#endif
#include <span>
#include <vector>

#include "net/vec2.hpp"
#include "sim/ids.hpp"

namespace masnet::net {

/// (x − cx)² + (y − cy)²: the one expression every range test here shares.
inline double squared_distance(double x, double y, double cx, double cy) {
  const double ddx = x - cx, ddy = y - cy;
  return ddx * ddx + ddy * ddy;
}

/// Bit k set iff point k of (xs, ys) lies within r2 (squared) of (cx, cy), for count <= 64
/// points: every test without a branch (in or out is a coin toss for points near the circle),
/// two per SSE2 register with the same arithmetic as squared_distance.
inline std::uint64_t disk_mask(const double* xs, const double* ys, std::size_t count, double cx,
                               double cy, double r2) {
  std::uint64_t inside = 0;
  std::size_t k = 0;
#if defined(__SSE2__)
  const __m128d vcx = _mm_set1_pd(cx), vcy = _mm_set1_pd(cy), vr2 = _mm_set1_pd(r2);
  for (; k + 2 <= count; k += 2) {
    const __m128d ex = _mm_sub_pd(_mm_loadu_pd(xs + k), vcx);
    const __m128d ey = _mm_sub_pd(_mm_loadu_pd(ys + k), vcy);
    const __m128d d2 = _mm_add_pd(_mm_mul_pd(ex, ex), _mm_mul_pd(ey, ey));
    inside |= static_cast<std::uint64_t>(_mm_movemask_pd(_mm_cmple_pd(d2, vr2))) << k;
  }
#endif
  for (; k < count; ++k)
    inside |= static_cast<std::uint64_t>(squared_distance(xs[k], ys[k], cx, cy) <= r2) << k;
  return inside;
}

class SpatialGrid {
 public:
  /// Indexes `positions[i]` under `ids[i]`. `cell_size` <= 0 picks a size giving about four
  /// points per cell.
  void build(std::span<const Vec2> positions, std::span<const sim::NodeId> ids,
             double cell_size = 0.0);

  std::size_t size() const { return ids_.size(); }
  double cell_size() const { return cell_; }
  /// Points in cell order: slot k holds ids()[k]. Callers may keep per-point data by slot
  /// so that a range query touches contiguous memory.
  const std::vector<sim::NodeId>& ids() const { return ids_; }

  /// Calls `visit(id, position, squared_distance)` for every indexed point within `radius`
  /// of `center` (inclusive), in cell order.
  template <class Visit>
  void for_each_within(const Vec2& center, double radius, Visit&& visit) const {
    for_each_slot_within(center, radius, [&](std::uint32_t k, double d2) {
      visit(ids_[k], Vec2{xs_[k], ys_[k]}, d2);
    });
  }

  /// Calls `visit(slot, squared_distance)` for every point within `radius` of `center`
  /// (inclusive), slot by slot in cell order: one contiguous run of slots per grid row.
  template <class Visit>
  void for_each_slot_within(const Vec2& center, double radius, Visit&& visit) const {
    if (ids_.empty() || !(radius >= 0.0)) return;
    const double r2 = radius * radius;
    const double cx = center.x(), cy = center.y();
    // Candidate rows and columns are widened by a hair: a point at exactly the range (common on
    // sensor grids) must reach the exact test below, whatever the rounding of cy ± radius.
    const double slack = 1e-12 * (std::fabs(cx) + std::fabs(cy) + radius) + 1e-300;
    const int row_lo = row_of(cy - radius - slack);
    const int row_hi = row_of(cy + radius + slack);
    // Local pointers: the visitor's stores must not make the compiler reload them.
    const double* const xs = xs_.data();
    const double* const ys = ys_.data();
    const std::uint32_t* const starts = cell_start_.data();
    for (int row = row_lo; row <= row_hi; ++row) {
      // Nearest y of this row to the centre bounds the x-extent of the disk in the row.
      const double row_y0 = y0_ + row * cell_, row_y1 = row_y0 + cell_;
      const double dy = cy < row_y0 ? row_y0 - cy : (cy > row_y1 ? cy - row_y1 : 0.0);
      const double half2 = r2 - dy * dy;
      if (half2 < -slack * radius) continue;
      const double half = std::sqrt(std::max(half2, 0.0)) + slack;
      const int col_lo = col_of(cx - half);
      const int col_hi = col_of(cx + half);
      const std::uint32_t begin = starts[row * nx_ + col_lo];
      const std::uint32_t end = starts[row * nx_ + col_hi + 1];
      // The tests of up to 64 slots first (disk_mask), then the visits, in slot order, with the
      // same d2.
      for (std::uint32_t base = begin; base < end; base += 64) {
        const std::uint32_t stop = std::min(end, base + 64);
        std::uint64_t inside = disk_mask(xs + base, ys + base, stop - base, cx, cy, r2);
        for (; inside != 0; inside &= inside - 1) {
          const std::uint32_t slot = base + static_cast<std::uint32_t>(std::countr_zero(inside));
          visit(slot, squared_distance(xs[slot], ys[slot], cx, cy));
        }
      }
    }
  }

 private:
  // Clamped in double first, so a huge radius cannot overflow the int conversion.
  // A multiply, not a divide: these run twice per grid row of every query.
  int row_of(double y) const {
    const double r = (y - y0_) * inv_cell_;
    return r < 1.0 ? 0 : (r >= ny_ - 1 ? ny_ - 1 : static_cast<int>(r));
  }
  int col_of(double x) const {
    const double c = (x - x0_) * inv_cell_;
    return c < 1.0 ? 0 : (c >= nx_ - 1 ? nx_ - 1 : static_cast<int>(c));
  }

  double x0_ = 0, y0_ = 0, cell_ = 1, inv_cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> cell_start_;  // nx*ny + 1 offsets
  std::vector<double> xs_, ys_;
  std::vector<sim::NodeId> ids_;
};

}  // namespace masnet::net
