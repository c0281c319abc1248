#pragma once
// A running hash of the ordered stream of executed events and the payload digests models
// add while handling them. Two runs with the same fingerprint executed the same events at
// the same times in the same order with the same digested payloads.
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

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
  void mix(std::uint64_t word) { state_ = mix_word(state_, word); }
  void mix(double x) { mix(bits_of(x)); }
  std::uint64_t value() const { return state_; }
  /// 16 lowercase hex digits, as written to summary.json.
  std::string hex() const;

 private:
  std::uint64_t state_ = 0xCBF29CE484222325ULL;
};

}  // namespace masnet::sim
