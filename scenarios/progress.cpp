#include "scenarios/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>
#include <unistd.h>

namespace masnet::scenarios {

ProgressBar::ProgressBar(double total_s, bool enabled)
    : total_s_(total_s), enabled_(enabled), start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

ProgressBar::~ProgressBar() { finish(); }

bool ProgressBar::stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

std::string ProgressBar::line(double t_s, double total_s, double events_per_s, double eta_s, int width) {
  const double fraction = total_s > 0 ? std::clamp(t_s / total_s, 0.0, 1.0) : 1.0;
  const int filled = static_cast<int>(std::lround(fraction * width));
  return fmt::format("[{}{}] {:5.1f}%  t = {:.3f} / {:.3f} s  {:.2f} M events/s  ETA {:.0f} s",
                     std::string(static_cast<std::size_t>(filled), '#'),
                     std::string(static_cast<std::size_t>(width - filled), ' '), 100.0 * fraction, t_s, total_s,
                     events_per_s / 1e6, eta_s);
}

void ProgressBar::update(double t_s, std::uint64_t events) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  // Redraw at most four times a second, and only once the run has lasted half a second.
  if (now - last_draw_ < std::chrono::milliseconds(250) || now - start_ < std::chrono::milliseconds(500)) return;
  last_draw_ = now;
  const double wall = std::chrono::duration<double>(now - start_).count();
  const double eta = t_s > 0 ? wall * (total_s_ - t_s) / t_s : 0.0;
  std::fprintf(stderr, "\r%s", line(t_s, total_s_, static_cast<double>(events) / wall, eta, 30).c_str());
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
