#pragma once
// Scripted faults (docs/faults-and-lifetime.md): nodes killed (and maybe restarted), a line no
// frame crosses, a region of extra loss — each from `at_s` until `until_s`.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "net/link_faults.hpp"

namespace masnet::agents {

enum class FaultKind { kill, partition, degrade };
/// Which nodes a kill takes.
enum class FaultNodes { robots, sensors };

struct FaultDef {
  double at_s = 0.0;
  /// A killed node restarts, a partition heals, a degraded region clears then; never if infinite.
  double until_s = std::numeric_limits<double>::infinity();
  FaultKind kind = FaultKind::kill;
  // kill: exactly one of ids, fraction, region chooses the nodes.
  FaultNodes nodes = FaultNodes::robots;
  std::vector<std::uint32_t> ids;     ///< robot or sensor numbers (0-based, by class)
  std::optional<double> fraction;     ///< this share of the class, chosen by the run's seed
  std::optional<net::Region> region;  ///< the nodes of the class inside it when the fault strikes
  // partition
  net::LineCut line;
  // degrade: `region` and this loss
  double loss = 0.0;

  bool restarts() const { return until_s < std::numeric_limits<double>::infinity(); }
};

/// Locomotion energy of the robots: per metre travelled and per unit of |acceleration|·time
/// (m/s), booked from the closed-form motion. Defaults: a small ground robot of about 9 kg
/// (docs/faults-and-lifetime.md).
struct LocomotionEnergy {
  double per_metre_j = 7.4;   ///< J per metre travelled
  double per_accel_j = 2.25;  ///< J per (m/s² · s)
};

}  // namespace masnet::agents
