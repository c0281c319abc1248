#pragma once
// "--key=value" arguments and the RESULT line shared by the kernel benchmarks. The workloads
// and their output format match the ns-3 peers, so both can run side by side.
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <string>

namespace masnet::bench {

inline double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Args {
  int argc;
  char** argv;
  const char* find(const char* key) const {
    const std::size_t k = std::strlen(key);
    for (int i = 1; i < argc; ++i) {
      const char* a = argv[i];
      if (a[0] == '-' && a[1] == '-' && std::strncmp(a + 2, key, k) == 0 && a[2 + k] == '=')
        return a + 3 + k;
    }
    return nullptr;
  }
  double number(const char* key, double fallback) const {
    const char* v = find(key);
    return v ? std::atof(v) : fallback;
  }
};

/// The peers' draws from the raw 64-bit stream: uniform in (0, 1].
inline double unit_open_closed(std::uint64_t bits) {
  return static_cast<double>((bits >> 11) + 1) * (1.0 / 9007199254740992.0);
}

/// FNV-1a over 64-bit words: the peers' checksum.
inline std::uint64_t fnv_word(std::uint64_t h, std::uint64_t w) {
  return (h ^ w) * 1099511628211ULL;
}
inline constexpr std::uint64_t kFnvBasis = 1469598103934665603ULL;

}  // namespace masnet::bench
