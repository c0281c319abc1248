#include "sim/log.hpp"

#include <cerrno>
#include <cstring>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#include "sim/simulator.hpp"

namespace masnet::sim {

Log::Log(const Simulator& simulator, std::shared_ptr<spdlog::logger> logger)
    : simulator_(&simulator), logger_(logger ? std::move(logger) : spdlog::default_logger()) {}

std::string Log::prefix(Time t) {
  return fmt::format("[t={:>15.9f} s] ", to_seconds(t));
}

std::string_view Log::level_name(spdlog::level::level_enum level) {
  switch (level) {
    case spdlog::level::trace:
      return "trace";
    case spdlog::level::debug:
      return "debug";
    case spdlog::level::info:
      return "info";
    case spdlog::level::warn:
      return "warn";
    case spdlog::level::err:
      return "error";
    case spdlog::level::critical:
      return "critical";
    default:
      return "off";
  }
}

void Log::write_line(spdlog::level::level_enum level, fmt::string_view format,
                     fmt::format_args args) const {
  fmt::memory_buffer line;
  fmt::format_to(std::back_inserter(line), "[t={:>15.9f} s] [{}] ", to_seconds(simulator_->now()),
                 level_name(level));
  fmt::vformat_to(std::back_inserter(line), format, args);
  logger_->log(level, spdlog::string_view_t(line.data(), line.size()));
}

CheckedFileSink::CheckedFileSink(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw std::system_error(errno, std::generic_category(), "cannot open '" + path + "'");
}

CheckedFileSink::~CheckedFileSink() {
  write_out();
  if (fd_ >= 0) ::close(fd_);
}

std::string CheckedFileSink::error() {
  std::lock_guard<std::mutex> lock(mutex_);
  write_out();
  return error_;
}

void CheckedFileSink::sink_it_(const spdlog::details::log_msg& message) {
  formatter_->format(message, buffer_);
  if (buffer_.size() >= (std::size_t{1} << 16)) write_out();
}

void CheckedFileSink::flush_() {
  write_out();
}

void CheckedFileSink::write_out() {
  const char* p = buffer_.data();
  std::size_t left = buffer_.size();
  while (left > 0 && error_.empty()) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      error_ = "cannot write '" + path_ + "': " + std::strerror(errno);
      break;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  buffer_.clear();
}

}  // namespace masnet::sim
