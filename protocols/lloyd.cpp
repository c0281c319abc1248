#include "protocols/lloyd.hpp"

namespace masnet::protocols {

Vec2 lloyd_force(double k, double k_v, const Vec2& position, const Vec2& velocity,
                 const Vec2& centroid) {
  return -k * (position - centroid) - k_v * velocity;
}

}  // namespace masnet::protocols
