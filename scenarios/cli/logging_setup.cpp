#include "scenarios/cli/logging_setup.hpp"

#include <spdlog/sinks/stdout_sinks.h>

namespace masnet::cli {

const std::vector<std::string> kLogLevels{"trace", "debug", "info", "warn", "error", "off"};

std::shared_ptr<spdlog::logger> make_logger(spdlog::sink_ptr sink,
                                            spdlog::level::level_enum level) {
  auto logger = std::make_shared<spdlog::logger>("masnet", std::move(sink));
  logger->set_pattern("%v");  // sim::Log writes the simulated-time prefix and the level itself
  logger->set_level(level);
  logger->flush_on(spdlog::level::warn);
  return logger;
}

void log_to_stderr() {
  spdlog::set_default_logger(
      make_logger(std::make_shared<spdlog::sinks::stderr_sink_mt>(), spdlog::level::warn));
}

}  // namespace masnet::cli
