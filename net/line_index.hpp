#pragma once
// Static points grouped into horizontal lines (equal y), each sorted by x. When the points lie
// on rows — a sensor grid — a disk meets every line in one contiguous run of slots, found with a
// few exact distance tests (none when the estimate is provably exact): a range query costs
// O(lines crossed), not O(points inside). The radio uses it to book a frame heard by thousands
// of sensors as a handful of runs.
#include <algorithm>
#include <cmath>
#include <cstdint>
#if defined(__SSE2__)
#include <emmintrin.h>  // baseline x86-64
#endif
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
  bool build(std::span<const Vec2> positions, std::span<const sim::NodeId> ids,
             double min_mean_length = 8.0);

  /// Points in line-major order: slot k holds ids()[k].
  const std::vector<sim::NodeId>& ids() const { return ids_; }
  bool empty() const { return ids_.empty(); }
  const double& x(std::uint32_t k) const { return xs_[k]; }
  double y(std::uint32_t k) const { return ys_[k]; }

  /// Calls `visit(line, y, begin, end)` for every line with y in [y0, y1]: its slots [begin, end).
  template <class Visit>
  void for_each_line_between(double y0, double y1, Visit&& visit) const {
    for (std::size_t l = first_line_at_or_above(y0); l < lines_.size() && lines_[l].y <= y1; ++l)
      visit(l, lines_[l].y, lines_[l].begin, lines_[l].end);
  }
  /// A guess at first_at_or_after(line, value) that reads no coordinates (exact for evenly
  /// spaced lines but for rounding): where to prefetch before the exact search.
  std::uint32_t guess_at_or_after(std::size_t line, double value) const {
    return estimate(lines_[line], value, true);
  }
  /// First slot of `line` whose x is >= value (the line's end if none).
  std::uint32_t first_at_or_after(std::size_t line, double value) const {
    const Line& l = lines_[line];
    std::uint32_t k = estimate(l, value, true);
    while (k > l.begin && xs_[k - 1] >= value)
      --k;
    while (k < l.end && xs_[k] < value)
      ++k;
    return k;
  }

  /// True iff slot k is within `radius` of `center`: the same arithmetic as the run search, and
  /// as SpatialGrid, so a point is in or out whatever index found it.
  bool within(std::uint32_t k, const Vec2& center, double radius) const {
    const double ddx = xs_[k] - center.x(), ddy = ys_[k] - center.y();
    return ddx * ddx + ddy * ddy <= radius * radius;
  }

  /// Whether sure_slots() may be used for intervals whose ends lie within [−extent, extent] and
  /// whose points must moreover be more than `guard` (world units) from either end: a bound on
  /// the rounding of the slot estimates, and the guard, both well below the sure margin.
  bool slot_estimates_are_sure(double extent, double guard) const {
    return estimate_rounding(extent) <= 0.25 * kSureMargin &&
           guard * max_inv_dx_ <= 0.25 * kSureMargin;  // false on NaN
  }
  /// The slots [a, c) of `line` whose x lie in [lo, hi], from O(1) estimates, when the line is
  /// evenly spaced and both ends lie at least kSureMargin (in slots) from every point; false
  /// otherwise. Call only when slot_estimates_are_sure(extent, guard) holds for the ends: every
  /// point outside [a, c) is then also more than `guard` outside [lo, hi].
  bool sure_slots(std::size_t line, double lo, double hi, std::uint32_t& a,
                  std::uint32_t& c) const {
#if defined(__SSE2__)
    const Line& l = lines_[line];
    return l.even && sure_slots_of_ends(l, _mm_set_pd(hi, lo), a, c);
#else
    (void)line, (void)lo, (void)hi, (void)a, (void)c;
    return false;
#endif
  }

  /// Calls `visit(begin, end)` for each run of slots [begin, end) whose points lie within
  /// `radius` of `center` (inclusive), one run per line crossed. `prefetch(a, c)` (optional) is
  /// told every line's estimated run first, so the caller can prefetch what it will touch there.
  /// Both are taken by value: the loop then keeps what they capture in registers (a reference
  /// would be reloaded after every write the caller makes through a pointer). Returns the number
  /// of slots in the runs, so a visitor need not count (small visitors travel in registers).
  template <class Visit, class Prefetch>
  std::uint64_t for_each_run_within(const Vec2& center, double radius, Visit visit,
                                    Prefetch prefetch) const {
    // A sensor grid's lines all share one spacing and start: its constants then stay in
    // registers instead of being loaded (and broadcast) line by line.
    return uniform_x_ ? runs_within<true>(center, radius, visit, prefetch)
                      : runs_within<false>(center, radius, visit, prefetch);
  }
  template <class Visit>
  std::uint64_t for_each_run_within(const Vec2& center, double radius, Visit&& visit) const {
    return for_each_run_within(center, radius, std::forward<Visit>(visit),
                               [](std::uint32_t, std::uint32_t) {});
  }

 private:
  template <bool kUniform, class Visit, class Prefetch>
  std::uint64_t runs_within(const Vec2& center, double radius, Visit visit,
                            Prefetch prefetch) const {
    std::uint64_t covered = 0;
    if (lines_.empty() || !(radius >= 0.0)) return covered;
    const double r2 = radius * radius, cx = center.x(), cy = center.y();
    const double* const xs = xs_.data();
    // Lines are picked with a hair of slack; the exact test decides (a point at exactly the
    // range must not be lost to the rounding of cy ± radius).
    const double slack = 1e-12 * (std::fabs(cx) + std::fabs(cy) + radius) + 1e-300;
    const std::size_t lo = first_line_at_or_above(cy - radius - slack);
    const bool sure_estimates = estimates_are_sure(cx, radius);
#if defined(__SSE2__)
    const __m128d uniform_x0 = _mm_set1_pd(uniform_x0_),
                  uniform_inv_dx = _mm_set1_pd(uniform_inv_dx_);
    const __m128d uniform_last_half = _mm_set1_pd(uniform_last_half_);
#endif
    const double min_sure_half = radius * kMinSureHalf;
    // Two passes over batches of lines: first the estimates, with prefetches of the memory each
    // line will touch (on large networks every line is a cache miss: overlapping them is most of
    // the cost), then the exact steps where the estimate is not sure. A sure line leaves only
    // its run; the others also their line and dy² (bit i of `unsure` marks entry i).
    constexpr std::size_t kBatch = 32;
    std::uint32_t run_a[kBatch], run_c[kBatch], unsure_line[kBatch];
    double unsure_dy2[kBatch];
    const double y_top = cy + radius + slack;
    const std::size_t line_count = lines_.size();
    std::size_t l = lo;
    while (l < line_count && lines_[l].y <= y_top) {
      std::size_t n = 0;
      std::uint32_t unsure = 0;
      for (; n < kBatch && l < line_count && lines_[l].y <= y_top; ++l) {
        const Line& line = lines_[l];
        const double ddy = line.y - cy, dy2 = ddy * ddy;
        if (dy2 > r2) continue;
        const double half = std::sqrt(r2 - dy2);
        std::uint32_t a, c;
        bool sure = false;
        if constexpr (kUniform) {
#if defined(__SSE2__)
          sure = sure_estimates && half >= min_sure_half &&
                 sure_slots_of_ends(line.begin, chord_ends(cx, half), uniform_x0, uniform_inv_dx,
                                    uniform_last_half, a, c);
#endif
        } else {
          sure = sure_estimates && line.even && half >= min_sure_half &&
                 sure_run(line, cx, half, a, c);
        }
        if (!sure) {
          // Starting points only: the steps below are exact.
          a = estimate(line, cx - half, true);
          c = estimate(line, cx + half, false);
          __builtin_prefetch(xs + (a > line.begin ? a - 1 : a));
          __builtin_prefetch(xs + (c < line.end ? c : c - 1));
          unsure |= std::uint32_t{1} << n;
          unsure_line[n] = static_cast<std::uint32_t>(l);
          unsure_dy2[n] = dy2;
        }
        prefetch(a, c);
        run_a[n] = a;
        run_c[n] = c;
        ++n;
      }
      for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t a = run_a[i], c = run_c[i];
        if ((unsure >> i) & 1u) {
          const Line& line = lines_[unsure_line[i]];
          const double dy2 = unsure_dy2[i];
          auto inside = [&](std::uint32_t k) {
            const double ddx = xs[k] - cx;
            return ddx * ddx + dy2 <= r2;
          };
          // From the estimate (exact for evenly spaced lines) step with the exact test: the run
          // is where `inside` holds, an interval of the sorted line.
          while (a > line.begin && inside(a - 1))
            --a;
          while (a < line.end && !inside(a) && xs[a] < cx)
            ++a;
          if (c < a) c = a;
          while (c < line.end && inside(c))
            ++c;
          while (c > a && !inside(c - 1))
            --c;
        }
        if (a < c) {
          visit(a, c);
          covered += c - a;
        }
      }
    }
    return covered;
  }

  struct Line {
    double y;
    std::uint32_t begin, end;  // slots
    double x0, inv_dx;         // evenly spaced lines: slot ≈ begin + (x − x0)·inv_dx
    double last_half;          // end − begin − 0.5: clamp for sure_run
    bool even;
  };

  // Sure estimates. On an evenly spaced line the run of a disk is [ceil(kl), floor(kr) + 1) in
  // slot coordinates kl, kr of the chord's ends. When kl and kr lie at least kSureMargin (in
  // slots) from an integer, and the rounding of the whole computation — estimate, the line's
  // deviation from even spacing, and the uncertainty of the float test (x − cx)² + dy² <= r²
  // itself — is provably smaller, that run is exactly what the float test decides: no point is
  // near enough to the circle for rounding to move it across. The bound on the test's
  // uncertainty grows as the chord shrinks (tangent lines), so short chords are never sure.
  static constexpr double kSureMargin = 1e-6;
  static constexpr double kMinSureHalf = 1.0 / 1024;  // of the radius
  static constexpr double kUlp = 0x1p-52;

  /// A bound, in slots, on the rounding of a slot estimate of a value within [−span, span] on any
  /// evenly spaced line. Terms: 1e-8 the lines' deviation from even spacing (<= 1e-9, checked by
  /// build); 16u·(span + max|x|)·inv_dx the rounding of the value, of its offset from the line's
  /// start and of the product by inv_dx; 4u·count the shift by one.
  double estimate_rounding(double span) const {
    return 1e-8 + kUlp * (max_inv_dx_ * 16.0 * (span + max_abs_x_) +
                          4.0 * (static_cast<double>(max_even_count_) + 2.0));
  }
  /// Whether sure_run may be used for a disk at x = cx with this radius: the estimates' rounding
  /// for chord ends within |cx| + r, plus 4096u·r·inv_dx for the float test's own uncertainty
  /// (about 2.3u·r²/half with half >= r/1024), well below the margin.
  bool estimates_are_sure(double cx, double radius) const {
    const double rounding =
        estimate_rounding(std::fabs(cx) + radius) + kUlp * max_inv_dx_ * 4096.0 * radius;
    return rounding <= 0.25 * kSureMargin;  // false on NaN
  }

  /// The run [a, c) of an evenly spaced line inside the chord [cx − half, cx + half], if both
  /// ends lie at least kSureMargin from a slot; false otherwise. Both ends in one SSE2 register.
  static bool sure_run(const Line& line, double cx, double half, std::uint32_t& a,
                       std::uint32_t& c) {
#if !defined(__SSE2__)
    return false;  // the exact steps do it all
#else
    return sure_slots_of_ends(line, chord_ends(cx, half), a, c);
#endif
  }
