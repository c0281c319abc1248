#pragma once
// The protocol's statistics over all updates of a run (summary.json `protocol`), accumulated as
// the updates finish so that a run need not keep every update to report them.

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "protocols/host.hpp"

namespace masnet::scenarios {

class UpdateStatistics {
 public:
  /// Adds one finished update; `correct` and `correct_heard` are its cell-correctness verdicts.
  void add(const protocols::UpdateSummary& update, bool correct, bool correct_heard);

  std::uint64_t count() const { return count_; }
  /// Fraction of updates whose neighbour set was right (1 before the first update).
  double cell_correctness() const { return fraction(correct_); }
  double cell_correctness_heard() const { return fraction(correct_heard_); }
  std::uint64_t correct() const { return correct_; }

  /// summary.json's `protocol` fields (docs/outputs.md); `sensor_point_in_cell_tests` is the
  /// sensors' share of the computation load.
  void fill_summary(nlohmann::json& protocol, std::uint64_t sensor_point_in_cell_tests) const;

 private:
  double fraction(std::uint64_t part) const {
    return count_ == 0 ? 1.0 : static_cast<double>(part) / static_cast<double>(count_);
  }

  // Sums in update order (then message type order): the same bits as summing a kept list.
  std::uint64_t count_ = 0, correct_ = 0, correct_heard_ = 0;
  double rounds_ = 0, latency_s_ = 0, latency_max_s_ = 0, radius_ = 0, update_bytes_ = 0;
  std::uint32_t rounds_max_ = 0;
  std::uint64_t truncated_ = 0, delayed_ = 0, no_mass_ = 0;
  std::vector<double> messages_per_type_;
  protocols::GeometryWork geometry_;
};

}  // namespace masnet::scenarios
