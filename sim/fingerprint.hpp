#pragma once
// A running hash of the ordered stream of executed events and the payload digests models
// add while handling them. Two runs with the same fingerprint executed the same events at
// the same times in the same order with the same digested payloads. In the origin order each
// origin keeps its own stream, combined in origin order at the end, so that the parts of a
// partitioned run can each keep the streams of their own nodes
// (docs/time-and-ordering.md).
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace masnet::sim {

/// Mixes one 64-bit word into a hash state (multiply-xorshift; fixed forever: fingerprints
/// of reference scenarios are checked in).
inline constexpr std::uint64_t mix_word(std::uint64_t state, std::uint64_t word) {
  state = (state ^ word) * 0x9E3779B97F4A7C15ULL;
  return state ^ (state >> 29);
}

/// The bits of a double, so that digests see exactly what was computed.
inline std::uint64_t bits_of(double x) {
  return std::bit_cast<std::uint64_t>(x);
}

class Fingerprint {
 public:
  Fingerprint() = default;
  /// A stream continued from its value (carried from another process of a partitioned run).
  static Fingerprint resumed(std::uint64_t value) {
    Fingerprint f;
    f.state_ = value;
    return f;
  }
  void mix(std::uint64_t word) { state_ = mix_word(state_, word); }
  void mix(double x) { mix(bits_of(x)); }
  std::uint64_t value() const { return state_; }
  /// 16 lowercase hex digits, as written to summary.json.
  std::string hex() const;
  /// Nothing mixed in yet (or, once in 2^64, back at the start).
  bool untouched() const { return state_ == kBasis; }

 private:
  static constexpr std::uint64_t kBasis = 0xCBF29CE484222325ULL;
  std::uint64_t state_ = kBasis;
};

/// One fingerprint of per-origin streams (index = origin): each touched stream's origin and
/// value in origin order. Where the streams were computed — in one run or spread over the parts
/// of a partitioned one — does not matter, only what each origin's stream holds.
inline Fingerprint combine_origin_streams(const std::vector<Fingerprint>& by_origin) {
  Fingerprint combined;
  for (std::size_t origin = 0; origin < by_origin.size(); ++origin) {
    if (by_origin[origin].untouched()) continue;
    combined.mix(static_cast<std::uint64_t>(origin));
    combined.mix(by_origin[origin].value());
  }
  return combined;
}

}  // namespace masnet::sim
