#include "sim/log.hpp"

#include "sim/simulator.hpp"

namespace masnet::sim {

Log::Log(const Simulator& simulator, std::shared_ptr<spdlog::logger> logger)
    : simulator_(&simulator), logger_(logger ? std::move(logger) : spdlog::default_logger()) {}

Time Log::now() const { return simulator_->now(); }

std::string Log::prefix(Time t) { return fmt::format("[t={:>15.9f} s] ", to_seconds(t)); }

}  // namespace masnet::sim
