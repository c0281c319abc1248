#include "sim/random.hpp"

#include <cmath>

#include "sim/assert.hpp"

namespace masnet::sim {
namespace {
__extension__ typedef unsigned __int128 U128;  // GCC/Clang 128-bit product
}

RandomStream::RandomStream(std::uint64_t raw_seed) {
  std::uint64_t x = raw_seed;
  for (auto& word : s_) {
    word = splitmix64(x);
    x += 0x9E3779B97F4A7C15ULL;
  }
}

std::uint64_t RandomStream::below(std::uint64_t n) {
  MASNET_ASSERT(n > 0, "below(0)");
  U128 m = static_cast<U128>(next_u64()) * n;
  auto low = static_cast<std::uint64_t>(m);
  if (low < n) {
    const std::uint64_t threshold = (0 - n) % n;
    while (low < threshold) {
      m = static_cast<U128>(next_u64()) * n;
      low = static_cast<std::uint64_t>(m);
    }
  }
  return static_cast<std::uint64_t>(m >> 64);
}

double RandomStream::exponential(double mean) {
  // 1 - u is in (0, 1], so the logarithm is finite.
  return -mean * std::log(1.0 - uniform01());
}

double RandomStream::normal(double mean, double sd) {
  for (;;) {
    const double u = 2.0 * uniform01() - 1.0;
    const double v = 2.0 * uniform01() - 1.0;
    const double s = u * u + v * v;
    if (s > 0.0 && s < 1.0) return mean + sd * u * std::sqrt(-2.0 * std::log(s) / s);
  }
}

}  // namespace masnet::sim
