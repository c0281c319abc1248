#pragma once
// The Lloyd control target (paper §III-B, SPEC §5.2): the centroid of the readings inside a
// cell, each weighted by SK(ρ)·A(s), over positive readings only.
#include <cstdint>

#include "net/vec2.hpp"
#include "protocols/density_scaling.hpp"

namespace masnet::protocols {

using net::Vec2;

class CentroidAccumulator {
 public:
  explicit CentroidAccumulator(const DensityScaling& scaling) : scaling_(scaling) {}

  /// Adds sensor `at` with reading `rho` standing for `area` of the domain.
  void add(const Vec2& at, double rho, double area) {
    const double w = scaling_(rho) * area;
    if (!(w > 0.0)) return;
    mass_ += w;
    moment_x_ += w * at.x();
    moment_y_ += w * at.y();
    ++weighted_;
  }
  /// True when at least one positive reading was added.
  bool has_mass() const { return weighted_ > 0 && mass_ > 0.0; }
  /// Σ w·s / Σ w; precondition has_mass().
  Vec2 centroid() const { return Vec2{moment_x_ / mass_, moment_y_ / mass_}; }
  double mass() const { return mass_; }
  std::uint32_t weighted_count() const { return weighted_; }

 private:
  DensityScaling scaling_;
  double mass_ = 0.0, moment_x_ = 0.0, moment_y_ = 0.0;
  std::uint32_t weighted_ = 0;
};

/// The control force of paper eq. (2): f = −k (p − c) − k_v ṗ (world units / s²).
Vec2 lloyd_force(double k, double k_v, const Vec2& position, const Vec2& velocity, const Vec2& centroid);

}  // namespace masnet::protocols
