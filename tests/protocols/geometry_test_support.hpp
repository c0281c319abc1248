#pragma once
// What the geometry tests share: a seeded generator, the unit square and a comparison of
// vertex cycles.
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "protocols/geometry.hpp"

namespace geometry_test {

using masnet::protocols::ConvexPolygon;
using masnet::protocols::Vec2;

using Ids = std::vector<std::uint32_t>;

struct Rng {
  std::mt19937_64 engine;
  explicit Rng(std::uint64_t seed) : engine(seed) {}
  double uniform() { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
};

inline const ConvexPolygon kUnitSquare = masnet::protocols::rectangle(0.0, 0.0, 1.0, 1.0);

inline bool same_vertices(const ConvexPolygon& p, const std::vector<Vec2>& expected,
                          double tol = 1e-15) {
  if (p.vertices.size() != expected.size()) return false;
  // Same cyclic sequence, starting anywhere.
  for (std::size_t shift = 0; shift < expected.size(); ++shift) {
    bool all = true;
    for (std::size_t k = 0; k < expected.size() && all; ++k)
      all = (p.vertices[(k + shift) % expected.size()] - expected[k]).norm() <= tol;
    if (all) return true;
  }
  return false;
}

}  // namespace geometry_test
