#pragma once
// A log whose prefix is *simulated* time, on top of spdlog. Bound to one Simulator (no
// global clock); the sink and level are spdlog's, so the CLI decides where lines go.
#include <memory>
#include <utility>

#include <spdlog/spdlog.h>

#include "sim/time.hpp"

namespace masnet::sim {

class Simulator;

class Log {
 public:
  /// Logs through `logger` (spdlog's default logger when null).
  explicit Log(const Simulator& simulator, std::shared_ptr<spdlog::logger> logger = nullptr);

  template <class... Args>
  void debug(fmt::format_string<Args...> format, Args&&... args) const {
    write(spdlog::level::debug, format, std::forward<Args>(args)...);
  }
  template <class... Args>
  void info(fmt::format_string<Args...> format, Args&&... args) const {
    write(spdlog::level::info, format, std::forward<Args>(args)...);
  }
  template <class... Args>
  void warn(fmt::format_string<Args...> format, Args&&... args) const {
    write(spdlog::level::warn, format, std::forward<Args>(args)...);
  }
  bool enabled(spdlog::level::level_enum level) const { return logger_->should_log(level); }

  /// "[t=   12.345678900 s] " — the prefix every line gets.
  static std::string prefix(Time t);

 private:
  template <class... Args>
  void write(spdlog::level::level_enum level, fmt::format_string<Args...> format,
             Args&&... args) const {
    if (!logger_->should_log(level)) return;
    logger_->log(level, "{}{}", prefix(now()), fmt::format(format, std::forward<Args>(args)...));
  }
  Time now() const;

  const Simulator* simulator_;
  std::shared_ptr<spdlog::logger> logger_;
};

}  // namespace masnet::sim
