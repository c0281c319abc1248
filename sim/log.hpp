#pragma once
// A log whose prefix is *simulated* time, on top of spdlog. Bound to one Simulator (no
// global clock); the sink and level are spdlog's, so the CLI decides where lines go.
// Every line reads "[t=    1.234567890 s] [debug] message" (docs/logging.md).
//
// Formatting costs only when the level is on: callers on busy paths write
// MASNET_LOG(log, debug, "...", args) — one pointer test and one level compare when off, the
// arguments not even evaluated.
#include <iterator>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>

#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

#include "sim/time.hpp"

namespace masnet::sim {

class Simulator;

class Log {
 public:
  /// Logs through `logger` (spdlog's default logger when null).
  explicit Log(const Simulator& simulator, std::shared_ptr<spdlog::logger> logger = nullptr);

  template <class... Args>
  void trace(fmt::format_string<Args...> format, Args&&... args) const {
    write(spdlog::level::trace, format, std::forward<Args>(args)...);
  }
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
  template <class... Args>
  void error(fmt::format_string<Args...> format, Args&&... args) const {
    write(spdlog::level::err, format, std::forward<Args>(args)...);
  }
  bool enabled(spdlog::level::level_enum level) const { return logger_->should_log(level); }

  /// "[t=   12.345678900 s] " — the prefix every line gets.
  static std::string prefix(Time t);
  /// The level's name in a line and on the command line: trace, debug, info, warn, error, off.
  static std::string_view level_name(spdlog::level::level_enum level);

 private:
  template <class... Args>
  void write(spdlog::level::level_enum level, fmt::format_string<Args...> format,
             Args&&... args) const {
    if (!logger_->should_log(level)) return;
    write_line(level, format, fmt::make_format_args(args...));
  }
  // Out of line and cold: a caller's code holds only the level test and this call, not the
  // formatting (which would bloat hot functions such as a sensor's frame handler).
  [[gnu::cold]] void write_line(spdlog::level::level_enum level, fmt::string_view format,
                                fmt::format_args args) const;

  const Simulator* simulator_;
  std::shared_ptr<spdlog::logger> logger_;
};

/// A sink that appends to a file it was given open, buffered, every write checked: the first
/// failure is kept (error()) instead of being thrown from inside the simulation.
class CheckedFileSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  /// Opens `path` for appending (created if absent, 0644). Throws std::system_error naming
  /// the reason when it cannot be opened.
  explicit CheckedFileSink(const std::string& path);
  ~CheckedFileSink() override;
  /// Empty, or "cannot write 'PATH': REASON" for the first failed write.
  std::string error();

 protected:
  void sink_it_(const spdlog::details::log_msg& message) override;
  void flush_() override;

 private:
  void write_out();
  std::string path_;
  int fd_ = -1;
  spdlog::memory_buf_t buffer_;
  std::string error_;
};

}  // namespace masnet::sim

/// Logs through `log` (a `const sim::Log*`, may be null) at `severity` (trace, debug, info, warn,
/// error) — the arguments are evaluated only when that level is on.
#define MASNET_LOG(log, severity, ...)                                      \
  do {                                                                      \
    const ::masnet::sim::Log* masnet_log_ = (log);                          \
    if (masnet_log_ != nullptr &&                                           \
        masnet_log_->enabled(::spdlog::level::MASNET_LOG_LEVEL_##severity)) \
      masnet_log_->severity(__VA_ARGS__);                                   \
  } while (false)
#define MASNET_LOG_LEVEL_trace trace
#define MASNET_LOG_LEVEL_debug debug
#define MASNET_LOG_LEVEL_info info
#define MASNET_LOG_LEVEL_warn warn
#define MASNET_LOG_LEVEL_error err
