#pragma once
// Seeded random streams keyed by (seed, node, purpose), so that adding a node or a draw in
// one place never shifts another node's numbers. The generator is
// xoshiro256** and every distribution is written here from integer arithmetic and IEEE
// operations, so the numbers are the same on every platform with the same libm.
#include <cstdint>
#include <string_view>

#include "sim/ids.hpp"

namespace masnet::sim {

/// Names a use of randomness ("radio.loss", "robot.phase"); a compile-time FNV-1a hash.
inline constexpr std::uint64_t purpose(std::string_view name) {
  std::uint64_t h = 0xCBF29CE484222325ULL;
  for (char c : name)
    h = (h ^ static_cast<unsigned char>(c)) * 0x100000001B3ULL;
  return h;
}

/// splitmix64's output function: a bijective 64-bit mixer.
inline constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

/// A counter-based draw: a well-mixed 64-bit value determined only by its key. Used where a
/// stream per key would be too much state (e.g. one loss draw per link and frame).
inline constexpr std::uint64_t keyed_u64(std::uint64_t seed, std::uint64_t a, std::uint64_t b,
                                         std::uint64_t c = 0, std::uint64_t d = 0) {
  std::uint64_t h = splitmix64(seed);
  h = splitmix64(h ^ a);
  h = splitmix64(h ^ b);
  h = splitmix64(h ^ c);
  return splitmix64(h ^ d);
}
/// `keyed_u64` as a double uniform in [0, 1).
inline constexpr double keyed_uniform01(std::uint64_t seed, std::uint64_t a, std::uint64_t b,
                                        std::uint64_t c = 0, std::uint64_t d = 0) {
  return static_cast<double>(keyed_u64(seed, a, b, c, d) >> 11) * 0x1.0p-53;
}

class RandomStream {
 public:
  /// The stream of `node` for `purpose_hash` in a run seeded with `seed`.
  static RandomStream keyed(std::uint64_t seed, NodeId node, std::uint64_t purpose_hash) {
    return keyed(seed, std::uint64_t{index(node)}, purpose_hash);
  }
  /// The same, for a caller-chosen node key (e.g. role and index, stable when nodes are added).
  static RandomStream keyed(std::uint64_t seed, std::uint64_t node_key,
                            std::uint64_t purpose_hash) {
    return RandomStream(keyed_u64(seed, node_key, purpose_hash));
  }
  /// A stream from one raw 64-bit seed (splitmix64 expansion, the generator authors' advice).
  explicit RandomStream(std::uint64_t raw_seed);

  std::uint64_t next_u64() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  /// Uniform in [0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  /// Uniform integer in [0, n), unbiased (Lemire's multiply-shift with rejection). n > 0.
  std::uint64_t below(std::uint64_t n);
  /// Exponential with the given mean (> 0), by inversion.
  double exponential(double mean);
  /// Normal(mean, sd) by Marsaglia's polar method (no cached second value: one call, one
  /// pair of uniforms consumed per accepted try).
  double normal(double mean, double sd);
  /// True with probability p.
  bool bernoulli(double p) { return uniform01() < p; }

 private:
  static constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

}  // namespace masnet::sim
