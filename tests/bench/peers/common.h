// common.h - shared helpers for the kernel benchmarks (own code).
// RNG: splitmix64-seeded xoshiro256** (deterministic, identical stream in every kernel).
#pragma once
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace anchors {

struct Rng {
    uint64_t s[4];
    static uint64_t splitmix(uint64_t& x) {
        uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    explicit Rng(uint64_t seed = 12345) {
        for (auto& v : s) v = splitmix(seed);
    }
    static inline uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    inline uint64_t next() {
        const uint64_t r = rotl(s[1] * 5, 7) * 9;
        const uint64_t t = s[1] << 17;
        s[2] ^= s[0]; s[3] ^= s[1]; s[1] ^= s[2]; s[0] ^= s[3];
        s[2] ^= t; s[3] = rotl(s[3], 45);
        return r;
    }
    // uniform in [0, n) (Lemire multiply-shift, tiny bias irrelevant here)
    inline uint32_t below(uint32_t n) {
        return (uint32_t)(((unsigned __int128)next() * n) >> 64);
    }
    // uniform double in (0,1]
    inline double unit() { return ((next() >> 11) + 1) * (1.0 / 9007199254740992.0); }
    // exponential delay in integer ticks with the given mean (ticks), at least 1 tick
    inline int64_t expTicks(double meanTicks) {
        int64_t d = (int64_t)(-std::log(unit()) * meanTicks);
        return d < 1 ? 1 : d;
    }
};

inline double nowSec() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// tiny "--key=value" argument parser
struct Args {
    int argc; char** argv;
    Args(int c, char** v) : argc(c), argv(v) {}
    const char* find(const char* key) const {
        size_t k = std::strlen(key);
        for (int i = 1; i < argc; ++i) {
            const char* a = argv[i];
            if (a[0] == '-' && a[1] == '-' && std::strncmp(a + 2, key, k) == 0 && a[2 + k] == '=')
                return a + 3 + k;
        }
        return nullptr;
    }
    double num(const char* key, double def) const { const char* v = find(key); return v ? std::atof(v) : def; }
    std::string str(const char* key, const char* def) const { const char* v = find(key); return v ? v : def; }
};

} // namespace anchors
