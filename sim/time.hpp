#pragma once
// Simulated time: integer nanoseconds. `double` seconds appear only in
// formulas and files, converted at the edges with `seconds()` / `to_seconds()`.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>

namespace masnet::sim {

/// A span of simulated time, in integer nanoseconds.
using Duration = std::chrono::duration<std::int64_t, std::nano>;

/// The clock of a simulation: starts at 0 and only advances when events run.
struct SimClock {
  using rep = std::int64_t;
  using period = std::nano;
  using duration = Duration;
  using time_point = std::chrono::time_point<SimClock, Duration>;
  static constexpr bool is_steady = true;
};

/// A point in simulated time (nanoseconds since the start of the run).
using Time = SimClock::time_point;

inline constexpr Time kTimeZero{Duration{0}};
inline constexpr Time kTimeMax{Duration{std::numeric_limits<std::int64_t>::max()}};

/// Seconds (double) to the nearest nanosecond; the one place where rounding happens.
inline Duration seconds(double s) {
  return Duration{std::llround(s * 1e9)};
}
/// The time `s` seconds after the start of the run, rounded to the nanosecond.
inline Time time_at(double s) {
  return kTimeZero + seconds(s);
}

inline constexpr double to_seconds(Duration d) {
  return static_cast<double>(d.count()) * 1e-9;
}
inline constexpr double to_seconds(Time t) {
  return to_seconds(t.time_since_epoch());
}
inline constexpr std::int64_t to_ns(Time t) {
  return t.time_since_epoch().count();
}

}  // namespace masnet::sim
