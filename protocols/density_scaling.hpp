#pragma once
// SK(ρ): the class-K scaling applied to readings before centroids (paper §IV;
// docs/field-models.md).
#include <cmath>

namespace masnet::protocols {

enum class ScalingKind { identity, power, log1p, saturate };

struct DensityScaling {
  ScalingKind kind = ScalingKind::identity;
  double gamma = 1.0;       ///< exponent of `power` (> 0)
  double saturation = 1.0;  ///< c of `saturate`: ρ/(ρ + c) (> 0)

  /// SK(ρ) for ρ >= 0; zero for ρ <= 0 (only positive readings weigh a centroid).
  double operator()(double rho) const {
    if (!(rho > 0.0)) return 0.0;
    switch (kind) {
      case ScalingKind::identity:
        return rho;
      case ScalingKind::power:
        return std::pow(rho, gamma);
      case ScalingKind::log1p:
        return std::log1p(rho);
      case ScalingKind::saturate:
        return rho / (rho + saturation);
    }
    return rho;
  }
};

}  // namespace masnet::protocols