#if defined(__SSE2__)
  /// {cx − half, cx + half}.
  static __m128d chord_ends(double cx, double half) {
    return _mm_add_pd(_mm_set1_pd(cx), _mm_mul_pd(_mm_set1_pd(half), _mm_set_pd(1.0, -1.0)));
  }
  /// The slots [a, c) of an evenly spaced line between ends = {left, right}, if both lie at least
  /// kSureMargin from a slot.
  static bool sure_slots_of_ends(const Line& line, __m128d ends, std::uint32_t& a,
                                 std::uint32_t& c) {
    return sure_slots_of_ends(line.begin, ends, _mm_set1_pd(line.x0), _mm_set1_pd(line.inv_dx),
                              _mm_set1_pd(line.last_half), a, c);
  }
  /// The same from the line's first slot and its constants, each in both lanes.
  static bool sure_slots_of_ends(std::uint32_t begin, __m128d ends, __m128d x0, __m128d inv_dx,
                                 __m128d last_half, std::uint32_t& a, std::uint32_t& c) {
    __m128d k = _mm_mul_pd(_mm_sub_pd(ends, x0), inv_dx);
    // Clamped to the line (a chord end beyond it is half a slot past the end slot), then
    // shifted by one: truncation is then floor, and floor(k + 1) = ceil(k) = floor(k) + 1 for
    // the non-integer k that pass the margin test.
    k = _mm_min_pd(_mm_max_pd(k, _mm_set1_pd(-0.5)), last_half);
    k = _mm_add_pd(k, _mm_set1_pd(1.0));
    const __m128i slots = _mm_cvttpd_epi32(k);
    const __m128d fraction = _mm_sub_pd(k, _mm_cvtepi32_pd(slots));
    const __m128d from_middle =
        _mm_andnot_pd(_mm_set1_pd(-0.0), _mm_sub_pd(fraction, _mm_set1_pd(0.5)));
    if (_mm_movemask_pd(_mm_cmple_pd(from_middle, _mm_set1_pd(0.5 - kSureMargin))) != 3)
      return false;
    a = begin + static_cast<std::uint32_t>(_mm_cvtsi128_si32(slots));
    c = begin + static_cast<std::uint32_t>(_mm_cvtsi128_si32(_mm_shuffle_epi32(slots, 1)));
    return true;
  }
