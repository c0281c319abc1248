#pragma once
// A sum of non-negative doubles that does not depend on the order of its terms: each term is
// cut to a multiple of 2^-64 and added as a 128-bit integer. The radio's energy totals use it
// so that the parts of a partitioned run, each adding its own senders' frames, give the same
// total as the whole run (docs/decisions/0012-partitioned-runs.md).
#include <cstdint>

#include "sim/assert.hpp"

namespace masnet::sim {

class ExactSum {
  __extension__ using Fixed = unsigned __int128;  // GCC and Clang; -Wpedantic would object

 public:
  /// Adds `x` (0 <= x < 2^63, asserted) truncated to a multiple of 2^-64.
  void add(double x) {
    MASNET_ASSERT(x >= 0.0 && x < 0x1p63, "an exact sum takes terms in [0, 2^63)");
    const auto whole = static_cast<std::uint64_t>(x);
    // x - whole is exact (both are doubles of the same binade or below), and so is scaling it.
    const auto fraction = static_cast<std::uint64_t>((x - static_cast<double>(whole)) * 0x1p64);
    sum_ += (static_cast<Fixed>(whole) << 64) + fraction;
  }
  void add(const ExactSum& other) { sum_ += other.sum_; }
  /// The sum, rounded to a double (the same bits whatever the order of the terms).
  double value() const {
    return static_cast<double>(static_cast<std::uint64_t>(sum_ >> 64)) +
           static_cast<double>(static_cast<std::uint64_t>(sum_)) * 0x1p-64;
  }
  friend bool operator==(const ExactSum&, const ExactSum&) = default;

 private:
  Fixed sum_ = 0;
};

}  // namespace masnet::sim
