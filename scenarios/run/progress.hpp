#pragma once
// A progress line for long runs on a terminal (stderr): share done, simulated time, events per
// second and an ETA. Silent when stderr is not a terminal or with --quiet. It is told the
// progress often (the simulator calls back every few thousand events, docs/logging.md) and
// decides from the wall clock when to draw: not before the run has lasted half a second, then
// at most four times a second.
#include <chrono>
#include <cstdint>
#include <string>

namespace masnet::scenarios {

class ProgressBar {
 public:
  /// `enabled` false: every call does nothing.
  ProgressBar(double total_s, bool enabled);
  ~ProgressBar();
  void update(double t_s, std::uint64_t events);
  /// Clears the line (also done by the destructor).
  void finish();
  /// True when stderr is a terminal.
  static bool stderr_is_terminal();
  /// The text of one line (tests). `eta_s` < 0: not known yet.
  static std::string line(double t_s, double total_s, double events_per_s, double eta_s, int width);
  /// A duration as "mm:ss", or "h:mm:ss" from an hour on (rounded to the second).
  static std::string clock_text(double seconds);

 private:
  double total_s_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace masnet::scenarios
