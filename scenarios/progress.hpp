#pragma once
// A progress line for long runs on a terminal (stderr): simulated time, events per second and
// an ETA. Silent when stderr is not a terminal or with --quiet.
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
  void finish();
  /// True when stderr is a terminal.
  static bool stderr_is_terminal();
  /// The text of one line (tests).
  static std::string line(double t_s, double total_s, double events_per_s, double eta_s, int width);

 private:
  double total_s_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace masnet::scenarios