#endif

  /// The first line with y >= value (the line count if none). Evenly spaced lines (a grid's
  /// rows) start from an O(1) estimate; the steps make it exact either way.
  [[gnu::always_inline]] std::size_t first_line_at_or_above(double value) const {
    const std::size_t count = lines_.size();
    std::size_t l;
    if (lines_even_) {
      const double k = (value - lines_[0].y) * inv_line_dy_;
      l = !(k > 0.0) ? 0 : k >= static_cast<double>(count) ? count : static_cast<std::size_t>(k);
      while (l > 0 && lines_[l - 1].y >= value)
        --l;
      while (l < count && lines_[l].y < value)
        ++l;
      return l;
    }
    std::size_t hi = count;
    l = 0;
    while (l < hi) {
      const std::size_t mid = (l + hi) / 2;
      if (lines_[mid].y < value)
        l = mid + 1;
      else
        hi = mid;
    }
    return l;
  }

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
      if (from_left ? xs_[mid] < x : xs_[mid] <= x)
        lo = mid + 1;
      else
        hi = mid;
    }
    return lo;
  }

  std::vector<Line> lines_;
  // For the rounding bound of sure estimates (0 / 0 / 0 when no line is evenly spaced).
  double max_abs_x_ = 0.0, max_inv_dx_ = 0.0;
  std::uint32_t max_even_count_ = 0;
  bool lines_even_ =
      false;  // line y evenly spaced (to 1e-9 of the spacing): see first_line_at_or_above
  // Every line evenly spaced with the same start, spacing and length (a grid's rows): their
  // common x0, inv_dx and last_half.
  bool uniform_x_ = false;
  double uniform_x0_ = 0.0, uniform_inv_dx_ = 0.0, uniform_last_half_ = 0.0;
  double inv_line_dy_ = 0.0;
  std::vector<double> xs_, ys_;
  std::vector<sim::NodeId> ids_;
};

}  // namespace masnet::net
