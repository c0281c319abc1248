#pragma once
// A uniform grid over a set of points, stored cell by cell (CSR) with positions copied in
// cell order, so a range query scans a few contiguous runs of memory (one per grid row).
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "net/vec2.hpp"
#include "sim/ids.hpp"

namespace masnet::net {

class SpatialGrid {
 public:
  /// Indexes `positions[i]` under `ids[i]`. `cell_size` <= 0 picks a size giving about four
  /// points per cell.
  void build(std::span<const Vec2> positions, std::span<const sim::NodeId> ids,
             double cell_size = 0.0);

  std::size_t size() const { return ids_.size(); }
  double cell_size() const { return cell_; }

  /// Calls `visit(id, position, squared_distance)` for every indexed point within `radius`
  /// of `center` (inclusive), in cell order.
  template <class Visit>
  void for_each_within(const Vec2& center, double radius, Visit&& visit) const {
    if (ids_.empty() || !(radius >= 0.0)) return;
    const double r2 = radius * radius;
    const double cx = center.x(), cy = center.y();
    const int row_lo = row_of(cy - radius);
    const int row_hi = row_of(cy + radius);
    for (int row = row_lo; row <= row_hi; ++row) {
      // Nearest y of this row to the centre bounds the x-extent of the disk in the row.
      const double row_y0 = y0_ + row * cell_, row_y1 = row_y0 + cell_;
      const double dy = cy < row_y0 ? row_y0 - cy : (cy > row_y1 ? cy - row_y1 : 0.0);
      const double half2 = r2 - dy * dy;
      if (half2 < 0.0) continue;
      const double half = std::sqrt(half2);
      const int col_lo = col_of(cx - half);
      const int col_hi = col_of(cx + half);
      const std::uint32_t begin = cell_start_[row * nx_ + col_lo];
      const std::uint32_t end = cell_start_[row * nx_ + col_hi + 1];
      for (std::uint32_t k = begin; k < end; ++k) {
        const double ddx = xs_[k] - cx, ddy = ys_[k] - cy;
        const double d2 = ddx * ddx + ddy * ddy;
        if (d2 <= r2) visit(ids_[k], Vec2{xs_[k], ys_[k]}, d2);
      }
    }
  }

 private:
  int clamp_row(int r) const { return r < 0 ? 0 : (r >= ny_ ? ny_ - 1 : r); }
  int clamp_col(int c) const { return c < 0 ? 0 : (c >= nx_ ? nx_ - 1 : c); }
  // Clamped in double first, so a huge radius cannot overflow the int conversion.
  int row_of(double y) const {
    const double r = std::floor((y - y0_) / cell_);
    return r <= 0.0 ? 0 : (r >= ny_ - 1 ? ny_ - 1 : static_cast<int>(r));
  }
  int col_of(double x) const {
    const double c = std::floor((x - x0_) / cell_);
    return c <= 0.0 ? 0 : (c >= nx_ - 1 ? nx_ - 1 : static_cast<int>(c));
  }

  double x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> cell_start_;  // nx*ny + 1 offsets
  std::vector<double> xs_, ys_;
  std::vector<sim::NodeId> ids_;
};

}  // namespace masnet::net
