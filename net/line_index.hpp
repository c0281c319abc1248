#pragma once
// Static points grouped into horizontal lines (equal y), each sorted by x. When the points lie
// on rows — a sensor grid — a disk meets every line in one contiguous run of slots, found with a
// few exact distance tests: a range query costs O(lines crossed), not O(points inside). The
// radio uses it to book a frame heard by thousands of sensors as a handful of runs.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "net/vec2.hpp"
#include "sim/ids.hpp"

namespace masnet::net {

class LineIndex {
 public:
  /// Indexes the points if they form lines of at least `min_mean_length` points on average;
  /// returns false (and stays empty) otherwise.
  bool build(std::span<const Vec2> positions, std::span<const sim::NodeId> ids, double min_mean_length = 8.0);

  /// Points in line-major order: slot k holds ids()[k].
  const std::vector<sim::NodeId>& ids() const { return ids_; }
  bool empty() const { return ids_.empty(); }
  const double& x(std::uint32_t k) const { return xs_[k]; }
  double y(std::uint32_t k) const { return ys_[k]; }

  /// Calls `visit(line, y, begin, end)` for every line with y in [y0, y1]: its slots [begin, end).
  template <class Visit>
  void for_each_line_between(double y0, double y1, Visit&& visit) const {
    std::size_t lo = 0, hi = lines_.size();
    while (lo < hi) {
      const std::size_t mid = (lo + hi) / 2;
      if (lines_[mid].y < y0) lo = mid + 1; else hi = mid;
    }
    for (std::size_t l = lo; l < lines_.size() && lines_[l].y <= y1; ++l)
      visit(l, lines_[l].y, lines_[l].begin, lines_[l].end);
  }
  /// A guess at first_at_or_after(line, value) that reads no coordinates (exact for evenly
  /// spaced lines but for rounding): where to prefetch before the exact search.
  std::uint32_t guess_at_or_after(std::size_t line, double value) const { return estimate(lines_[line], value, true); }
  /// First slot of `line` whose x is >= value (the line's end if none).
  std::uint32_t first_at_or_after(std::size_t line, double value) const {
    const Line& l = lines_[line];
    std::uint32_t k = estimate(l, value, true);
    while (k > l.begin && xs_[k - 1] >= value) --k;
    while (k < l.end && xs_[k] < value) ++k;
    return k;
  }

  /// True iff slot k is within `radius` of `center`: the same arithmetic as the run search, and
  /// as SpatialGrid, so a point is in or out whatever index found it.
  bool within(std::uint32_t k, const Vec2& center, double radius) const {
    const double ddx = xs_[k] - center.x(), ddy = ys_[k] - center.y();
    return ddx * ddx + ddy * ddy <= radius * radius;
  }

  /// Calls `visit(begin, end)` for each run of slots [begin, end) whose points lie within
  /// `radius` of `center` (inclusive), one run per line crossed. `prefetch(a, c)` (optional) is
  /// told every line's estimated run first, so the caller can prefetch what it will touch there.
  template <class Visit, class Prefetch>
  void for_each_run_within(const Vec2& center, double radius, Visit&& visit, Prefetch&& prefetch) const {
    if (lines_.empty() || !(radius >= 0.0)) return;
    const double r2 = radius * radius, cx = center.x(), cy = center.y();
    const double* const xs = xs_.data();
    // Lines are picked with a hair of slack; the exact test decides (a point at exactly the
    // range must not be lost to the rounding of cy ± radius).
    const double slack = 1e-12 * (std::fabs(cx) + std::fabs(cy) + radius) + 1e-300;
    std::size_t lo = 0, hi = lines_.size();
    while (lo < hi) {
      const std::size_t mid = (lo + hi) / 2;
      if (lines_[mid].y < cy - radius - slack) lo = mid + 1; else hi = mid;
    }
    // Two passes over batches of lines: first the estimates, with prefetches of the memory each
    // line will touch (on large networks every line is a cache miss: overlapping them is most of
    // the cost), then the exact steps.
    struct Pending {
      std::uint32_t line, a, c;
      double dy2;
    };
    constexpr std::size_t kBatch = 32;
    Pending pending[kBatch];
    std::size_t l = lo;
    while (l < lines_.size() && lines_[l].y <= cy + radius + slack) {
      std::size_t n = 0;
      for (; n < kBatch && l < lines_.size() && lines_[l].y <= cy + radius + slack; ++l) {
        const Line& line = lines_[l];
        const double ddy = line.y - cy, dy2 = ddy * ddy;
        if (dy2 > r2) continue;
        const double half = std::sqrt(r2 - dy2);  // starting points only: the steps are exact
        const std::uint32_t a = estimate(line, cx - half, true), c = estimate(line, cx + half, false);
        __builtin_prefetch(xs + (a > line.begin ? a - 1 : a));
        __builtin_prefetch(xs + (c < line.end ? c : c - 1));
        prefetch(a, c);
        pending[n++] = Pending{static_cast<std::uint32_t>(l), a, c, dy2};
      }
      for (std::size_t i = 0; i < n; ++i) {
        const Line& line = lines_[pending[i].line];
        const double dy2 = pending[i].dy2;
        auto inside = [&](std::uint32_t k) {
          const double ddx = xs[k] - cx;
          return ddx * ddx + dy2 <= r2;
        };
        // From the estimate (exact for evenly spaced lines) step with the exact test: the run is
        // where `inside` holds, an interval of the sorted line.
        std::uint32_t a = pending[i].a, c = pending[i].c;
        while (a > line.begin && inside(a - 1)) --a;
        while (a < line.end && !inside(a) && xs[a] < cx) ++a;
        if (c < a) c = a;
        while (c < line.end && inside(c)) ++c;
        while (c > a && !inside(c - 1)) --c;
        if (a < c) visit(a, c);
      }
    }
  }
  template <class Visit>
  void for_each_run_within(const Vec2& center, double radius, Visit&& visit) const {
    for_each_run_within(center, radius, std::forward<Visit>(visit), [](std::uint32_t, std::uint32_t) {});
  }

 private:
  struct Line {
    double y;
    std::uint32_t begin, end;  // slots
    double x0, inv_dx;         // evenly spaced lines: slot ≈ begin + (x − x0)·inv_dx
    bool even;
  };
  // A slot near x on the line: first slot with x_k >= x (from_left) or one past the last with
  // x_k <= x; evenly spaced lines answer in O(1), others by binary search.
  std::uint32_t estimate(const Line& line, double x, bool from_left) const {
    if (line.even) {
      // ceil(k) (from the left) or floor(k) + 1 without calling libm: truncation is floor for
      // k >= 0, and baseline x86-64 has no rounding instruction.
      const double k = (x - line.x0) * line.inv_dx;
      const double count = static_cast<double>(line.end - line.begin);
      if (!(k >= 0.0)) return line.begin;  // ceil(k) <= 0 and floor(k) + 1 <= 0
      if (k >= count) return line.end;
      const auto t = static_cast<std::uint32_t>(k);
      const std::uint32_t i = from_left ? t + (static_cast<double>(t) < k ? 1u : 0u) : t + 1u;
      return std::min(line.begin + i, line.end);
    }
    std::uint32_t lo = line.begin, hi = line.end;
    while (lo < hi) {
      const std::uint32_t mid = lo + (hi - lo) / 2;
      if (from_left ? xs_[mid] < x : xs_[mid] <= x) lo = mid + 1; else hi = mid;
    }
    return lo;
  }

  std::vector<Line> lines_;
  std::vector<double> xs_, ys_;
  std::vector<sim::NodeId> ids_;
};

}  // namespace masnet::net
