#include "net/propagation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "sim/random.hpp"

namespace masnet::net {
namespace {
constexpr std::uint64_t kShadowingPurpose = sim::purpose("radio.shadowing");

// (−1)^k C(16, k) for k = 0..16.
constexpr std::array<double, 17> kSignedBinomial16 = {1,    -16,    120,   -560,   1820, -4368,
                                                      8008, -11440, 12870, -11440, 8008, -4368,
                                                      1820, -560,   120,   -16,    1};
}  // namespace

double path_loss_db(const PropagationParams& p, double distance_m) {
  return p.reference_loss_db + 10.0 * p.exponent * std::log10(std::max(distance_m, 1.0));
}

double shadowing_db(const PropagationParams& p, std::uint64_t seed, std::uint64_t key_a,
                    std::uint64_t key_b) {
  if (p.shadowing_sigma_db <= 0) return 0.0;
  const std::uint64_t lo = std::min(key_a, key_b), hi = std::max(key_a, key_b);
  // Box–Muller on two keyed uniforms: one deviate per link, whatever the order of first use.
  const double u1 = 1.0 - sim::keyed_uniform01(seed, kShadowingPurpose, lo, hi, 0);  // (0, 1]
  const double u2 = sim::keyed_uniform01(seed, kShadowingPurpose, lo, hi, 1);
  return p.shadowing_sigma_db * std::sqrt(-2.0 * std::log(u1)) *
         std::cos(2.0 * std::numbers::pi * u2);
}

double oqpsk_bit_error_rate(double sinr) {
  double sum = 0.0;
  for (int k = 2; k <= 16; ++k)
    sum += kSignedBinomial16[static_cast<std::size_t>(k)] * std::exp(20.0 * sinr * (1.0 / k - 1.0));
  return std::clamp(sum * 8.0 / 15.0 / 16.0, 0.0, 1.0);
}

double oqpsk_frame_success(double sinr, double bits) {
  return std::pow(1.0 - oqpsk_bit_error_rate(sinr), bits);
}

}  // namespace masnet::net
