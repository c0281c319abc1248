#pragma once
// The log (docs/logging.md): spdlog's default logger, on stderr at warn for every command, or
// as `masnet run --log-level --log-file` ask.
#include <memory>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>

#include "sim/log.hpp"

namespace masnet::cli {

/// The values of --log-level.
extern const std::vector<std::string> kLogLevels;

/// Where the log goes: stderr (never stdout, which carries the summary lines) unless a file
/// was named. Nothing is logged below warn today, so the default leaves the terminal as it was.
struct Logging {
  std::shared_ptr<masnet::sim::CheckedFileSink> file;  // null: stderr
  bool shows_on_terminal = false;                      // lines may land on stderr
};

/// A logger named masnet on `sink` that writes lines as sim::Log formats them.
std::shared_ptr<spdlog::logger> make_logger(spdlog::sink_ptr sink, spdlog::level::level_enum level);

/// Every command: the default logger writes to stderr at warn.
void log_to_stderr();

}  // namespace masnet::cli
