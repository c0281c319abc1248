#pragma once
// What a stretch of motion costs a robot's wheels (docs/faults-and-lifetime.md): the distance
// travelled and ∫|acceleration| dt, integrated over the closed-form motion of a segment.
#include "agents/robot_motion.hpp"

namespace masnet::agents {

struct TravelIntegrals {
  double distance = 0.0;  ///< ∫|v| dt, world units
  double accel = 0.0;     ///< ∫|a| dt, world units / s
  TravelIntegrals& operator+=(const TravelIntegrals& o) {
    distance += o.distance;
    accel += o.accel;
    return *this;
  }
};

/// Over [t0_s, t1_s] of `segment` (t0_s at or after its start): Gauss–Legendre on the closed
/// form, or the trapezoid rule on the substep grid when the speed is limited.
TravelIntegrals travel_between(const MotionSegment& segment, const MotionParams& params,
                               double t0_s, double t1_s);

}  // namespace masnet::agents
