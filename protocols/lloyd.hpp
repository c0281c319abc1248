#pragma once
// The Lloyd control target (paper §III-B; docs/protocols.md): the centroid of the readings inside a
// cell, each weighted by SK(ρ)·A(s), over positive readings only.
#include <cstddef>
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
  /// Adds the n sensors (xs[k], y) with readings rhos[k], each standing for `area`: the same
  /// arithmetic, in the same order, as n calls of add(), with the scaling chosen once per row.
  void add_row(double y, const double* xs, const double* rhos, std::size_t n, double area) {
    switch (scaling_.kind) {
      case ScalingKind::identity:
        add_row_scaled(y, xs, rhos, n, area, [](double rho) { return rho > 0.0 ? rho : 0.0; });
        return;
      default:
        add_row_scaled(y, xs, rhos, n, area, [this](double rho) { return scaling_(rho); });
    }
  }
  /// Adds the n sensors (xs[k], y) all reading `rho` (a uniform field): n calls of add() to the
  /// bit, with the weight computed once.
  void add_row_uniform(double y, const double* xs, std::size_t n, double rho, double area) {
    const double w = scaling_(rho) * area;
    if (!(w > 0.0) || n == 0) return;
    double mass = mass_, mx = moment_x_, my = moment_y_;
    const double wy = w * y;
    for (std::size_t k = 0; k < n; ++k) {
      mass += w;
      mx += w * xs[k];
      my += wy;
    }
    mass_ = mass;
    moment_x_ = mx;
    moment_y_ = my;
    weighted_ += static_cast<std::uint32_t>(n);
  }
  /// True when at least one positive reading was added.
  bool has_mass() const { return weighted_ > 0 && mass_ > 0.0; }
  /// Σ w·s / Σ w; precondition has_mass().
  Vec2 centroid() const { return Vec2{moment_x_ / mass_, moment_y_ / mass_}; }
  double mass() const { return mass_; }
  std::uint32_t weighted_count() const { return weighted_; }

 private:
  template <class Scale>
  void add_row_scaled(double y, const double* xs, const double* rhos, std::size_t n, double area,
                      Scale scale) {
    double mass = mass_, mx = moment_x_, my = moment_y_;
    std::uint32_t weighted = weighted_;
    for (std::size_t k = 0; k < n; ++k) {
      const double w = scale(rhos[k]) * area;
      if (!(w > 0.0)) continue;
      mass += w;
      mx += w * xs[k];
      my += w * y;
      ++weighted;
    }
    mass_ = mass;
    moment_x_ = mx;
    moment_y_ = my;
    weighted_ = weighted;
  }

  DensityScaling scaling_;
  double mass_ = 0.0, moment_x_ = 0.0, moment_y_ = 0.0;
  std::uint32_t weighted_ = 0;
};

/// The control force of paper eq. (2): f = −k (p − c) − k_v ṗ (world units / s²).
Vec2 lloyd_force(double k, double k_v, const Vec2& position, const Vec2& velocity,
                 const Vec2& centroid);

}  // namespace masnet::protocols
