#include "scenarios/run/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>
#include <unistd.h>

namespace masnet::scenarios {

namespace {
constexpr auto kFirstDraw = std::chrono::milliseconds(500);  // short runs draw nothing
constexpr auto kRedraw = std::chrono::milliseconds(250);     // at most four lines a second
}  // namespace

ProgressBar::ProgressBar(double total_s, bool enabled)
    : total_s_(total_s),
      enabled_(enabled),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() {
  finish();
}

bool ProgressBar::stderr_is_terminal() {
  return ::isatty(STDERR_FILENO) == 1;
}

std::string ProgressBar::clock_text(double seconds) {
  const auto total = static_cast<long long>(std::llround(std::max(seconds, 0.0)));
  const long long hours = total / 3600, minutes = total / 60 % 60, secs = total % 60;
  if (hours > 0) return fmt::format("{}:{:02}:{:02}", hours, minutes, secs);
  return fmt::format("{:02}:{:02}", minutes, secs);
}

std::string ProgressBar::line(double t_s, double total_s, double events_per_s, double eta_s,
                              int width) {
  const double fraction = total_s > 0 ? std::clamp(t_s / total_s, 0.0, 1.0) : 1.0;
  const int filled = static_cast<int>(std::lround(fraction * width));
  return fmt::format("[{}{}] {:5.1f}%  t = {:.3f} / {:.3f} s  {:.2f} M events/s  ETA {}",
                     std::string(static_cast<std::size_t>(filled), '#'),
                     std::string(static_cast<std::size_t>(width - filled), ' '), 100.0 * fraction,
                     t_s, total_s, events_per_s / 1e6,
                     eta_s < 0 ? std::string("--:--") : clock_text(eta_s));
}

void ProgressBar::update(double t_s, std::uint64_t events) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - start_ < kFirstDraw || now - last_draw_ < kRedraw) return;
  last_draw_ = now;
  const double wall = std::chrono::duration<double>(now - start_).count();
  // Linear in simulated time: the rate so far, applied to what is left.
  const double eta = t_s > 0 ? wall * std::max(total_s_ - t_s, 0.0) / t_s : -1.0;
  // "\033[K" clears what a longer previous line left behind.
  std::fprintf(stderr, "\r%s\033[K",
               line(t_s, total_s_, static_cast<double>(events) / wall, eta, 30).c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::finish() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace masnet::scenarios
