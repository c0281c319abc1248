#include "net/line_index.hpp"

#include <algorithm>
#include <numeric>

namespace masnet::net {

bool LineIndex::build(std::span<const Vec2> positions, std::span<const sim::NodeId> ids,
                      double min_mean_length) {
  lines_.clear();
  max_abs_x_ = max_inv_dx_ = 0.0;
  max_even_count_ = 0;
  lines_even_ = uniform_x_ = false;
  xs_.clear();
  ys_.clear();
  ids_.clear();
  const std::size_t n = positions.size();
  if (n == 0) return false;
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  // By y, then x, then input order (a stable layout for coincident points).
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (positions[a].y() != positions[b].y()) return positions[a].y() < positions[b].y();
    return positions[a].x() < positions[b].x();
  });
  std::size_t line_count = 1;
  for (std::size_t k = 1; k < n; ++k)
    line_count += positions[order[k]].y() != positions[order[k - 1]].y() ? 1 : 0;
  if (static_cast<double>(n) / static_cast<double>(line_count) < min_mean_length) return false;

  xs_.resize(n);
  ys_.resize(n);
  ids_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    xs_[k] = positions[order[k]].x();
    ys_[k] = positions[order[k]].y();
    ids_[k] = ids[order[k]];
  }
  for (std::uint32_t begin = 0; begin < n;) {
    std::uint32_t end = begin + 1;
    while (end < n && ys_[end] == ys_[begin])
      ++end;
    Line line{ys_[begin], begin, end, xs_[begin], 0.0, static_cast<double>(end - begin) - 0.5,
              false};
    const std::uint32_t count = end - begin;
    if (count >= 2) {
      // Evenly spaced (to 1e-9 of the spacing): slot estimates are then exact up to ±1, and the
      // exact test corrects any error in either case.
      const double dx = (xs_[end - 1] - xs_[begin]) / static_cast<double>(count - 1);
      bool even = dx > 0.0;
      for (std::uint32_t k = begin; even && k < end; ++k)
        even = std::fabs(xs_[k] - (xs_[begin] + static_cast<double>(k - begin) * dx)) <= 1e-9 * dx;
      if (even) {
        line.inv_dx = 1.0 / dx;
        line.even = true;
        max_inv_dx_ = std::max(max_inv_dx_, line.inv_dx);
        max_even_count_ = std::max(max_even_count_, count);
        max_abs_x_ = std::max({max_abs_x_, std::fabs(xs_[begin]), std::fabs(xs_[end - 1])});
      }
    }
    lines_.push_back(line);
    begin = end;
  }
  uniform_x_ = std::all_of(lines_.begin(), lines_.end(), [&](const Line& line) {
    return line.even && line.x0 == lines_[0].x0 && line.inv_dx == lines_[0].inv_dx &&
           line.last_half == lines_[0].last_half;
  });
  if (uniform_x_) {
    uniform_x0_ = lines_[0].x0;
    uniform_inv_dx_ = lines_[0].inv_dx;
    uniform_last_half_ = lines_[0].last_half;
  }
  lines_even_ = false;
  if (lines_.size() >= 2) {
    const double dy = (lines_.back().y - lines_.front().y) / static_cast<double>(lines_.size() - 1);
    bool even = dy > 0.0;
    for (std::size_t l = 0; even && l < lines_.size(); ++l)
      even = std::fabs(lines_[l].y - (lines_.front().y + static_cast<double>(l) * dy)) <= 1e-9 * dy;
    if (even) {
      lines_even_ = true;
      inv_line_dy_ = 1.0 / dy;
    }
  }
  return true;
}

}  // namespace masnet::net
