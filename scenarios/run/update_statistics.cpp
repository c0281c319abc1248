#include "scenarios/run/update_statistics.hpp"

#include <algorithm>
#include <string>

#include "net/messages.hpp"
#include "scenarios/run/geometry_outputs.hpp"
#include "sim/time.hpp"

namespace masnet::scenarios {

void UpdateStatistics::add(const protocols::UpdateSummary& update, bool correct,
                           bool correct_heard) {
  ++count_;
  correct_ += correct ? 1 : 0;
  correct_heard_ += correct_heard ? 1 : 0;
  geometry_ += update.geometry;
  rounds_ += update.rounds;
  rounds_max_ = std::max(rounds_max_, update.rounds);
  const double latency_s = sim::to_seconds(update.finished - update.started);
  latency_s_ += latency_s;
  latency_max_s_ = std::max(latency_max_s_, latency_s);
  radius_ += update.radius;
  truncated_ += update.truncated ? 1 : 0;
  delayed_ += update.delayed ? 1 : 0;
  no_mass_ += update.no_mass ? 1 : 0;
  // Message types registered after the first update are counted from when they appear.
  const std::size_t types = net::message_type_count();
  if (messages_per_type_.size() < types) messages_per_type_.resize(types, 0.0);
  for (std::size_t t = 0; t < types; ++t) {
    messages_per_type_[t] += static_cast<double>(update.messages[t].count);
    update_bytes_ += static_cast<double>(update.messages[t].bytes);
  }
}

void UpdateStatistics::fill_summary(nlohmann::json& p,
                                    std::uint64_t sensor_point_in_cell_tests) const {
  const double div = std::max(1.0, static_cast<double>(count_));
  p["updates"] = count_;
  p["rounds_mean"] = rounds_ / div;
  p["rounds_max"] = rounds_max_;
  p["truncated"] = truncated_;
  p["cell_correctness"] = cell_correctness();
  p["cell_correctness_heard"] = cell_correctness_heard();
  p["delayed_updates"] = delayed_;
  p["no_mass_updates"] = no_mass_;
  p["latency_mean_s"] = latency_s_ / div;
  p["latency_max_s"] = latency_max_s_;
  p["radius_mean"] = radius_ / div;
  nlohmann::json per_update = nlohmann::json::object();
  for (std::size_t t = 0; t < messages_per_type_.size(); ++t)
    if (messages_per_type_[t] > 0)
      per_update[std::string(net::name_of(t))] = messages_per_type_[t] / div;
  p["messages_per_update"] = per_update;
  p["bytes_per_update"] = update_bytes_ / div;
  p["geometry"] = geometry_summary(geometry_, sensor_point_in_cell_tests, count_);
}

}  // namespace masnet::scenarios
